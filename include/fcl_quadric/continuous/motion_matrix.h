#pragma once
/// \file motion_matrix.h
/// Rational rigid and affine motions in homogeneous coordinates (Choi 2008, thesis §5.1).
///
/// A motion is a 4x4 matrix M(t) of polynomials in t in [0, 1], mapping body coordinates to world
/// coordinates: X_world ~ M(t) X_body, with last row [0, 0, 0, w(t)] and w(t) != 0 on [0, 1].
/// The upper-left 3x3 block L(t) is non-singular on [0, 1] (rigid: L = w R with R a rotation).
///
/// A quadric X^T Q X <= 0 carried by the motion is X^T Q(t) X <= 0 with
/// Q(t) = M(t)^{-T} Q M(t)^{-1}. M(t)^{-1} is rational; the class keeps a polynomial matrix
/// N(t) = c(t) M(t)^{-1} with a scalar polynomial c(t) that has no root in [0, 1], so that
/// N(t)^T Q N(t) = c(t)^2 Q(t). The factor c(t)^2 > 0 changes neither the sign of X^T Q(t) X nor the
/// root pattern of det(lambda A(t) - B(t)) in lambda up to a positive rescaling of lambda
/// (lambda -> lambda c_B^2 / c_A^2), so every separation condition of the thesis (Theorem 4.1,
/// Theorem 5.1) holds for the polynomial matrices unchanged. This avoids all divisions.
///
/// Degrees (thesis §5.1): from two poses, the rotation interpolates the quaternions linearly,
/// which is rational of degree 2; the translation is linear. For that motion
/// M = [[R~(t), E(t) p(t)], [0, E(t)]] (R~ the unnormalised quaternion rotation, E = |q(t)|^2) and
/// N = [[R~^T, -R~^T p(t)], [0, E(t)]], so N M = E^2 I: columns of N have degrees (2, 2, 2, 3) and
/// the CCD function of two such motions has degree at most 2 (2+2+2+3) = 18 in t. A general
/// affine motion uses N = [[w adj L, -adj(L) v], [0, det L]] (N M = w det(L) I); a rigid one
/// (L^T L = sigma I with sigma = w^2 as polynomials, detected to rounding; a uniform scaling is
/// not rigid) uses N = [[w L^T, -L^T v], [0, sigma]]
/// (N M = w sigma I), of lower degree. Compositions keep the product of the factors' inverses.
///
/// Part of the continuous-collision layer: standard library and Eigen only.

#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "fcl_quadric/algebra/polynomial.h"
#include "fcl_quadric/algebra/polynomial_matrix.h"

namespace fcl_quadric {

/// 4x4 matrices in extended precision (long double: a 64-bit significand on x86-64).
using Matrix4ld = Eigen::Matrix<long double, 4, 4>;

/// Largest degree of an entry of a motion given by its polynomial matrix
/// (MotionMatrix::fromPolynomialMatrix): its validation converts det L(t), of degree up to three
/// times that, to the Bernstein form, whose conversions stop at kMaxBernsteinDegree = 1000. The
/// solvers have lower limits of their own (tolerance::kCcdMaxDegree, kRegionCcdMaxDegree), on
/// the degree of what a pair of motions produces (CcdDegreeError).
constexpr int kMaxMotionDegree = 300;

/// Thrown by the continuous solvers when a pair's motions would give a CCD function (or moving
/// quadric) of a higher degree in t than the solver supports: the polynomial arithmetic would
/// leave the range of its binomial tables. A std::invalid_argument whose message names both
/// degrees; degree() and limit() give them to a caller that reports it (the CLI names the
/// motion's JSON path).
class CcdDegreeError : public std::invalid_argument {
 public:
  CcdDegreeError(const std::string& what, int degree, int limit)
      : std::invalid_argument(what), degree_(degree), limit_(limit) {}
  int degree() const { return degree_; }
  int limit() const { return limit_; }

 private:
  int degree_;
  int limit_;
};

/// A rational motion M(t), t in [0, 1], with its polynomial inverse N(t) (see the file comment).
class MotionMatrix {
 public:
  /// The identity motion.
  MotionMatrix();

  /// The constant pose x -> R x + p. \throws std::invalid_argument for a non-rotation R
  /// (orthogonality error above 1e-9 or det < 0) or a non-finite entry.
  static MotionMatrix constant(const Eigen::Matrix3d& R, const Eigen::Vector3d& p);

