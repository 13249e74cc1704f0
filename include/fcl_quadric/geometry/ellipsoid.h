#pragma once
/// \file ellipsoid.h
/// An ellipsoid posed in the world frame W, the value type of the static narrow phase.

#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace fcl_quadric {

/// The solid ellipsoid E = { x in W : |S^-1 R^T (x - p)| <= 1 }, S = diag(radii), where R = R_WE
/// is the orientation and p = p_WE the centre of its body frame E in the world frame W.
///
/// Thesis convention (Choi 2008 §4.1): the homogeneous matrix A of E satisfies X^T A X < 0
/// exactly in the interior; quadricMatrix() returns it.
///
/// \pre radii finite, in [kMinRadius, kMaxLength]; R finite, orthogonal within
///      tolerance::kRotationOrthogonality and
///      det R > 0; p finite with coordinates within kMaxLength. A violation throws
///      std::invalid_argument naming the bad value.
///
/// rotation() is R itself when max|R^T R - I| <= tolerance::kStoredRotationDefect (2^-48; every
/// quaternion-derived rotation), otherwise its nearest rotation (detail::nearestRotation(), within
/// ~1e-9 of R): the solid is then the one of the stored rotation, which every test uses.
class Ellipsoid {
 public:
  Ellipsoid(const Eigen::Vector3d& radii, const Eigen::Matrix3d& R_WE, const Eigen::Vector3d& p_WE);
  /// From an isometry X_WE (its linear part must be a rotation).
  Ellipsoid(const Eigen::Vector3d& radii, const Eigen::Isometry3d& X_WE);
  /// A sphere of radius r centred at p_WE. \throws std::invalid_argument as the constructor (r
  /// outside [kMinRadius, kMaxLength] or not finite, p_WE not finite or beyond kMaxLength).
  static Ellipsoid sphere(double r, const Eigen::Vector3d& p_WE);
  /// The affine image { M u + p : |u| <= 1 } of the unit ball (the ellipsoids of affine motions,
  /// thesis §4.1.2 and §5.2), converted to principal axes by the symmetric eigen-decomposition
  /// M M^T = R S^2 R^T (relative perturbation of the solid ~1e-16 cond(M)).
  /// \throws std::invalid_argument if M or p is not finite or M is singular (cond > 1e12).
  static Ellipsoid fromAffine(const Eigen::Matrix3d& M, const Eigen::Vector3d& p);

  /// The stored pose [R p] as a row-major 3x4 matrix: row i is (R(i,0), R(i,1), R(i,2), p_i).
  using Pose = Eigen::Matrix<double, 3, 4, Eigen::RowMajor>;
  /// rotation() and center(): read-only views of the stored pose (Eigen expressions, as
  /// Eigen::Transform::linear() and translation() are). They convert implicitly to
  /// Eigen::Matrix3d and Eigen::Vector3d; their storage is strided (no data() pointer to a
  /// column-major matrix).
  using RotationView = Eigen::Block<const Pose, 3, 3>;
  using CenterView = Eigen::Block<const Pose, 3, 1>;
  /// radii(): a view of the three stored radii (contiguous; data() points to them).
  using RadiiView = Eigen::Map<const Eigen::Vector3d>;

  RadiiView radii() const { return RadiiView(shape_); }
  /// 1 / radii (computed on use: three divisions cost less than streaming 24 more bytes per
  /// ellipsoid through the cache in the batch loops that dominate the static benchmarks).
  Eigen::Vector3d inverseRadii() const { return radii().cwiseInverse(); }
  RotationView rotation() const { return RotationView(pose_, 0, 0); }
  CenterView center() const { return CenterView(pose_, 0, 3); }
  /// The stored pose, rows (R(i,0), R(i,1), R(i,2), p_i). These accessors have no failure mode:
  /// the constructor validated what they return.
  const Pose& pose() const { return pose_; }
  /// |p|_1 + r_0 + r_1 + r_2, rounded in double (relative error below 6 eps): the scale of the
  /// rounding errors of a plane test on this ellipsoid (CachedPlane::separates()).
  double extent() const { return shape_[3]; }
  /// The four doubles (r_0, r_1, r_2, extent()), contiguous and 32-byte aligned.
  const double* shapeData() const { return shape_; }

