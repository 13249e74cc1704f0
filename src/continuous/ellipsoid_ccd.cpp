#include "fcl_quadric/continuous/ellipsoid_ccd.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <Eigen/LU>

#include "fcl_quadric/algebra/bernstein_polynomial.h"
#include "fcl_quadric/algebra/bivariate_bernstein.h"
#include "fcl_quadric/algebra/double_double.h"
#include "fcl_quadric/algebra/quadric_matrix.h"
#include "fcl_quadric/algebra/root_isolation.h"
#include "fcl_quadric/continuous/ccd_function.h"
#include "fcl_quadric/geometry/ellipsoid_separation.h"
#include "fcl_quadric/geometry/separating_plane.h"
#include "fcl_quadric/tolerances.h"

namespace fcl_quadric {

namespace {

Ellipsoid worldEllipsoidFromMap(const Ellipsoid& e, const Eigen::Matrix4d& T) {
  const Eigen::Matrix3d L = T.topLeftCorner<3, 3>();
  return Ellipsoid::fromAffine(L * e.rotation() * e.radii().asDiagonal(), L * e.center() + T.block<3, 1>(0, 3));
}

Ellipsoid worldEllipsoid(const Ellipsoid& body, const MotionMatrix& m, double t) {
  const Eigen::Matrix4d T = m.evaluate(t);
  if (m.isRigid()) {  // no eigen-decomposition: the axes just rotate
    const Eigen::Matrix3d R = T.topLeftCorner<3, 3>();
    return Ellipsoid(body.radii(), R * body.rotation(), R * body.center() + T.block<3, 1>(0, 3));
  }
  return worldEllipsoidFromMap(body, T);
}

}  // namespace

Ellipsoid ellipsoidAt(const MovingEllipsoid& m, double t) { return worldEllipsoidFromMap(m.body, m.motion.evaluate(t)); }

namespace {

/// Newton/bisection steps per monotone piece of the quartic's derivative (quadratic convergence:
/// a handful suffices; the cap bounds the work).
constexpr int kQuarticSteps = 40;

using Vec4P = std::array<Polynomial, 4>;

Vec4P times(const PolynomialMatrix4& M, const Eigen::Vector4d& v) {  // M(t) v
  Vec4P r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      if (v[j] != 0.0) r[i] += M(i, j) * v[j];
  return r;
}


// Certified sign of a polynomial on [0, 1] from its Bernstein coefficients: +1 if all > margin,
// -1 if all < -margin, 0 otherwise. The margin covers a relative 1e-10 of the coefficients and
// the rounding of the formula that produced p: magnitude >= 0 is the same formula on absolute
// values (its value at 1, the sum of its coefficients, bounds it on [0, 1]), `error` the relative
// error bound per unit of magnitude.
int certifiedSign(const Polynomial& p, const Polynomial& magnitude, double error) {
  const BernsteinPolynomial b = BernsteinPolynomial::fromPower(p.trimmed(), 0.0, 1.0);
  double scale = 0.0;
  for (double c : b.coefficients()) {
    // A coefficient that overflowed (inf, or NaN, which std::max and every comparison below
    // would pass over) certifies nothing.
    if (!std::isfinite(c)) return 0;
    scale = std::max(scale, std::abs(c));
  }
  double mag = 0.0;
  for (double c : magnitude.coefficients()) mag += c;
  const double margin = 1e-10 * scale + error * mag;
  if (!std::isfinite(margin)) return 0;
  if (b.minCoefficient() > margin) return 1;
  if (b.maxCoefficient() < -margin) return -1;
  return 0;
}

// Rounding chain of the cull polynomials below (a few products and 4-term sums, convolutions of
// <= 2 (degree + 1) terms), in unit roundoffs, for coefficient count n.
double cullRoundingError(std::size_t n) { return 4.0 * (static_cast<double>(n) + 16.0) * tolerance::kUnitRoundoff; }

// Thesis §5.4.1 bounding-sphere cull for rigid motions: |c_a(t) - c_b(t)|^2 > (r_a + r_b)^2 on
// [0, 1], multiplied through by the squared homogeneous weights.
bool sphereCull(const MovingEllipsoid& a, const MotionMatrix& ma, const MovingEllipsoid& b, const MotionMatrix& mb) {
  if (ma.linearTranslation() && mb.linearTranslation()) {
    // Bounding spheres about the body origins, whose paths are segments: |d0 + t v|^2 > R^2 on
    // [0, 1] by the minimum of the quadratic (margin relative to R^2 for rounding).
    const double R = a.body.center().norm() + a.body.radii().maxCoeff() + b.body.center().norm() + b.body.radii().maxCoeff();
    const auto& [a0, a1] = *ma.linearTranslation();
    const auto& [b0, b1] = *mb.linearTranslation();
    const Eigen::Vector3d d0 = b0 - a0, v = (b1 - b0) - (a1 - a0);
    const double vv = v.squaredNorm();
    const double t = vv > 0.0 ? std::clamp(-d0.dot(v) / vv, 0.0, 1.0) : 0.0;
    return (d0 + t * v).squaredNorm() > R * R * (1.0 + 1e-12);
  }
  const PolynomialMatrix4 Ma = ma.matrix(), Mb = mb.matrix();
  const Vec4P ca = times(Ma, a.body.center().homogeneous());
  const Vec4P cb = times(Mb, b.body.center().homogeneous());
  const Vec4P ca_abs = times(coefficientMagnitudes(Ma), a.body.center().cwiseAbs().homogeneous());
  const Vec4P cb_abs = times(coefficientMagnitudes(Mb), b.body.center().cwiseAbs().homogeneous());
  const double r = a.body.radii().maxCoeff() + b.body.radii().maxCoeff();
  Polynomial g, g_abs;
  for (int i = 0; i < 3; ++i) {
    const Polynomial d = cb[3] * ca[i] - ca[3] * cb[i];
    const Polynomial d_abs = cb_abs[3] * ca_abs[i] + ca_abs[3] * cb_abs[i];
    g += d * d;
    g_abs += d_abs * d_abs;
  }
  const Polynomial w = ca[3] * cb[3], w_abs = ca_abs[3] * cb_abs[3];
  g -= w * w * (r * r);
  g_abs += w_abs * w_abs * (r * r);
  return certifiedSign(g, g_abs, cullRoundingError(g_abs.coefficients().size())) > 0;
}

// Thesis §5.4.1 separating-plane cull: the plane separating a(0) and b(0) moves with b; a never
// reaches it iff q(t)^T Q_a^{-1} q(t) < 0 on [0, 1], q(t) = M_a(t)^T N_b(t)^T pi_b the plane in a's
// body frame and Q_a^{-1} a's dual quadric (in closed form: T diag(r^2, -1) T^T, T = [[R, c],
// [0, 1]]; computed on coefficient matrices). Rounding: the products, as cullRoundingError, on
// the same formula evaluated on absolute values (N_b of a rigid motion is exact to rounding).
bool planeCull(const MovingEllipsoid& a, const MotionMatrix& ma, const MotionMatrix& mb, const Plane& plane) {
  const Eigen::Vector4d pi_world(plane.normal.x(), plane.normal.y(), plane.normal.z(), -plane.offset);
  const Eigen::Vector4d pi_body_b = mb.evaluate(0.0).transpose() * pi_world;  // scale irrelevant
  const std::vector<Eigen::Matrix4d>& Nb = mb.inverseCoefficients();
  const std::vector<Eigen::Matrix4d>& Ma = ma.matrixCoefficients();
  const std::size_t nq = Nb.size() + Ma.size() - 1;
  std::vector<Eigen::Vector4d> q(nq, Eigen::Vector4d::Zero()), q_abs(nq, Eigen::Vector4d::Zero());
  for (std::size_t k = 0; k < Nb.size(); ++k) {
    const Eigen::Vector4d pk = Nb[k].transpose() * pi_body_b;
    for (std::size_t l = 0; l < Ma.size(); ++l) q[k + l].noalias() += Ma[l].transpose() * pk;
  }
  for (std::size_t k = 0; k < Nb.size(); ++k) {
    const Eigen::Vector4d pk = Nb[k].transpose().cwiseAbs() * pi_body_b.cwiseAbs();
    for (std::size_t l = 0; l < Ma.size(); ++l) q_abs[k + l].noalias() += Ma[l].transpose().cwiseAbs() * pk;
  }
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = a.body.rotation();
  T.topRightCorner<3, 1>() = a.body.center();
  const Eigen::Vector3d r2 = a.body.radii().cwiseProduct(a.body.radii());
  const Eigen::Vector4d d(r2[0], r2[1], r2[2], -1.0);
  const Eigen::Matrix4d dual = T * d.asDiagonal() * T.transpose();
  const Eigen::Matrix4d dual_abs = T.cwiseAbs() * d.cwiseAbs().asDiagonal() * T.transpose().cwiseAbs();
  std::vector<double> g(2 * nq - 1, 0.0), g_abs(2 * nq - 1, 0.0);
  for (std::size_t k = 0; k < nq; ++k) {
    const Eigen::Vector4d dq = dual * q[k], dq_abs = dual_abs * q_abs[k];
    for (std::size_t l = 0; l < nq; ++l) {
      g[k + l] += q[l].dot(dq);
      g_abs[k + l] += q_abs[l].dot(dq_abs);
    }
  }
  const double error = cullRoundingError(nq);
  return certifiedSign(Polynomial(std::move(g)), Polynomial(std::move(g_abs)), error) < 0;
}

// The balancing factor: |det Q(1/2)|^(1/4), so that det A and det B are both about -1 in
// mid-motion. A positive factor changes no sign decision, but balancing keeps the negative roots
// of det(lambda A - B) near lambda = -1, i.e. the maximiser of u -> F(u, t) away from u = 0 and
// u = 1 where F = u^4 f(lambda) is flattened by the factor u^4.
double balanceScale(const PolynomialMatrix4& Q) {
  const double det = std::abs(Q.evaluate(0.5).determinant());
  double scale = std::pow(det, 0.25);
  if (!(scale > 0.0) || !std::isfinite(scale)) {
    scale = 0.0;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) scale = std::max(scale, Q(i, j).maxAbsCoefficient());
  }
  return scale;
}

// Symmetrised and divided by `scale`.
PolynomialMatrix4 balanced(const PolynomialMatrix4& Q, double scale) {
  PolynomialMatrix4 R;
  for (int i = 0; i < 4; ++i) {
    R(i, i) = Q(i, i) * (1.0 / scale);
    for (int j = i + 1; j < 4; ++j) {
      R(i, j) = (Q(i, j) + Q(j, i)) * (0.5 / scale);
      R(j, i) = R(i, j);
    }
  }
  return R;
}

// Condition estimate of a moving ellipsoid's quadric matrix: (aspect ratio x condition of the
// motion's linear part)^2 (tolerance::kCcdCheckedCondition).
double quadricCondition(const Ellipsoid& body, const MotionMatrix& m) {
  const double aspect = body.radii().maxCoeff() / body.radii().minCoeff();
  const double linear = m.isRigid() ? 1.0 : m.linearCondition();
  return (aspect * linear) * (aspect * linear);
}

// A moving quadric in the scaled frame, balanced (divided by `scale`).
struct ScaledQuadric {
  PolynomialMatrix4 Q;
  double scale = 1.0;
};

// (N S)^T Q (N S), balanced.
ScaledQuadric scaledQuadric(const Eigen::Matrix4d& Q_body, const std::vector<Eigen::Matrix4d>& N, const Eigen::Matrix4d& S) {
  const PolynomialMatrix4 Q = congruence(Q_body, N, S);
  const double scale = balanceScale(Q);
  return {balanced(Q, scale), scale};
}

// The same in extended precision from N's extended coefficient matrices (the precision check):
// coefficient matrices of the symmetrised (N S)^T Q (N S) / scale. Q is the body's quadric formed
// in long double too: until session 26 it was body.quadricMatrix(), rounded in double, so the
// double and extended expansions started from the same rounded matrix and their difference (the
// error estimate) could not see its rounding, ~eps relative in entries of size 1/r^2 (finding 16's
// audit, docs/reliability.md).
std::vector<Matrix4ld> scaledQuadricExtended(const Ellipsoid& body, const std::vector<Matrix4ld>& N,
                                            const Eigen::Matrix4d& S, double scale) {
  const Matrix4ld Sl = S.cast<long double>();
  const Matrix4ld Ql = quadric::posedEllipsoidExtended(body.radii(), body.rotation(), body.center());
  std::vector<Matrix4ld> NS(N.size()), QNS(N.size());
  for (std::size_t k = 0; k < N.size(); ++k) {
    NS[k] = N[k] * Sl;
    QNS[k] = Ql * NS[k];
  }
  std::vector<Matrix4ld> A(2 * N.size() - 1, Matrix4ld::Zero());
  for (std::size_t k = 0; k < N.size(); ++k)
    for (std::size_t l = 0; l < N.size(); ++l) A[k + l].noalias() += NS[k].transpose() * QNS[l];
  for (Matrix4ld& m : A) m = ((m + m.transpose()) * (0.5L / scale)).eval();  // eval: no aliasing
  return A;
}

// Thesis §5.2: the affine interpolant of b's state relative to a, in a's body frame.
PolynomialMatrix4 affineInterpolant(const Eigen::Matrix3d B0, const Eigen::Vector3d& c0, const Eigen::Matrix3d& B1,
                                    const Eigen::Vector3d& c1, const Eigen::Matrix4d& S) {
  // In scaled coordinates y = S^{-1} x (S = [[L I, c_ref], [0, 1]]): shape L^2 B, centre (c - c_ref) / L.
  const double L = S(0, 0);
  const Eigen::Vector3d cref = S.block<3, 1>(0, 3);
  PolynomialMatrix4 Bt;
  Polynomial c[3];
  for (int i = 0; i < 3; ++i) {
    c[i] = Polynomial{(c0[i] - cref[i]) / L, (c1[i] - c0[i]) / L};
    for (int j = 0; j < 3; ++j) Bt(i, j) = Polynomial{L * L * B0(i, j), L * L * (B1(i, j) - B0(i, j))};
  }
  PolynomialMatrix4 Q;
  Polynomial Bc[3];
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      Q(i, j) = Bt(i, j);
      Bc[i] += Bt(i, j) * c[j];
    }
  }
  Polynomial cBc;
  for (int i = 0; i < 3; ++i) {
    Q(i, 3) = -Bc[i];
    Q(3, i) = -Bc[i];
    cBc += c[i] * Bc[i];
  }
  Q(3, 3) = cBc - Polynomial{1.0};
  return Q;
}

