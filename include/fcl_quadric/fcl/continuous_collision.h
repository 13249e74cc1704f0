#pragma once
/// \file continuous_collision.h
/// fcl_quadric::continuousCollide: FCL's continuousCollide (<fcl/narrowphase/continuous_collision.h>)
/// with exact or certified-conservative answers for ellipsoid and sphere pairs.
///
/// Same three overloads, arguments and result semantics as fcl::continuousCollide:
///  - result.is_collide, result.time_of_contact (the first contact time in [0, 1]; 1 when there is
///    no collision, as FCL), result.contact_tf1 / contact_tf2 (the poses of the two motions at the
///    contact time; left untouched when there is no collision, as FCL);
///  - the return value is result.time_of_contact (FCL returns -1 for settings it does not
///    support; delegated pairs keep that).
///
/// Dispatch (o1 and o2 both fcl::Ellipsoid or fcl::Sphere, in any combination):
///  - both motions RationalMotion or fcl::TranslationMotion (a TranslationMotion is the rational
///    motion MotionMatrix::fromPoses(R, p0, R, p1)): EXACT, continuousCollideEllipsoids with
///    all_intervals = false. The contact time is never later than the exact first contact (by at
///    most ~1e-12, tolerances.h kCcdTimeTolerance / kCcdTouchingRelative) and errs early only at
///    near-tangent grazes. request.ccd_solver_type, num_max_iterations and toc_err are ignored.
///  - some motion fcl::InterpMotion, fcl::ScrewMotion or fcl::SplineMotion (the other any of
///    the five): CERTIFIED-CONSERVATIVE advancement driven by the exact signed distance
///    (signedDistance of the world ellipsoids at t, a certified lower bound of the distance: it is
///    the support gap along a unit normal) and a certified bound of the relative velocity of the
///    two solids' points, from the motions' parameters: |v1 - v2| + W1 + W2, with v the motion's
///    constant translational velocity (none for a spline or a RationalMotion) and W a bound of the
///    rest (rotation; a spline's whole velocity, from its control points). t advances by d over
///    that bound; contact is reported at the first t where the pair is not certified separate or
///    d <= tolerance (see kAdvancement* below); the reported time is never later than the true
///    first contact. On the step cap the current t is reported as contact (conservative; stats
///    step_cap).
///  - another MotionBase: no certified bound is available: delegated to fcl::continuousCollide
///    (NOT certified: FCL's naive sampling or its conservative advancement, per
///    request.ccd_solver_type).
/// Quadric shapes (quadric_shapes.h: EllipticCylinder, Quadric, QuadricCSG) against each other,
/// an fcl Sphere / Ellipsoid / Box / Cylinder / Cone / Capsule / Halfspace, a BVH mesh or an
/// fcl::OcTree (piece by piece: each triangle, each occupied leaf; docs/fcl_integration.md §9):
///  - both motions RationalMotion (rigid or affine) or fcl::TranslationMotion: EXACT up to the
///    stated band, the certified space-time search of continuous/region_ccd.h. "No collision" is
///    certified; a contact time is never later than the true first contact and within
///    kRegionCcdTimeTolerance (2^-27 ~ 7.5e-9) of it unless the pair only comes within the band (then the
///    contact is reported early: stats near_tangent) or the box cap is reached (step_cap). Stats
///    contact_point holds the contact point. request's solver settings are ignored.
///    Against a mesh the contact with a triangle (no interior) is always a band answer.
///  - any other motion type: std::invalid_argument (no certified method; FCL's own solvers do not
///    know these shapes). The transforms overload accepts only CCDM_TRANS for them.
/// Every other pair of geometries is delegated unchanged to fcl::continuousCollide with the same
/// request (a RationalMotion works there with CCDC_NAIVE and CCDC_CONSERVATIVE_ADVANCEMENT).
///
/// Transforms overload: the motions are built as fcl::continuousCollide builds them from
/// request.ccd_motion_type (CCDM_TRANS: TranslationMotion, which keeps tf_beg's rotation;
/// CCDM_LINEAR: InterpMotion; CCDM_SCREW: ScrewMotion). CCDM_SPLINE throws: FCL 0.7's
/// SplineMotion(tf1, tf2) leaves its control points uninitialised (pass SplineMotion objects built
/// from control points to the motion overload). CCDM_SCREW is FCL's ScrewMotion(tf1, tf2)
/// unchanged, including its pure translation (no rotation): the axis is then T2 - T1 unnormalised
/// and the speed |T2 - T1|, so the motion runs |T2 - T1| times past tf_end (a unit-length move
/// ends at tf_end; a move of 3 ends 9 away). For
/// ellipsoid pairs the InterpMotion is built with its reference point at the body origin (FCL's
/// InterpMotion(tf1, tf2) constructor leaves the reference point uninitialised). FCL's
/// CCDM_LINEAR is not a rational motion (it rotates at constant angular velocity about a fixed
/// axis); for fcl_quadric's exact rational interpolation between two poses pass
/// RationalMotion(tf_beg, tf_end) objects to the motion overload.
///
/// State: fcl_quadric's paths evaluate the motions from t = 0 whatever their current state and
/// leave them integrated to the contact time (as FCL does). FCL's conservative advancement (on
/// delegated pairs) starts from the motions' current state: re-create or integrate(0) a motion
/// before reusing it there.
///
/// Bad input throws std::invalid_argument naming the argument: a null geometry, object or
/// motion, a non-finite transform, a transforms-overload pose that is not rigid or lies beyond
/// +-1e100, a delegated pair's CCDC_NAIVE request with num_max_iterations < 2 (FCL samples
/// t = i / (n - 1)), a motion whose pose at some visited time is not finite, a
/// non-rigid RationalMotion on a pair that is not ellipsoid/sphere, and CCDC_POLYNOMIAL_SOLVER
/// with a motion that is not an fcl::TranslationMotion (FCL would reinterpret it as one); and
/// CcdDegreeError (a std::invalid_argument) for RationalMotions of a degree the continuous
/// solvers do not take (tolerance::kCcdMaxDegree, kRegionCcdMaxDegree).
///
/// Call it qualified (fcl_quadric::continuousCollide): with FCL argument types an unqualified
/// call also finds fcl::continuousCollide by argument-dependent lookup. Only S = double is
/// instantiated (src/fcl/continuous_collision.cpp).