  /// The rigid motion between two poses (thesis §5.4.1): translation (1-t) p0 + t p1, rotation by
  /// the linear interpolation q(t) = (1-t) q0 + t q1 of unit quaternions, with q1 negated if
  /// needed so that q0 . q1 >= 0 (the shorter arc; then |q(t)|^2 >= 1/2 on [0, 1]). Rational of
  /// degree 2 in the rotation: the rotation angle does not grow uniformly in t (it is not slerp),
  /// but the motion is the exact rational motion used by the solver.
  /// \throws std::invalid_argument for a non-rotation or a non-finite entry, naming it.
  static MotionMatrix fromPoses(const Eigen::Matrix3d& R0, const Eigen::Vector3d& p0, const Eigen::Matrix3d& R1,
                                const Eigen::Vector3d& p1);
  /// The same from isometries. \throws std::invalid_argument as above.
  static MotionMatrix fromPoses(const Eigen::Isometry3d& X0, const Eigen::Isometry3d& X1);

  /// A motion given by its polynomial matrix (power basis in t, t in [0, 1]). Validated:
  /// entries (3,0), (3,1), (3,2) must be the zero polynomial; w(t) = M(3,3) and det L(t) must
  /// have no root in [0, 1] (certified by Bernstein root isolation; a root that cannot be
  /// excluded counts as a root). \throws std::invalid_argument naming the failed condition and
  /// where in [0, 1] it fails. M and s M are the same motion: when the largest coefficient is
  /// outside [2^-32, 2^32] the matrix is first rescaled by a power of two (exact), so that huge or
  /// tiny coefficients cannot overflow the validation or the CCD (matrix() returns the rescaled
  /// matrix). Entries of degree above kMaxMotionDegree are rejected (std::invalid_argument naming
  /// the entry and its degree).
  static MotionMatrix fromPolynomialMatrix(const PolynomialMatrix4& M);

  /// The composition outer(inner(x)): M = M_outer M_inner with the polynomial inverse
  /// N = N_inner N_outer (no adjugate: the degrees of the factors add, e.g. a link of a serial
  /// chain is the product of its joints' motions). Rigid if both are. No failure mode (both
  /// factors are valid motions, so the product's w and inverse factor stay root-free).
  static MotionMatrix compose(const MotionMatrix& outer, const MotionMatrix& inner);

  /// M(t) (homogeneous, not normalised), built from the coefficient matrices.
  PolynomialMatrix4 matrix() const;
  /// N(t) = c(t) M(t)^{-1} with c(t) != 0 on [0, 1], built from the coefficient matrices.
  PolynomialMatrix4 inverse() const;
  /// The power-basis coefficient matrices of M and N: M(t) = sum_k matrixCoefficients()[k] t^k,
  /// trailing zero matrices removed. They are the stored representation (a motion from poses is
  /// built with two allocations; the solver works on fixed-size 4x4 products).
  const std::vector<Eigen::Matrix4d>& matrixCoefficients() const { return Mk_; }
  const std::vector<Eigen::Matrix4d>& inverseCoefficients() const { return Nk_; }
  /// The same coefficient matrices of N computed in extended precision from M's coefficients
  /// (inverseCoefficients() are these rounded to double). The CCD's precision check of
  /// ill-conditioned motions starts from them (docs/algorithms.md section 8).
  const std::vector<Matrix4ld>& inverseCoefficientsExtended() const { return Nk_ext_; }
  /// Condition estimate of the linear part: max over t in {0, 1/2, 1} of |L(t)|_F |L(t)^-1|_F
  /// (3 for a rigid motion; large for a strong shear or a near-singular scaling). No failure mode:
  /// +infinity when the map M / w overflows or det L underflows at one of those times.
  double linearCondition() const;
  /// True for motions built by constant() or fromPoses() (rigid by construction).
  bool isRigid() const { return rigid_; }
  /// For motions built by fromPoses() (and their restrictions): the path of the body origin is
  /// the segment (1-t) p0 + t p1, returned as {p0, p1}; empty otherwise. Used by the culls.
  const std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>>& linearTranslation() const {
    return linear_translation_;
  }
  /// Largest degree of the entries of M.
  int degree() const { return static_cast<int>(Mk_.size()) - 1; }

  /// The affine map at time t: M(t) / w(t), last row [0, 0, 0, 1]. \throws std::invalid_argument
  /// if t is not finite.
  Eigen::Matrix4d evaluate(double t) const;
  /// M(t) itself (homogeneous, not divided by w; Horner on the coefficient matrices). No failure
  /// mode: a non-finite t gives a non-finite matrix.
  Eigen::Matrix4d homogeneous(double t) const;

  /// The same motion on the sub-interval [t0, t1] of its parameter, reparametrised to [0, 1]:
  /// the result at s is this motion at t0 + (t1 - t0) s. \throws std::invalid_argument unless
  /// 0 <= t0 < t1 <= 1.
  MotionMatrix restricted(double t0, double t1) const;