// affineInterpolant's quadric recomputed in long double from the same inputs (power-basis
// coefficient matrices, degree 3), symmetric and divided by `scale` as balanced() does: the
// precision check's extended operand. The constant term c^T B c - 1 cancels heavily (a centre
// several radii away along a short axis), which the double interpolant carries into F.
std::vector<Matrix4ld> affineInterpolantExtended(const Eigen::Matrix3d& B0, const Eigen::Vector3d& c0,
                                                 const Eigen::Matrix3d& B1, const Eigen::Vector3d& c1,
                                                 const Eigen::Matrix4d& S, double scale) {
  using ld = long double;
  const ld L = S(0, 0);
  Eigen::Matrix<ld, 3, 1> c[2];   // centre: c[0] + t c[1], scaled
  Eigen::Matrix<ld, 3, 3> Bt[2];  // shape: Bt[0] + t Bt[1], scaled
  for (int i = 0; i < 3; ++i) {
    c[0][i] = (static_cast<ld>(c0[i]) - S(i, 3)) / L;
    c[1][i] = (static_cast<ld>(c1[i]) - c0[i]) / L;
    for (int j = 0; j < 3; ++j) {
      Bt[0](i, j) = L * L * B0(i, j);
      Bt[1](i, j) = L * L * (static_cast<ld>(B1(i, j)) - B0(i, j));
    }
  }
  std::vector<Matrix4ld> Q(4, Matrix4ld::Zero());
  for (int k = 0; k < 2; ++k) Q[k].topLeftCorner<3, 3>() = Bt[k];
  Eigen::Matrix<ld, 3, 1> Bc[3] = {Bt[0] * c[0], Bt[0] * c[1] + Bt[1] * c[0], Bt[1] * c[1]};  // by power of t
  for (int k = 0; k < 3; ++k) {
    Q[k].block<3, 1>(0, 3) = -Bc[k];
    Q[k].block<1, 3>(3, 0) = -Bc[k].transpose();
  }
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 2; ++l) Q[k + l](3, 3) += c[l].dot(Bc[k]);
  Q[0](3, 3) -= 1.0L;
  for (Matrix4ld& m : Q) m = ((m + m.transpose()) * (0.5L / scale)).eval();
  return Q;
}

// de Casteljau restriction of Bernstein coefficients on [0, 1] to [a, b] (0 <= a < b <= 1),
// applied alike to the margins (every weight is convex, so restricted margins bound the
// restricted errors: a margin of the form ulps |c| + e covers the rounding of the restriction,
// a few (n + 1) ulps of the restricted |c| by the standard running error bound of de
// Casteljau's algorithm, plus the restricted input error e).
// In place, no allocation: the de Casteljau triangle keeps P_j^(n-j) (the coefficients on [s, 1])
// when updated from the left, and P_0^j (those on [0, s]) when updated from the right.
void keepRight(double* c, int n, double s) {
  const double r = 1.0 - s;
  for (int level = 1; level <= n; ++level)
    for (int i = 0; i <= n - level; ++i) c[i] = r * c[i] + s * c[i + 1];
}
void keepLeft(double* c, int n, double s) {
  const double r = 1.0 - s;
  for (int level = 1; level <= n; ++level)
    for (int i = n; i >= level; --i) c[i] = r * c[i - 1] + s * c[i];
}

void restrictWithBound(std::vector<double>* c, std::vector<double>* margin, double a, double b) {
  const int n = static_cast<int>(c->size()) - 1;
  if (a > 0.0) {
    keepRight(c->data(), n, a);
    keepRight(margin->data(), n, a);
  }
  if (b < 1.0) {
    const double s = (b - a) / (1.0 - a);
    keepLeft(c->data(), n, s);
    keepLeft(margin->data(), n, s);
  }
}

