// Moving ellipses: thesis ch.2 (CD-DISC) and ch.3 (CD-DISC3D). See ellipse_ccd.h for the maths
// and the numerical policy.
#include "fcl_quadric/continuous/ellipse_ccd.h"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include <Eigen/Geometry>

#include "fcl_quadric/algebra/root_isolation.h"
#include "fcl_quadric/algebra/sturm_sequence.h"

namespace fcl_quadric {
namespace {

// ----------------------------------------------------------------------------------------------
// Small helpers.

std::string fmt(double v) {
  std::ostringstream os;
  os.precision(17);
  os << v;
  return os.str();
}

void checkRadius(const char* where, const char* name, double r) {
  if (!std::isfinite(r) || !(r > 0.0)) {
    throw std::invalid_argument(std::string(where) + ": radius " + name + " = " + fmt(r) +
                                " must be finite and positive");
  }
}

/// 2^e with 2^e <= max|coefficient| < 2^(e+1); scaling by 2^-e is exact (no rounding).
double powerOfTwoScale(double max_abs) {
  if (!(max_abs > 0.0) || !std::isfinite(max_abs)) return 1.0;
  int e = 0;
  std::frexp(max_abs, &e);  // max_abs = m 2^e, m in [1/2, 1)
  return std::ldexp(1.0, e);
}

double maxAbsCoefficient(const PolynomialMatrix3& M) {
  double m = 0.0;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) m = std::max(m, M(i, j).maxAbsCoefficient());
  }
  return m;
}

/// Certifies that p has no root in [0, 1] (Bernstein root exclusion); throws naming `what`.
void requireRootFree(const char* where, const std::string& what, const Polynomial& p) {
  if (p.isZero()) {
    throw std::invalid_argument(std::string(where) + ": " + what + " is identically zero");
  }
  const BernsteinPolynomial bp = BernsteinPolynomial::fromPower(p, 0.0, 1.0);
  const std::optional<double> r = firstRoot(bp, kEllipseValidationTolerance);
  if (r) {
    throw std::invalid_argument(std::string(where) + ": " + what + " may vanish in [0, 1] (near t = " + fmt(*r) +
                                ")");
  }
}

/// det(lambda A - B) of numeric matrices, and the matching absolute scale: the coefficients of
/// the permanent of lambda |A| + |B| (every term of the determinant expansion, in absolute
/// value), which bounds the rounding of each coefficient up to a small multiple of u.
void cubicAndScale(const Eigen::Matrix3d& A, const Eigen::Matrix3d& B, std::array<double, 4>* f,
                   std::array<double, 4>* s) {
  const Polynomial p = pencilDeterminant3(A, B);
  for (int k = 0; k < 4; ++k) (*f)[static_cast<std::size_t>(k)] = p.coefficient(k);
  // Permanent of E = lambda |A| + |B| (entries linear in lambda, nonnegative coefficients).
  auto e = [&](int i, int j) { return Polynomial{std::abs(B(i, j)), std::abs(A(i, j))}; };
  const Polynomial per = e(0, 0) * (e(1, 1) * e(2, 2) + e(1, 2) * e(2, 1)) +
                         e(0, 1) * (e(1, 0) * e(2, 2) + e(1, 2) * e(2, 0)) +
                         e(0, 2) * (e(1, 0) * e(2, 1) + e(1, 1) * e(2, 0));
  for (int k = 0; k < 4; ++k) (*s)[static_cast<std::size_t>(k)] = per.coefficient(k);
}

/// Contact point of Lemma 2.5: the null vector of Q = lambda A - B (rank 2 at a negative double
/// root), as the cross product of the pair of rows with the largest cross product.
bool nullPoint(const Eigen::Matrix3d& Q, Eigen::Vector2d* point) {
  const Eigen::Vector3d r0 = Q.row(0).transpose();
  const Eigen::Vector3d r1 = Q.row(1).transpose();
  const Eigen::Vector3d r2 = Q.row(2).transpose();
  const std::array<Eigen::Vector3d, 3> c = {r0.cross(r1), r0.cross(r2), r1.cross(r2)};
  std::size_t best = 0;
  for (std::size_t i = 1; i < 3; ++i) {
    if (c[i].squaredNorm() > c[best].squaredNorm()) best = i;
  }
  const Eigen::Vector3d X = c[best];
  const double n = X.norm();
  if (!(n > 0.0) || !(std::abs(X(2)) > 1e-300) || std::abs(X(2)) < 1e-14 * n) return false;
  *point = X.head<2>() / X(2);
  return std::isfinite((*point)(0)) && std::isfinite((*point)(1));
}

