// OMPL front end: RationalSE3StateSpace, StateValidityChecker, ContinuousMotionValidator.
#include "fcl_quadric/ompl/ompl_planning.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <typeinfo>

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SE2StateSpace.h>

namespace ob = ompl::base;

namespace fcl_quadric {
namespace planning {

RationalSE3StateSpace::RationalSE3StateSpace() { setName("RationalSE3" + getName()); }

void RationalSE3StateSpace::interpolate(const ob::State* from, const ob::State* to, double t, ob::State* state) const {
  const auto* f = from->as<StateType>();
  const auto* g = to->as<StateType>();
  // The end quaternions normalised first (OMPL's bounds allow |q| = 1 +- 1e-9): the path is then
  // MotionMatrix::fromPoses of the two poses, which the exact CCD certifies, for any such states.
  const ob::SO3StateSpace::StateType& a = f->rotation();
  const ob::SO3StateSpace::StateType& b = g->rotation();
  const double na = std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z + a.w * a.w);
  const double nb = std::sqrt(b.x * b.x + b.y * b.y + b.z * b.z + b.w * b.w);
  const double u = (1.0 - t) / na;
  const double s = ((a.x * b.x + a.y * b.y + a.z * b.z + a.w * b.w) < 0.0 ? -t : t) / nb;
  double qx = u * a.x + s * b.x, qy = u * a.y + s * b.y;
  double qz = u * a.z + s * b.z, qw = u * a.w + s * b.w;
  const double n = std::sqrt(qx * qx + qy * qy + qz * qz + qw * qw);
  const double x = (1.0 - t) * f->getX() + t * g->getX();
  const double y = (1.0 - t) * f->getY() + t * g->getY();
  const double z = (1.0 - t) * f->getZ() + t * g->getZ();
  auto* out = state->as<StateType>();  // may alias from / to: everything is read above
  out->setXYZ(x, y, z);
  out->rotation().x = qx / n;
  out->rotation().y = qy / n;
  out->rotation().z = qz / n;
  out->rotation().w = qw / n;
}

Interpolation interpolationOf(const ob::StateSpace& space) {
  const std::type_info& t = typeid(space);
  if (t == typeid(ob::SE2StateSpace)) return Interpolation::Planar;
  if (t == typeid(ob::SE3StateSpace)) return Interpolation::Slerp;
  if (t == typeid(RationalSE3StateSpace)) return Interpolation::QuaternionLerp;
  if (t == typeid(ob::RealVectorStateSpace)) return Interpolation::Joints;
  throw std::invalid_argument("fcl_quadric planning: unsupported state space \"" + space.getName() +
                              "\" (SE2StateSpace, SE3StateSpace, RationalSE3StateSpace or RealVectorStateSpace; "
                              "the motion certificate depends on the exact interpolate())");
}

Configuration toConfiguration(const ob::StateSpace& space, const ob::State* state) {
  Configuration q;
  switch (interpolationOf(space)) {
    case Interpolation::Planar: {
      const auto* s = state->as<ob::SE2StateSpace::StateType>();
      q.base.linear() = Eigen::AngleAxisd(s->getYaw(), Eigen::Vector3d::UnitZ()).toRotationMatrix();
      q.base.translation() = Eigen::Vector3d(s->getX(), s->getY(), 0.0);
      break;
    }
    case Interpolation::Slerp:
    case Interpolation::QuaternionLerp: {
      const auto* s = state->as<ob::SE3StateSpace::StateType>();
      const auto& r = s->rotation();
      const Eigen::Quaterniond quat(r.w, r.x, r.y, r.z);
      const double n = quat.norm();
      // (Eigen's normalized() leaves a zero quaternion as it is, and its matrix is I: a silent
      // identity rotation.)
      if (!std::isfinite(n) || !(n > 1e-6))
        throw std::invalid_argument("toConfiguration: the state's quaternion (" + std::to_string(r.w) + ", " +
                                    std::to_string(r.x) + ", " + std::to_string(r.y) + ", " + std::to_string(r.z) +
                                    ") is zero or not finite");
      q.base.linear() = quat.normalized().toRotationMatrix();
      q.base.translation() = Eigen::Vector3d(s->getX(), s->getY(), s->getZ());
      break;
    }
    case Interpolation::Joints: {
      const auto* s = state->as<ob::RealVectorStateSpace::StateType>();
      q.joints.assign(s->values, s->values + space.getDimension());
      break;
    }
  }
  return q;
}

ob::StateSpacePtr makeStateSpace(const RobotModel& robot, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                                 bool rational) {
  robot.validate();
  if (robot.base() != RobotModel::Base::Fixed) {
    const int n = robot.base() == RobotModel::Base::Planar ? 2 : 3;
    for (int i = 0; i < n; ++i)
      if (!std::isfinite(lo[i]) || !std::isfinite(hi[i]) || !(lo[i] < hi[i]))
        throw std::invalid_argument("makeStateSpace: bound " + std::to_string(i) + " must be finite with lo < hi, got [" +
                                    std::to_string(lo[i]) + ", " + std::to_string(hi[i]) + "]");
    ob::RealVectorBounds b(n);
    for (int i = 0; i < n; ++i) b.setLow(i, lo[i]), b.setHigh(i, hi[i]);
    if (n == 2) {
      auto s = std::make_shared<ob::SE2StateSpace>();
      s->setBounds(b);
      return s;
    }
    std::shared_ptr<ob::SE3StateSpace> s =
        rational ? std::make_shared<RationalSE3StateSpace>() : std::make_shared<ob::SE3StateSpace>();
    s->setBounds(b);
    return s;
  }
  const unsigned n = static_cast<unsigned>(robot.jointCount());
  auto s = std::make_shared<ob::RealVectorStateSpace>(n);
  ob::RealVectorBounds b(n);
  for (unsigned i = 0; i < n; ++i) b.setLow(i, robot.joint(i).lower), b.setHigh(i, robot.joint(i).upper);
  s->setBounds(b);
  return s;
}

StateValidityChecker::StateValidityChecker(const ob::SpaceInformationPtr& si,
                                           std::shared_ptr<const RobotCollisionChecker> checker)
    : ob::StateValidityChecker(si), checker_(std::move(checker)) {
  if (!si) throw std::invalid_argument("StateValidityChecker: null SpaceInformation");
  if (!checker_) throw std::invalid_argument("StateValidityChecker: null RobotCollisionChecker");
  interpolationOf(*si->getStateSpace());
  specs_.clearanceComputationType = ob::StateValidityCheckerSpecs::EXACT;
}

bool StateValidityChecker::isValid(const ob::State* state) const {
  if (!si_->satisfiesBounds(state)) return false;
  return checker_->isValid(toConfiguration(*si_->getStateSpace(), state));
}

double StateValidityChecker::clearance(const ob::State* state) const {
  return checker_->clearance(toConfiguration(*si_->getStateSpace(), state));
}

ContinuousMotionValidator::ContinuousMotionValidator(const ob::SpaceInformationPtr& si,
                                                     std::shared_ptr<const RobotCollisionChecker> checker,
                                                     MotionCheckOptions options)
    : ob::MotionValidator(si), checker_(std::move(checker)), options_(options), kind_(Interpolation::Joints) {
  if (!si) throw std::invalid_argument("ContinuousMotionValidator: null SpaceInformation");
  if (!checker_) throw std::invalid_argument("ContinuousMotionValidator: null RobotCollisionChecker");
  kind_ = interpolationOf(*si->getStateSpace());
}

namespace {

/// OMPL's SO3StateSpace asserts unit quaternions (to MAX_QUATERNION_NORM_ERROR, 1e-9) in
/// interpolate(), and Debian's OMPL keeps its assertions: a state it would abort on is rejected
/// here with an exception instead.
void checkUnitQuaternion(const ob::State* state, const char* which) {
  const auto& r = state->as<ob::SE3StateSpace::StateType>()->rotation();
  const double n = std::sqrt(r.w * r.w + r.x * r.x + r.y * r.y + r.z * r.z);
  if (!std::isfinite(n) || std::abs(n - 1.0) >= 1e-9)  // (no comparison with a NaN: FE_INVALID)
    throw std::invalid_argument(std::string("ContinuousMotionValidator: the quaternion of ") + which + " has norm " +
                                std::to_string(n) + "; SE3StateSpace's interpolation needs |norm - 1| < 1e-9");
}

/// OMPL's SO2 interpolation turns along the shorter arc, as the Planar speed bound assumes, only
/// for yaws within [-pi, pi] (SE2StateSpace's bounds): from a yaw of 10 it turned 6.2 rad where
/// the bound allowed 0.07 (reliability.md finding 33).
void checkYaw(const ob::State* state, const char* which) {
  const double yaw = state->as<ob::SE2StateSpace::StateType>()->getYaw();
  if (!std::isfinite(yaw) || std::abs(yaw) > M_PI)
    throw std::invalid_argument(std::string("ContinuousMotionValidator: the yaw of ") + which + " is " +
                                std::to_string(yaw) + ", outside [-pi, pi] (SE2StateSpace's bounds)");
}

/// The constant-speed geodesic between two base poses: translation linear, rotation by slerp along
/// the shorter arc (for two rotations about z: the yaw linear along the shorter arc). Its speed
/// bound is that of Interpolation::Slerp (and of Planar for planar poses).
void geodesic(const Configuration& a, const Configuration& b, double t, Configuration& q) {
  const Eigen::Quaterniond qa(a.base.linear()), qb(b.base.linear());
  q.base.linear() = qa.slerp(t, qb).toRotationMatrix();
  q.base.translation() = (1.0 - t) * a.base.translation() + t * b.base.translation();
  q.joints = b.joints;
}

}  // namespace

MotionCheckResult ContinuousMotionValidator::check(const ob::State* s1, const ob::State* s2, bool stop_at_first) const {
  const ob::StateSpace& space = *si_->getStateSpace();
  if (kind_ == Interpolation::Slerp) {
    checkUnitQuaternion(s1, "s1");
    checkUnitQuaternion(s2, "s2");
  }
  if (kind_ == Interpolation::Planar) {
    checkYaw(s1, "s1");
    checkYaw(s2, "s2");
  }
  ob::State* scratch = si_->allocState();
  MotionCheckResult r;
  try {
    const Configuration c2 = toConfiguration(space, s2);
    r = checker_->checkMotion(
        toConfiguration(space, s1), c2, kind_,
        [&](double t, Configuration& q) {
          space.interpolate(s1, s2, t, scratch);
          q = toConfiguration(space, scratch);
        },
        options_, stop_at_first);
    // The motion ends at s2, but OMPL's SE3 slerp keeps the start rotation for every t, t = 1
    // included, when |q1 . q2| > 1 - 1e-9 (SO3StateSpace::arcLength is then 0): a rotation of up
    // to 9e-5 rad, then, is never interpolated, and s2 itself was not checked (reliability.md
    // finding 33). Whenever interpolate(s1, s2, 1) is not s2's pose, the step from it to s2 is
    // certified too, along the constant-speed geodesic (a rounding-level step costs one distance
    // query). Joint and SE(2) interpolations reach s2 up to rounding and are left as they are.
    if (r.valid && (kind_ == Interpolation::Slerp || kind_ == Interpolation::QuaternionLerp)) {
      space.interpolate(s1, s2, 1.0, scratch);
      const Configuration c_end = toConfiguration(space, scratch);
      if (c_end.base.matrix() != c2.base.matrix()) {
        const MotionCheckResult step = checker_->checkMotion(
            c_end, c2, Interpolation::Slerp, [&](double t, Configuration& q) { geodesic(c_end, c2, t, q); }, options_,
            true);
        r.advancement_steps += step.advancement_steps;
        r.exact_solves += step.exact_solves;
        if (!step.valid) {
          r.valid = false;
          r.contact_time = 1.0;
          r.last_valid_time = 1.0 - 1e-9;  // interpolate() was certified on all of [0, 1]
        }
      }
    }
  } catch (...) {
    si_->freeState(scratch);
    throw;
  }
  si_->freeState(scratch);
  total_steps_.fetch_add(r.advancement_steps, std::memory_order_relaxed);
  total_exact_.fetch_add(r.exact_solves, std::memory_order_relaxed);
  return r;
}

bool ContinuousMotionValidator::endsAreValid(const ob::State* s1, const ob::State* s2) const {
  // As OMPL's DiscreteMotionValidator: s2 must be a valid state. s1 is the planner's (valid) tree
  // state, but its bounds are checked too: outside them (an SE(2) yaw of 10, a joint beyond its
  // limit) the interpolation is not the one the speed bound describes (reliability.md finding 33).
  return si_->satisfiesBounds(s1) && si_->isValid(s2);
}

bool ContinuousMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2) const {
  const bool ok = endsAreValid(s1, s2) && check(s1, s2, true).valid;
  if (ok)
    ++valid_;
  else
    ++invalid_;
  return ok;
}

