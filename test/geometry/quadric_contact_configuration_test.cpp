// Contact configuration of tangent quadrics (quadric_contact_configuration.h, Choi 2008 §6.3):
//  - the 35 representative pairs of Tables 7-9, typed in from the thesis text: the
//    characteristic polynomial (against coefficients expanded by a computer-algebra system),
//    the multiple roots, the signature brackets (multiplicity, inertia) and the Procedure's
//    verdict at the root that carries the real contact of the 22 checkmarked cases, and no
//    genuine real contact in the 13 others; invariance under swapping A and B, scaling them and
//    rigid motions;
//  - Example 6.3 (two cylinders);
//  - a geometric oracle independent of the tables: for affine pairs touching at a known point p,
//    points of one (smooth) surface are sampled around p and the sign of the other quadric's
//    function is read there (both signs = the surfaces cross = not genuine), in the canonical
//    pose and under random rigid motions applied to both quadrics;
//  - the polynomial against determinants, multiple roots of congruent diagonal pencils, roots
//    at infinity, non-multiple lambda0, singular and coincident pencils, and bad input.
#include <gtest/gtest.h>

#include <array>
#include <cctype>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "fcl_quadric/geometry/quadric_contact_configuration.h"
#include "support/expect_invalid.h"
#include "support/random_ellipsoids.h"

namespace fcl_quadric {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// The matrix of a quadratic form written as in the thesis tables: integer coefficients,
/// monomials x^2, xy, ... in x, y, z, w ("2xy + y^2 - z^2 + w^2"). xy contributes 1/2 to the
/// (x, y) and (y, x) entries.
Eigen::Matrix4d parseQuadric(const std::string& s) {
  Eigen::Matrix4d Q = Eigen::Matrix4d::Zero();
  std::size_t i = 0;
  const auto skip = [&] {
    while (i < s.size() && s[i] == ' ') ++i;
  };
  const auto var = [&](char c) {
    const std::string names = "xyzw";
    const std::size_t k = names.find(c);
    if (k == std::string::npos) ADD_FAILURE() << "bad variable '" << c << "' in " << s;
    return k == std::string::npos ? 0 : static_cast<int>(k);
  };
  while (true) {
    skip();
    if (i >= s.size()) break;
    double sign = 1.0;
    if (s[i] == '+' || s[i] == '-') {
      sign = s[i] == '-' ? -1.0 : 1.0;
      ++i;
      skip();
    }
    double coef = 1.0;
    if (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) {
      coef = 0.0;
      while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) coef = 10.0 * coef + (s[i++] - '0');
    }
    if (i >= s.size()) {
      ADD_FAILURE() << "dangling coefficient in " << s;
      break;
    }
    const int a = var(s[i++]);
    int b = a;
    if (i < s.size() && s[i] == '^') {
      if (i + 1 >= s.size() || s[i + 1] != '2') ADD_FAILURE() << "only ^2 is supported: " << s;
      i += 2;
    } else if (i < s.size() && std::isalpha(static_cast<unsigned char>(s[i]))) {
      b = var(s[i++]);
    } else {
      ADD_FAILURE() << "a monomial needs degree 2: " << s;
    }
    if (a == b) {
      Q(a, a) += sign * coef;
    } else {
      Q(a, b) += 0.5 * sign * coef;
      Q(b, a) += 0.5 * sign * coef;
    }
  }
  return Q;
}

double evalPoly(const std::array<double, 5>& c, double x) {
  double v = 0.0;
  for (int k = 4; k >= 0; --k) v = v * x + c[k];
  return v;
}

/// Homogeneous 4x4 of x -> R x + t and the quadric / plane / point maps under it.
struct Motion {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  Eigen::Matrix4d Tinv = Eigen::Matrix4d::Identity();
  Eigen::Matrix4d quadric(const Eigen::Matrix4d& Q) const {
    const Eigen::Matrix4d M = Tinv.transpose() * Q * Tinv;
    return 0.5 * (M + M.transpose());
  }
  Eigen::Vector4d plane(const Eigen::Vector4d& P) const { return Tinv.transpose() * P; }
  Eigen::Vector4d point(const Eigen::Vector4d& X) const { return T * X; }
};

Motion randomMotion(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Eigen::Matrix3d R = test::randomRotation(rng);
  const double tz = u(rng), ty = u(rng), tx = u(rng);
  const Eigen::Vector3d t(tx, ty, tz);
  Motion m;
  m.T.topLeftCorner<3, 3>() = R;
  m.T.topRightCorner<3, 1>() = t;
  m.Tinv.topLeftCorner<3, 3>() = R.transpose();
  m.Tinv.topRightCorner<3, 1>() = -R.transpose() * t;
  return m;
}

/// Distance between unit homogeneous points up to sign.
double pointDistance(const Eigen::Vector4d& a, const Eigen::Vector4d& b) {
  const Eigen::Vector4d an = a.normalized(), bn = b.normalized();
  return std::min((an - bn).norm(), (an + bn).norm());
}

bool containsPoint(const std::vector<Eigen::Vector4d>& pts, const Eigen::Vector4d& X, double tol) {
  for (const auto& p : pts) {
    if (pointDistance(p, X) <= tol) return true;
  }
  return false;
}

double swappedLambda(double l) {
  if (l == 0.0) return kInf;
  if (std::isinf(l)) return 0.0;
  return 1.0 / l;
}

// --- Tables 7-9 -----------------------------------------------------------------------------

struct TableRow {
  int id;
  const char* A;
  const char* B;
  std::array<double, 5> f;            // det(lambda A - B), ascending (computer algebra)
  std::vector<double> multiple_roots;  // real multiple roots, +inf last (computer algebra)
};