void checkEllipseMatrix(const char* name, const Eigen::Matrix3d& A) {
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (!std::isfinite(A(i, j))) {
        throw std::invalid_argument(std::string("classifyEllipses: non-finite entry (") + std::to_string(i) + ", " +
                                    std::to_string(j) + ") of " + name);
      }
    }
  }
  const double d2 = A(0, 0) * A(1, 1) - A(0, 1) * A(1, 0);
  if (!(A(0, 0) > 0.0) || !(d2 > 0.0) || !(A.determinant() < 0.0)) {
    throw std::invalid_argument(std::string("classifyEllipses: ") + name +
                                " is not an ellipse matrix with negative interior (need A(0,0) > 0, "
                                "det of the upper 2x2 block > 0, det < 0)");
  }
}

/// The static test of Theorem 2.6 without input validation (see classifyEllipses()).
EllipsePairState classifyUnchecked(const Eigen::Matrix3d& A, const Eigen::Matrix3d& B) {
  EllipsePairState r;
  std::array<double, 4> f{};
  std::array<double, 4> s{};
  cubicAndScale(A, B, &f, &s);
  // Normalise by a power of two (exact) to keep the Sturm sequence away from under/overflow.
  const double norm = powerOfTwoScale(std::max({std::abs(f[0]), std::abs(f[1]), std::abs(f[2]), std::abs(f[3])}));
  for (std::size_t k = 0; k < 4; ++k) {
    f[k] /= norm;
    s[k] /= norm;
  }
  const double a3 = f[3], a2 = f[2], a1 = f[1];
  // Negative local minimiser of f: the smaller root of f' = 3 a3 l^2 + 2 a2 l + a1 (a3 < 0, so f
  // decreases, increases, decreases). With no real critical point (negative discriminant of f')
  // the inflection point -a2 / (3 a3) is the closest candidate for a double root.
  double lambda1 = 0.0;
  bool has_negative_min = false;
  if (a3 < 0.0) {
    const double disc = a2 * a2 - 3.0 * a3 * a1;
    const double sq = disc > 0.0 ? std::sqrt(disc) : 0.0;
    const double q = -(a2 + std::copysign(sq, a2));
    double r1 = 0.0;
    double r2 = 0.0;
    if (q != 0.0) {
      r1 = q / (3.0 * a3);
      r2 = a1 / q;
    } else {
      r1 = r2 = -a2 / (3.0 * a3);
    }
    lambda1 = std::min(r1, r2);
    has_negative_min = lambda1 < 0.0 && std::isfinite(lambda1);
  }
  // Value of f at lambda1 and its scale.
  double value = 0.0;
  double scale = 0.0;
  if (has_negative_min) {
    const Polynomial fp(std::vector<double>(f.begin(), f.end()));
    double bound = 0.0;
    value = fp.evaluateWithBound(lambda1, &bound);
    const double al = std::abs(lambda1);
    scale = ((s[3] * al + s[2]) * al + s[1]) * al + s[0];
    scale = std::max(scale, bound / kEllipseTouchingRelativeBand);
  }
  // Sturm count of distinct negative roots (0, 1 or 2 by Lemma 2.1).
  int count = 0;
  {
    const Polynomial fp(std::vector<double>(f.begin(), f.end()));
    if (fp.effectiveDegree() >= 1) {
      const SturmSequence seq(fp);
      count = seq.countDistinctRoots(-std::numeric_limits<double>::infinity(), 0.0);
    }
  }
  const double band = kEllipseTouchingRelativeBand * scale;
  if (!has_negative_min) {
    r.status = count == 0 ? Separation::Overlapping : Separation::Touching;
  } else if (count == 2 && value < -band) {
    r.status = Separation::Separated;
  } else if (count == 0 && value > band) {
    r.status = Separation::Overlapping;
  } else {
    r.status = Separation::Touching;
  }
  r.lambda = has_negative_min ? lambda1 : 0.0;
  if (has_negative_min) r.point_valid = nullPoint(lambda1 * A - B, &r.point);
  return r;
}