// Lower bound of the first root in [0, 1] of the Bernstein polynomial with coefficients c (unit
// parameter), by one-sided Bezier clipping (Sederberg-Nishita) with midpoint subdivision: the
// control points lie above the line from (0, c_0) with the steepest descent toward any (j/n, c_j),
// so no root precedes its zero crossing s. When s >= 1/2 the interval is clipped to [s, 1]
// (quadratic convergence to a simple root); otherwise (a large coefficient far to the right makes
// the hull bound weak) it is halved and the left half examined first, a half whose coefficients
// all exceed their margins being certified root-free. Sub-intervals are visited left to right, so
// the left end of the current one is always a lower bound of the first root. Each coefficient is
// lowered by its own margin (carried along through every restriction): the caller's margins are
// kCcdClipMarginUlps (n + 1) ulps of |c| (the rounding of the restrictions) plus the coefficients'
// own error bound; local margins stay meaningful where the polynomial is small (F varies by
// orders of magnitude along t for high-degree motions). Returns nullopt when [0, 1] is certified
// root-free; otherwise stops at the first sub-interval whose left value is within its margin, or
// after kCcdMaxClipSteps steps, returning that left end.
std::optional<double> firstRootLowerBound(std::vector<double> c, std::vector<double> margin) {
  const int n = static_cast<int>(c.size()) - 1;
  const std::size_t m = c.size();
  // Pending right halves, innermost last: their intervals and coefficients in flat buffers.
  struct Pending {
    double lo, width;
  };
  std::vector<Pending> pending;
  std::vector<double> pool_c, pool_abs;
  double lo = 0.0, width = 1.0;
  for (int step = 0;; ++step) {
    if (step >= tolerance::kCcdMaxClipSteps) return lo;
    const double c0 = c[0] - margin[0];
    if (!(c0 > 0.0)) return lo;
    double s = 2.0;
    int j_min = 0;
    bool positive = true;
    for (int j = 1; j <= n; ++j) {
      const double cj = c[j] - margin[j];
      positive = positive && cj > 0.0;
      if (cj < c0) {
        const double sj = (static_cast<double>(j) / n) * c0 / (c0 - cj);
        if (sj < s) {
          s = sj;
          j_min = j;
        }
      }
    }
    if (positive) {  // root-free piece: continue with the next pending one, if any
      if (pending.empty()) return std::nullopt;
      lo = pending.back().lo;
      width = pending.back().width;
      pending.pop_back();
      std::copy(pool_c.end() - m, pool_c.end(), c.begin());
      std::copy(pool_abs.end() - m, pool_abs.end(), margin.begin());
      pool_c.resize(pool_c.size() - m);
      pool_abs.resize(pool_abs.size() - m);
      continue;
    }
    s = std::min(s, 1.0) * (1.0 - 8.0 * tolerance::kUnitRoundoff);
    // Clip to [s, 1] when the bound is strong (s >= 1/2) or set by the tangent at the left end
    // (j = 1: repeated clipping is then Newton's method from the left, quadratic near a simple
    // root); a weak bound set by a distant large coefficient is replaced by a split.
    if (s >= 0.5 || j_min == 1) {
      const double next = lo + width * s;
      if (!(next > lo)) return lo;
      keepRight(c.data(), n, s);
      keepRight(margin.data(), n, s);
      lo = next;
      width *= 1.0 - s;
      continue;
    }
    // Split: the right part waits, the left one is examined first. The split point is 1/2, or
    // four times the tangent estimate c_0 / (n (c_0 - c_1)) of the root when that is smaller, so
    // that a small value at the left end (a shoot close to contact) is reached in a few splits
    // rather than by repeated halving.
    double split = 0.5;
    if (c[1] < c[0]) split = std::clamp(4.0 * c[0] / (n * (c[0] - c[1])), 1.0 / 64.0, 0.5);
    const double left_width = width * split;
    if (!(lo + left_width > lo)) return lo;
    pending.push_back({lo + left_width, width - left_width});
    pool_c.insert(pool_c.end(), c.begin(), c.end());
    pool_abs.insert(pool_abs.end(), margin.begin(), margin.end());
    keepRight(pool_c.data() + pool_c.size() - m, n, split);
    keepRight(pool_abs.data() + pool_abs.size() - m, n, split);
    keepLeft(c.data(), n, split);
    keepLeft(margin.data(), n, split);
    width = left_width;
  }
}

struct QuarticMax {
  double u;
  double value;
};

// Maximum over [0, 1] of the quartic with Bernstein coefficients c: its power form q, the
// critical points from the monotone pieces of q' (split at the roots of the quadratic q'') by
// safeguarded Newton (bisection whenever a step leaves the bracket; at most kQuarticSteps steps per
// piece), and the ends. The maximiser only needs to be approximate (the value is second order in
// its error); the value is evaluated at it.
QuarticMax maximiseQuartic(const std::array<double, 5>& c) {
  // Power form: q(u) = sum_k a_k u^k.
  const double a0 = c[0], a1 = 4 * (c[1] - c[0]), a2 = 6 * (c[2] - 2 * c[1] + c[0]),
               a3 = 4 * (c[3] - 3 * c[2] + 3 * c[1] - c[0]), a4 = c[4] - 4 * c[3] + 6 * c[2] - 4 * c[1] + c[0];
  auto q = [&](double u) { return (((a4 * u + a3) * u + a2) * u + a1) * u + a0; };
  auto dq = [&](double u) { return ((4 * a4 * u + 3 * a3) * u + 2 * a2) * u + a1; };
  auto ddq = [&](double u) { return (12 * a4 * u + 6 * a3) * u + 2 * a2; };
  QuarticMax best{c[0] >= c[4] ? 0.0 : 1.0, std::max(c[0], c[4])};
  // Breakpoints: 0, roots of q'' in (0, 1), 1.
  double br[4];
  int nb = 0;
  br[nb++] = 0.0;
  const double A = 12 * a4, B = 6 * a3, C = 2 * a2;
  if (A != 0.0) {
    const double disc = B * B - 4 * A * C;
    if (disc > 0.0) {
      const double sq = std::sqrt(disc), qq = -0.5 * (B + (B >= 0 ? sq : -sq));
      double r1 = qq / A, r2 = qq != 0.0 ? C / qq : r1;
      if (r1 > r2) std::swap(r1, r2);
      if (r1 > 0.0 && r1 < 1.0) br[nb++] = r1;
      if (r2 > 0.0 && r2 < 1.0 && r2 != r1) br[nb++] = r2;
    }
  } else if (B != 0.0) {
    const double r = -C / B;
    if (r > 0.0 && r < 1.0) br[nb++] = r;
  }
  br[nb++] = 1.0;
  for (int k = 0; k + 1 < nb; ++k) {
    double lo = br[k], hi = br[k + 1];
    double flo = dq(lo), fhi = dq(hi);
    if (!(flo > 0.0 && fhi < 0.0)) continue;  // a maximum needs q' from + to -
    double u = 0.5 * (lo + hi);
    for (int it = 0; it < kQuarticSteps; ++it) {
      const double f = dq(u);
      if (f > 0.0) lo = u; else hi = u;
      const double d = ddq(u);
      double next = d != 0.0 ? u - f / d : 0.5 * (lo + hi);
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
      if (std::abs(next - u) <= 1e-15) { u = next; break; }
      u = next;
    }
    const double v = q(u);
    if (v > best.value) best = {u, v};
  }
  return best;
}

struct State {
  int sign = 0;        // +1 separate, 0 touching (within the band), -1 overlapping
  double u = 0.5;      // maximiser of u -> F(u, t)
  double value = 0.0;  // max_u F(u, t)
  double band = 0.0;   // touching band at t
};

enum class ChainEnd { Reached, Contact, Stalled };

class IntervalSolver {
 public:
  // E: entry-wise bound of the error of F's coefficients (every decision below widens its margin
  // by the matching combination of E). E_end: the same for the end rows u = 0 and u = 1 on their
  // own (CheckedCcdFunction::end_error), for the sign precondition only; empty when E is.
  IntervalSolver(const BivariateBernstein& F, const Eigen::MatrixXd& E, const Eigen::MatrixXd& E_end,
                 EllipsoidCcdResult* result)
      : F_(F), E_(E), E_end_(E_end), has_error_(E.size() > 0 && E.maxCoeff() > 0.0), result_(result) {
    const int n = F.degreeT();
    binomial_t_.resize(n + 1);
    for (int j = 0; j <= n; ++j) binomial_t_[j] = detail::binomial(n, j);
    basis_.resize(n + 1);
  }

  struct Piece {
    double begin, end;
    bool closed_begin, closed_end;  // the end point itself is certified separate
  };
  std::vector<Piece> separation;
  std::vector<double> overlap_times;  // instants certified overlapping (state -1)

  // The Bernstein coefficients in u of F(., t): rows of F dotted with the degree-n Bernstein
  // basis at t (all terms of one sign: relative accuracy ~ n ulps).
  // t -> F(u, t) in the Bernstein basis of [t0, t1]: the rows combined with B_i^4(u).
  // *error: the matching combination of E (the coefficients' error bound).
  BernsteinPolynomial atU(double u, std::vector<double>* error) const {
    const double v = 1.0 - u;
    const double w[5] = {v * v * v * v, 4 * u * v * v * v, 6 * u * u * v * v, 4 * u * u * u * v, u * u * u * u};
    const Eigen::MatrixXd& C = F_.coefficients();
    std::vector<double> g(C.cols());
    error->resize(C.cols());
    for (Eigen::Index j = 0; j < C.cols(); ++j) {
      g[j] = w[0] * C(0, j) + w[1] * C(1, j) + w[2] * C(2, j) + w[3] * C(3, j) + w[4] * C(4, j);
      (*error)[j] =
          has_error_ ? w[0] * E_(0, j) + w[1] * E_(1, j) + w[2] * E_(2, j) + w[3] * E_(3, j) + w[4] * E_(4, j) : 0.0;
    }
    return BernsteinPolynomial(std::move(g), F_.tLower(), F_.tUpper());
  }

  std::array<double, 5> rowsAt(double t) {
    const int n = F_.degreeT();
    const double x = (t - F_.tLower()) / (F_.tUpper() - F_.tLower()), y = 1.0 - x;
    double xp = 1.0;
    for (int j = 0; j <= n; ++j, xp *= x) basis_[j] = binomial_t_[j] * xp;
    double yp = 1.0;
    for (int j = n; j >= 0; --j, yp *= y) basis_[j] *= yp;
    std::array<double, 5> c{};
    const Eigen::MatrixXd& C = F_.coefficients();
    error_at_t_ = 0.0;
    for (int i = 0; i <= 4; ++i) {
      double v = 0.0;
      for (int j = 0; j <= n; ++j) v += C(i, j) * basis_[j];
      c[i] = v;
      if (has_error_) {
        double e = 0.0;
        for (int j = 0; j <= n; ++j) e += E_(i, j) * basis_[j];
        error_at_t_ = std::max(error_at_t_, e);
      }
      if (i == 0 || i == 4) {  // the ends' own bounds (the sign precondition in state())
        double v_abs = 0.0, e_end = 0.0;
        for (int j = 0; j <= n; ++j) v_abs += std::abs(C(i, j)) * basis_[j];
        if (has_error_)
          for (int j = 0; j <= n; ++j) e_end += E_end_(i / 4, j) * basis_[j];
        end_bound_[i / 4] = tolerance::kCcdTouchingRelative * v_abs + 2.0 * e_end;
      }
    }
    return c;
  }