// Representative Quadric Pair column of Tables 7, 8, 9, as printed ("A: ... = 0", "B: ... = 0").
// Every row of the extracted text is legible in this column and in the signature sequences
// (the Illustration column and several index sequences are garbled; some checkmarks of the
// "Real Contact Point" column came out as "~"; the 22 checkmarked cases are the ones the
// Procedure lists).
const std::vector<TableRow>& tableRows() {
  static const std::vector<TableRow> rows = {
      {1, "x^2 + y^2 + z^2 - w^2", "2x^2 + 4y^2 - w^2", {0.0, 8.0, -14.0, 7.0, -1.0}, {}},
      {2, "x^2 + y^2 + z^2 - w^2", "2x^2 + 4y^2 + 3z^2 - w^2", {-24.0, 50.0, -35.0, 10.0, -1.0}, {}},
      {3, "2xy + z^2 + w^2", "-x^2 + y^2 + z^2 + 2w^2", {-2.0, 3.0, -3.0, 3.0, -1.0}, {}},
      {4, "xy + zw", "-x^2 + y^2 - 2z^2 + zw + 2w^2", {4.25, -0.5, 1.3125, -0.125, 0.0625}, {}},
      {5, "x^2 - y^2 + z^2 + 4yw", "-3x^2 + y^2 + z^2", {0.0, 0.0, 12.0, -8.0, -4.0}, {0.0}},
      {6, "-x^2 - z^2 + 2yw", "-3x^2 + y^2 - z^2", {0.0, 0.0, -3.0, 4.0, -1.0}, {0.0}},
      {7, "x^2 + z^2 + 2yw", "3x^2 + y^2 + z^2", {0.0, 0.0, -3.0, 4.0, -1.0}, {0.0}},
      {8, "xy + zw", "2xy + y^2 - z^2 + w^2", {1.0, -1.0, 0.5, -0.25, 0.0625}, {2.0}},
      {9, "xy + zw", "y^2 + 2zw + w^2", {0.0, 0.0, 0.25, -0.25, 0.0625}, {0.0, 2.0}},
      {10, "xw + yz", "xz - yw", {0.0625, 0.0, 0.125, 0.0, 0.0625}, {}},
      {11, "y^2 + 2xz + w^2", "2yz + w^2", {0.0, 0.0, 0.0, 1.0, -1.0}, {0.0}},
      {12, "xw + yz", "z^2 + 2yw", {0.0, 0.0, 0.0, 0.0, 0.0625}, {0.0}},
      {13, "x^2 - y^2 + z^2 - w^2", "x^2 - 2y^2", {0.0, 0.0, 2.0, -3.0, 1.0}, {0.0}},
      {14, "-x^2 + y^2 + z^2 + w^2", "-x^2 + 2y^2", {0.0, 0.0, -2.0, 3.0, -1.0}, {0.0}},
      {15, "x^2 + y^2 + z^2 - w^2", "x^2 + 2y^2", {0.0, 0.0, -2.0, 3.0, -1.0}, {0.0}},
      {16, "x^2 + y^2 - z^2 - w^2", "x^2 + 2y^2", {0.0, 0.0, 2.0, -3.0, 1.0}, {0.0}},
      {17, "x^2 + y^2 + 2zw", "-z^2 + w^2 + 2zw", {0.0, 0.0, -2.0, 2.0, -1.0}, {0.0}},
      {18, "x^2 - y^2 - 2zw", "-z^2 + w^2 + 2zw", {0.0, 0.0, 2.0, 2.0, 1.0}, {0.0}},
      {19, "y^2 + z^2 - w^2", "x^2", {0.0, 0.0, 0.0, 1.0, 0.0}, {0.0}},
      {20, "y^2 + z^2 + w^2", "x^2", {0.0, 0.0, 0.0, -1.0, 0.0}, {0.0}},
      {21, "y^2 - z^2 + 2zw", "-x^2 + z^2", {0.0, 0.0, 0.0, -1.0, 0.0}, {0.0}},
      {22, "y^2 - z^2 + 2zw", "x^2 + z^2", {0.0, 0.0, 0.0, 1.0, 0.0}, {0.0}},
      {23, "2xy - y^2", "y^2 + z^2 - w^2", {0.0, 0.0, 1.0, 0.0, 0.0}, {0.0, kInf}},
      {24, "2xy - y^2", "y^2 - z^2 - w^2", {0.0, 0.0, -1.0, 0.0, 0.0}, {0.0, kInf}},
      {25, "2xy - y^2", "y^2 + z^2 + w^2", {0.0, 0.0, -1.0, 0.0, 0.0}, {0.0, kInf}},
      {26, "y^2 + 2xz - w^2", "yz", {0.0, 0.0, 0.0, 0.0, 1.0}, {0.0}},
      {27, "y^2 + 2xz + w^2", "yz", {0.0, 0.0, 0.0, 0.0, -1.0}, {0.0}},
      {28, "x^2 - y^2", "z^2 - w^2", {0.0, 0.0, 1.0, 0.0, 0.0}, {0.0, kInf}},
      {29, "x^2 + y^2", "z^2 + w^2", {0.0, 0.0, 1.0, 0.0, 0.0}, {0.0, kInf}},
      {30, "x^2 + y^2", "z^2 - w^2", {0.0, 0.0, -1.0, 0.0, 0.0}, {0.0, kInf}},
      {31, "xy + zw", "-x^2 + y^2 - z^2 + w^2", {1.0, 0.0, 0.5, 0.0, 0.0625}, {}},
      {32, "x^2 - y^2 + 2zw", "z^2", {0.0, 0.0, 0.0, 0.0, 1.0}, {0.0}},
      {33, "x^2 + y^2 + 2zw", "z^2", {0.0, 0.0, 0.0, 0.0, -1.0}, {0.0}},
      {34, "xy + zw", "y^2 + w^2", {0.0, 0.0, 0.0, 0.0, 0.0625}, {0.0}},
      {35, "xy - zw", "y^2 - w^2", {0.0, 0.0, 0.0, 0.0, 0.0625}, {0.0}},
  };
  return rows;
}

const TableRow& tableRow(int id) { return tableRows()[static_cast<std::size_t>(id - 1)]; }

/// One multiple root of a checkmarked case, read off its signature sequence: the number of
/// brackets (multiplicity), the bracket (p, n) (inertia of lambda0 A - B, up to order), the
/// parity of the indices before / after it ('E': both odd, both Q(lambda0 -/+ eps) ellipsoids;
/// 'H': both even; 'M': one of each), whether the tangency there is real, and the verdict.
struct TableRoot {
  double lambda0;
  int brackets;
  int p, n;
  char sides;
  bool real;
  bool genuine;
  const char* why;
};

struct CheckedCase {
  int id;
  std::vector<TableRoot> roots;
};