// ----------------------------------------------------------------------------------------------
// Motion validation shared by the constructors.

void validatePlanarMotion(const char* where, const char* what, const PolynomialMatrix3& M) {
  if (M.maxDegree() > kMaxEllipseMotionDegree) {
    throw std::invalid_argument(std::string(where) + ": degree " + std::to_string(M.maxDegree()) + " of " + what +
                                " exceeds kMaxEllipseMotionDegree = " + std::to_string(kMaxEllipseMotionDegree));
  }
  for (int j = 0; j < 2; ++j) {
    if (!M(2, j).isZero()) {
      throw std::invalid_argument(std::string(where) + ": last row of " + what + " must be [0, 0, w(t)] (entry (2, " +
                                  std::to_string(j) + ") is not zero)");
    }
  }
  requireRootFree(where, std::string("w(t) = entry (2, 2) of ") + what, M(2, 2));
  const Polynomial det_l = M(0, 0) * M(1, 1) - M(0, 1) * M(1, 0);
  requireRootFree(where, std::string("det of the linear 2x2 part of ") + what, det_l);
}

/// Bernstein coefficients with absolute values (an upper bound of |p| on the interval).
BernsteinPolynomial addB(const BernsteinPolynomial& x, const BernsteinPolynomial& y) {
  const int n = std::max(x.degree(), y.degree());
  return x.elevateTo(n) + y.elevateTo(n);
}

BernsteinPolynomial subB(const BernsteinPolynomial& x, const BernsteinPolynomial& y) {
  const int n = std::max(x.degree(), y.degree());
  return x.elevateTo(n) - y.elevateTo(n);
}

/// Delta = 18 g3 g2 g1 g0 - 4 g2^3 g0 + g2^2 g1^2 - 4 g3 g1^3 - 27 g3^2 g0^2 (eq. 2.2), by Bernstein
/// products.
BernsteinPolynomial discriminantFormula(const std::array<BernsteinPolynomial, 4>& g) {
  const BernsteinPolynomial& g0 = g[0];
  const BernsteinPolynomial& g1 = g[1];
  const BernsteinPolynomial& g2 = g[2];
  const BernsteinPolynomial& g3 = g[3];
  const BernsteinPolynomial g32 = g3 * g2;
  const BernsteinPolynomial g10 = g1 * g0;
  const BernsteinPolynomial g22 = g2 * g2;
  const BernsteinPolynomial g11 = g1 * g1;
  const BernsteinPolynomial t1 = (g32 * g10) * 18.0;
  const BernsteinPolynomial t2 = (g22 * (g2 * g0)) * 4.0;
  const BernsteinPolynomial t3 = g22 * g11;
  const BernsteinPolynomial t4 = (g11 * (g3 * g1)) * 4.0;
  const BernsteinPolynomial t5 = ((g3 * g3) * (g0 * g0)) * 27.0;
  return t1 - t2 + t3 - t4 - t5;
}

}  // namespace

// ------------------------------------------------------------------------------------------------
// Static test.

EllipsePairState classifyEllipses(const Eigen::Matrix3d& A, const Eigen::Matrix3d& B) {
  checkEllipseMatrix("A", A);
  checkEllipseMatrix("B", B);
  return classifyUnchecked(A, B);
}