#include <fcl/common/types.h>
#include <fcl/math/motion/motion_base.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/continuous_collision_request.h>
#include <fcl/narrowphase/continuous_collision_result.h>

namespace fcl_quadric {

/// Conservative advancement (InterpMotion / ScrewMotion ellipsoid pairs): contact is reported at
/// the first advancement time at which the certified distance lower bound is at most this times
/// (largest radius of o1 + largest radius of o2). At the reported time t_r the pair is within that
/// distance (or not certified separate); the true first contact t* satisfies t_r <= t*.
constexpr double kAdvancementDistanceRelative = 1e-6;
/// Step cap of the conservative advancement; on reaching it the current time is reported as the
/// contact time (conservative; the result is then early, never late).
constexpr int kAdvancementMaxSteps = 10000;

template <typename S>
S continuousCollide(const fcl::CollisionGeometry<S>* o1, const fcl::MotionBase<S>* motion1,
                    const fcl::CollisionGeometry<S>* o2, const fcl::MotionBase<S>* motion2,
                    const fcl::ContinuousCollisionRequest<S>& request, fcl::ContinuousCollisionResult<S>& result);

template <typename S>
S continuousCollide(const fcl::CollisionGeometry<S>* o1, const fcl::Transform3<S>& tf1_beg,
                    const fcl::Transform3<S>& tf1_end, const fcl::CollisionGeometry<S>* o2,
                    const fcl::Transform3<S>& tf2_beg, const fcl::Transform3<S>& tf2_end,
                    const fcl::ContinuousCollisionRequest<S>& request, fcl::ContinuousCollisionResult<S>& result);

/// The objects' current transforms are the begin poses.
template <typename S>
S continuousCollide(const fcl::CollisionObject<S>* o1, const fcl::Transform3<S>& tf1_end,
                    const fcl::CollisionObject<S>* o2, const fcl::Transform3<S>& tf2_end,
                    const fcl::ContinuousCollisionRequest<S>& request, fcl::ContinuousCollisionResult<S>& result);

/// Diagnostics of the last fcl_quadric::continuousCollide call on this thread: which path
/// answered and how much work it took (for tests and benchmarks).
struct ContinuousCollideStats {
  enum class Path { None, Exact, ConservativeAdvancement, Delegated };
  Path path = Path::None;
  int steps = 0;            ///< advancement steps, or the exact solver's work count
  bool step_cap = false;    ///< the advancement stopped on kAdvancementMaxSteps
  bool near_tangent = false;  ///< exact path: a decision was taken in the touching band
  /// Exact path of quadric shapes with CCDC_POLYNOMIAL_SOLVER: the dimension reduction answered
  /// (steps = candidates verified); false when it was undecided and the space-time search answered.
  bool dimension_reduction = false;
  /// Exact path of quadric shapes (region_ccd.h) with a contact: the contact point (world) at
  /// the contact time.
  Eigen::Vector3d contact_point = Eigen::Vector3d::Zero();
};
const ContinuousCollideStats& lastContinuousCollideStats();

extern template double continuousCollide(const fcl::CollisionGeometry<double>*, const fcl::MotionBase<double>*,
                                         const fcl::CollisionGeometry<double>*, const fcl::MotionBase<double>*,
                                         const fcl::ContinuousCollisionRequest<double>&,
                                         fcl::ContinuousCollisionResult<double>&);
extern template double continuousCollide(const fcl::CollisionGeometry<double>*, const fcl::Transform3<double>&,
                                         const fcl::Transform3<double>&, const fcl::CollisionGeometry<double>*,
                                         const fcl::Transform3<double>&, const fcl::Transform3<double>&,
                                         const fcl::ContinuousCollisionRequest<double>&,
                                         fcl::ContinuousCollisionResult<double>&);
extern template double continuousCollide(const fcl::CollisionObject<double>*, const fcl::Transform3<double>&,
                                         const fcl::CollisionObject<double>*, const fcl::Transform3<double>&,
                                         const fcl::ContinuousCollisionRequest<double>&,
                                         fcl::ContinuousCollisionResult<double>&);

}  // namespace fcl_quadric