// The 22 cases with a checkmark in the "Real Contact Point" column. Where a pair has several
// multiple roots, the comment says which carries the real contact (the Procedure's input);
// the others are listed with real = false and are checked to have imaginary tangency only.
const std::vector<CheckedCase>& checkedCases() {
  static const std::vector<CheckedCase> cases = {
      {5, {{0.0, 2, 2, 1, 'H', true, false, "(2,((2,1)),2,...): the only multiple root"}}},
      {6, {{0.0, 2, 1, 2, 'E', true, true, "(1,((1,2)),1,...)"}}},
      {7, {{0.0, 2, 0, 3, 'E', true, true, "(1,((0,3)),1,...)"}}},
      {8, {{2.0, 2, 2, 1, 'H', true, false, "(2,((2,1)),2); the other roots are complex"}}},
      // Both double roots carry a 2x2 Jordan block (two index-sequence variants with the same
      // brackets) and both have a real tangency point: both examined.
      {9,
       {{0.0, 2, 2, 1, 'H', true, false, "(2,((2,1)),2,((2,1)),2): first bracket"},
        {2.0, 2, 2, 1, 'H', true, false, "second bracket ((2,1)) or ((1,2))"}}},
      {11, {{0.0, 3, 1, 2, 'M', true, false, "(1,(((1,2))),2,...): Case 11 of Table 10"}}},
      {12, {{0.0, 4, 2, 1, 'H', true, false, "(2,((((2,1)))),2)"}}},
      {13, {{0.0, 2, 1, 1, 'H', true, false, "(2,((1,1)),2,...)"}}},
      {15, {{0.0, 2, 0, 2, 'E', true, true, "(1,((0,2)),1,...)"}}},
      {18, {{0.0, 2, 1, 1, 'H', true, false, "(2,((1,1)),2)"}}},
      {21, {{0.0, 3, 1, 1, 'M', true, false, "(1,(((1,1))),2,...): Case 21 of Table 10"}}},
      {22, {{0.0, 3, 0, 2, 'M', true, true, "(1,(((0,2))),2,...): Case 22 of Table 10"}}},
      // lambda = 0 carries the Jordan block (the wavy symbols, ((2,1))) and the contact
      // (1,0,0,0); the double root at infinity ((1,1)) has real tangency points too (the null
      // line x = y = 0 of A meets B at z = +-w): examined as well, also not genuine.
      {23,
       {{0.0, 2, 2, 1, 'H', true, false, "(2,((2,1)),2,...): the Jordan-block root"},
        {kInf, 2, 1, 1, 'H', true, false, "((1,1)) at infinity: real, also hyperboloids"}}},
      // lambda = 0 carries the Jordan block ((1,2)) and the real contact (1,0,0,0) (at infinity
      // in R^3); at lambda = inf the null line of A meets B in z^2 + w^2 = 0: imaginary.
      {24,
       {{0.0, 2, 1, 2, 'E', true, true, "(1,((1,2)),1,...): the Jordan-block root"},
        {kInf, 2, 1, 1, 'E', false, false, "((1,1)) at infinity: imaginary tangency"}}},
      {25,
       {{0.0, 2, 0, 3, 'E', true, true, "(1,((0,3)),1,...): the Jordan-block root"},
        {kInf, 2, 1, 1, 'E', false, false, "((1,1)) at infinity: imaginary tangency"}}},
      {26, {{0.0, 4, 1, 1, 'H', true, false, "(2,((((1,1)))),2)"}}},
      {27, {{0.0, 4, 1, 1, 'E', true, false, "(1,((((1,1)))),3): Case 27 of Table 10"}}},
      // Both double roots ((1,1)) have real tangency points, (+-1,1,0,0) at 0 (the null line
      // z = w = 0 of B on A) and (0,0,+-1,1) at infinity: A and B play symmetric roles; both
      // examined.
      {28,
       {{0.0, 2, 1, 1, 'H', true, false, "(2,((1,1)),2,((1,1)),2): first bracket"},
        {kInf, 2, 1, 1, 'H', true, false, "second bracket, at infinity"}}},
      // The real contact is at lambda = inf: the null line of A (the z axis, A = x^2 + y^2) meets
      // the planes z = +-w of B at (0,0,+-1). At lambda = 0 the null line of B (x, y, 0, 0) meets
      // A in x^2 + y^2 = 0: imaginary.
      {30,
       {{kInf, 2, 0, 2, 'E', true, true, "(1,((0,2)),1,...) at infinity"},
        {0.0, 2, 1, 1, 'E', false, false, "((1,1)) at 0: imaginary tangency"}}},
      {32, {{0.0, 4, 1, 0, 'H', true, false, "(2,((((1,0)))),2)"}}},
      {33, {{0.0, 4, 1, 0, 'E', true, true, "(1,((((1,0)))),3): quadruple, yet genuine"}}},
      {35, {{0.0, 4, 1, 1, 'H', true, false, "(2,((((1,1)))),2)"}}},
  };
  return cases;
}

Eigen::Matrix4d tableA(int id) { return parseQuadric(tableRow(id).A); }
Eigen::Matrix4d tableB(int id) { return parseQuadric(tableRow(id).B); }

TEST(QuadricContactConfigurationTable, CharacteristicPolynomialAndMultipleRootsOfAll35Pairs) {
  ASSERT_EQ(tableRows().size(), 35u);
  for (const TableRow& row : tableRows()) {
    SCOPED_TRACE("case " + std::to_string(row.id));
    const Eigen::Matrix4d A = parseQuadric(row.A), B = parseQuadric(row.B);
    const std::array<double, 5> f = characteristicQuartic(A, B);
    for (int k = 0; k < 5; ++k) EXPECT_EQ(f[k], row.f[k]) << "coefficient " << k;  // exact: dyadic entries
    const std::vector<double> roots = multipleRoots(A, B);
    ASSERT_EQ(roots.size(), row.multiple_roots.size());
    for (std::size_t i = 0; i < roots.size(); ++i) {
      if (std::isinf(row.multiple_roots[i])) {
        EXPECT_TRUE(std::isinf(roots[i]) && roots[i] > 0.0) << roots[i];
      } else {
        EXPECT_NEAR(roots[i], row.multiple_roots[i], 1e-12);
      }
    }
  }
}

