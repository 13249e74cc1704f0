#pragma once
/// \file robot_checker.h
/// Static and continuous collision of a RobotModel against an Environment and itself (the engine
/// behind the OMPL StateValidityChecker and ContinuousMotionValidator; no OMPL types here).
///
/// Static: isValid (exact collide of every body against the broad-phase manager and of every
/// self-collision body pair), clearance (the minimum signed distance, exact for ellipsoid bodies).
///
/// Continuous (docs/ompl.md "Certification"): the motion is q(t), t in [0, 1], given by a callback
/// (the state space's own interpolate()) together with the Interpolation that names it, from which
/// a certified bound V_b of the speed of every point of each body b over [0, 1] is derived:
///  - Planar (OMPL SE2): x, y linear, yaw linear along the shorter arc:
///      V_b = |p1 - p0| + |dyaw| reach_b;
///  - Slerp (OMPL SE3): translation linear, rotation by slerp at constant angular speed 2 theta
///    (theta the quaternion arc): V_b = |p1 - p0| + 2 theta reach_b;
///  - QuaternionLerp (RationalSE3StateSpace): translation linear, rotation by the normalised linear
///    interpolation of the quaternions (MotionMatrix::fromPoses); |omega| <= 2 |q1 - q0| / |q(t)|
///    and |q(t)| >= |q0 + q1| / 2: V_b = |p1 - p0| + 4 |q1 - q0| / |q0 + q1| reach_b;
///  - Joints (OMPL RealVector, linear in joint space): V_b = sum over joints j before the body's
///    link of |dq_j| (chainLength(j, link) + reach_b) for revolute joints and |dq_j| for prismatic;
/// where reach_b = |ball_centre| + ball_radius bounds the distance of the body's points from the
/// link origin. Conservative advancement per body: at t the exact distance d of the body to the
/// environment is a lower bound, so no point can reach an obstacle before t + d / V_b; t advances
/// by that step until it passes 1 (free) or d <= contact_distance (contact reported at t, never
/// later than the true first contact). Self pairs advance by d / (V_a + V_b).
/// With QuaternionLerp, pairs of an ellipsoid / sphere body and an ellipsoid / sphere obstacle are
/// decided by the exact continuous solver (continuousCollideEllipsoids, thesis ch.5) instead: the
/// base motion is exactly MotionMatrix::fromPoses of the two end poses.

#include <cstddef>
#include <functional>
#include <memory>

#include "fcl_quadric/ompl/environment.h"
#include "fcl_quadric/ompl/robot_model.h"

namespace fcl_quadric {
namespace planning {

enum class Interpolation { Planar, Slerp, QuaternionLerp, Joints };

struct MotionCheckOptions {
  /// Contact is reported once the certified distance of a body is at most this (world units).
  /// Motions that pass closer than this to an obstacle are rejected (conservative).
  double contact_distance = 1e-9;
  /// Advancement steps per body before the current time is reported as contact (conservative).
  int max_steps = 200000;
  /// Use the exact ellipsoid CCD for ellipsoid pairs under QuaternionLerp.
  bool exact_ellipsoid_pairs = true;
};

struct MotionCheckResult {
  bool valid = true;
  /// If !valid: a time never later than the first contact (the earliest non-certified instant).
  double contact_time = 1.0;
  /// If !valid: an instant in [0, contact_time] at which the robot is certified collision-free
  /// (0 when the motion starts in contact; then the start state itself is the caller's business).
  double last_valid_time = 1.0;
  std::size_t advancement_steps = 0;
  std::size_t exact_solves = 0;
};

class RobotCollisionChecker {
 public:
  /// \throws std::invalid_argument for null pointers or an invalid robot (RobotModel::validate).
  RobotCollisionChecker(std::shared_ptr<const RobotModel> robot, std::shared_ptr<const Environment> environment);

  const RobotModel& robot() const { return *robot_; }
  const Environment& environment() const { return *env_; }

  /// No body touches the environment or a self-collision partner (touching counts as collision).
  /// Box, cylinder, cone and capsule bodies, whose contacts with boxes, meshes, octrees and each
  /// other fcl_quadric::collide leaves to FCL's libccd (which missed overlaps of 1e-12 to 3e-7),
  /// are also in contact where GJK's certified lower bound (distanceLowerBound) is 0: this errs
  /// toward contact by GJK's certified error, ~1e-10 of the size.
  bool isValid(const Configuration& q) const;
  /// Minimum signed distance over bodies vs environment and self pairs (negative: penetration, the
  /// deepest over every obstacle the body overlaps; 0 for an overlap whose depth is not computed,
  /// see docs/ompl.md; +infinity if there is nothing to be near).
  double clearance(const Configuration& q) const;

  /// Certified speed bound of each body (flattened in link order) for the motion from -> to.
  std::vector<double> speedBounds(const Configuration& from, const Configuration& to, Interpolation kind) const;

  /// Continuous check of the motion from `from` (t = 0) to `to` (t = 1); `at(t, q)` must fill q
  /// with the configuration the planner executes at t (e.g. via StateSpace::interpolate), and
  /// `kind` must name that interpolation. `stop_at_first`: return as soon as one contact is found
  /// (contact_time then is a contact, not necessarily the first).
  /// \throws std::invalid_argument for a non-finite configuration, bad options, or (Fixed base) a
  /// configuration with the wrong number of joint values or a value outside its joint's limits
  /// (the speed bound of a prismatic joint's chain assumes the limits).
  MotionCheckResult checkMotion(const Configuration& from, const Configuration& to, Interpolation kind,
                                const std::function<void(double, Configuration&)>& at,
                                const MotionCheckOptions& options = {}, bool stop_at_first = false) const;

 private:
  std::shared_ptr<const RobotModel> robot_;
  std::shared_ptr<const Environment> env_;
};

}  // namespace planning
}  // namespace fcl_quadric
