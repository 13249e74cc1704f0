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
#include "fcl_quadric/continuous/motion_matrix.h"
#include "algebra/dense_decompositions.h"

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

/// Certifies that p has no root in [0, 1]; throws naming `where` and `what` (the motion layer's
/// check, detail::checkNoRootOnUnitInterval: Bernstein root exclusion, a possible root counts).
void requireRootFree(const char* where, const std::string& what, const Polynomial& p) {
  detail::checkNoRootOnUnitInterval(p, (std::string(where) + ": " + what).c_str());
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

// ------------------------------------------------------------------------------------------------
// Chapter 3: ellipses moving in 3D.

MovingEllipse3::MovingEllipse3(double a, double b, const PolynomialMatrix4& motion) : a_(a), b_(b), m_(motion) {
  checkRadius("MovingEllipse3", "a", a);
  checkRadius("MovingEllipse3", "b", b);
  if (motion.maxDegree() > kMaxEllipseMotionDegree) {
    throw std::invalid_argument("MovingEllipse3: degree " + std::to_string(motion.maxDegree()) +
                                " of motion M(t) exceeds kMaxEllipseMotionDegree = " +
                                std::to_string(kMaxEllipseMotionDegree));
  }
  for (int j = 0; j < 3; ++j) {
    if (!motion(3, j).isZero()) {
      throw std::invalid_argument("MovingEllipse3: last row of motion M(t) must be [0, 0, 0, w(t)] (entry (3, " +
                                  std::to_string(j) + ") is not zero)");
    }
  }
  requireRootFree("MovingEllipse3", "w(t) = entry (3, 3) of motion M(t)", motion(3, 3));
  PolynomialMatrix3 l;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) l(i, j) = motion(i, j);
  }
  requireRootFree("MovingEllipse3", "det of the linear 3x3 part of motion M(t)", l.determinant());
}

Eigen::Vector3d MovingEllipse3::centerAt(double t) const {
  const Eigen::Matrix4d M = m_.evaluate(t);
  return M.block<3, 1>(0, 3) / M(3, 3);
}
Eigen::Vector3d MovingEllipse3::axisUAt(double t) const {
  const Eigen::Matrix4d M = m_.evaluate(t);
  return M.block<3, 1>(0, 0) / M(3, 3);
}
Eigen::Vector3d MovingEllipse3::axisVAt(double t) const {
  const Eigen::Matrix4d M = m_.evaluate(t);
  return M.block<3, 1>(0, 1) / M(3, 3);
}
Eigen::Vector3d MovingEllipse3::normalAt(double t) const {
  const Eigen::Matrix4d M = m_.evaluate(t);
  return M.block<3, 1>(0, 0).cross(M.block<3, 1>(0, 1));
}

