#pragma once
/// \file ompl_planning.h
/// OMPL 1.5 front end of the planning layer (docs/ompl.md): a state validity checker with exact
/// clearance, a continuous motion validator that certifies the motion the planner executes, and
/// RationalSE3StateSpace, an SE(3) space whose interpolate() is the rational motion the exact
/// ellipsoid CCD solves (MotionMatrix::fromPoses).
///
/// Supported state spaces (checked by exact type, because the certification depends on the
/// interpolation formula; a derived space could override interpolate()):
///  - ompl::base::SE2StateSpace             robot Base::Planar   Interpolation::Planar
///  - ompl::base::SE3StateSpace (slerp)     robot Base::Free     Interpolation::Slerp
///  - RationalSE3StateSpace (quat. lerp)    robot Base::Free     Interpolation::QuaternionLerp
///  - ompl::base::RealVectorStateSpace      robot Base::Fixed    Interpolation::Joints
/// Anything else throws std::invalid_argument naming the space.
///
/// Usage with SimpleSetup (planners unchanged):
///   auto space = makeStateSpace(*robot, lo, hi);         // or your own space of a supported type
///   ompl::geometric::SimpleSetup ss(space);
///   auto checker = std::make_shared<RobotCollisionChecker>(robot, env);
///   installCollisionChecking(ss.getSpaceInformation(), checker);
///   ss.setPlanner(std::make_shared<ompl::geometric::RRTConnect>(ss.getSpaceInformation()));

#include <atomic>
#include <memory>

#include <Eigen/Core>
#include <ompl/base/MotionValidator.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateValidityChecker.h>
#include <ompl/base/spaces/SE3StateSpace.h>

#include "fcl_quadric/ompl/robot_checker.h"

namespace fcl_quadric {
namespace planning {

/// SE(3) with the rational interpolation of MotionMatrix::fromPoses: translation (1-t) p0 + t p1,
/// rotation by the normalised linear interpolation of the quaternions, each normalised first (q1
/// negated first if q0 . q1 < 0). Same path of orientations as slerp (the great arc), traversed
/// at a different speed; the exact ellipsoid CCD solves exactly this motion.
class RationalSE3StateSpace : public ompl::base::SE3StateSpace {
 public:
  RationalSE3StateSpace();
  void interpolate(const ompl::base::State* from, const ompl::base::State* to, double t,
                   ompl::base::State* state) const override;
};

/// The interpolation of a supported space. \throws std::invalid_argument otherwise.
Interpolation interpolationOf(const ompl::base::StateSpace& space);

/// The configuration of an OMPL state of a supported space (SE2: base = Rz(yaw) at (x, y, 0)).
/// \throws std::invalid_argument for an unsupported space.
Configuration toConfiguration(const ompl::base::StateSpace& space, const ompl::base::State* state);

/// A state space for the robot: Free -> RationalSE3StateSpace (or SE3StateSpace if !rational)
/// with translation bounds [lo, hi]; Planar -> SE2StateSpace with xy bounds; Fixed ->
/// RealVectorStateSpace with the joint limits (lo / hi unused). \throws std::invalid_argument
/// for lo > hi or non-finite bounds, or an invalid robot.
ompl::base::StateSpacePtr makeStateSpace(const RobotModel& robot, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                                         bool rational = true);

/// isValid: within the space's bounds and RobotCollisionChecker::isValid (exact narrow phase).
/// clearance: RobotCollisionChecker::clearance (exact signed distance for ellipsoid bodies).
class StateValidityChecker : public ompl::base::StateValidityChecker {
 public:
  /// \throws std::invalid_argument for a null si or checker, or an unsupported state space.
  StateValidityChecker(const ompl::base::SpaceInformationPtr& si, std::shared_ptr<const RobotCollisionChecker> checker);
  bool isValid(const ompl::base::State* state) const override;
  double clearance(const ompl::base::State* state) const override;

 private:
  std::shared_ptr<const RobotCollisionChecker> checker_;
};

/// checkMotion(s1, s2): RobotCollisionChecker::checkMotion over the space's own interpolate()
/// (certified: never accepts a motion that touches an obstacle or a self-collision partner).
/// checkMotion(s1, s2, lastValid): on failure lastValid.second is a certified collision-free time
/// <= the first contact time and lastValid.first (if non-null) the state there. With
/// RationalSE3StateSpace the direct motion from s1 to that state (which planners such as PRM add
/// as an edge) is certified too: the quaternion lerp is not sub-path consistent, so the direct
/// motion is not the prefix of s1 -> s2; f is halved until the direct motion is valid.
/// As OMPL's DiscreteMotionValidator, a motion is valid only if si->isValid(s2); s1 must lie within
/// the space's bounds (else rejected, lastValid = s1, 0: outside them the interpolation is not the
/// one the speed bound describes). s2 outside the bounds, or invalid for a reason other than a
/// collision the certificate finds, gives lastValid = (s1, 0). Where OMPL's SE3 slerp does not
/// reach s2 (it keeps the start rotation when |q1 . q2| > 1 - 1e-9), the remaining rotation to s2
/// is certified as well.
class ContinuousMotionValidator : public ompl::base::MotionValidator {
 public:
  /// \throws std::invalid_argument for a null si or checker, or an unsupported state space.
  ContinuousMotionValidator(const ompl::base::SpaceInformationPtr& si,
                            std::shared_ptr<const RobotCollisionChecker> checker, MotionCheckOptions options = {});
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2) const override;
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2,
                   std::pair<ompl::base::State*, double>& lastValid) const override;

  /// The full result of the continuous check of s1 -> s2 (for tests and statistics; no bounds or
  /// isValid(s2) test, unlike checkMotion). \throws std::invalid_argument for states the
  /// interpolation cannot certify: an SE(2) yaw outside [-pi, pi], an SE3StateSpace quaternion
  /// with |norm - 1| >= 1e-9 (OMPL's interpolate() asserts on it), a zero quaternion, or as
  /// RobotCollisionChecker::checkMotion.
  MotionCheckResult check(const ompl::base::State* s1, const ompl::base::State* s2, bool stop_at_first) const;
  /// Advancement steps and exact solves summed over all checks. Atomic: planners such as PRM call
  /// checkMotion from several threads (OMPL's own valid/invalid counters are not atomic).
  std::size_t totalSteps() const { return total_steps_.load(std::memory_order_relaxed); }
  std::size_t totalExactSolves() const { return total_exact_.load(std::memory_order_relaxed); }

 private:
  /// s1 within the space's bounds and si->isValid(s2).
  bool endsAreValid(const ompl::base::State* s1, const ompl::base::State* s2) const;
  std::shared_ptr<const RobotCollisionChecker> checker_;
  MotionCheckOptions options_;
  Interpolation kind_;
  mutable std::atomic<std::size_t> total_steps_{0};
  mutable std::atomic<std::size_t> total_exact_{0};
};

/// Installs StateValidityChecker and ContinuousMotionValidator on si and calls si->setup().
void installCollisionChecking(const ompl::base::SpaceInformationPtr& si,
                              const std::shared_ptr<const RobotCollisionChecker>& checker,
                              const MotionCheckOptions& options = {});

}  // namespace planning
}  // namespace fcl_quadric
