#pragma once
/// \file rational_motion.h
/// fcl_quadric::RationalMotion<S>: an fcl::MotionBase<S> carrying fcl_quadric's rational motions
/// (thesis ch.5, continuous/motion_matrix.h), so that they can be handed to FCL's continuous
/// collision (fcl::continuousCollide, CCDC_NAIVE and CCDC_CONSERVATIVE_ADVANCEMENT) as well as to
/// fcl_quadric::continuousCollide, which answers ellipsoid and sphere pairs under these motions
/// exactly (continuous/ellipsoid_ccd.h).
///
/// The motion maps body coordinates to world coordinates over the normalised time t in [0, 1]:
///  - from two poses: MotionMatrix::fromPoses (translation linear in t, rotation by the linear
///    interpolation of the unit quaternions, rational of degree 2; not slerp);
///  - from keyframes: PiecewiseMotion::fromKeyframes (one such piece between consecutive poses);
///  - from a polynomial matrix: MotionMatrix::fromPolynomialMatrix (any rational affine motion).
///
/// What FCL's MotionBase requires, and what this class does:
///  - integrate(t): evaluates the motion at t (clamped to [0, 1], as FCL's motions clamp t > 1)
///    and stores t and the pose; returns false, changing nothing, if t is NaN.
///  - getCurrentTransform: that pose. For a non-rigid (affine) motion the linear part is not a
///    rotation; FCL's shapes and solvers assume rigid poses, so only fcl_quadric::continuousCollide's
///    ellipsoid pairs accept non-rigid motions (other pairs throw std::invalid_argument there).
///  - computeMotionBound(visitor): a certified upper bound of the speed along the visitor's
///    direction n, sup over the remaining time t' in [t, 1] and over the points x of the visitor's
///    bounding volume (TBVMotionBoundVisitor<RSS> and <OBBRSS>, the ones FCL's conservative
///    advancement builds) or triangle (TriangleMotionBoundVisitor) of n . dx/dt(t'). This is the
///    quantity FCL's conservative advancement divides the distance by (delta_t = d / bound, e.g.
///    shape_conservative_advancement_traversal_node-inl.h:88-92): a displacement over the whole
///    remaining time would make that step unsafe when 1 - t < 1. The bound is computed from the
///    Bernstein coefficients of the derivative's numerator, n^T (M' w - M w')(t) (x, 1), on
///    [t, 1] (convex hull property), divided by a Bernstein lower bound of w(t)^2, and widened by a
///    relative 1e-12 for rounding. A visitor of another type throws std::logic_error (its bounding
///    volume is not readable; FCL's own motions return 0 for unknown visitors, which is not a
///    bound).
///  - getTaylorModel: throws std::logic_error. FCL uses Taylor models only in
///    CCDC_POLYNOMIAL_SOLVER, for BVH-BVH pairs under TranslationMotion; use
///    CCDC_CONSERVATIVE_ADVANCEMENT or CCDC_NAIVE with this motion, or fcl_quadric::continuousCollide.
///
/// A RationalMotion is not thread-safe (integrate mutates it, as every FCL motion). Only
/// S = double is instantiated (src/fcl/continuous_collision.cpp).

#include <vector>

#include <Eigen/Core>

#include <fcl/common/types.h>
#include <fcl/math/motion/motion_base.h>

#include "fcl_quadric/algebra/polynomial_matrix.h"
#include "fcl_quadric/continuous/motion_matrix.h"

namespace fcl_quadric {

template <typename S>
class RationalMotion : public fcl::MotionBase<S> {
 public:
  /// The rational rigid motion from tf_beg (t = 0) to tf_end (t = 1) (MotionMatrix::fromPoses).
  /// \throws std::invalid_argument if a transform is not finite or not rigid, naming it.
  RationalMotion(const fcl::Transform3<S>& tf_beg, const fcl::Transform3<S>& tf_end);

  /// Keyframes: poses[k] at times[k], 0 = times[0] < ... < times.back() = 1
  /// (PiecewiseMotion::fromKeyframes). \throws std::invalid_argument naming the bad time or pose.
  RationalMotion(const std::vector<S>& times, const std::vector<fcl::Transform3<S>>& poses);

  /// An explicit motion matrix (MotionMatrix::fromPolynomialMatrix; may be affine).
  /// \throws std::invalid_argument if the matrix is not a valid motion on [0, 1] or an entry's
  /// degree exceeds kMaxMotionDegree.
  explicit RationalMotion(const PolynomialMatrix4& M);

  /// Any piecewise rational motion.
  explicit RationalMotion(PiecewiseMotion motion);

  /// Evaluates the motion at dt (clamped to [0, 1]); false (and no change) if dt is NaN.
  bool integrate(S dt) const override;

  /// Certified bound of the speed along the visitor's n over [current time, 1] (file comment).
  /// \throws std::logic_error for a visitor that is not a TBVMotionBoundVisitor<RSS<S>> or
  ///         TBVMotionBoundVisitor<OBBRSS<S>>.
  S computeMotionBound(const fcl::BVMotionBoundVisitor<S>& mb_visitor) const override;

  /// Certified bound of the speed along the visitor's n of the visitor's triangle (body frame)
  /// over [current time, 1].
  S computeMotionBound(const fcl::TriangleMotionBoundVisitor<S>& mb_visitor) const override;

  void getCurrentTransform(fcl::Transform3<S>& tf) const override;
  /// MotionBase's (R, T) / quaternion forms of the current pose.
  using fcl::MotionBase<S>::getCurrentTransform;

  /// \throws std::logic_error always (file comment).
  void getTaylorModel(fcl::TMatrix3<S>& tm, fcl::TVector3<S>& tv) const override;

  /// The motion (double precision, as the continuous-collision layer uses it).
  const PiecewiseMotion& piecewiseMotion() const { return motion_; }
  /// Time of the last successful integrate() (0 initially).
  S currentTime() const { return static_cast<S>(time_); }
  /// The affine map body -> world at the current time (last row [0, 0, 0, 1]).
  const Eigen::Matrix4d& currentMatrix() const { return current_; }

  /// Certified upper bound of sup n . dx/dt over t in [t0, 1] and x in `points` (body frame)
  /// plus `radius` times sup |n^T L'(t)| (the ball of that radius around each point). n is not
  /// required to be a unit vector. \throws std::invalid_argument unless 0 <= t0 <= 1.
  double directionalSpeedBound(const Eigen::Vector3d& n, const std::vector<Eigen::Vector3d>& points, double radius,
                               double t0) const;

  /// Certified upper bound of the speed |dx/dt| of any point of the ball (centre, radius) (body
  /// frame) over t in [t0, 1]: sup |p'(t)| + radius sup ||L'(t)||_F, from Bernstein bounds.
  /// \throws std::invalid_argument unless 0 <= t0 <= 1.
  double speedBound(const Eigen::Vector3d& centre, double radius, double t0 = 0.0) const;

 private:
  PiecewiseMotion motion_;
  mutable double time_ = 0.0;
  mutable Eigen::Matrix4d current_ = Eigen::Matrix4d::Identity();
  mutable fcl::Transform3<S> tf_ = fcl::Transform3<S>::Identity();

 public:
  EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};

extern template class RationalMotion<double>;

}  // namespace fcl_quadric
