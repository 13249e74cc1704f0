// Environment: FCL collision objects in a dynamic AABB tree manager.
#include "fcl_quadric/ompl/environment.h"
#include "finite.h"
#include "geometry_checks.h"

#include <stdexcept>
#include <string>

#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>
#include <unordered_set>
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
  detail::checkSupportedGeometry(*geometry, "Environment::add");
  checkPose(pose, "Environment::add");
  registerObject(std::move(geometry), pose);
  manager_->setup();
}

namespace {

/// Leaves wider than this many finest voxels are registered as they are, not split into voxels.
constexpr long kMaxMergedLeafVoxels = 16;

struct Key {
  long x, y, z;
  bool operator==(const Key& o) const { return x == o.x && y == o.y && z == o.z; }
};
struct KeyHash {
  std::size_t operator()(const Key& k) const {
    return std::hash<long>()(k.x) ^ (std::hash<long>()(k.y) * 0x9e3779b97f4a7c15ULL) ^ (std::hash<long>()(k.z) << 1);
  }
};

/// Greedy merge of unit voxels into maximal boxes: returns (min key, extent in voxels) per box.
std::vector<std::pair<Key, Key>> mergeVoxels(std::vector<Key> keys) {
  std::sort(keys.begin(), keys.end(), [](const Key& a, const Key& b) {
    return std::tie(a.z, a.y, a.x) < std::tie(b.z, b.y, b.x);
  });
  std::unordered_set<Key, KeyHash> free_cells(keys.begin(), keys.end());
  auto isFree = [&](long x, long y, long z) { return free_cells.count(Key{x, y, z}) != 0; };
  std::vector<std::pair<Key, Key>> boxes;
  for (const Key& k : keys) {
    if (!isFree(k.x, k.y, k.z)) continue;
    long lx = 1, ly = 1, lz = 1;
    while (isFree(k.x + lx, k.y, k.z)) ++lx;
    auto rowFree = [&](long y, long z) {
      for (long i = 0; i < lx; ++i)
        if (!isFree(k.x + i, y, z)) return false;
      return true;
    };
    while (rowFree(k.y + ly, k.z)) ++ly;
    auto layerFree = [&](long z) {
      for (long j = 0; j < ly; ++j)
        if (!rowFree(k.y + j, z)) return false;
      return true;
    };
    while (layerFree(k.z + lz)) ++lz;
    for (long c = 0; c < lz; ++c)
      for (long j = 0; j < ly; ++j)
        for (long i = 0; i < lx; ++i) free_cells.erase(Key{k.x + i, k.y + j, k.z + c});
    boxes.push_back({k, Key{lx, ly, lz}});
  }
  return boxes;
}

}  // namespace

std::size_t Environment::addOcTree(std::shared_ptr<const octomap::OcTree> tree, const Eigen::Isometry3d& pose,
                                   OcTreeMode mode) {
  if (!tree) throw std::invalid_argument("Environment::addOcTree: null octomap tree");
  checkPose(pose, "Environment::addOcTree");
  auto fcl_tree = std::make_shared<fcl::OcTree<double>>(tree);
  if (mode == OcTreeMode::WholeTree) {
    registerObject(fcl_tree, pose);
    manager_->setup();
    return 1;
  }
  // toBoxes: (x, y, z, size, cost, threshold) of every leaf FCL considers occupied.
  const std::vector<std::array<double, 6>> leaves = fcl_tree->toBoxes();
  std::size_t added = 0;
  auto addBox = [&](const Eigen::Vector3d& centre, const Eigen::Vector3d& size) {
    Eigen::Isometry3d X = pose;
    X.translation() = pose * centre;
    registerObject(std::make_shared<fcl::Box<double>>(size), X);
    ++added;
  };
  if (mode == OcTreeMode::LeafBoxes) {
    for (const auto& b : leaves) addBox(Eigen::Vector3d(b[0], b[1], b[2]), Eigen::Vector3d::Constant(b[3]));
  } else {
    // Every leaf as finest-level voxels (a pruned leaf of size s covers (s / res)^3 of them),
    // indexed by the integer coordinates of their minimum corners.
    const double res = tree->getResolution();
    std::vector<Key> voxels;
    for (const auto& b : leaves) {
      const long n = std::lround(b[3] / res);
      if (n > kMaxMergedLeafVoxels) {  // a large pruned leaf is already a big box
        addBox(Eigen::Vector3d(b[0], b[1], b[2]), Eigen::Vector3d::Constant(b[3]));
        continue;
      }
      const long x0 = std::lround((b[0] - 0.5 * b[3]) / res), y0 = std::lround((b[1] - 0.5 * b[3]) / res);
      const long z0 = std::lround((b[2] - 0.5 * b[3]) / res);
      for (long k = 0; k < n; ++k)
        for (long j = 0; j < n; ++j)
          for (long i = 0; i < n; ++i) voxels.push_back(Key{x0 + i, y0 + j, z0 + k});
    }
    for (const auto& [k, n] : mergeVoxels(std::move(voxels)))
      addBox(res * Eigen::Vector3d(k.x + 0.5 * n.x, k.y + 0.5 * n.y, k.z + 0.5 * n.z),
             res * Eigen::Vector3d(double(n.x), double(n.y), double(n.z)));
  }
  manager_->setup();
  return added;
}

}  // namespace planning
}  // namespace fcl_quadric
