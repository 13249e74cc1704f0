#pragma once
// Shared helpers of the OMPL-layer tests: scenes, state construction and the independent oracles
// (pairwise fcl_quadric::collide over every obstacle and self pair, no broad phase, no
// advancement; dense sampling of the space's own interpolate()).
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include <Eigen/Geometry>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/sphere.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>

#include "fcl_quadric/fcl/collision.h"
#include "fcl_quadric/fcl/distance.h"
#include "fcl_quadric/ompl/ompl_planning.h"

namespace fcl_quadric {
namespace planning {
namespace test {

namespace ob = ompl::base;

inline Eigen::Isometry3d translation(double x, double y, double z) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(x, y, z);
  return X;
}

inline fcl::Transform3<double> toFcl(const Eigen::Isometry3d& X) {
  fcl::Transform3<double> tf = fcl::Transform3<double>::Identity();
  tf.linear() = X.linear();
  tf.translation() = X.translation();
  return tf;
}

/// Oracle: pairwise exact collide of every body with every obstacle and every self pair.
inline bool oracleCollides(const RobotModel& robot, const Environment& env, const Configuration& q) {
  std::vector<Eigen::Isometry3d> links;
  robot.linkPoses(q, links);
  fcl::CollisionRequest<double> req;
  for (std::size_t l = 0; l < links.size(); ++l)
    for (const Body& b : robot.bodies(l))
      for (const auto& obj : env.objects()) {
        fcl::CollisionResult<double> res;
        if (fcl_quadric::collide(b.geometry.get(), toFcl(links[l] * b.offset), obj->collisionGeometry().get(),
                                 obj->getTransform(), req, res) > 0)
          return true;
      }
  for (const auto& [la, lb] : robot.selfCollisionPairs())
    for (const Body& a : robot.bodies(la))
      for (const Body& b : robot.bodies(lb)) {
        fcl::CollisionResult<double> res;
        if (fcl_quadric::collide(a.geometry.get(), toFcl(links[la] * a.offset), b.geometry.get(),
                                 toFcl(links[lb] * b.offset), req, res) > 0)
          return true;
      }
  return false;
}

/// First of n + 1 uniform samples of the space's interpolate() at which the oracle finds a
/// collision, as a time in [0, 1]; -1 if none.
inline double oracleFirstCollidingSample(const ob::SpaceInformation& si, const RobotModel& robot, const Environment& env,
                                         const ob::State* s1, const ob::State* s2, int n) {
  ob::State* s = si.allocState();
  double hit = -1.0;
  for (int i = 0; i <= n; ++i) {
    const double t = static_cast<double>(i) / n;
    si.getStateSpace()->interpolate(s1, s2, t, s);
    if (oracleCollides(robot, env, toConfiguration(*si.getStateSpace(), s))) {
      hit = t;
      break;
    }
  }
  si.freeState(s);
  return hit;
}

inline void setSE3(ob::State* s, const Eigen::Vector3d& p, const Eigen::Quaterniond& q) {
  auto* st = s->as<ob::SE3StateSpace::StateType>();
  st->setXYZ(p.x(), p.y(), p.z());
  st->rotation().x = q.x();
  st->rotation().y = q.y();
  st->rotation().z = q.z();
  st->rotation().w = q.w();
}

inline void setSE2(ob::State* s, double x, double y, double yaw) {
  auto* st = s->as<ob::SE2StateSpace::StateType>();
  st->setXY(x, y);
  st->setYaw(yaw);
}

inline Eigen::Quaterniond randomQuaternion(std::mt19937_64& rng) {
  std::normal_distribution<double> n;
  Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
  return q.normalized();
}

/// An ellipsoid-modelled rigid robot: a body ellipsoid and a sphere "head" offset along x.
inline std::shared_ptr<RobotModel> rigidRobot(RobotModel::Base base, double scale = 1.0) {
  auto robot = std::make_shared<RobotModel>(base);
  robot->addBody(0, std::make_shared<fcl::Ellipsoid<double>>(0.3 * scale, 0.12 * scale, 0.08 * scale));
  robot->addBody(0, std::make_shared<fcl::Sphere<double>>(0.07 * scale), translation(0.3 * scale, 0.0, 0.0));
  return robot;
}

}  // namespace test
}  // namespace planning
}  // namespace fcl_quadric