Eigen::Matrix3d ellipseMatrix(double a, double b, double angle, const Eigen::Vector2d& c) {
  checkRadius("ellipseMatrix", "a", a);
  checkRadius("ellipseMatrix", "b", b);
  if (!std::isfinite(angle) || !std::isfinite(c(0)) || !std::isfinite(c(1))) {
    throw std::invalid_argument("ellipseMatrix: non-finite angle or centre");
  }
  // X^T A X = |D R^T (x - c)|^2 - 1 = X^T N^T J N X with N = [D R^T, -D R^T c; 0 1].
  const double cs = std::cos(angle);
  const double sn = std::sin(angle);
  Eigen::Matrix2d Rt;
  Rt << cs, sn, -sn, cs;
  const Eigen::Matrix2d DRt = Eigen::Vector2d(1.0 / a, 1.0 / b).asDiagonal() * Rt;
  Eigen::Matrix3d N = Eigen::Matrix3d::Zero();
  N.topLeftCorner<2, 2>() = DRt;
  N.topRightCorner<2, 1>() = -DRt * c;
  N(2, 2) = 1.0;
  const Eigen::Matrix3d J = Eigen::Vector3d(1.0, 1.0, -1.0).asDiagonal();
  return N.transpose() * J * N;
}

// ------------------------------------------------------------------------------------------------
// MovingEllipse2.

namespace {

using BernsteinMatrix3 = std::array<BernsteinPolynomial, 9>;

BernsteinMatrix3 toBernstein(const PolynomialMatrix3& M) {
  BernsteinMatrix3 r;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) r[static_cast<std::size_t>(3 * i + j)] = BernsteinPolynomial::fromPower(M(i, j), 0.0, 1.0);
  }
  return r;
}

/// Adjugate in Bernstein form (cyclic cofactor formula, as PolynomialMatrix3::adjugate()).
BernsteinMatrix3 adjugateB(const BernsteinMatrix3& m) {
  auto e = [&m](int i, int j) -> const BernsteinPolynomial& { return m[static_cast<std::size_t>(3 * i + j)]; };
  BernsteinMatrix3 r;
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3;
    const int i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3;
      const int j2 = (j + 2) % 3;
      const BernsteinPolynomial p = e(i1, j1) * e(i2, j2);
      const BernsteinPolynomial q = e(i1, j2) * e(i2, j1);
      r[static_cast<std::size_t>(3 * j + i)] = subB(p, q);
    }
  }
  return r;
}

/// N^T diag(d) N in Bernstein form.
BernsteinMatrix3 congruenceB(const BernsteinMatrix3& n, const Eigen::Vector3d& d) {
  auto e = [&n](int i, int j) -> const BernsteinPolynomial& { return n[static_cast<std::size_t>(3 * i + j)]; };
  BernsteinMatrix3 r;
  for (int i = 0; i < 3; ++i) {
    for (int j = i; j < 3; ++j) {
      BernsteinPolynomial s = (e(0, i) * e(0, j)) * d(0);
      for (int k = 1; k < 3; ++k) s = addB(s, (e(k, i) * e(k, j)) * d(k));
      r[static_cast<std::size_t>(3 * i + j)] = s;
      r[static_cast<std::size_t>(3 * j + i)] = s;
    }
  }
  return r;
}

double maxAbsB(const BernsteinMatrix3& m) {
  double v = 0.0;
  for (const BernsteinPolynomial& p : m) v = std::max({v, std::abs(p.minCoefficient()), std::abs(p.maxCoefficient())});
  return v;
}

}  // namespace

MovingEllipse2::MovingEllipse2(double a, double b, const PolynomialMatrix3& m, bool is_inverse) : a_(a), b_(b) {
  BernsteinMatrix3 nb;
  if (is_inverse) {
    n_ = m;
    nb = toBernstein(m);
  } else {
    n_ = m.adjugate();
    nb = adjugateB(toBernstein(m));
  }
  // Scale N by a power of two (exact) so that its coefficients are O(1): a positive constant
  // factor, squared in the conic, never changes a root pattern.
  n_ = n_ * (1.0 / powerOfTwoScale(maxAbsCoefficient(n_)));
  const Eigen::Vector3d d(1.0 / (a * a), 1.0 / (b * b), -1.0);
  PolynomialMatrix3 a0(Eigen::Matrix3d(d.asDiagonal()));
  conic_ = n_.transpose() * a0 * n_;
  conic_ = conic_ * (1.0 / powerOfTwoScale(maxAbsCoefficient(conic_)));
  // Bernstein chain (used by CD-DISC).
  const double kn = 1.0 / powerOfTwoScale(maxAbsB(nb));
  for (std::size_t k = 0; k < 9; ++k) nb[k] = nb[k] * kn;
  conic_b_ = congruenceB(nb, d);
  const double kc = 1.0 / powerOfTwoScale(maxAbsB(conic_b_));
  for (std::size_t k = 0; k < 9; ++k) conic_b_[k] = conic_b_[k] * kc;
}