  State state(double t) {
    ++result_->work;
    const std::array<double, 5> c = rowsAt(t);
    State s;
    double scale = 0.0;
    int best = 0;
    for (int i = 0; i <= 4; ++i) {
      scale = std::max(scale, std::abs(c[i]));
      if (c[i] > c[best]) best = i;
    }
    // The band also covers the coefficients' error bound: F(u, t) is a convex combination of the
    // c_i, so its error is at most max_i of theirs (an ill-conditioned motion widens the band
    // instead of certifying rounding noise).
    s.band = std::max(tolerance::kCcdTouchingRelative * scale, 2.0 * error_at_t_);
    // Theorem 5.1 needs F(0, t) = det A(t) < 0 and F(1, t) = det B(t) < 0 (two ellipsoids). A
    // computed end value not clearly negative means F is rounding noise here: not separate.
    // "Clearly" is relative to the end value's own evaluation, 2^-40 sum_j |C(i, j)| B_j(t), plus
    // twice that row's own error estimate (end_bound_, from E_end_), not to the state band
    // s.band: that band is relative to the largest c_i, and the interior c_i of two thin bodies
    // exceed the ends by up to their aspect ratios to the fourth power (det-balanced, det A ~
    // det B ~ -1); nor to E, whose rows all carry the interior rows' differences and rounding.
    // From aspect ~2^10 on, |det A| fell inside the band and a pair far apart was reported
    // touching at every instant (session 26, docs/reliability.md finding 21: first contact at
    // t = 0 in 26 of 60 grazing translations at aspect 1,000, 54 of 60 at 2,000 and 37 of 39 at
    // 5,000, most of them after running to the work cap).
    if (!(c[0] < -end_bound_[0] && c[4] < -end_bound_[1])) {
      s.sign = 0;
      s.value = std::max(c[0], c[4]);
      s.u = c[0] >= c[4] ? 0.05 : 0.95;
      return s;
    }
    if (c[best] < -s.band) {  // convex hull: F(., t) < 0, overlapping
      s.sign = -1;
      overlap_times.push_back(t);
      s.value = c[best];
      s.u = std::clamp(best / 4.0, 0.05, 0.95);
      return s;
    }
    // max over [0, 1] of the quartic: the ends (det A, det B < 0) and the critical points.
    const QuarticMax m = maximiseQuartic(c);
    s.value = m.value;
    s.u = m.u;
    s.sign = s.value > s.band ? 1 : (s.value < -s.band ? -1 : 0);
    if (s.sign < 0) overlap_times.push_back(t);
    return s;
  }

  // Repeated Bezier shoots from t1 (separate) toward t2 (thesis §5.3.1 BezierShoot, §5.3.3):
  // each shoot certifies F(u^, t) > 0 on [t_k, t_{k+1}) for u^ the maximiser at t_k.
  ChainEnd chain(double t1, State s1, double t2, bool rightward, double* end, State* s_end) {
    double t = t1;
    State s = s1;
    while (true) {
      if (result_->work >= tolerance::kCcdMaxWork) {
        result_->unresolved = true;
        *end = t;
        *s_end = s;
        return ChainEnd::Stalled;
      }
      ++result_->work;
      std::vector<double> margin;
      const BernsteinPolynomial g = atU(s.u, &margin);
      const double lo = rightward ? t : t2, hi = rightward ? t2 : t;
      const double t0 = F_.tLower(), w = F_.tUpper() - F_.tLower();
      std::vector<double> c = g.coefficients();
      const double ulps = tolerance::kCcdClipMarginUlps * static_cast<double>(c.size()) * tolerance::kUnitRoundoff;
      for (std::size_t j = 0; j < c.size(); ++j) margin[j] += ulps * std::abs(c[j]);
      restrictWithBound(&c, &margin, (lo - t0) / w, (hi - t0) / w);
      if (!rightward) {
        std::reverse(c.begin(), c.end());
        std::reverse(margin.begin(), margin.end());
      }
      const std::optional<double> root = firstRootLowerBound(std::move(c), std::move(margin));
      double next;
      if (!root) {
        next = t2;
      } else if (rightward) {
        next = std::min(hi, lo + *root * (hi - lo));
      } else {
        next = std::max(lo, hi - *root * (hi - lo));
      }
      if (!root) {
        *end = t2;
        *s_end = s;
        return ChainEnd::Reached;
      }
      const bool progressed = rightward ? next > t : next < t;
      if (!progressed) {  // cannot certify past t: treat t as contact (conservative)
        result_->near_tangent = true;
        *end = t;
        *s_end = s;
        s_end->sign = 0;
        return ChainEnd::Stalled;
      }
      t = next;
      s = state(t);
      // A shoot needs F(u^, t) above the touching band at its start: below it the sign of F is
      // not trusted (coefficient rounding), so entering the band ends the chain with a contact at
      // the current instant, which precedes the exact contact by at most band / |dF/dt|.
      if (s.sign <= 0) {
        *end = t;
        *s_end = s;
        return ChainEnd::Contact;
      }
    }
  }

  // Candidate overlap interval with max_u F <= band at both ends: certified colliding throughout
  // when on every u-slab either F <= band (convex hull) or F_t has one strict sign (then F is
  // monotone in t on each vertical line and cannot exceed its end values; no loop of the zero
  // set, thesis §5.3.1).
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

  bool overlapCertified(double t1, double t2, double band) {
    // Each slab counts as one unit of the solve's work (kCcdMaxWork): a slab restricts every
    // column of F, about the cost of a state evaluation. Uncounted, a solve that bisected down to
    // the work cap with a failing certificate at each step spent up to 127 slabs per unit: 7 s
    // for one degree-6 motion of fuzz_motion's corpus (docs/reliability.md, finding 39). The
    // certificate never changes the intervals (where it holds, F <= band throughout, so the
    // bisection would certify no separation there either), only the work spent.
    const int limit = std::min(tolerance::kCcdMaxSlabVisits, tolerance::kCcdMaxWork - result_->work);
    if (limit <= 0) return false;
    // F restricted to [t1, t2] in t, row by row in place (no allocation per row).
    RowMajor G = F_.coefficients();
    const int n = static_cast<int>(G.cols()) - 1;
    const double w = F_.tUpper() - F_.tLower();
    const double a = (t1 - F_.tLower()) / w, b = (t2 - F_.tLower()) / w;
    for (Eigen::Index i = 0; i < G.rows(); ++i) {
      if (a > 0.0) keepRight(G.row(i).data(), n, a);
      if (b < 1.0) keepLeft(G.row(i).data(), n, (b - a) / (1.0 - a));
    }
    RowMajor S(G.rows(), G.cols());
    int budget = limit;
    const bool certified = slabCertified(G, &S, 0.0, 1.0, band, 0, &budget);
    result_->work += limit - budget;
    return certified;
  }

  // G on [0, 1] in u; S is scratch space of the same size. At most *budget slabs (kCcdMaxSlabVisits,
  // or less at the end of the work budget; each examined slab takes one) down to depth
  // kCcdMaxSlabDepth: the budget goes where the slabs fail, e.g. to the u where F of two thin
  // bodies is largest (finding 21), instead of a full tree of depth 6.
  bool slabCertified(const RowMajor& G, RowMajor* S, double ua, double ub, double band, int depth, int* budget) {
    if (*budget <= 0) return false;
    --*budget;
    const int m = static_cast<int>(G.rows()) - 1;
    *S = G;
    if (ua > 0.0 || ub < 1.0) {  // restrict every column (degree 4 in u) to [ua, ub]
      double col[8];
      for (Eigen::Index j = 0; j < G.cols(); ++j) {
        for (int i = 0; i <= m; ++i) col[i] = G(i, j);
        if (ua > 0.0) keepRight(col, m, ua);
        if (ub < 1.0) keepLeft(col, m, (ub - ua) / (1.0 - ua));
        for (int i = 0; i <= m; ++i) (*S)(i, j) = col[i];
      }
    }
    if (S->maxCoeff() <= band) return true;
    // The Bernstein coefficients of F_t are positive multiples of the differences along t.
    bool increasing = true, decreasing = true;
    for (Eigen::Index i = 0; i < S->rows() && (increasing || decreasing); ++i) {
      for (Eigen::Index j = 0; j + 1 < S->cols(); ++j) {
        const double d = (*S)(i, j + 1) - (*S)(i, j);
        increasing = increasing && d > 0.0;
        decreasing = decreasing && d < 0.0;
      }
    }
    if (increasing || decreasing) return true;
    if (depth >= tolerance::kCcdMaxSlabDepth) return false;
    const double um = 0.5 * (ua + ub);
    return slabCertified(G, S, ua, um, band, depth + 1, budget) && slabCertified(G, S, um, ub, band, depth + 1, budget);
  }

  void process(double t1, State s1, double t2, State s2) {
    if (result_->work >= tolerance::kCcdMaxWork) {
      result_->unresolved = true;
      return;  // left uncertified: reported colliding
    }
    if (s1.sign > 0) {
      double x;
      State sx;
      const ChainEnd e = chain(t1, s1, t2, true, &x, &sx);
      if (x > t1) separation.push_back({t1, x, true, e == ChainEnd::Reached && s2.sign > 0});
      if (e == ChainEnd::Reached) return;
      if (sx.sign > 0) sx.sign = 0;  // stalled: treated as contact
      if (e == ChainEnd::Stalled && result_->unresolved) return;
      process(x, sx, t2, s2);
      return;
    }
    if (s2.sign > 0) {
      double y;
      State sy;
      const ChainEnd e = chain(t2, s2, t1, false, &y, &sy);
      if (y < t2) separation.push_back({y, t2, e == ChainEnd::Reached && s1.sign > 0, true});
      if (e == ChainEnd::Reached) return;
      if (sy.sign > 0) sy.sign = 0;
      if (e == ChainEnd::Stalled && result_->unresolved) return;
      process(t1, s1, y, sy);
      return;
    }
    if (t2 - t1 <= tolerance::kCcdMinIntervalWidth) return;  // Remark 5.4: reported colliding
    if (overlapCertified(t1, t2, std::max(s1.band, s2.band))) return;
    const double m = 0.5 * (t1 + t2);
    const State sm = state(m);
    process(t1, s1, m, sm);
    process(m, sm, t2, s2);
  }

 private:
  const BivariateBernstein& F_;
  const Eigen::MatrixXd& E_;
  const Eigen::MatrixXd& E_end_;
  bool has_error_;  // E is not all zero (the precision check ran)
  EllipsoidCcdResult* result_;
  double error_at_t_ = 0.0;  // set by rowsAt: max_i error bound of c_i(t)
  // Set by rowsAt: the bounds 2^-40 sum_j |C(i, j)| B_j(t) + 2 E_end(i, t) of the end rows i = 0, 4.
  double end_bound_[2] = {0.0, 0.0};
  std::vector<double> binomial_t_;
  std::vector<double> basis_;
};