  /// 4x4 symmetric A with X^T A X < 0 inside: A = M^-T diag(1/a^2,1/b^2,1/c^2,-1) M^-1,
  /// M = [R p; 0 1], with M^-1 formed as [R^T, -R^T p] (rigid).
  Eigen::Matrix4d quadricMatrix() const;
  /// Implicit value q(x) = |S^-1 R^T (x - p)|^2 - 1 (negative inside, zero on the surface).
  /// No failure mode; a non-finite x gives a non-finite value.
  double implicit(const Eigen::Vector3d& x_W) const;
  /// Outward unit normal of the level set of q through x. \pre x != centre (at the centre the
  /// gradient vanishes and the zero vector is returned).
  Eigen::Vector3d normalAt(const Eigen::Vector3d& x_W) const;
  /// Support function h(n) = max_{x in E} n.x, for any finite n (not necessarily unit; h(0) = 0).
  double support(const Eigen::Vector3d& n_W) const;
  /// The point of E where the support in direction n is attained (n finite, not necessarily unit).
  /// For n = 0 every point of E attains h(0) = 0 and the centre is returned (never NaN).
  Eigen::Vector3d supportPoint(const Eigen::Vector3d& n_W) const;
  /// Largest radius (a bound on the distance from the centre to any point of E).
  double maxRadius() const { return radii().maxCoeff(); }

 private:
  // 128 bytes on a 64-byte boundary: exactly two cache lines. The pose is stored by rows, so that
  // R^T n (a world direction in the body frame, the core of every support function) is the sum
  // n_0 row_0 + n_1 row_1 + n_2 row_2 of three contiguous 4-vectors, whose fourth lane is n.p
  // (the cached-plane kernel, separating_plane.cpp).
  alignas(64) Pose pose_;
  alignas(32) double shape_[4];  // r_0, r_1, r_2, extent()
};

namespace detail {
/// Throws std::invalid_argument if `R` is not a finite proper rotation within
/// tolerance::kRotationOrthogonality. `what` names the value in the message. Returns the
/// orthogonality defect max|R^T R - I| (as computed in double).
double checkRotation(const Eigen::Matrix3d& R, const char* what);
/// checkRotation's test without the throw: true iff R is a finite proper rotation within
/// tolerance::kRotationOrthogonality. Any input (no floating-point exception on huge or
/// non-finite entries).
bool isRotation(const Eigen::Matrix3d& R);
/// The nearest rotation to R (the orthogonal polar factor) by Newton-Schulz steps
/// R <- R (3 I - R^T R) / 2, each of which squares the defect; at most 4 steps, until
/// max|R^T R - I| <= tolerance::kStoredRotationDefect. \pre checkRotation(R) passed (defect <= 1e-9:
/// one or two steps). Fallback if 4 steps do not reach it (not expected): the rotation of the
/// normalised quaternion of R.
Eigen::Matrix3d nearestRotation(const Eigen::Matrix3d& R);
/// checkRotation(R, what), then the rotation a solid is stored with: R itself when its defect is
/// at most tolerance::kStoredRotationDefect, otherwise nearestRotation(R) (Ellipsoid, cylinders and
/// cones: their supports assume orthonormal axes). Throws as checkRotation.
Eigen::Matrix3d storedRotation(const Eigen::Matrix3d& R, const char* what);
/// The absolute rounding bound of coordinates in e's unit frame S^-1 R^T (x - c) computed from
/// world vectors whose l1 norms sum to `world_l1`: tolerance::kUnitFrameRoundingBound * world_l1 *
/// (1/r_0 + 1/r_1 + 1/r_2). No failure mode (a non-finite world_l1 gives a non-finite bound).
double unitFrameRounding(const Ellipsoid& e, double world_l1);
/// Throws std::invalid_argument("<what> must be finite, ...") if v has a NaN or infinite entry.
void checkFinite(const Eigen::Vector3d& v, const char* what);
/// checkFinite(v, what), then throws std::invalid_argument("<what> coordinates must be within
/// +-1e+100, ...") unless every |v_i| <= tolerance::kMaxLength: the range of positions every
/// solid's tests are exact in (the Ellipsoid constructor's check of its centre). Beyond it
/// their products overflow; a box 1e300 away was reported colliding with an ellipsoid at the
/// origin (session 35, an audit).
void checkPosition(const Eigen::Vector3d& v, const char* what);
/// Throws std::invalid_argument("<what>[ <name>][ <index>] must be finite and in [0, 1e+100], got
/// <v>") unless v is finite, >= 0 and <= tolerance::kMaxLength: a length of a solid (a radius, a
/// side, a height), in the range its tests are exact in (as the Ellipsoid's radii). A capsule
/// 1.7e308 long was measured wrong otherwise (session 36, an audit). No allocation unless it
/// throws (it runs for every posed solid of every query).
void checkLength(double v, const char* what, const char* name = nullptr, int index = -1);
}  // namespace detail

}  // namespace fcl_quadric