MovingEllipse2::MovingEllipse2(double a, double b, const PolynomialMatrix3& motion)
    : MovingEllipse2(
          [&]() {
            checkRadius("MovingEllipse2", "a", a);
            checkRadius("MovingEllipse2", "b", b);
            validatePlanarMotion("MovingEllipse2", "motion M(t)", motion);
            return a;
          }(),
          b, motion, false) {}

MovingEllipse2 MovingEllipse2::fromInverseMotion(double a, double b, const PolynomialMatrix3& inverse_motion) {
  checkRadius("MovingEllipse2::fromInverseMotion", "a", a);
  checkRadius("MovingEllipse2::fromInverseMotion", "b", b);
  validatePlanarMotion("MovingEllipse2::fromInverseMotion", "inverse motion N(t)", inverse_motion);
  return MovingEllipse2(a, b, inverse_motion, true);
}

Eigen::Matrix3d MovingEllipse2::conicAt(double t) const {
  const Eigen::Matrix3d N = n_.evaluate(t);
  const Eigen::Vector3d d(1.0 / (a_ * a_), 1.0 / (b_ * b_), -1.0);
  return N.transpose() * d.asDiagonal() * N;
}

Eigen::Vector2d MovingEllipse2::centerAt(double t) const {
  // N maps world to body (up to a factor): the centre is N^-1 (0, 0, 1).
  const Eigen::Matrix3d N = n_.evaluate(t);
  const Eigen::Vector3d X = N.partialPivLu().solve(Eigen::Vector3d(0.0, 0.0, 1.0));
  return X.head<2>() / X(2);
}

// ------------------------------------------------------------------------------------------------
// CD-DISC.

Eigen::MatrixXd characteristicPolynomial2(const MovingEllipse2& a, const MovingEllipse2& b) {
  return pencilDeterminant3(a.conic(), b.conic());
}