 private:
  MotionMatrix(std::vector<Eigen::Matrix4d> M, std::vector<Matrix4ld> N, bool rigid);
  std::vector<Eigen::Matrix4d> Mk_;
  std::vector<Eigen::Matrix4d> Nk_;
  std::vector<Matrix4ld> Nk_ext_;  // Nk_ before rounding to double
  bool rigid_ = true;
  std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>> linear_translation_;
};

/// Q(t) up to the positive factor c(t)^2: N(t)^T Q N(t), symmetrised. Q is the body-frame quadric
/// matrix (interior X^T Q X < 0). \throws std::invalid_argument if Q is not finite.
PolynomialMatrix4 movingQuadric(const Eigen::Matrix4d& Q_body, const MotionMatrix& motion);

/// (N(t) S)^T Q (N(t) S) for a polynomial matrix N and a constant S, symmetrised, computed on the
/// coefficient matrices (N = sum_k N_k t^k gives sum_m t^m sum_{k+l=m} (N_k S)^T Q N_l S):
/// fixed-size 4x4 products instead of per-entry polynomial arithmetic (thesis §5.1: the moving
/// quadric A(t) = M^{-T} A M^{-1} up to c(t)^2). Inputs are taken as given (no validation; a
/// non-finite entry yields a non-finite result, which the consumers' constructors reject).
PolynomialMatrix4 congruence(const Eigen::Matrix4d& Q, const PolynomialMatrix4& N,
                             const Eigen::Matrix4d& S = Eigen::Matrix4d::Identity());
/// The same from the coefficient matrices N_k (e.g. MotionMatrix::inverseCoefficients()).
PolynomialMatrix4 congruence(const Eigen::Matrix4d& Q, const std::vector<Eigen::Matrix4d>& N,
                             const Eigen::Matrix4d& S = Eigen::Matrix4d::Identity());

/// The product of two polynomial matrices given by their power-basis coefficient matrices:
/// (sum_k N_k t^k)(sum_l M_l t^l), N.size() + M.size() - 1 coefficients. Both lists must be
/// non-empty (no other failure mode).
std::vector<Eigen::Matrix4d> multiplyCoefficients(const std::vector<Eigen::Matrix4d>& N,
                                                  const std::vector<Eigen::Matrix4d>& M);

/// The coefficient matrices of a polynomial matrix: M(t) = sum_k result[k] t^k (maxDegree() + 1
/// of them). No failure mode (PolynomialMatrix4 entries are finite by construction).
std::vector<Eigen::Matrix4d> coefficientMatrices(const PolynomialMatrix4& M);

/// Entry-wise |coefficients| of M (power basis): the magnitude from which rounding bounds of
/// polynomial formulas in M are built. No failure mode.
PolynomialMatrix4 coefficientMagnitudes(const PolynomialMatrix4& M);

/// A piecewise rational motion over [0, 1]: motion k is used on [breaks[k], breaks[k+1]] and is
/// parametrised over its own [0, 1] (so piece k at local s is the motion at
/// breaks[k] + (breaks[k+1] - breaks[k]) s). Built from keyframes: consecutive poses are joined by
/// MotionMatrix::fromPoses. Continuity at the breaks is the caller's business for explicit
/// pieces; fromKeyframes is continuous by construction.
class PiecewiseMotion {
 public:
  /// A single piece over [0, 1].
  explicit PiecewiseMotion(MotionMatrix motion = MotionMatrix());
  /// \throws std::invalid_argument unless breaks start at 0, end at 1, increase strictly and
  /// number pieces.size() + 1.
  PiecewiseMotion(std::vector<double> breaks, std::vector<MotionMatrix> pieces);
  /// Keyframe poses at strictly increasing times from 0 to 1 (at least two), joined by
  /// MotionMatrix::fromPoses. \throws std::invalid_argument naming the bad time or pose.
  static PiecewiseMotion fromKeyframes(const std::vector<double>& times, const std::vector<Eigen::Isometry3d>& poses);

  const std::vector<double>& breaks() const { return breaks_; }
  const std::vector<MotionMatrix>& pieces() const { return pieces_; }
  bool isRigid() const;
  /// The affine map at global time t in [0, 1] (t outside extrapolates the first / last piece).
  /// \throws std::invalid_argument if t is not finite.
  Eigen::Matrix4d evaluate(double t) const;
  /// The motion on [t0, t1] inside one piece, reparametrised to [0, 1].
  /// \throws std::invalid_argument if [t0, t1] is not inside a single piece.
  MotionMatrix restricted(double t0, double t1) const;

 private:
  std::vector<double> breaks_;
  std::vector<MotionMatrix> pieces_;
};

namespace detail {
/// Throws std::invalid_argument("<what> vanishes ...") unless p has no root in [0, 1], certified
/// by the Bernstein form (all coefficients of one strict sign, or isolateRoots finds nothing).
void checkNoRootOnUnitInterval(const Polynomial& p, const char* what);
}  // namespace detail

}  // namespace fcl_quadric