namespace {

/// The conic (3x3, interior negative) of ellipse `e` at time t in the 2D coordinates (o, f1, f2) of
/// a plane containing it: x = o + X f1 + Y f2.
Eigen::Matrix3d conicInPlane(const MovingEllipse3& e, double t, const Eigen::Vector3d& o, const Eigen::Vector3d& f1,
                             const Eigen::Vector3d& f2) {
  const Eigen::Vector3d c = e.centerAt(t);
  const Eigen::Vector3d u = e.axisUAt(t);
  const Eigen::Vector3d v = e.axisVAt(t);
  // Body -> plane: (X, Y) = [f1.u f1.v; f2.u f2.v] (alpha, beta) + (f1.(c-o), f2.(c-o)).
  Eigen::Matrix3d M = Eigen::Matrix3d::Identity();
  M(0, 0) = f1.dot(u);
  M(0, 1) = f1.dot(v);
  M(1, 0) = f2.dot(u);
  M(1, 1) = f2.dot(v);
  M(0, 2) = f1.dot(c - o);
  M(1, 2) = f2.dot(c - o);
  const Eigen::Matrix3d N = M.inverse();
  const Eigen::Vector3d d(1.0 / (e.a() * e.a()), 1.0 / (e.b() * e.b()), -1.0);
  return N.transpose() * d.asDiagonal() * N;
}

/// Chord [lo, hi] of the disk alpha^2/a^2 + beta^2/b^2 <= 1 of `e` along the world line
/// x(s) = p0 + s d; false if the line misses the disk. Uses the body coordinates of x(s) in e's plane.
bool chord(const MovingEllipse3& e, double t, const Eigen::Vector3d& p0, const Eigen::Vector3d& d, double* lo,
           double* hi) {
  const Eigen::Vector3d c = e.centerAt(t);
  const Eigen::Vector3d u = e.axisUAt(t);
  const Eigen::Vector3d v = e.axisVAt(t);
  const Eigen::Vector3d n = u.cross(v);
  const double nn = n.squaredNorm();
  // alpha(s) = ((x - c) x v).n / |n|^2, beta(s) = (u x (x - c)).n / |n|^2, both affine in s.
  const Eigen::Vector3d y0 = p0 - c;
  const double a0 = y0.cross(v).dot(n) / nn, a1 = d.cross(v).dot(n) / nn;
  const double b0 = u.cross(y0).dot(n) / nn, b1 = u.cross(d).dot(n) / nn;
  const double ia = 1.0 / (e.a() * e.a()), ib = 1.0 / (e.b() * e.b());
  // h(s) = A2 s^2 + 2 A1 s + A0 <= 0.
  const double A2 = ia * a1 * a1 + ib * b1 * b1;
  const double A1 = ia * a0 * a1 + ib * b0 * b1;
  const double A0 = ia * a0 * a0 + ib * b0 * b0 - 1.0;
  if (!(A2 > 0.0)) return false;
  const double disc = A1 * A1 - A2 * A0;
  if (disc < 0.0) return false;
  const double sq = std::sqrt(disc);
  *lo = (-A1 - sq) / A2;
  *hi = (-A1 + sq) / A2;
  return true;
}

}  // namespace

Separation classifyEllipses3(const MovingEllipse3& a, const MovingEllipse3& b, double t) {
  const Eigen::Vector3d na = a.normalAt(t);
  const Eigen::Vector3d nb = b.normalAt(t);
  const Eigen::Vector3d dir = na.cross(nb);
  const Eigen::Vector3d ca = a.centerAt(t);
  const Eigen::Vector3d cb = b.centerAt(t);
  const double length = (cb - ca).norm() + std::max({a.a(), a.b()}) * a.axisUAt(t).norm() +
                        std::max({b.a(), b.b()}) * b.axisVAt(t).norm() + a.axisVAt(t).norm() + b.axisUAt(t).norm();
  if (dir.norm() <= kEllipseParallelPlanesRelative * na.norm() * nb.norm()) {
    // Parallel planes (Step 7): distinct -> no contact; coincident -> Theorem 2.6 in the plane.
    const Eigen::Vector3d n = na.normalized();
    if (std::abs(n.dot(cb - ca)) > kEllipseCoplanarRelative * length) return Separation::Separated;
    const Eigen::Vector3d f1 = a.axisUAt(t).normalized();
    const Eigen::Vector3d f2 = n.cross(f1);
    return classifyUnchecked(conicInPlane(a, t, ca, f1, f2), conicInPlane(b, t, ca, f1, f2)).status;
  }
  // A point of the intersection line: minimum-norm solution of na.x = na.ca, nb.x = nb.cb.
  Eigen::Matrix<double, 2, 3> N;
  N.row(0) = na.transpose();
  N.row(1) = nb.transpose();
  const Eigen::Vector2d rhs(na.dot(ca), nb.dot(cb));
  const Eigen::Vector3d p0 = N.transpose() * detail::ldltSolve(Eigen::Matrix2d(N * N.transpose()), rhs);
  const Eigen::Vector3d d = dir.normalized();
  double a_lo = 0.0, a_hi = 0.0, b_lo = 0.0, b_hi = 0.0;
  const bool ha = chord(a, t, p0, d, &a_lo, &a_hi);
  const bool hb = chord(b, t, p0, d, &b_lo, &b_hi);
  if (!ha || !hb) return Separation::Separated;
  const double gap = std::max(a_lo, b_lo) - std::min(a_hi, b_hi);
  const double band = kEllipseTouchingRelativeBand * 64.0 *
                      (length + std::abs(a_lo) + std::abs(a_hi) + std::abs(b_lo) + std::abs(b_hi));
  if (gap > band) return Separation::Separated;
  if (gap < -band) return Separation::Overlapping;
  return Separation::Touching;
}