namespace {

/// Polynomials in lambda whose coefficients are Bernstein polynomials in t on [0, 1] (index =
/// power of lambda). Sums elevate to the larger degree first.
using BernsteinBivariate = std::vector<BernsteinPolynomial>;

BernsteinBivariate mulBB(const BernsteinBivariate& x, const BernsteinBivariate& y) {
  BernsteinBivariate z(x.size() + y.size() - 1);
  std::vector<bool> set(z.size(), false);
  for (std::size_t i = 0; i < x.size(); ++i) {
    for (std::size_t j = 0; j < y.size(); ++j) {
      const BernsteinPolynomial p = x[i] * y[j];
      z[i + j] = set[i + j] ? addB(z[i + j], p) : p;
      set[i + j] = true;
    }
  }
  return z;
}

BernsteinBivariate addBB(const BernsteinBivariate& x, const BernsteinBivariate& y, double sign) {
  BernsteinBivariate z(std::max(x.size(), y.size()));
  for (std::size_t i = 0; i < z.size(); ++i) {
    if (i < x.size() && i < y.size()) {
      z[i] = sign > 0.0 ? addB(x[i], y[i]) : subB(x[i], y[i]);
    } else if (i < x.size()) {
      z[i] = x[i];
    } else {
      z[i] = sign > 0.0 ? y[i] : -y[i];
    }
  }
  return z;
}

/// det (sign = -1 on the odd permutations) or permanent (sign = +1) of a 3x3 array of
/// BernsteinBivariate entries, by expansion along the first row.
BernsteinBivariate det3(const std::array<BernsteinBivariate, 9>& e, double sign) {
  auto E = [&e](int i, int j) -> const BernsteinBivariate& { return e[static_cast<std::size_t>(3 * i + j)]; };
  const BernsteinBivariate c0 = addBB(mulBB(E(1, 1), E(2, 2)), mulBB(E(1, 2), E(2, 1)), sign);
  const BernsteinBivariate c1 = addBB(mulBB(E(1, 2), E(2, 0)), mulBB(E(1, 0), E(2, 2)), sign);
  const BernsteinBivariate c2 = addBB(mulBB(E(1, 0), E(2, 1)), mulBB(E(1, 1), E(2, 0)), sign);
  // det: e00 (e11 e22 - e12 e21) + e01 (e12 e20 - e10 e22) + e02 (e10 e21 - e11 e20);
  // permanent: the same with every sign +.
  return addBB(addBB(mulBB(E(0, 0), c0), mulBB(E(0, 1), c1), 1.0), mulBB(E(0, 2), c2), 1.0);
}

BernsteinPolynomial computeDiscriminant(const MovingEllipse2& a, const MovingEllipse2& b) {
  // Steps 2-3 entirely in the Bernstein basis of [0, 1]. The thesis (§2.5.3) forms g_k(t) in power
  // form and converts them; here the conversion happens already at the motion entries
  // (MovingEllipse2::conicBernstein()), because with the adjugate the g_k have degree 12k and the
  // power-form g_k of Example 2.2 (degree 48) lose Delta entirely to cancellation.
  std::array<BernsteinBivariate, 9> pencil;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const std::size_t k = static_cast<std::size_t>(3 * i + j);
      pencil[k] = {-b.conicBernstein()[k], a.conicBernstein()[k]};
    }
  }
  const BernsteinBivariate gdet = det3(pencil, -1.0);
  int n = 0;
  for (std::size_t k = 0; k < 4; ++k) n = std::max(n, gdet[k].degree());
  std::array<BernsteinPolynomial, 4> g;
  double gmax = 0.0;
  for (std::size_t k = 0; k < 4; ++k) {
    g[k] = gdet[k].elevateTo(n);
    gmax = std::max({gmax, std::abs(g[k].minCoefficient()), std::abs(g[k].maxCoefficient())});
  }
  // Common power-of-two factors (exact, positive) keep the quartic products in range.
  const double inv = 1.0 / powerOfTwoScale(gmax);
  for (std::size_t k = 0; k < 4; ++k) g[k] = g[k] * inv;
  BernsteinPolynomial delta = discriminantFormula(g);
  const double dmax = std::max(std::abs(delta.minCoefficient()), std::abs(delta.maxCoefficient()));
  return delta * (1.0 / powerOfTwoScale(dmax));
}

/// A candidate event time.
struct Event {
  double t;         ///< candidate time, and boundary of the constant-state segments
  bool delta_root;  ///< a (transversal) root of Delta; otherwise an extremum of Delta
};

/// A point of a root interval: refined simple root, or (conservatively) the lower end.
double rootPoint(const BernsteinPolynomial& p, const RootInterval& ri) {
  if (ri.lo == ri.hi) return ri.lo;
  if (ri.kind == RootKind::Single) {
    const double flo = p.evaluate(ri.lo);
    const double fhi = p.evaluate(ri.hi);
    if ((flo < 0.0 && fhi > 0.0) || (flo > 0.0 && fhi < 0.0) || flo == 0.0 || fhi == 0.0) {
      return refineRoot(p, ri.lo, ri.hi, kEllipseRootTolerance);
    }
    return 0.5 * ri.lo + 0.5 * ri.hi;
  }
  return ri.lo;
}

EllipsePairState stateAt(const MovingEllipse2& a, const MovingEllipse2& b, double t) {
  return classifyUnchecked(a.conicAt(t), b.conicAt(t));
}

}  // namespace