// Collision intervals: the complement in [0, tmax] of the certified separation pieces.
void assemble(std::vector<IntervalSolver::Piece> pieces, double tmax, EllipsoidCcdResult* r) {
  std::sort(pieces.begin(), pieces.end(), [](const auto& x, const auto& y) { return x.begin < y.begin; });
  std::vector<IntervalSolver::Piece> merged;
  for (const auto& p : pieces) {
    if (!merged.empty() && (p.begin < merged.back().end ||
                            (p.begin == merged.back().end && (merged.back().closed_end || p.closed_begin)))) {
      if (p.end > merged.back().end) {
        merged.back().end = p.end;
        merged.back().closed_end = p.closed_end;
      } else if (p.end == merged.back().end) {
        merged.back().closed_end = merged.back().closed_end || p.closed_end;
      }
      continue;
    }
    merged.push_back(p);
  }
  double cursor = 0.0;
  bool cursor_covered = false;  // is `cursor` itself certified separate?
  for (const auto& p : merged) {
    r->separation_intervals.push_back({p.begin, p.end});
    const bool gap = p.begin > cursor || (!cursor_covered && !p.closed_begin);
    if (gap) r->collision_intervals.push_back({cursor, p.begin});
    cursor = p.end;
    cursor_covered = p.closed_end;
  }
  if (cursor < tmax || !cursor_covered) {
    if (!(cursor == tmax && cursor_covered)) r->collision_intervals.push_back({cursor, tmax});
  }
  r->collide = !r->collision_intervals.empty();
  if (r->collide) r->first_contact_time = r->collision_intervals.front().begin;
}

// World point of contact at local time t: the centre of the pencil member (1-u) A + u B.
Eigen::Vector3d pencilCentre(const PolynomialMatrix4& A, const PolynomialMatrix4& B, double t, double u) {
  const Eigen::Matrix4d Q = (1.0 - u) * A.evaluate(t) + u * B.evaluate(t);
  return -Q.topLeftCorner<3, 3>().ldlt().solve(Q.block<3, 1>(0, 3));
}

// The pencil of one segment as the solver uses it: A(t), B(t) in scaled coordinates y = S^{-1} x
// (origin between the centres ca0, cb0 at t = 0, unit ~ the largest radius), balanced, and F(u, t)
// normalised to largest coefficient 1, with the error estimate E of F's coefficients (zero unless
// the precision check ran). Empty when the moving quadrics or the affine interpolant's end states
// are not representable in double (overflow).
struct SegmentPencil {
  ScaledQuadric A, B;
  Eigen::Matrix4d S = Eigen::Matrix4d::Identity();
  BivariateBernstein F;
  Eigen::MatrixXd E;
  Eigen::MatrixXd E_end;  ///< CheckedCcdFunction::end_error (the sign precondition's estimate)
  bool precision_checked = false;  ///< condition above kCcdCheckedCondition (diagnostic)
};

std::optional<SegmentPencil> segmentPencil(const MovingEllipsoid& a, const MotionMatrix& ma, const MovingEllipsoid& b,
                                           const MotionMatrix& mb, const Eigen::Vector3d& ca0, const Eigen::Vector3d& cb0,
                                           bool affine, double condition) {
  SegmentPencil p;
  const double L = std::max(a.body.radii().maxCoeff(), b.body.radii().maxCoeff());
  p.S.topLeftCorner<3, 3>() *= L;
  if (!affine) {
    p.S.block<3, 1>(0, 3) = 0.5 * (ca0 + cb0);
    // A motion whose affine map M / w overflows (w(t) ~ 1e-308 passes validation: it has no root)
    // has no representable moving quadric: no pencil (the caller's conservative fallback).
    if (!p.S.array().isFinite().all()) return std::nullopt;
    try {
      p.A = scaledQuadric(a.body.quadricMatrix(), ma.inverseCoefficients(), p.S);
      p.B = scaledQuadric(b.body.quadricMatrix(), mb.inverseCoefficients(), p.S);
    } catch (const std::invalid_argument&) {
      return std::nullopt;  // a coefficient overflowed to inf / NaN (Polynomial rejects it)
    }
    // Precision check (docs/algorithms.md section 8): F is rebuilt in extended precision from N's
    // extended coefficients and the difference widens every margin (finding 8: a shear of
    // condition 6e7 was certified separate on rounding noise). Every rigid pair since session 18:
    // the touching band 2^-40 max|c_i(t)| is relative to F's value at t, but F's rounding is
    // relative to its coefficients over the whole segment, and at a grazing instant F(., t) is
    // 1e-5 .. 1e-7 of those, so even a pair of aspect ratio 50-100 under a pure translation could
    // be certified separate on rounding noise (finding 16: computed max_u F = +4e-15 against a band
    // of 6e-19 where the exact pair overlaps). precision_checked still flags the ill-conditioned
    // pairs (condition above kCcdCheckedCondition), whose answers the estimate moves further
    // toward contact.
    CheckedCcdFunction checked = ccdFunctionChecked(
        p.A.Q, p.B.Q, scaledQuadricExtended(a.body, ma.inverseCoefficientsExtended(), p.S, p.A.scale),
        scaledQuadricExtended(b.body, mb.inverseCoefficientsExtended(), p.S, p.B.scale));
    p.F = std::move(checked.F);
    p.E = std::move(checked.error);
    p.E_end = std::move(checked.end_error);
    p.precision_checked = condition > tolerance::kCcdCheckedCondition;
  } else {
    // In a's body frame: a is constant, b's shape and centre are interpolated (thesis §5.2).
    Eigen::Matrix3d Bs[2];
    Eigen::Vector3d cs[2];
    for (int k = 0; k < 2; ++k) {
      const Eigen::Matrix4d Ta = ma.evaluate(k);
      std::optional<Ellipsoid> bk;
      try {
        bk = worldEllipsoid(b.body, mb, k);
      } catch (const std::invalid_argument&) {
        return std::nullopt;  // b's end state is not representable: no interpolant
      }
      const Eigen::Matrix3d Lin = Ta.topLeftCorner<3, 3>().inverse();
      cs[k] = Lin * (bk->center() - Ta.block<3, 1>(0, 3));
      // b's shape in a's frame, B = (Lb Lb^T)^-1 with Lb = Lin R_b diag(r_b), formed from its
      // inverse factor Lb^-1 = diag(1/r_b) R_b^T Ta_lin (R_b orthonormal): inverting Lb Lb^T in
      // double amplified rounding by its condition, the aspect ratio squared (at aspect 100 the
      // interpolant's b was 1e-8 of its length too long or short along its long axis; finding 18).
      const Eigen::Matrix3d Linv = bk->radii().cwiseInverse().asDiagonal() * bk->rotation().transpose() * Ta.topLeftCorner<3, 3>();
      Bs[k] = Linv.transpose() * Linv;
      // a's map so ill-conditioned that b's end state in a's frame overflows: no interpolant, as
      // for the rigid path above. Such maps are refused by their condition first (finding 42's
      // motion reached here while MotionMatrix::linearCondition() lost a NaN); this is reached
      // with max_condition raised above them, where the overflow may also form inf - inf before
      // it is seen (harmless without floating-point traps: Polynomial rejects it, caught below).
      if (!cs[k].allFinite() || !Bs[k].allFinite()) return std::nullopt;
    }
    p.S.block<3, 1>(0, 3) = 0.5 * (a.body.center() + cs[0]);
    if (!p.S.array().isFinite().all()) return std::nullopt;
    double b_scale = 1.0;
    try {
      p.A = scaledQuadric(a.body.quadricMatrix(), {Eigen::Matrix4d::Identity()}, p.S);
      const PolynomialMatrix4 Bq = affineInterpolant(Bs[0], cs[0], Bs[1], cs[1], p.S);
      b_scale = balanceScale(Bq);
      p.B = {balanced(Bq, b_scale), 1.0};
    } catch (const std::invalid_argument&) {
      return std::nullopt;  // a coefficient overflowed to inf / NaN (Polynomial rejects it)
    }
    // The precision check as for rigid pairs (finding 16 holds for the interpolant too: F's
    // rounding is relative to its coefficients, the touching band to F's value at t). a's
    // quadric and the interpolant are rebuilt in extended precision from the same inputs (the
    // interpolant is defined by b's end states B_k, c_k in a's frame, as computed above).
    CheckedCcdFunction checked = ccdFunctionChecked(
        p.A.Q, p.B.Q, scaledQuadricExtended(a.body, {Matrix4ld::Identity()}, p.S, p.A.scale),
        affineInterpolantExtended(Bs[0], cs[0], Bs[1], cs[1], p.S, b_scale));
    p.F = std::move(checked.F);
    p.E = std::move(checked.error);
    p.E_end = std::move(checked.end_error);
    p.precision_checked = condition > tolerance::kCcdCheckedCondition;
  }
  const double m = p.F.coefficients().cwiseAbs().maxCoeff();
  if (m > 0.0 && std::isfinite(m)) {
    p.F = BivariateBernstein(p.F.coefficients() / m);
    p.E /= m;
    p.E_end /= m;
  }
  return p;
}

// World centre of a moving ellipsoid at local time 0 (no eigen-decomposition); empty when the
// affine map M(0) / w(0) overflows (checked before any product, so that no inf * 0 is formed;
// isFinite, not allFinite, which computes x - x and raises FE_INVALID on inf).
std::optional<Eigen::Vector3d> centreAtStart(const MovingEllipsoid& e, const MotionMatrix& m) {
  const Eigen::Matrix4d T = m.evaluate(0.0);
  if (!T.array().isFinite().all()) return std::nullopt;
  const Eigen::Vector3d c = T.topLeftCorner<3, 3>() * e.body.center() + T.block<3, 1>(0, 3);
  if (!c.array().isFinite().all()) return std::nullopt;
  return c;
}

