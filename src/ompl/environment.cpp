// Environment: FCL collision objects in a dynamic AABB tree manager.
#include "fcl_quadric/ompl/environment.h"
#include "finite.h"

#include <stdexcept>
#include <string>

#include <fcl/geometry/octree/octree.h>

namespace fcl_quadric {
namespace planning {

namespace {
void checkPose(const Eigen::Isometry3d& X, const char* where) {
  if (!detail::allFinite(X.matrix())) throw std::invalid_argument(std::string(where) + ": obstacle pose is not finite");
  const Eigen::Matrix3d R = X.linear();
  if ((R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-9 || R.determinant() <= 0.0)
    throw std::invalid_argument(std::string(where) + ": obstacle pose is not rigid");
}
}  // namespace

Environment::Environment() : manager_(std::make_unique<fcl::DynamicAABBTreeCollisionManager<double>>()) {}

void Environment::add(std::shared_ptr<fcl::CollisionGeometry<double>> geometry, const Eigen::Isometry3d& pose) {
  if (!geometry) throw std::invalid_argument("Environment::add: null geometry");
  checkPose(pose, "Environment::add");
  fcl::Transform3<double> tf = fcl::Transform3<double>::Identity();
  tf.linear() = pose.linear();
  tf.translation() = pose.translation();
  auto obj = std::make_shared<fcl::CollisionObject<double>>(geometry, tf);
  obj->computeAABB();
  objects_.push_back(obj);
  manager_->registerObject(obj.get());
  manager_->setup();
}

void Environment::addOcTree(std::shared_ptr<const octomap::OcTree> tree, const Eigen::Isometry3d& pose) {
  if (!tree) throw std::invalid_argument("Environment::addOcTree: null octomap tree");
  add(std::make_shared<fcl::OcTree<double>>(tree), pose);
}

}  // namespace planning
}  // namespace fcl_quadric