TEST(QuadricContactConfigurationTable, ProcedureVerdictsOfThe22CasesWithARealContactPoint) {
  ASSERT_EQ(checkedCases().size(), 22u);
  int genuine = 0, not_genuine = 0;
  for (const CheckedCase& cc : checkedCases()) {
    const Eigen::Matrix4d A = tableA(cc.id), B = tableB(cc.id);
    // Every multiple root of the pair is accounted for.
    EXPECT_EQ(cc.roots.size(), tableRow(cc.id).multiple_roots.size()) << "case " << cc.id;
    bool counted = false;
    for (const TableRoot& r : cc.roots) {
      SCOPED_TRACE("case " + std::to_string(cc.id) + " at lambda0 = " + std::to_string(r.lambda0) + ": " + r.why);
      const ContactConfiguration c = contactConfiguration(A, B, r.lambda0);
      // Signature sequence: number of brackets = multiplicity = n of the derivative test.
      EXPECT_EQ(c.multiplicity, r.brackets);
      EXPECT_EQ(c.first_nonzero_derivative, r.brackets);
      // (p, n) of the bracket = inertia of lambda0 A - B up to order; rank = p + n.
      EXPECT_EQ(c.rank, r.p + r.n);
      EXPECT_EQ(std::min(c.positive, c.negative), std::min(r.p, r.n));
      EXPECT_EQ(std::max(c.positive, c.negative), std::max(r.p, r.n));
      // Index parity on both sides (Step 1).
      const char sides = c.ellipsoid_before == c.ellipsoid_after ? (c.ellipsoid_before ? 'E' : 'H') : 'M';
      EXPECT_EQ(sides, r.sides);
      const TangencyKind kind = r.p + r.n == 3   ? TangencyKind::SinglePoint
                                : r.p + r.n == 2 ? TangencyKind::TwoPointsOrLine
                                                 : TangencyKind::Conic;
      EXPECT_EQ(c.kind, kind) << toString(c.kind);
      EXPECT_EQ(c.real_contact, r.real);
      if (r.real) {
        EXPECT_EQ(c.genuine, r.genuine);
        EXPECT_EQ(c.genuineRealContact(), r.genuine);
        // Every reported contact point lies on both quadrics and is a null vector of
        // lambda0 A - B (common tangent plane).
        for (const Eigen::Vector4d& X : c.contact_points) {
          EXPECT_NEAR(X.norm(), 1.0, 1e-12);
          EXPECT_NEAR(X.dot(A * X), 0.0, 1e-9);
          EXPECT_NEAR(X.dot(B * X), 0.0, 1e-9);
          const Eigen::Vector4d residual = std::isinf(r.lambda0) ? Eigen::Vector4d(A * X)
                                                                 : Eigen::Vector4d((r.lambda0 * A - B) * X);
          EXPECT_LT(residual.norm(), 1e-9);
        }
        if (!counted) (r.genuine ? genuine : not_genuine) += 1;
        counted = true;
      } else {
        EXPECT_FALSE(c.genuineRealContact());
      }
    }
  }
  // The Procedure's lists: genuine 6, 7, 15, 22, 24, 25, 30, 33; not genuine 5, 8, 9, 11, 12,
  // 13, 18, 21, 23, 26, 27, 28, 32, 35.
  EXPECT_EQ(genuine, 8);
  EXPECT_EQ(not_genuine, 14);
}

TEST(QuadricContactConfigurationTable, NoGenuineRealContactInThe13CasesWithoutOne) {
  // Cases 1-4, 10, 31: no real multiple root. 14, 16, 17, 20, 29: imaginary tangency only.
  // 19: a cylinder cut by the double plane x^2 = 0 (a double conic, not a tangency: header,
  // item 3). 34: the real line y = w = 0 (at infinity) lies on A and is the singular line of
  // B = y^2 + w^2; the module reports it as a line of tangency (Lemma 6.2), the table as no
  // real contact point; the Procedure's verdict there is "hyperboloids: not genuine" anyway.
  const std::vector<int> ids = {1, 2, 3, 4, 10, 14, 16, 17, 19, 20, 29, 31, 34};
  int with_roots = 0;
  for (int id : ids) {
    SCOPED_TRACE("case " + std::to_string(id));
    const Eigen::Matrix4d A = tableA(id), B = tableB(id);
    for (double l : multipleRoots(A, B)) {
      ++with_roots;
      const ContactConfiguration c = contactConfiguration(A, B, l);
      EXPECT_GE(c.multiplicity, 2);
      EXPECT_FALSE(c.genuineRealContact()) << "lambda0 = " << l;
      if (id != 34) {
        EXPECT_FALSE(c.real_contact) << "lambda0 = " << l;
      }
    }
  }
  EXPECT_EQ(with_roots, 8);  // 14, 16, 17, 19, 20, 34 and the two roots of 29
}

TEST(QuadricContactConfigurationTable, VerdictInvariantUnderSwapScalingAndRigidMotion) {
  std::mt19937_64 rng(20080601);
  for (const CheckedCase& cc : checkedCases()) {
    const Eigen::Matrix4d A = tableA(cc.id), B = tableB(cc.id);
    for (const TableRoot& r : cc.roots) {
      SCOPED_TRACE("case " + std::to_string(cc.id) + " at lambda0 = " + std::to_string(r.lambda0));
      const ContactConfiguration c = contactConfiguration(A, B, r.lambda0);
      const auto same = [&](const ContactConfiguration& d, const char* what) {
        EXPECT_EQ(d.multiplicity, c.multiplicity) << what;
        EXPECT_EQ(d.rank, c.rank) << what;
        EXPECT_EQ(d.kind, c.kind) << what;
        EXPECT_EQ(std::min(d.positive, d.negative), std::min(c.positive, c.negative)) << what;
        EXPECT_EQ(d.genuine, c.genuine) << what;
        EXPECT_EQ(d.real_contact, c.real_contact) << what;
        EXPECT_EQ(d.contact_points.size(), c.contact_points.size()) << what;
      };
      if (std::isinf(r.lambda0)) same(contactConfiguration(A, B, -kInf), "-infinity");
      // Swapping A and B: lambda0 -> 1/lambda0, lambda runs the other way.
      const ContactConfiguration s = contactConfiguration(B, A, swappedLambda(r.lambda0));
      same(s, "swap");
      EXPECT_EQ(s.ellipsoid_before, c.ellipsoid_after);
      EXPECT_EQ(s.ellipsoid_after, c.ellipsoid_before);
      if (!c.contact_curve) {
        for (const auto& X : c.contact_points) EXPECT_TRUE(containsPoint(s.contact_points, X, 1e-9)) << X.transpose();
      }
      // Scaling A by 3 and B by -0.7 (not powers of two: inexact, and the orientation flips).
      const double l_scaled = std::isinf(r.lambda0) ? kInf : r.lambda0 * (-0.7 / 3.0);
      const ContactConfiguration k = contactConfiguration(3.0 * A, -0.7 * B, l_scaled);
      same(k, "scale");
      EXPECT_EQ(k.ellipsoid_before, c.ellipsoid_after);
      // Rigid motions (same motion on both quadrics): congruence by T^-1, det T = 1.
      for (int trial = 0; trial < 3; ++trial) {
        const Motion m = randomMotion(rng);
        const ContactConfiguration g = contactConfiguration(m.quadric(A), m.quadric(B), r.lambda0);
        same(g, "rigid motion");
        EXPECT_EQ(g.ellipsoid_before, c.ellipsoid_before);
        EXPECT_EQ(g.ellipsoid_after, c.ellipsoid_after);
        if (!c.contact_curve) {
          for (const auto& X : c.contact_points) {
            EXPECT_TRUE(containsPoint(g.contact_points, m.point(X), 1e-7)) << m.point(X).transpose();
          }
        }
      }
    }
  }
}

// --- Example 6.3 ------------------------------------------------------------------------------