bool ContinuousMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2,
                                            std::pair<ob::State*, double>& lastValid) const {
  MotionCheckResult r;
  r.valid = false;
  r.contact_time = 0.0;
  r.last_valid_time = 0.0;
  if (si_->satisfiesBounds(s1) && si_->satisfiesBounds(s2)) {
    // A colliding s2 still gets its certified last valid time; an s2 invalid for another reason
    // (a validity checker other than ours) gets (s1, 0).
    const bool s2_valid = si_->isValid(s2);
    r = check(s1, s2, false);
    if (r.valid && !s2_valid) {
      r.valid = false;
      r.contact_time = 1.0;
      r.last_valid_time = 0.0;
    }
  }
  if (r.valid) {
    ++valid_;
    return true;
  }
  ++invalid_;
  // Planners may connect s1 to the returned state directly (e.g. PRM's random bounce motions), and
  // that direct motion is the prefix [0, f] of s1 -> s2 only if the interpolation is
  // sub-path consistent (linear, shorter-arc yaw, slerp). The quaternion lerp of
  // RationalSE3StateSpace is not (its angle is not uniform in t while the translation is), so
  // the direct motion s1 -> state(f) is certified as well, halving f until it is.
  double f = r.last_valid_time;
  ob::State* candidate = si_->allocState();
  const ob::StateSpace& space = *si_->getStateSpace();
  if (kind_ == Interpolation::QuaternionLerp) {
    for (int attempt = 0; f > 0.0; ++attempt) {
      space.interpolate(s1, s2, f, candidate);
      if (attempt == 8) {
        f = 0.0;
        break;
      }
      if (check(s1, candidate, true).valid) break;
      f *= 0.5;
    }
  }
  space.interpolate(s1, s2, f, candidate);
  if (lastValid.first != nullptr) space.copyState(lastValid.first, candidate);  // may alias s2
  si_->freeState(candidate);
  lastValid.second = f;
  return false;
}

void installCollisionChecking(const ob::SpaceInformationPtr& si, const std::shared_ptr<const RobotCollisionChecker>& checker,
                              const MotionCheckOptions& options) {
  if (!si) throw std::invalid_argument("installCollisionChecking: null SpaceInformation");
  si->setStateValidityChecker(std::make_shared<StateValidityChecker>(si, checker));
  si->setMotionValidator(std::make_shared<ContinuousMotionValidator>(si, checker, options));
  si->setup();
}

}  // namespace planning
}  // namespace fcl_quadric
