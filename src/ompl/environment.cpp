// Environment: FCL collision objects in a dynamic AABB tree manager.
#include "fcl_quadric/ompl/environment.h"
#include "finite.h"

#include <stdexcept>
#include <string>

#include <array>
#include <utility>

#include <fcl/geometry/octree/octree.h>
#include <fcl/geometry/shape/box.h>

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

void Environment::registerObject(std::shared_ptr<fcl::CollisionGeometry<double>> geometry,
                                 const Eigen::Isometry3d& pose) {
  fcl::Transform3<double> tf = fcl::Transform3<double>::Identity();
  tf.linear() = pose.linear();
  tf.translation() = pose.translation();
  auto obj = std::make_shared<fcl::CollisionObject<double>>(geometry, tf);
  obj->computeAABB();
  objects_.push_back(obj);
  manager_->registerObject(obj.get());
}

void Environment::add(std::shared_ptr<fcl::CollisionGeometry<double>> geometry, const Eigen::Isometry3d& pose) {
  if (!geometry) throw std::invalid_argument("Environment::add: null geometry");
  checkPose(pose, "Environment::add");
  registerObject(std::move(geometry), pose);
  manager_->setup();
}

std::size_t Environment::addOcTree(std::shared_ptr<const octomap::OcTree> tree, const Eigen::Isometry3d& pose,
                                   bool as_leaf_boxes) {
  if (!tree) throw std::invalid_argument("Environment::addOcTree: null octomap tree");
  checkPose(pose, "Environment::addOcTree");
  auto fcl_tree = std::make_shared<fcl::OcTree<double>>(tree);
  if (!as_leaf_boxes) {
    registerObject(fcl_tree, pose);
    manager_->setup();
    return 1;
  }
  // toBoxes: (x, y, z, size, cost, threshold) of every leaf FCL considers occupied.
  const std::vector<std::array<double, 6>> boxes = fcl_tree->toBoxes();
  for (const auto& b : boxes) {
    Eigen::Isometry3d X = pose;
    X.translation() = pose * Eigen::Vector3d(b[0], b[1], b[2]);
    registerObject(std::make_shared<fcl::Box<double>>(b[3], b[3], b[3]), X);
  }
  manager_->setup();
  return boxes.size();
}

}  // namespace planning
}  // namespace fcl_quadric