TEST(QuadricContactConfigurationExample63, TwoCylinders) {
  // A: x^2 + z^2 = 1, B: y^2 + z^2 = 1. The thesis writes f = lambda (lambda - 1)^2.
  const Eigen::Matrix4d A = Eigen::Vector4d(1, 0, 1, -1).asDiagonal();
  const Eigen::Matrix4d B = Eigen::Vector4d(0, 1, 1, -1).asDiagonal();
  const std::array<double, 5> f = characteristicQuartic(A, B);
  const std::array<double, 5> expected{0.0, 1.0, -2.0, 1.0, 0.0};  // lambda - 2 lambda^2 + lambda^3
  for (int k = 0; k < 5; ++k) EXPECT_EQ(f[k], expected[k]) << k;
  const std::vector<double> roots = multipleRoots(A, B);
  ASSERT_EQ(roots.size(), 1u);
  EXPECT_NEAR(roots[0], 1.0, 1e-15);
  const ContactConfiguration c = contactConfiguration(A, B, 1.0);
  EXPECT_EQ(c.multiplicity, 2);
  EXPECT_EQ(c.first_nonzero_derivative, 2);  // f'(1) = 0, f''(1) = 2 > 0
  EXPECT_FALSE(c.ellipsoid_before);          // Q(1 +- eps) are both hyperboloids
  EXPECT_FALSE(c.ellipsoid_after);
  EXPECT_EQ(c.rank, 2);
  EXPECT_EQ(c.kind, TangencyKind::TwoPointsOrLine);
  ASSERT_EQ(c.contact_points.size(), 2u);
  const double h = std::sqrt(0.5);
  EXPECT_TRUE(containsPoint(c.contact_points, Eigen::Vector4d(0, 0, h, h), 1e-12));
  EXPECT_TRUE(containsPoint(c.contact_points, Eigen::Vector4d(0, 0, -h, h), 1e-12));
  EXPECT_FALSE(c.contact_curve);
  EXPECT_TRUE(c.real_contact);
  EXPECT_FALSE(c.genuine);  // Step 1: hyperboloids on both sides
  // The simple roots 0 and infinity (A singular, deg f = 3) are not multiple roots.
  for (double l : {0.0, kInf}) {
    const ContactConfiguration s = contactConfiguration(A, B, l);
    EXPECT_EQ(s.multiplicity, 1) << l;
    EXPECT_EQ(s.kind, TangencyKind::None) << l;
    EXPECT_FALSE(s.genuine) << l;
    EXPECT_TRUE(s.contact_points.empty()) << l;
  }
}

// --- geometric oracle --------------------------------------------------------------------------

Eigen::Matrix4d sphere(const Eigen::Vector3d& c, double r2) {
  Eigen::Matrix4d Q = Eigen::Matrix4d::Identity();
  Q.topRightCorner<3, 1>() = -c;
  Q.bottomLeftCorner<1, 3>() = -c.transpose();
  Q(3, 3) = c.squaredNorm() - r2;
  return Q;
}

/// An affine pair touching at p. The classifier gets (A, B); the oracle samples the smooth
/// surface `sampled` (0: A, 1: B) around p and evaluates the other one's function there -- the
/// plane's linear form P.X when the other is the double plane P P^T.
struct OracleCase {
  const char* name;
  Eigen::Matrix4d A, B;
  int sampled;
  bool other_is_plane;
  Eigen::Vector4d plane;
  Eigen::Vector3d p;
  bool genuine;  // expected (the oracle must agree: a check of the oracle itself)
  int rank, multiplicity;
};

std::vector<OracleCase> oracleCases() {
  const Eigen::Matrix4d unit_sphere = sphere(Eigen::Vector3d::Zero(), 1.0);
  // x^2 - y^2 - 2z = 0: the saddle z = (x^2 - y^2)/2.
  Eigen::Matrix4d saddle = Eigen::Matrix4d::Zero();
  saddle(0, 0) = 1.0;
  saddle(1, 1) = -1.0;
  saddle(2, 3) = saddle(3, 2) = -1.0;
  const Eigen::Matrix4d cyl_y = Eigen::Vector4d(1, 0, 1, -1).asDiagonal();  // x^2 + z^2 = 1
  const Eigen::Matrix4d cyl_z = Eigen::Vector4d(1, 1, 0, -1).asDiagonal();  // x^2 + y^2 = 1
  const Eigen::Matrix4d cone = Eigen::Vector4d(1, 1, -1, 0).asDiagonal();   // x^2 + y^2 = z^2
  const Eigen::Matrix4d ellipsoid = Eigen::Vector4d(1, 0.25, 4, -1).asDiagonal();  // radii 1, 2, 1/2
  // Cylinder along x through (0, 0, c) of squared radius r2: y^2 + (z - c)^2 = r2.
  const auto cyl_x = [](double c, double r2) {
    Eigen::Matrix4d Q = Eigen::Vector4d(0, 1, 1, c * c - r2).asDiagonal();
    Q(2, 3) = Q(3, 2) = -c;
    return Q;
  };
  const Eigen::Vector4d plane_z1(0, 0, 1, -1), plane_z0(0, 0, 1, 0);
  const Eigen::Vector3d origin = Eigen::Vector3d::Zero(), ex(1, 0, 0), ez(0, 0, 1);
  const Eigen::Vector4d none = Eigen::Vector4d::Zero();
  return {
      {"sphere resting on a plane (quadruple root, Case 33-like)", unit_sphere, plane_z1 * plane_z1.transpose(), 0,
       true, plane_z1, ez, true, 1, 4},
      {"plane tangent to a saddle (Case 32-like)", saddle, plane_z0 * plane_z0.transpose(), 0, true, plane_z0, origin,
       false, 1, 4},
      {"sphere inside a sphere, touching", unit_sphere, sphere({0.6, 0, 0}, 0.16), 1, false, none, ex, true, 3, 2},
      {"spheres touching externally", unit_sphere, sphere({1.5, 0, 0}, 0.25), 1, false, none, ex, true, 3, 2},
      {"equal cylinders crossing at right angles (Example 6.3)", cyl_y, Eigen::Vector4d(0, 1, 1, -1).asDiagonal(), 1,
       false, none, ez, false, 2, 2},
      {"crossed cylinders of radii 1 and 1/2 touching", cyl_y, cyl_x(1.5, 0.25), 1, false, none, ez, true, 3, 2},
      {"sphere inside a cylinder of the same radius (circle)", cyl_z, unit_sphere, 1, false, none, ex, true, 1, 3},
      {"sphere touching a cone from outside", cone, sphere({2, 0, 1}, 0.5), 1, false, none, {1.5, 0, 1.5}, true, 3,
       2},
      {"sphere r = 1/2 under a saddle", saddle, sphere({0, 0, -0.5}, 0.25), 1, false, none, origin, true, 3, 2},
      {"sphere r = 1 under a saddle (triple root)", saddle, sphere({0, 0, -1}, 1.0), 1, false, none, origin, true, 2,
       3},
      {"sphere r = 2 under a saddle", saddle, sphere({0, 0, -2}, 4.0), 1, false, none, origin, false, 3, 2},
      {"sphere r = 1/2 on a saddle", saddle, sphere({0, 0, 0.5}, 0.25), 1, false, none, origin, true, 3, 2},
      {"sphere r = 1 on a saddle (triple root)", saddle, sphere({0, 0, 1}, 1.0), 1, false, none, origin, true, 2, 3},
      {"sphere r = 2 on a saddle", saddle, sphere({0, 0, 2}, 4.0), 1, false, none, origin, false, 3, 2},
      {"cylinder r = 1/2 under a saddle", saddle, cyl_x(-0.5, 0.25), 1, false, none, origin, true, 3, 2},
      {"cylinder r = 2 under a saddle", saddle, cyl_x(-2.0, 4.0), 1, false, none, origin, false, 3, 2},
      {"sphere touching an ellipsoid externally", ellipsoid, sphere({1.5, 0, 0}, 0.25), 1, false, none, ex, true, 3,
       2},
      {"sphere r = 0.2 inside an ellipsoid (curvature radius 1/4)", ellipsoid, sphere({0.8, 0, 0}, 0.04), 1, false,
       none, ex, true, 3, 2},
      {"sphere r = 0.4 inside an ellipsoid pokes out", ellipsoid, sphere({0.6, 0, 0}, 0.16), 1, false, none, ex, false,
       3, 2},
      // A plane pair z = +-sqrt(2) y through the x axis, which touches the sphere x^2 + y^2 +
      // (z - 1)^2 = 1 at the origin: f = -lambda^3 (lambda + 2), Step 2 with -B indefinite (Case
      // 21-like): the planes cut the sphere in circles through the origin. With the imaginary
      // pair z^2 + 2 y^2 (real locus: the x axis) -B is semidefinite (Case 22-like).
      {"plane pair through a tangent line of a sphere (triple root)", sphere({0, 0, 1}, 1.0),
       Eigen::Vector4d(0, -2, 1, 0).asDiagonal(), 0, false, none, origin, false, 2, 3},
      {"imaginary plane pair on a tangent line of a sphere (triple root)", sphere({0, 0, 1}, 1.0),
       Eigen::Vector4d(0, 2, 1, 0).asDiagonal(), 0, false, none, origin, true, 2, 3},
  };
}