// One segment: both motions are single rational pieces on the local [0, 1]; t_max local.
// `work_used`: the work already spent on earlier segments of the same piece of the motions (the
// cap, kCcdMaxWork, holds per piece).
EllipsoidCcdResult solveSegment(const MovingEllipsoid& a, const MotionMatrix& ma, const MovingEllipsoid& b,
                                const MotionMatrix& mb, double tmax, const CcdOptions& opt, int work_used = 0) {
  EllipsoidCcdResult r;
  r.work = work_used;
  r.segments = 1;
  const bool affine = opt.interpolation == CcdInterpolation::Affine;
  if (opt.culling && !affine && ma.isRigid() && mb.isRigid() && sphereCull(a, ma, b, mb)) {
    r.culled_by = 1;
    r.separation_intervals.push_back({0.0, tmax});
    return r;
  }
  const std::optional<Eigen::Vector3d> ca = centreAtStart(a, ma), cb = centreAtStart(b, mb);
  auto conservative = [&] {
    r.unresolved = true;
    r.collide = true;
    r.first_contact_time = 0.0;
    r.collision_intervals.push_back({0.0, opt.all_intervals ? tmax : 0.0});
    // Indicative only: the midpoint of the centres at t = 0, or whichever centre exists (a motion
    // whose map overflows has none; NaN never leaks into a result).
    r.contact_point = ca && cb ? Eigen::Vector3d(0.5 * (*ca + *cb)) : cb ? *cb : ca ? *ca : Eigen::Vector3d::Zero();
    return r;
  };
  // A map that overflows (w(t) ~ 1e-308 passes validation: it has no root) has no representable
  // quadric: conservative fallback, as beyond kCcdMaxCondition, where even the extended-precision
  // F is rounding noise (docs/algorithms.md section 8).
  if (!ca || !cb) return conservative();
  const Eigen::Vector3d ca0 = *ca, cb0 = *cb;
  const double condition = std::max(quadricCondition(a.body, ma), quadricCondition(b.body, mb));
  if (!(condition <= opt.max_condition)) return conservative();
  // The world ellipsoids at t = 0 feed the plane cull and the first-contact static test only; an
  // ill-conditioned affine map may have none representable (Ellipsoid::fromAffine throws), and
  // then both shortcuts are skipped.
  std::optional<Ellipsoid> a0, b0;
  try {
    a0 = worldEllipsoid(a.body, ma, 0.0);
    b0 = worldEllipsoid(b.body, mb, 0.0);
  } catch (const std::invalid_argument&) {
    a0.reset();
    b0.reset();
  }
  // Rigid motions only for the plane cull: the plane is carried into b's body frame by
  // evaluate(0), exact to rounding for a rigid b (an ill-conditioned affine b would move it).
  if (opt.culling && !affine && a0 && b0 && ma.isRigid() && mb.isRigid()) {
    const std::optional<SeparatingPlane> sp = separatingPlane(*a0, *b0);
    if (sp && sp->certified && planeCull(a, ma, mb, sp->plane)) {
      r.culled_by = 2;
      r.separation_intervals.push_back({0.0, tmax});
      return r;
    }
  }
  if (!opt.all_intervals && !affine && a0 && b0) {
    // First contact only: a pair not separate at t = 0 (certified static test, Theorem 4.1)
    // collides at 0; no CCD function is needed.
    const SeparationCertificate c0 = classifyEllipsoids(*a0, *b0);
    if (c0.status != Separation::Separated) {
      r.collide = true;
      r.first_contact_time = 0.0;
      r.collision_intervals.push_back({0.0, 0.0});
      r.contact_point = c0.witness;
      r.near_tangent = c0.status == Separation::Touching;
      return r;
    }
  }

  const std::optional<SegmentPencil> pencil = segmentPencil(a, ma, b, mb, ca0, cb0, affine, condition);
  if (!pencil) return conservative();
  const PolynomialMatrix4& A = pencil->A.Q;
  const PolynomialMatrix4& B = pencil->B.Q;
  const Eigen::Matrix4d& S = pencil->S;
  const BivariateBernstein& F = pencil->F;
  r.precision_checked = pencil->precision_checked;
  r.degree_t = F.degreeT();

  IntervalSolver solver(F, pencil->E, pencil->E_end, &r);
  const State s0 = solver.state(0.0);
  double t_contact = 0.0;
  double u_contact = s0.u;
  if (!opt.all_intervals) {
    if (s0.sign > 0) {
      double x;
      State sx;
      const ChainEnd e = solver.chain(0.0, s0, tmax, true, &x, &sx);
      if (e == ChainEnd::Reached) {
        r.separation_intervals.push_back({0.0, tmax});
        return r;
      }
      r.separation_intervals.push_back({0.0, x});
      t_contact = x;
      u_contact = sx.u;
      // A contact inside the touching band with no overlap just after it may be a grazing touch.
      if (sx.sign == 0 && (x >= tmax || solver.state(std::min(tmax, x + tolerance::kCcdMinIntervalWidth)).sign >= 0))
        r.near_tangent = true;
    }
    r.collide = true;
    r.first_contact_time = t_contact;
    r.collision_intervals.push_back({t_contact, t_contact});
  } else {
    const State s1 = solver.state(tmax);
    solver.process(0.0, s0, tmax, s1);
    assemble(solver.separation, tmax, &r);
    if (!r.collide) return r;
    // near_tangent: some collision interval holds no instant certified overlapping (probe its
    // midpoint once): it may be a touch within the band, not a true overlap.
    for (const CcdInterval& c : r.collision_intervals) {
      bool witnessed = false;
      for (double t : solver.overlap_times) witnessed = witnessed || (t >= c.begin && t <= c.end);
      if (!witnessed) witnessed = solver.state(0.5 * (c.begin + c.end)).sign < 0;
      if (!witnessed) r.near_tangent = true;
    }
    t_contact = *r.first_contact_time;
    u_contact = t_contact == 0.0 ? s0.u : solver.state(t_contact).u;
  }
  Eigen::Vector3d x = pencilCentre(A, B, t_contact, u_contact);
  x = S.topLeftCorner<3, 3>() * x + S.block<3, 1>(0, 3);
  if (affine) {  // back from a's body frame to the world with a's motion
    const Eigen::Matrix4d Ta = ma.evaluate(t_contact);
    x = Ta.topLeftCorner<3, 3>() * x + Ta.block<3, 1>(0, 3);
  }
  r.contact_point = x;
  return r;
}

// The relative position of two spheres whose centres move on segments, D(t) = e0 + t (e1 - e0)
// with e0 = b0 - a0 and e1 = b1 - a1 (each exact as a double-double by TwoSum), and the gap
// function f(t) = |D(t)|^2 - R^2, R = ra + rb (exact), convex in t. Evaluated in double-double: a
// few operations of relative error below 2^-104 each (double_double.h), so the error of f is below
// 2^-99 of its absolute evaluation sum_i m_i^2 + R^2 with m_i = |e0_i| + |t| (|e0_i| + |e1_i|) a
// bound of |D_i| and of its evaluation, and the error of the slope f'/2 = D.(e1 - e0) below 2^-99
// of sum_i m_i (|e0_i| + |e1_i|); kSphereGapError = 2^-90 covers both with a wide margin.
class SphereGap {
 public:
  SphereGap(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& b0, const Eigen::Vector3d& b1,
            double ra, double rb) {
    for (int i = 0; i < 3; ++i) {
      e0_[i] = detail::twoSum(b0[i], -a0[i]);
      const DoubleDouble e1 = detail::twoSum(b1[i], -a1[i]);
      V_[i] = e1 - e0_[i];
      vmag_[i] = std::fabs(e0_[i].hi) + std::fabs(e1.hi);
    }
    const DoubleDouble R = detail::twoSum(ra, rb);
    R2_ = R * R;
  }

  /// t at or before the first root of f (or f has none): f(t) >= 0 and f'(t) <= 0, certified.
  bool beforeFirstRoot(double t) const { return certified(t, -1); }
  /// t at or after the last root of f (or f has none): f(t) >= 0 and f'(t) >= 0, certified.
  bool afterLastRoot(double t) const { return certified(t, +1); }

  /// The first root of f near t (two Newton steps in double-double from the double root t; t
  /// itself when the slope there is not clearly negative), then moved earlier until
  /// beforeFirstRoot() certifies it: a contact time never later than the exact first contact. The
  /// steps double from 2^-52 max(t, 2^-40); after 64 of them (not expected) t = 0, which is never
  /// late either (the pair is then reported colliding from the start).
  double notLaterThanFirstRoot(double t) const {
    t = newton(t);
    double step = 0x1p-52 * std::max(t, 0x1p-40);
    for (int i = 0; i < 64 && t > 0.0; ++i, step *= 2.0) {
      if (beforeFirstRoot(t)) return t;
      t = std::max(0.0, t - step);
    }
    return 0.0;
  }
  /// The same at the other end: the last root near t, moved later until afterLastRoot() certifies
  /// it, capped at t_max (and t_max after 64 steps): a collision interval never ends early.
  double notEarlierThanLastRoot(double t, double t_max) const {
    t = std::min(newton(t), t_max);
    double step = 0x1p-52 * std::max(t, 0x1p-40);
    for (int i = 0; i < 64 && t < t_max; ++i, step *= 2.0) {
      if (afterLastRoot(t)) return t;
      t = std::min(t_max, t + step);
    }
    return t_max;
  }
  /// f(t) minus its error bound: a lower bound of the exact gap function at t.
  double lowerBound(double t) const {
    const Value v = at(t);
    return toDouble(v.f - DoubleDouble(v.f_err));
  }

 private:
  static constexpr double kSphereGapError = 0x1p-90;
  struct Value {
    DoubleDouble f, slope;  // f(t) and f'(t) / 2
    double f_err = 0.0, slope_err = 0.0;
  };
  Value at(double t) const {
    Value v;
    v.f = -R2_;
    double mag_f = std::fabs(R2_.hi), mag_s = 0.0;
    for (int i = 0; i < 3; ++i) {
      const DoubleDouble D = e0_[i] + DoubleDouble(t) * V_[i];
      const double m = std::fabs(e0_[i].hi) + std::fabs(t) * vmag_[i];
      v.f += D * D;
      v.slope += D * V_[i];
      mag_f += m * m;
      mag_s += m * vmag_[i];
    }
    // The bounds are rounded up by the factor (1 + 2^-40), far above their own rounding.
    v.f_err = kSphereGapError * mag_f * (1.0 + 0x1p-40);
    v.slope_err = kSphereGapError * mag_s * (1.0 + 0x1p-40);
    return v;
  }
  bool certified(double t, int slope_sign) const {
    const Value v = at(t);
    if (!(v.f >= DoubleDouble(v.f_err))) return false;
    return slope_sign < 0 ? v.slope <= DoubleDouble(-v.slope_err) : v.slope >= DoubleDouble(v.slope_err);
  }
  // Two Newton steps on f from t; t unchanged when a step leaves [t - 2^-20, t + 2^-20] or the
  // slope is not clearly away from 0 (a grazing double root: the certification then steps).
  double newton(double t) const {
    double x = t;
    for (int k = 0; k < 2; ++k) {
      const Value v = at(x);
      if (!(abs(v.slope) > DoubleDouble(4.0 * v.slope_err))) break;
      const double next = toDouble(DoubleDouble(x) - v.f / (DoubleDouble(2.0) * v.slope));
      if (!(std::fabs(next - t) <= 0x1p-20)) return t;
      x = next;
    }
    return x;
  }