namespace {

using BVec3 = std::array<BernsteinPolynomial, 3>;

BernsteinPolynomial dotB(const BVec3& x, const BVec3& y) { return addB(addB(x[0] * y[0], x[1] * y[1]), x[2] * y[2]); }

BVec3 crossB(const BVec3& x, const BVec3& y) {
  return {subB(x[1] * y[2], x[2] * y[1]), subB(x[2] * y[0], x[0] * y[2]), subB(x[0] * y[1], x[1] * y[0])};
}

BVec3 scaleB(const BVec3& x, const BernsteinPolynomial& s) { return {x[0] * s, x[1] * s, x[2] * s}; }

BVec3 subV(const BVec3& x, const BVec3& y) { return {subB(x[0], y[0]), subB(x[1], y[1]), subB(x[2], y[2])}; }

struct Motion3B {
  BVec3 u, v, c;  // L e_x, L e_y, translation column
  BernsteinPolynomial w;
};

Motion3B toBernstein3(const PolynomialMatrix4& M) {
  auto B = [&M](int i, int j) { return BernsteinPolynomial::fromPower(M(i, j), 0.0, 1.0); };
  return {{B(0, 0), B(1, 0), B(2, 0)}, {B(0, 1), B(1, 1), B(2, 1)}, {B(0, 3), B(1, 3), B(2, 3)}, B(3, 3)};
}

BernsteinPolynomial normalised(const BernsteinPolynomial& p) {
  const double m = std::max(std::abs(p.minCoefficient()), std::abs(p.maxCoefficient()));
  return p * (1.0 / powerOfTwoScale(m));
}

/// True if every Bernstein coefficient of p is at most rel times max |coefficient of scale|.
bool negligible(const BernsteinPolynomial& p, double scale_max, double rel) {
  return std::max(std::abs(p.minCoefficient()), std::abs(p.maxCoefficient())) <= rel * scale_max;
}

double maxAbsCoef(const BernsteinPolynomial& p) { return std::max(std::abs(p.minCoefficient()), std::abs(p.maxCoefficient())); }

/// 2x2 quadratic form [[q2, q1], [q1, q0]] of s -> (x0 + s x1)^T diag(ia, ib, -1) (x0 + s x1) for
/// homogeneous body points x = (alpha, beta, omega).
std::array<BernsteinPolynomial, 3> restrictConic(const BVec3& x0, const BVec3& x1, double ia, double ib) {
  auto form = [&](const BVec3& p, const BVec3& q) {
    return subB(addB((p[0] * q[0]) * ia, (p[1] * q[1]) * ib), p[2] * q[2]);
  };
  return {form(x1, x1), form(x1, x0), form(x0, x0)};
}

}  // namespace