/// Does `other` take both signs on the surface S near p? Points of S are found on circles of
/// radii rho around p in the tangent plane, pushed along the normal onto S (the root of the
/// quadratic nearest 0); values beyond +-threshold count.
bool crosses(const Eigen::Matrix4d& S, const std::function<double(const Eigen::Vector3d&)>& other,
             const Eigen::Vector3d& p, double threshold) {
  const Eigen::Matrix3d S3 = S.topLeftCorner<3, 3>();
  const Eigen::Vector3d s = S.topRightCorner<3, 1>();
  const auto value = [&](const Eigen::Vector3d& x) { return x.dot(S3 * x) + 2.0 * s.dot(x) + S(3, 3); };
  const Eigen::Vector3d g = (S3 * p + s).normalized();
  Eigen::Vector3d u = g.unitOrthogonal();
  const Eigen::Vector3d v = g.cross(u);
  bool positive = false, negative = false;
  for (double rho : {1e-3, 1e-2, 3e-2}) {
    // 1440 directions: the region where a plane pair through a tangent line is positive on the
    // sphere is a wedge of half-angle ~rho / (2 sqrt 2) around the line (~0.01 at rho = 3e-2).
    for (int k = 0; k < 1440; ++k) {
      const double t = 2.0 * 3.14159265358979323846 * k / 1440.0;
      const Eigen::Vector3d y = p + rho * (std::cos(t) * u + std::sin(t) * v);
      const double a = g.dot(S3 * g), b = 2.0 * g.dot(S3 * y + s), c = value(y);
      const double disc = b * b - 4.0 * a * c;
      if (disc < 0.0 || b == 0.0) continue;
      const double h = -2.0 * c / (b + std::copysign(std::sqrt(disc), b));
      const double f = other(y + h * g);
      positive = positive || f > threshold;
      negative = negative || f < -threshold;
    }
  }
  return positive && negative;
}

TEST(QuadricContactConfigurationOracle, GenuinenessAgreesWithSamplingUnderRigidMotions) {
  std::mt19937_64 rng(6302);
  for (const OracleCase& oc : oracleCases()) {
    ContactConfiguration canonical;
    for (int trial = 0; trial < 6; ++trial) {
      SCOPED_TRACE(std::string(oc.name) + ", motion " + std::to_string(trial));
      const Motion m = trial == 0 ? Motion() : randomMotion(rng);
      const Eigen::Matrix4d A = m.quadric(oc.A), B = m.quadric(oc.B);
      const Eigen::Vector4d P = m.point(Eigen::Vector4d(oc.p.x(), oc.p.y(), oc.p.z(), 1.0));
      const Eigen::Vector3d p = P.head<3>();
      const Eigen::Matrix4d S = oc.sampled == 0 ? A : B;
      const Eigen::Matrix4d O = oc.sampled == 0 ? B : A;
      const Eigen::Vector4d plane = m.plane(oc.plane);
      const auto other = [&](const Eigen::Vector3d& x) {
        const Eigen::Vector4d X(x.x(), x.y(), x.z(), 1.0);
        return oc.other_is_plane ? plane.dot(X) : X.dot(O * X);
      };
      const bool oracle_genuine = !crosses(S, other, p, 1e-11);
      EXPECT_EQ(oracle_genuine, oc.genuine) << "the oracle disagrees with the expected geometry";

      // The multiple root whose lambda0 A - B annihilates the known contact point.
      int found = 0;
      ContactConfiguration c;
      for (double l : multipleRoots(A, B)) {
        const Eigen::Vector4d r = std::isinf(l) ? Eigen::Vector4d(A * P) : Eigen::Vector4d((l * A - B) * P);
        const double scale = (std::isinf(l) ? A.norm() : std::fabs(l) * A.norm() + B.norm()) * P.norm();
        if (r.norm() <= 1e-8 * scale) {
          ++found;
          c = contactConfiguration(A, B, l);
        }
      }
      ASSERT_EQ(found, 1);
      EXPECT_EQ(c.genuineRealContact(), oracle_genuine);
      EXPECT_EQ(c.rank, oc.rank);
      EXPECT_EQ(c.multiplicity, oc.multiplicity);
      EXPECT_EQ(c.first_nonzero_derivative, oc.multiplicity);
      EXPECT_TRUE(c.real_contact);
      if (!c.contact_curve) {
        EXPECT_TRUE(containsPoint(c.contact_points, P, 1e-7));
      } else {  // a representative of the contact curve: on both quadrics
        for (const auto& X : c.contact_points) {
          EXPECT_NEAR(X.dot(A * X), 0.0, 1e-9);
          EXPECT_NEAR(X.dot(B * X), 0.0, 1e-9);
        }
      }
      if (trial == 0) {
        canonical = c;
      } else {
        EXPECT_EQ(c.kind, canonical.kind);
        EXPECT_EQ(c.ellipsoid_before, canonical.ellipsoid_before);
        EXPECT_EQ(c.ellipsoid_after, canonical.ellipsoid_after);
        EXPECT_EQ(c.positive, canonical.positive);
        EXPECT_EQ(c.negative, canonical.negative);
        EXPECT_NEAR(c.lambda0, canonical.lambda0, 1e-9 * (1.0 + std::fabs(canonical.lambda0)));
      }
    }
  }
}