  DoubleDouble e0_[3], V_[3], R2_;
  double vmag_[3];
};

// Two spheres centred at their body origins under motions from poses: the centres move on
// segments, so |d0 + t v|^2 = R^2 is a quadratic and the collision interval is in closed form
// (no CCD function). Empty optional when the pair is not of that kind. The roots come from the
// quadratic formula in double and are then made conservative in double-double (SphereGap): the
// first contact is never later than the exact one and the end of the collision interval never
// earlier (finding 16 of docs/reliability.md: at grazing contacts the double roots were late by
// up to 7e-11). The touching decision uses the same certified lower bound of the gap.
std::optional<EllipsoidCcdResult> movingSpheres(const MovingEllipsoid& a, const MovingEllipsoid& b, const CcdOptions& opt) {
  const MotionMatrix& ma = a.motion.pieces().front();
  const MotionMatrix& mb = b.motion.pieces().front();
  auto isSphere = [](const Ellipsoid& e) {
    return e.radii().minCoeff() == e.radii().maxCoeff() && e.center() == Eigen::Vector3d::Zero();
  };
  if (!isSphere(a.body) || !isSphere(b.body) || !ma.linearTranslation() || !mb.linearTranslation()) return std::nullopt;
  const auto& [a0, a1] = *ma.linearTranslation();
  const auto& [b0, b1] = *mb.linearTranslation();
  const double ra = a.body.radii()[0], rb = b.body.radii()[0], R = ra + rb;
  const Eigen::Vector3d d0 = b0 - a0, v = (b1 - b0) - (a1 - a0);
  const double qa = v.squaredNorm(), qb = 2.0 * d0.dot(v), qc = d0.squaredNorm() - R * R;
  const double tmax = opt.t_max;
  const SphereGap gap(a0, a1, b0, b1, ra, rb);
  // Touching band: relative to R^2 as the static test's (2^-40).
  const double band = tolerance::kCertificateRelativeBoundDouble * R * R;
  EllipsoidCcdResult r;
  double t_in = 0.0, t_out = -1.0;  // the collision interval [t_in, t_out] of the quadratic
  if (gap.lowerBound(0.0) <= band) {
    t_in = 0.0;
    t_out = qa > 0.0 ? (-qb + std::sqrt(std::max(0.0, qb * qb - 4 * qa * qc))) / (2 * qa) : tmax;
    if (qa == 0.0) t_out = tmax;
  } else if (qa > 0.0) {
    const double disc = qb * qb - 4 * qa * qc;
    const double tv = std::clamp(-qb / (2 * qa), 0.0, tmax);  // closest approach in [0, tmax]
    // f(tv) exceeds the minimum of f over [0, tmax] by qa (tv - t*)^2, negligible for the
    // rounding of tv; its certified lower bound decides touching, erring toward contact.
    const double dmin = gap.lowerBound(tv);
    if (dmin <= band) {
      const double sq = std::sqrt(std::max(disc, 0.0));
      const double q = -0.5 * (qb + (qb >= 0 ? sq : -sq));  // stable roots q/qa and qc/q
      double r1 = q / qa, r2 = q != 0.0 ? qc / q : r1;
      if (r1 > r2) std::swap(r1, r2);
      t_in = std::max(0.0, disc > 0.0 ? r1 : tv);
      t_out = disc > 0.0 ? r2 : tv;
      r.near_tangent = dmin > -band;
    }
  }
  if (t_out < t_in || t_in > tmax) {
    r.separation_intervals.push_back({0.0, tmax});
    return r;
  }
  if (t_in > 0.0) t_in = gap.notLaterThanFirstRoot(t_in);
  t_out = t_out >= tmax ? tmax : gap.notEarlierThanLastRoot(std::max(t_out, t_in), tmax);
  r.collide = true;
  r.first_contact_time = t_in;
  r.collision_intervals.push_back({t_in, opt.all_intervals ? t_out : t_in});
  if (t_in > 0.0) r.separation_intervals.push_back({0.0, t_in});
  if (opt.all_intervals && t_out < tmax) r.separation_intervals.push_back({t_out, tmax});
  const Eigen::Vector3d ca = a0 + t_in * (a1 - a0), cb = b0 + t_in * (b1 - b0);
  const Eigen::Vector3d dc = cb - ca;
  r.contact_point = dc.norm() > 0.0 ? Eigen::Vector3d(ca + dc * (ra / R)) : ca;
  return r;
}

// --- Balance breaks (docs/algorithms.md section 8, "Nearly vanishing w") ----------------------
// M and g(t) M are the same motion for a scalar polynomial g without roots in [0, 1], but the
// moving quadric N^T Q N of such a matrix carries g's powers, and when g nearly vanishes near
// [0, 1] (finding 9: roots at -1e-8 and 1 + 1e-8) the pencil det(lambda A(t) - B(t)) drifts far
// from its balance lambda ~ -1 (balanceScale) along the segment: the maximiser u of F(u, t)
// slides toward u = 0 or 1, and each Bezier shoot along a fixed u certifies only a sliver of t.
// On a segment where the weights of the two motions keep their ratio within kCcdBalanceRatio the
// per-segment balancing holds, so the segment is bisected until they do. Which breaks are chosen
// never changes an answer: every segment is solved exactly on the restricted motions.

// The homogeneous matrix of `m` at global time t, from piece k (no division by w).
Eigen::Matrix4d homogeneousAt(const PiecewiseMotion& m, std::size_t k, double t) {
  const std::vector<double>& br = m.breaks();
  return m.pieces()[k].homogeneous((t - br[k]) / (br[k + 1] - br[k]));
}

std::size_t pieceOf(const PiecewiseMotion& m, double t) {
  const std::vector<double>& br = m.breaks();
  const auto it = std::upper_bound(br.begin(), br.end(), t);
  const std::size_t k = it == br.begin() ? 0 : static_cast<std::size_t>(it - br.begin()) - 1;
  return std::min(k, m.pieces().size() - 1);
}

// True when the weight ratio or the linear-scale ratio of the two motions varies by more than
// kCcdBalanceRatio over 9 samples of [s0, s1] (a heuristic: the breaks are a matter of speed).
// A zero or non-finite sample counts as unbalanced (the depth cap ends the bisection).
bool unbalanced(const MovingEllipsoid& a, const MovingEllipsoid& b, double s0, double s1) {
  const double mid = 0.5 * (s0 + s1);
  const std::size_t ka = pieceOf(a.motion, mid), kb = pieceOf(b.motion, mid);
  double w_lo = std::numeric_limits<double>::infinity(), w_hi = 0.0;
  double l_lo = std::numeric_limits<double>::infinity(), l_hi = 0.0;
  constexpr int kSamples = 8;
  for (int i = 0; i <= kSamples; ++i) {
    const double t = s0 + (s1 - s0) * i / kSamples;
    const Eigen::Matrix4d Ma = homogeneousAt(a.motion, ka, t), Mb = homogeneousAt(b.motion, kb, t);
    const double wa = std::abs(Ma(3, 3)), wb = std::abs(Mb(3, 3));
    const double la = std::abs(Ma.topLeftCorner<3, 3>().determinant()), lb = std::abs(Mb.topLeftCorner<3, 3>().determinant());
    // Finiteness first and no division by zero: an ordered comparison with NaN raises FE_INVALID
    // and x / 0 FE_DIVBYZERO (both trapped by the tests); a weight or determinant that underflows
    // or overflows here is judged unbalanced.
    if (!(std::isfinite(wa) && std::isfinite(wb) && std::isfinite(la) && std::isfinite(lb))) return true;
    if (wa == 0.0 || wb == 0.0 || la == 0.0 || lb == 0.0) return true;
    const double rw = wa / wb, rl = std::cbrt(la / lb);
    if (!(std::isfinite(rw) && std::isfinite(rl) && rw > 0.0 && rl > 0.0)) return true;
    w_lo = std::min(w_lo, rw);
    w_hi = std::max(w_hi, rw);
    l_lo = std::min(l_lo, rl);
    l_hi = std::max(l_hi, rl);
  }
  return w_hi > tolerance::kCcdBalanceRatio * w_lo || l_hi > tolerance::kCcdBalanceRatio * l_lo;
}

// Appends the right ends of the balanced sub-segments of [s0, s1] (bisection, capped: depth, and
// `*budget` segments for the piece being refined).
void balanceBreaks(const MovingEllipsoid& a, const MovingEllipsoid& b, double s0, double s1, int depth,
                   int* budget, std::vector<double>* out) {
  const double mid = 0.5 * (s0 + s1);
  if (depth < tolerance::kCcdMaxBalanceDepth && *budget > 1 && s0 < mid && mid < s1 && unbalanced(a, b, s0, s1)) {
    --*budget;  // one segment becomes two
    balanceBreaks(a, b, s0, mid, depth + 1, budget, out);
    balanceBreaks(a, b, mid, s1, depth + 1, budget, out);
    return;
  }
  out->push_back(s1);
}

// The union of both break sequences, clipped to [0, t_max].
std::vector<double> segmentBreaks(const MovingEllipsoid& a, const MovingEllipsoid& b, double tmax) {
  std::vector<double> breaks = a.motion.breaks();
  breaks.insert(breaks.end(), b.motion.breaks().begin(), b.motion.breaks().end());
  breaks.push_back(tmax);
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
  breaks.erase(std::remove_if(breaks.begin(), breaks.end(), [&](double x) { return x > tmax; }), breaks.end());
  return breaks;
}

