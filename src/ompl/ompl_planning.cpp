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
  const ob::SO3StateSpace::StateType& a = f->rotation();
  const ob::SO3StateSpace::StateType& b = g->rotation();
  const double s = (a.x * b.x + a.y * b.y + a.z * b.z + a.w * b.w) < 0.0 ? -1.0 : 1.0;
  double qx = (1.0 - t) * a.x + t * s * b.x, qy = (1.0 - t) * a.y + t * s * b.y;
  double qz = (1.0 - t) * a.z + t * s * b.z, qw = (1.0 - t) * a.w + t * s * b.w;
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
      q.base.linear() = Eigen::Quaterniond(r.w, r.x, r.y, r.z).normalized().toRotationMatrix();
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

MotionCheckResult ContinuousMotionValidator::check(const ob::State* s1, const ob::State* s2, bool stop_at_first) const {
  const ob::StateSpace& space = *si_->getStateSpace();
  ob::State* scratch = si_->allocState();
  MotionCheckResult r;
  try {
    r = checker_->checkMotion(
        toConfiguration(space, s1), toConfiguration(space, s2), kind_,
        [&](double t, Configuration& q) {
          space.interpolate(s1, s2, t, scratch);
          q = toConfiguration(space, scratch);
        },
        options_, stop_at_first);
  } catch (...) {
    si_->freeState(scratch);
    throw;
  }
  si_->freeState(scratch);
  total_steps_.fetch_add(r.advancement_steps, std::memory_order_relaxed);
  total_exact_.fetch_add(r.exact_solves, std::memory_order_relaxed);
  return r;
}

bool ContinuousMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2) const {
  const bool ok = si_->satisfiesBounds(s2) && check(s1, s2, true).valid;
  if (ok)
    ++valid_;
  else
    ++invalid_;
  return ok;
}

bool ContinuousMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2,
                                            std::pair<ob::State*, double>& lastValid) const {
  MotionCheckResult r;
  if (si_->satisfiesBounds(s2)) {
    r = check(s1, s2, false);
  } else {
    r.valid = false;
    r.contact_time = 0.0;
    r.last_valid_time = 0.0;
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