Ellipse3CcdResult collideMovingEllipses3(const MovingEllipse3& a, const MovingEllipse3& b) {
  Ellipse3CcdResult res;
  const Motion3B ma = toBernstein3(a.motion());
  const Motion3B mb = toBernstein3(b.motion());
  const BVec3 na = crossB(ma.u, ma.v);
  const BVec3 nb = crossB(mb.u, mb.v);
  // Step 1: identical planes for all t? n_A x n_B == 0 and n_A . (w_A c_B - w_B c_A) == 0.
  const BVec3 nx = crossB(na, nb);
  const BernsteinPolynomial off = dotB(na, subV(scaleB(mb.c, ma.w), scaleB(ma.c, mb.w)));
  double nscale = 0.0;
  for (int i = 0; i < 3; ++i) {
    nscale = std::max(nscale, maxAbsCoef(na[static_cast<std::size_t>(i)]) * maxAbsCoef(nb[static_cast<std::size_t>(i)]));
  }
  double nscale_full = 0.0;
  for (const auto& x : na) {
    for (const auto& y : nb) nscale_full = std::max(nscale_full, maxAbsCoef(x) * maxAbsCoef(y));
  }
  double oscale = 0.0;
  for (int i = 0; i < 3; ++i) {
    for (const auto& x : na) {
      oscale = std::max(oscale, maxAbsCoef(x) * (maxAbsCoef(mb.c[static_cast<std::size_t>(i)] * ma.w) +
                                                 maxAbsCoef(ma.c[static_cast<std::size_t>(i)] * mb.w)));
    }
  }
  const bool parallel_always = negligible(nx[0], nscale_full, 1e-12) && negligible(nx[1], nscale_full, 1e-12) &&
                               negligible(nx[2], nscale_full, 1e-12);
  (void)nscale;
  if (parallel_always && negligible(off, oscale, kEllipseCoplanarRelative)) {
    // Is the common plane fixed? Its unit normal and offset at t = 0 must hold at every t: n_A(t) x
    // n0 == 0 and n0.(c_A(t) - c_A(0)) == 0 (checked at the Bernstein level as above).
    const Eigen::Vector3d n0 = a.normalAt(0.0).normalized();
    const Eigen::Vector3d o = a.centerAt(0.0);
    BVec3 n0b = {BernsteinPolynomial({n0(0)}), BernsteinPolynomial({n0(1)}), BernsteinPolynomial({n0(2)})};
    const BVec3 nax0 = crossB(na, n0b);
    bool fixed = true;
    double sc = 0.0;
    for (const auto& x : na) sc = std::max(sc, maxAbsCoef(x));
    for (const auto& x : nax0) fixed = fixed && negligible(x, sc, 1e-12);
    BVec3 ob = {BernsteinPolynomial({o(0)}), BernsteinPolynomial({o(1)}), BernsteinPolynomial({o(2)})};
    const BernsteinPolynomial moved = dotB(n0b, subV(ma.c, scaleB(ob, ma.w)));
    double csc = o.norm();
    for (const auto& x : ma.c) csc = std::max(csc, maxAbsCoef(x));
    fixed = fixed && negligible(moved, csc * std::max(1.0, maxAbsCoef(ma.w)), kEllipseCoplanarRelative);
    if (fixed) {
      // Reduce to CD-DISC in the plane (o, f1, f2): 2D motion rows f1.(.), f2.(.), [0 0 w].
      res.coplanar = true;
      const Eigen::Vector3d f1 = a.axisUAt(0.0).normalized();
      const Eigen::Vector3d f2 = n0.cross(f1);
      auto planar = [&](const MovingEllipse3& e) {
        const PolynomialMatrix4& M = e.motion();
        PolynomialMatrix3 m2;
        const std::array<Eigen::Vector3d, 2> f = {f1, f2};
        for (int r = 0; r < 2; ++r) {
          const Eigen::Vector3d& fr = f[static_cast<std::size_t>(r)];
          for (int col = 0; col < 2; ++col) {
            m2(r, col) = M(0, col) * fr(0) + M(1, col) * fr(1) + M(2, col) * fr(2);
          }
          m2(r, 2) = M(0, 3) * fr(0) + M(1, 3) * fr(1) + M(2, 3) * fr(2) - M(3, 3) * fr.dot(o);
        }
        m2(2, 2) = M(3, 3);
        return MovingEllipse2(e.a(), e.b(), m2);
      };
      const EllipseCcdResult r2 = collideMovingEllipses(planar(a), planar(b), EllipseCcdQuery::FirstContact);
      res.collide = r2.collide;
      res.first_contact = r2.first_contact;
      res.capped = r2.capped;
      return res;
    }
  }
  // Step 0: the state at t = 0.
  if (classifyEllipses3(a, b, 0.0) != Separation::Separated) {
    res.collide = true;
    res.first_contact = 0.0;
    return res;
  }
  // Steps 2-4: line p alpha + q beta + r = 0 in A's body plane (B's plane cut with A's plane).
  const BernsteinPolynomial p = mb.w * dotB(nb, ma.u);
  const BernsteinPolynomial q = mb.w * dotB(nb, ma.v);
  const BernsteinPolynomial r = dotB(nb, subV(scaleB(ma.c, mb.w), scaleB(mb.c, ma.w)));
  // Homogeneous A-body points X(s) = X0 + s D: D = (-q, p, 0), X0 = (-r p, -r q, p^2 + q^2).
  const BernsteinPolynomial zero_d({0.0});
  const BVec3 D = {-q, p, zero_d};
  const BVec3 X0 = {-(r * p), -(r * q), addB(p * p, q * q)};
  const std::array<BernsteinPolynomial, 3> h =
      restrictConic(X0, D, 1.0 / (a.a() * a.a()), 1.0 / (a.b() * a.b()));
  // World points W = M_A X (homogeneous, last coordinate omega = w_A X_w):
  //   W_xyz = alpha u_A + beta v_A + omega_body c_A, W_w = w_A omega_body.
  auto world = [&](const BVec3& X) {
    BVec3 xyz;
    for (std::size_t i = 0; i < 3; ++i) {
      xyz[i] = addB(addB(X[0] * ma.u[i], X[1] * ma.v[i]), X[2] * ma.c[i]);
    }
    return std::make_pair(xyz, X[2] * ma.w);
  };
  // B-body homogeneous coordinates: Y = w_B W_xyz - W_w c_B; (alpha, beta, omega) =
  // ((Y x v_B).n_B, (u_B x Y).n_B, W_w |n_B|^2).
  const BernsteinPolynomial nbb = dotB(nb, nb);
  auto bodyB = [&](const BVec3& X) {
    const auto W = world(X);
    const BVec3 Y = subV(scaleB(W.first, mb.w), scaleB(mb.c, W.second));
    return BVec3{dotB(crossB(Y, mb.v), nb), dotB(crossB(mb.u, Y), nb), W.second * nbb};
  };
  const std::array<BernsteinPolynomial, 3> g =
      restrictConic(bodyB(X0), bodyB(D), 1.0 / (b.a() * b.a()), 1.0 / (b.b() * b.b()));
  // Step 5: f(lambda) = det(lambda H - G) = lambda^2 det H - lambda (h2 g0 + h0 g2 - 2 h1 g1) + det G.
  const BernsteinPolynomial h2 = normalised(h[0]), h1 = h[1] * (1.0 / powerOfTwoScale(maxAbsCoef(h[0]))),
                            h0 = h[2] * (1.0 / powerOfTwoScale(maxAbsCoef(h[0])));
  const double gs = 1.0 / powerOfTwoScale(std::max({maxAbsCoef(g[0]), maxAbsCoef(g[1]), maxAbsCoef(g[2])}));
  const BernsteinPolynomial g2 = g[0] * gs, g1 = g[1] * gs, g0 = g[2] * gs;
  const BernsteinPolynomial c2 = subB(h2 * h0, h1 * h1);
  const BernsteinPolynomial c1 = subB(addB(h2 * g0, h0 * g2), (h1 * g1) * 2.0);
  const BernsteinPolynomial c0 = subB(g2 * g0, g1 * g1);
  // Step 6: Delta_f = c1^2 - 4 c2 c0.
  const BernsteinPolynomial delta = normalised(subB(c1 * c1, (c2 * c0) * 4.0));
  res.discriminant_degree = delta.degree();
  // Steps 7-8: candidates (roots and extrema of Delta_f), validated by the static test.
  std::vector<double> cand;
  for (const RootInterval& ri : isolateRoots(delta, kEllipseIsolationWidth)) cand.push_back(rootPoint(delta, ri));
  const BernsteinPolynomial dd = delta.derivative();
  for (const RootInterval& ri : isolateRoots(dd, kEllipseIsolationWidth)) {
    cand.push_back(std::min(1.0, std::max(0.0, rootPoint(dd, ri))));
  }
  std::sort(cand.begin(), cand.end());
  if (static_cast<int>(cand.size()) > kMaxEllipseEvents) {
    res.capped = true;
    res.collide = true;
    res.first_contact = cand.front();
    return res;
  }
  cand.push_back(1.0);
  double prev = 0.0;
  for (double t : cand) {
    // A state change inside (prev, t) shows at the midpoint; a contact at t shows at t.
    if (t > prev && classifyEllipses3(a, b, 0.5 * prev + 0.5 * t) != Separation::Separated) {
      res.collide = true;
      res.first_contact = prev;
      return res;
    }
    if (classifyEllipses3(a, b, t) != Separation::Separated) {
      res.collide = true;
      res.first_contact = t;
      return res;
    }
    prev = t;
  }
  return res;
}

}  // namespace fcl_quadric