// The segments the solver cuts [0, t_max] into: the breaks of both piecewise motions, each piece
// interval refined by balanceBreaks (skipped when both motions are single pieces from poses) into
// at most kCcdMaxBalanceSegments segments. `piece_starts`, when given, receives for each segment
// whether it begins a piece (where the work cap kCcdMaxWork starts afresh).
std::vector<double> solverBreaks(const MovingEllipsoid& a, const MovingEllipsoid& b, double tmax, bool from_poses,
                                 std::vector<bool>* piece_starts = nullptr) {
  const std::vector<double> piece_breaks = segmentBreaks(a, b, tmax);
  std::vector<double> breaks{piece_breaks.front()};
  for (std::size_t k = 0; k + 1 < piece_breaks.size(); ++k) {
    const std::size_t first = breaks.size() - 1;  // index of the piece's first segment
    if (from_poses) {
      breaks.push_back(piece_breaks[k + 1]);
    } else {
      // The segment cap holds per piece, as the work cap does: until session 53 it counted every
      // break of the query, so a motion of more than 256 pieces got no balance breaks after them.
      int budget = tolerance::kCcdMaxBalanceSegments;
      balanceBreaks(a, b, piece_breaks[k], piece_breaks[k + 1], 0, &budget, &breaks);
    }
    if (piece_starts) {
      piece_starts->resize(breaks.size() - 1, false);
      (*piece_starts)[first] = true;
    }
  }
  return breaks;
}

// c'_j of ccdFunctionDegree(): the degree of column j of N(t) S over the motion's pieces, S
// mixing every column of N into the last one (segmentPencil()'s frame).
std::array<int, 4> columnDegrees(const PiecewiseMotion& motion) {
  std::array<int, 4> c{0, 0, 0, 0};
  for (const MotionMatrix& m : motion.pieces()) {
    const std::vector<Eigen::Matrix4d>& N = m.inverseCoefficients();
    for (int k = static_cast<int>(N.size()) - 1; k > 0; --k)
      for (int j = 0; j < 4; ++j)
        if (c[j] < k && !N[k].col(j).isZero(0.0)) c[j] = k;
  }
  c[3] = *std::max_element(c.begin(), c.end());
  return c;
}

// The up-front degree check of the exact solver (tolerance::kCcdMaxDegree): above it the
// Bernstein conversions would leave their binomial tables, and the culls would run on overflowed
// coefficients (session 34: a translation of degree 512 was "certified" collision-free).
void checkCcdDegree(const MovingEllipsoid& a, const MovingEllipsoid& b, const char* where) {
  const int degree = ccdFunctionDegree(a, b);
  if (degree > tolerance::kCcdMaxDegree) {
    std::ostringstream os;
    os << where << ": the motions give a CCD function of degree " << degree << " in t, above kCcdMaxDegree = "
       << tolerance::kCcdMaxDegree << " (split a motion into pieces of lower degree, or use the affine interpolation)";
    throw CcdDegreeError(os.str(), degree, tolerance::kCcdMaxDegree);
  }
}

}  // namespace

int ccdFunctionDegree(const MovingEllipsoid& a, const MovingEllipsoid& b) {
  const std::array<int, 4> ca = columnDegrees(a.motion), cb = columnDegrees(b.motion);
  int sum = 0;
  for (int j = 0; j < 4; ++j) sum += std::max(ca[j], cb[j]);
  return 2 * sum;
}

EllipsoidCcdResult continuousCollideEllipsoids(const MovingEllipsoid& a, const MovingEllipsoid& b,
                                               const CcdOptions& options) {
  // std::isnan first: an ordered comparison with NaN raises FE_INVALID (trapped by the tests).
  if (std::isnan(options.t_max) || !(options.t_max > 0.0 && options.t_max <= 1.0)) {
    std::ostringstream os;
    os << "continuousCollideEllipsoids: t_max must be in (0, 1], got " << options.t_max;
    throw std::invalid_argument(os.str());
  }
  if (std::isnan(options.max_condition) || !(options.max_condition > 0.0)) {
    std::ostringstream os;
    os << "continuousCollideEllipsoids: max_condition must be positive, got " << options.max_condition;
    throw std::invalid_argument(os.str());
  }
  if (options.interpolation == CcdInterpolation::Rigid) checkCcdDegree(a, b, "continuousCollideEllipsoids");
  const bool single = a.motion.pieces().size() == 1 && b.motion.pieces().size() == 1;
  if (single && options.interpolation == CcdInterpolation::Rigid) {
    if (std::optional<EllipsoidCcdResult> r = movingSpheres(a, b, options)) return *r;
  }
  EllipsoidCcdResult total;
  // Single pieces examined on [0, t_max] with t_max < 1: the culls certify [0, 1] on the
  // unrestricted motions (which implies [0, t_max]) before any restriction is computed.
  if (single && options.culling && options.interpolation == CcdInterpolation::Rigid && options.t_max < 1.0) {
    const MotionMatrix& ma = a.motion.pieces().front();
    const MotionMatrix& mb = b.motion.pieces().front();
    if (ma.isRigid() && mb.isRigid() && sphereCull(a, ma, b, mb)) {
      total.culled_by = 1;
      total.separation_intervals.push_back({0.0, options.t_max});
      return total;
    }
  }
  // Motions from two poses (or constant) have weights within a factor 2 of each other: balanced
  // by construction, no sampling needed.
  const bool from_poses = single && a.motion.pieces().front().linearTranslation() &&
                          b.motion.pieces().front().linearTranslation();
  if (single && options.t_max == 1.0 && (from_poses || !unbalanced(a, b, 0.0, 1.0))) {
    // The common case: one segment, no copies.
    return solveSegment(a, a.motion.pieces().front(), b, b.motion.pieces().front(), 1.0, options);
  }
  std::vector<bool> piece_starts;
  const std::vector<double> breaks = solverBreaks(a, b, options.t_max, from_poses, &piece_starts);
  total.segments = static_cast<int>(breaks.size()) - 1;
  int piece_work = 0;  // work spent on the current piece of the motions so far
  for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
    const double s0 = breaks[k], s1 = breaks[k + 1], w = s1 - s0;
    CcdOptions local = options;
    local.t_max = 1.0;
    const bool whole = s0 == 0.0 && s1 == 1.0;  // single pieces over [0, 1]: no copies
    // The work cap holds per piece of the motions (shared by the piece's balance segments), as
    // the region and dimension-reduction engines' caps do: a keyframed motion gets the answers
    // its pieces would get one by one. Until session 53 it was shared by the whole query, so a
    // motion of some hundreds of near-contact pieces ran out of it part way (unresolved contact
    // reported over the rest of [0, t_max]).
    if (piece_starts[k]) piece_work = 0;
    const EllipsoidCcdResult r =
        whole ? solveSegment(a, a.motion.pieces().front(), b, b.motion.pieces().front(), 1.0, local, piece_work)
              : solveSegment(a, a.motion.restricted(s0, s1), b, b.motion.restricted(s0, s1), 1.0, local, piece_work);
    // r started from piece_work; the sum over pieces saturates (more than 10^5 capped pieces).
    total.work = static_cast<int>(std::min<long long>(std::numeric_limits<int>::max(),
                                                      static_cast<long long>(total.work) + (r.work - piece_work)));
    piece_work = r.work;
    total.degree_t = std::max(total.degree_t, r.degree_t);
    total.near_tangent = total.near_tangent || r.near_tangent;
    total.unresolved = total.unresolved || r.unresolved;
    total.precision_checked = total.precision_checked || r.precision_checked;
    if (breaks.size() == 2) total.culled_by = r.culled_by;
    auto map = [&](const CcdInterval& i) { return CcdInterval{s0 + w * i.begin, s0 + w * i.end}; };
    for (const CcdInterval& i : r.separation_intervals) {
      const CcdInterval g = map(i);
      if (!total.separation_intervals.empty() && total.separation_intervals.back().end == g.begin &&
          (total.collision_intervals.empty() || total.collision_intervals.back().end < g.begin)) {
        total.separation_intervals.back().end = g.end;  // continues across the break
      } else {
        total.separation_intervals.push_back(g);
      }
    }
    for (const CcdInterval& i : r.collision_intervals) {
      const CcdInterval g = map(i);
      if (!total.collision_intervals.empty() && total.collision_intervals.back().end >= g.begin) {
        total.collision_intervals.back().end = std::max(total.collision_intervals.back().end, g.end);
      } else {
        total.collision_intervals.push_back(g);
      }
    }
    if (r.collide && !total.collide) {
      total.collide = true;
      total.first_contact_time = s0 + w * *r.first_contact_time;
      total.contact_point = r.contact_point;
      if (!options.all_intervals) break;
    }
  }
  return total;
}

std::vector<CcdFunctionSegment> ccdFunctionSegments(const MovingEllipsoid& a, const MovingEllipsoid& b,
                                                    CcdInterpolation interpolation) {
  const bool affine = interpolation == CcdInterpolation::Affine;
  if (!affine) checkCcdDegree(a, b, "ccdFunctionSegments");
  const std::vector<double> breaks = solverBreaks(a, b, 1.0, false);
  std::vector<CcdFunctionSegment> segments;
  for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
    const double s0 = breaks[k], s1 = breaks[k + 1];
    const bool whole = s0 == 0.0 && s1 == 1.0;
    const MotionMatrix ma = whole ? a.motion.pieces().front() : a.motion.restricted(s0, s1);
    const MotionMatrix mb = whole ? b.motion.pieces().front() : b.motion.restricted(s0, s1);
    const double condition = std::max(quadricCondition(a.body, ma), quadricCondition(b.body, mb));
    const std::optional<Eigen::Vector3d> ca = centreAtStart(a, ma), cb = centreAtStart(b, mb);
    const std::optional<SegmentPencil> p =
        ca && cb ? segmentPencil(a, ma, b, mb, *ca, *cb, affine, condition) : std::nullopt;
    if (!p) {
      std::ostringstream os;
      os << "ccdFunctionSegments: the affine interpolant of segment [" << s0 << ", " << s1
         << "] is not representable in double (an affine map overflows or is too ill-conditioned)";
      throw std::invalid_argument(os.str());
    }
    segments.push_back({s0, s1, p->F});
  }
  return segments;
}

}  // namespace fcl_quadric