TEST(QuadricContactConfigurationOracle, ThesisLiteralQuadrupleRuleWouldRejectASphereOnAPlane) {
  // Step 1 as printed: ellipsoids on both sides and a quadruple root -> "not genuine". A sphere
  // resting on a plane is exactly that (and so is Case 33), yet the surfaces do not cross.
  const Eigen::Matrix4d A = sphere(Eigen::Vector3d::Zero(), 1.0);
  const Eigen::Vector4d P(0, 0, 1, -1);
  const ContactConfiguration c = contactConfiguration(A, P * P.transpose(), 0.0);
  EXPECT_EQ(c.multiplicity, 4);
  EXPECT_TRUE(c.ellipsoid_before);
  EXPECT_TRUE(c.ellipsoid_after);
  EXPECT_EQ(c.positive + c.negative, 1);  // semidefinite: the differentiator from Case 27
  EXPECT_TRUE(c.genuine);
  ASSERT_EQ(c.contact_points.size(), 1u);
  EXPECT_LT(pointDistance(c.contact_points[0], Eigen::Vector4d(0, 0, 1, 1)), 1e-12);
}

TEST(QuadricContactConfigurationOracle, PlaneCuttingASphereIsNoContact) {
  // det(lambda A - P P^T) always has a triple root at 0 for a plane: the section circle counted
  // twice. The plane z = 1/2 crosses the unit sphere: no real contact point, under motions too.
  std::mt19937_64 rng(19);
  const Eigen::Vector4d plane(0, 0, 1, -0.5);
  for (int trial = 0; trial < 6; ++trial) {
    const Motion m = trial == 0 ? Motion() : randomMotion(rng);
    const Eigen::Matrix4d A = m.quadric(sphere(Eigen::Vector3d::Zero(), 1.0));
    const Eigen::Vector4d Pm = m.plane(plane);
    const Eigen::Matrix4d B = Pm * Pm.transpose();
    const std::vector<double> roots = multipleRoots(A, B);
    ASSERT_EQ(roots.size(), 1u) << trial;
    EXPECT_NEAR(roots[0], 0.0, 1e-12);
    const ContactConfiguration c = contactConfiguration(A, B, roots[0]);
    EXPECT_EQ(c.multiplicity, 3);
    EXPECT_EQ(c.rank, 1);
    EXPECT_EQ(c.kind, TangencyKind::Conic);
    EXPECT_TRUE(c.contact_points.empty());
    EXPECT_FALSE(c.real_contact);
    EXPECT_FALSE(c.genuineRealContact());
  }
}

// --- polynomial and roots ---------------------------------------------------------------------

TEST(QuadricContactConfiguration, CharacteristicQuarticMatchesDeterminants) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int trial = 0; trial < 50; ++trial) {
    Eigen::Matrix4d A, B;
    for (int i = 0; i < 4; ++i) {
      for (int j = i; j < 4; ++j) {
        A(i, j) = A(j, i) = u(rng);
        B(i, j) = B(j, i) = u(rng);
      }
    }
    if (trial % 5 == 0) {  // singular A: degree drop
      A.row(2).setZero();
      A.col(2).setZero();
    }
    const std::array<double, 5> f = characteristicQuartic(A, B);
    if (trial % 5 == 0) {
      EXPECT_EQ(f[4], 0.0);
    }
    for (double l : {-3.0, -1.0, -0.25, 0.0, 0.5, 1.0, 2.5}) {
      const double det = (l * A - B).determinant();
      EXPECT_NEAR(evalPoly(f, l), det, 1e-11 * (1.0 + std::pow(1.0 + std::fabs(l), 4) * 16.0)) << trial << " " << l;
    }
  }
}

TEST(QuadricContactConfiguration, MultipleRootsOfCongruentDiagonalPencils) {
  // lambda A - B = P^T diag(a_i lambda - b_i) P: roots b_i / a_i (a_i = 0: infinity), the rank at
  // a root is the number of i with b_i != lambda0 a_i; a random congruence P (not orthogonal)
  // changes neither.
  struct Pencil {
    Eigen::Vector4d a, r;  // b_i = r_i a_i, or b_i = r_i when a_i = 0
    std::vector<double> roots;
    std::vector<int> multiplicity, rank;
  };
  const std::vector<Pencil> pencils = {
      {{1, 2, -1, 0.5}, {0.5, 0.5, 2, -1}, {0.5}, {2}, {2}},
      {{1, 2, -1, 0.5}, {0.5, 0.5, 0.5, -1}, {0.5}, {3}, {1}},
      {{1, 2, -1, 0.5}, {-1.5, -1.5, 3, 3}, {-1.5, 3}, {2, 2}, {2, 2}},
      {{1, 1, 0, 0}, {2, 3, 1, -1}, {kInf}, {2}, {2}},     // A singular of rank 2: double root at inf
      {{1, 0, 0, 0}, {4, 1, -1, 2}, {kInf}, {3}, {1}},     // A of rank 1: triple root at inf
      {{1, -1, 1, -1}, {0.7, 0.7, 0.7, 0.7}, {0.7}, {4}, {0}},  // B = 0.7 A: coincident
  };
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (std::size_t k = 0; k < pencils.size(); ++k) {
    const Pencil& pc = pencils[k];
    Eigen::Vector4d b;
    for (int i = 0; i < 4; ++i) b(i) = pc.a(i) == 0.0 ? pc.r(i) : pc.r(i) * pc.a(i);
    for (int trial = 0; trial < 5; ++trial) {
      SCOPED_TRACE("pencil " + std::to_string(k) + ", trial " + std::to_string(trial));
      Eigen::Matrix4d P = Eigen::Matrix4d::Identity();
      if (trial > 0) {
        for (int i = 0; i < 4; ++i)
          for (int j = 0; j < 4; ++j) P(i, j) += 0.4 * u(rng);
      }
      const Eigen::Matrix4d A = P.transpose() * pc.a.asDiagonal() * P;
      const Eigen::Matrix4d B = P.transpose() * b.asDiagonal() * P;
      const Eigen::Matrix4d As = 0.5 * (A + A.transpose()), Bs = 0.5 * (B + B.transpose());
      const std::vector<double> roots = multipleRoots(As, Bs);
      ASSERT_EQ(roots.size(), pc.roots.size());
      for (std::size_t i = 0; i < roots.size(); ++i) {
        if (std::isinf(pc.roots[i])) {
          EXPECT_TRUE(std::isinf(roots[i]));
        } else {
          EXPECT_NEAR(roots[i], pc.roots[i], 1e-8);
        }
        const ContactConfiguration c = contactConfiguration(As, Bs, roots[i]);
        EXPECT_EQ(c.multiplicity, pc.multiplicity[i]);
        EXPECT_EQ(c.rank, pc.rank[i]);
        if (pc.rank[i] == 0) {
          EXPECT_EQ(c.kind, TangencyKind::Coincident);
          EXPECT_FALSE(c.genuine);
          EXPECT_TRUE(c.contact_points.empty());
        }
      }
    }
  }
}