BernsteinPolynomial ellipseDiscriminant(const MovingEllipse2& a, const MovingEllipse2& b) {
  return computeDiscriminant(a, b);
}

EllipseCcdResult collideMovingEllipses(const MovingEllipse2& a, const MovingEllipse2& b, EllipseCcdQuery query) {
  EllipseCcdResult res;
  const bool all = query == EllipseCcdQuery::AllContacts;
  // Step 1: the static test at t = 0 (Theorem 2.6).
  const EllipsePairState s0 = stateAt(a, b, 0.0);
  res.separate_at_start = s0.status == Separation::Separated;
  if (!res.separate_at_start) {
    res.collide = true;
    res.first_contact = 0.0;
    res.first_contact_point_valid = s0.status == Separation::Touching && s0.point_valid;
    if (res.first_contact_point_valid) res.first_contact_point = s0.point;
    if (!all) return res;
  }
  // Steps 2-3: Delta(t) in Bernstein form.
  const BernsteinPolynomial delta = computeDiscriminant(a, b);
  res.discriminant_degree = delta.degree();
  // Step 4: candidate events. (a) Local extrema of Delta (roots of Delta'): a grazing contact is a
  // double root of Delta, which rounding may lift off zero (no computed root) or split into a
  // cluster of roots ~sqrt(rounding) apart; the extremum is its well-conditioned location. Every
  // extremum is checked with the static test (cheap), so no band on Delta is needed.
  std::vector<Event> events;
  std::vector<std::pair<double, EllipsePairState>> extrema;
  const BernsteinPolynomial ddelta = delta.derivative();
  for (const RootInterval& ri : isolateRoots(ddelta, kEllipseIsolationWidth)) {
    const double e = std::min(1.0, std::max(0.0, rootPoint(ddelta, ri)));
    extrema.emplace_back(e, stateAt(a, b, e));
    events.push_back({e, false});
    if (static_cast<int>(events.size()) > kMaxEllipseEvents) break;
  }
  // (b) Roots of Delta (Theorem 2.9 / Corollary 2.10). A root within kEllipseGrazingWindow of an
  // extremum where the static test says Touching is reported at the extremum; one next to an
  // extremum where the static test says Separated is a rounding root of a near miss (the static
  // test has the final word within the window); next to an Overlapping extremum it stays a
  // transversal root.
  // Such absorbed roots are dropped: the extremum's own event represents the cluster (and is a
  // contact iff the static test there says Touching), so rounding roots neither split the
  // constant-state segments nor widen the collision intervals.
  for (const RootInterval& ri : isolateRoots(delta, kEllipseIsolationWidth)) {
    const double t = rootPoint(delta, ri);
    bool absorbed = false;
    for (const auto& ex : extrema) {
      if (std::abs(ex.first - t) <= kEllipseGrazingWindow && ex.second.status != Separation::Overlapping) {
        absorbed = true;
        break;
      }
    }
    if (!absorbed) events.push_back({t, true});
    if (static_cast<int>(events.size()) > kMaxEllipseEvents) break;
  }
  std::sort(events.begin(), events.end(), [](const Event& x, const Event& y) { return x.t < y.t; });
  if (static_cast<int>(events.size()) > kMaxEllipseEvents) {
    res.capped = true;
    res.collide = true;
    if (!res.first_contact) res.first_contact = events.front().t;
    return res;
  }
  // Segments between consecutive boundaries; the state is constant inside each (a change needs an
  // external tangency, i.e. a root of Delta: Theorem 2.9).
  std::vector<double> bounds = {0.0};
  for (const Event& ev : events) {
    if (ev.t > bounds.back()) bounds.push_back(ev.t);
  }
  if (bounds.back() < 1.0) bounds.push_back(1.0);
  std::vector<Separation> seg_state(bounds.size() - 1, Separation::Separated);
  std::vector<bool> seg_known(bounds.size() - 1, false);
  auto segmentState = [&](std::size_t i) {
    if (!seg_known[i]) {
      seg_state[i] = stateAt(a, b, 0.5 * bounds[i] + 0.5 * bounds[i + 1]).status;
      seg_known[i] = true;
    }
    return seg_state[i];
  };
  auto segmentIndexAfter = [&](double t) -> std::size_t {
    // first segment whose lower bound is >= t (the one starting at t), or the last one
    const auto it = std::lower_bound(bounds.begin(), bounds.end(), t);
    std::size_t i = static_cast<std::size_t>(it - bounds.begin());
    return std::min(i, seg_state.size() - 1);
  };

  auto addContact = [&](double t, const EllipsePairState& st) {
    EllipseContact c;
    c.t = t;
    c.point = st.point;
    c.point_valid = st.point_valid;
    c.verified = st.status == Separation::Touching;
    if (!res.contacts.empty() && std::abs(res.contacts.back().t - t) <= kEllipseIsolationWidth) {
      if (c.verified && !res.contacts.back().verified) res.contacts.back() = c;
      return;
    }
    res.contacts.push_back(c);
  };

  for (const Event& ev : events) {
    const std::size_t after = segmentIndexAfter(ev.t);
    const std::size_t before = after > 0 ? after - 1 : 0;
    const bool sep_before = ev.t <= 0.0 ? res.separate_at_start : segmentState(before) == Separation::Separated;
    const bool sep_after = ev.t >= 1.0 ? sep_before : segmentState(after) == Separation::Separated;
    const EllipsePairState st = stateAt(a, b, ev.t);
    // An external contact at this event: Touching at the event (Theorem 2.6(1)), a change of
    // state, or a transversal root of Delta next to a separate interval (Corollary 2.10:
    // conservative even if the static value at the refined time lies just outside the band).
    const bool transversal_root = ev.delta_root;
    const bool contact = st.status == Separation::Touching || sep_before != sep_after ||
                         (transversal_root && (sep_before || sep_after)) ||
                         (sep_before && st.status != Separation::Separated);
    if (!contact) continue;
    res.collide = true;
    if (!res.first_contact) {
      res.first_contact = ev.t;
      res.first_contact_point = st.point;
      res.first_contact_point_valid = st.point_valid;
    }
    if (!all) return res;
    addContact(ev.t, st);
  }
  if (!all) {
    // No event was a contact; a segment can only be non-separate if some event was.
    return res;
  }
  // The end point t = 1 (a grazing contact exactly at the end has no extremum inside (0,1)).
  {
    const EllipsePairState s1 = stateAt(a, b, 1.0);
    if (s1.status == Separation::Touching && (res.contacts.empty() || res.contacts.back().t < 1.0)) {
      res.collide = true;
      if (!res.first_contact) {
        res.first_contact = 1.0;
        res.first_contact_point = s1.point;
        res.first_contact_point_valid = s1.point_valid;
      }
      addContact(1.0, s1);
    }
  }
  if (!res.separate_at_start) {
    EllipseContact c;
    c.t = 0.0;
    c.point = s0.point;
    c.point_valid = s0.point_valid;
    c.verified = s0.status == Separation::Touching;
    if (c.verified) res.contacts.insert(res.contacts.begin(), c);
  }
  // Collision intervals: non-separate segments merged, plus isolated contact instants.
  std::vector<std::pair<double, double>> iv;
  for (std::size_t i = 0; i < seg_state.size(); ++i) {
    if (segmentState(i) != Separation::Separated) iv.emplace_back(bounds[i], bounds[i + 1]);
  }
  if (!res.separate_at_start) iv.emplace_back(0.0, 0.0);
  for (const EllipseContact& c : res.contacts) iv.emplace_back(c.t, c.t);
  std::sort(iv.begin(), iv.end());
  for (const auto& x : iv) {
    if (!res.collision_intervals.empty() && x.first <= res.collision_intervals.back().second) {
      res.collision_intervals.back().second = std::max(res.collision_intervals.back().second, x.second);
    } else {
      res.collision_intervals.push_back(x);
    }
  }
  if (!res.collision_intervals.empty()) res.collide = true;
  if (res.collide && !res.first_contact) res.first_contact = res.collision_intervals.front().first;
  return res;
}

}  // namespace fcl_quadric