TEST(QuadricContactConfiguration, NonMultipleLambdaAndSingularPencil) {
  const Eigen::Matrix4d A = sphere(Eigen::Vector3d::Zero(), 1.0);
  const Eigen::Matrix4d B = sphere({1.5, 0, 0}, 0.25);  // f = -(l - 1)^2 (2 l + 1)^2 / 4
  for (double l : {0.0, 0.3, -2.0, 1e6, kInf, -kInf}) {
    const ContactConfiguration c = contactConfiguration(A, B, l);
    EXPECT_EQ(c.kind, TangencyKind::None) << l;
    EXPECT_EQ(c.multiplicity, 0) << l;
    EXPECT_EQ(c.first_nonzero_derivative, 0) << l;
    EXPECT_FALSE(c.genuine) << l;
    EXPECT_TRUE(c.contact_points.empty()) << l;
    EXPECT_EQ(c.rank, 4) << l;
  }
  // Near the double root -1/2 but not on it: f(-0.5 + 1e-3) ~ -1e-6, far above the tolerance.
  EXPECT_EQ(contactConfiguration(A, B, -0.5 + 1e-3).kind, TangencyKind::None);
  // On it up to rounding: refined to the root.
  const ContactConfiguration on = contactConfiguration(A, B, -0.5 * (1.0 + 1e-15));
  EXPECT_EQ(on.kind, TangencyKind::SinglePoint);
  EXPECT_NEAR(on.lambda0, -0.5, 1e-15);

  // Tolerance: spheres 1e-6 apart are not touching (the double root -1/2 has split; only the
  // double root 1 of the common imaginary circle at infinity is left), spheres within ~1e-14 of
  // touching are classified as touching.
  const std::vector<double> apart = multipleRoots(A, sphere({1.5 + 1e-6, 0, 0}, 0.25));
  ASSERT_EQ(apart.size(), 1u);
  EXPECT_NEAR(apart[0], 1.0, 1e-9);
  const Eigen::Matrix4d Bn = sphere({1.5 + 1e-14, 0, 0}, 0.25);
  const std::vector<double> nearly = multipleRoots(A, Bn);
  ASSERT_EQ(nearly.size(), 2u);
  const ContactConfiguration t = contactConfiguration(A, Bn, nearly[0]);
  EXPECT_NEAR(t.lambda0, -0.5, 1e-6);
  EXPECT_EQ(t.kind, TangencyKind::SinglePoint);
  EXPECT_TRUE(t.genuineRealContact());
  const ContactConfiguration circle = contactConfiguration(A, Bn, nearly[1]);  // lambda = 1
  EXPECT_EQ(circle.rank, 2);
  EXPECT_FALSE(circle.real_contact);  // the imaginary circle at infinity

  // Two parallel cylinders touching along a line: common null vector (0,0,1,0), f == 0.
  const Eigen::Matrix4d C1 = Eigen::Vector4d(1, 1, 0, -1).asDiagonal();
  Eigen::Matrix4d C2 = Eigen::Vector4d(1, 1, 0, 3).asDiagonal();  // (x - 2)^2 + y^2 = 1
  C2(0, 3) = C2(3, 0) = -2.0;
  for (double c : characteristicQuartic(C1, C2)) EXPECT_EQ(c, 0.0);
  EXPECT_TRUE(multipleRoots(C1, C2).empty());
  const ContactConfiguration s = contactConfiguration(C1, C2, 1.0);
  EXPECT_TRUE(s.singular_pencil);
  EXPECT_EQ(s.multiplicity, -1);
  EXPECT_EQ(s.kind, TangencyKind::None);
  EXPECT_FALSE(s.genuine);
  EXPECT_TRUE(s.contact_points.empty());
}

TEST(QuadricContactConfiguration, BadInputThrows) {
  const Eigen::Matrix4d A = Eigen::Vector4d(1, 1, 1, -1).asDiagonal();
  const Eigen::Matrix4d B = sphere({1.5, 0, 0}, 0.25);
  Eigen::Matrix4d nan = A, inf = B, asym = A;
  nan(1, 2) = std::numeric_limits<double>::quiet_NaN();
  inf(3, 3) = kInf;
  asym(0, 3) = 0.5;  // (3, 0) stays 0
  const Eigen::Matrix4d zero = Eigen::Matrix4d::Zero();
  test::expectInvalid([&] { characteristicQuartic(nan, B); }, "A must be finite");
  test::expectInvalid([&] { characteristicQuartic(A, inf); }, "B must be finite");
  test::expectInvalid([&] { characteristicQuartic(asym, B); }, "A must be symmetric");
  test::expectInvalid([&] { multipleRoots(A, asym); }, "B must be symmetric");
  test::expectInvalid([&] { multipleRoots(nan, B); }, "A must be finite");
  test::expectInvalid([&] { multipleRoots(zero, B); }, "A must not be zero");
  test::expectInvalid([&] { contactConfiguration(A, zero, 0.0); }, "B must not be zero");
  test::expectInvalid([&] { contactConfiguration(A, inf, 0.0); }, "B must be finite");
  test::expectInvalid([&] { contactConfiguration(asym, B, 0.0); }, "symmetric");
  test::expectInvalid([&] { contactConfiguration(A, B, std::numeric_limits<double>::quiet_NaN()); }, "NaN");
  // Asymmetry within the relative tolerance is accepted (and symmetrised).
  Eigen::Matrix4d nearly = A;
  nearly(0, 1) = 1e-14;
  EXPECT_NO_THROW(contactConfiguration(nearly, B, -0.5));
}

}  // namespace
}  // namespace fcl_quadric
