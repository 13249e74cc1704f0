// Broad phase unchanged: FCL's managers with fcl_quadric::defaultCollisionFunction /
// defaultDistanceFunction give exactly the brute-force answers of the geometry layer.
#include <algorithm>
#include <cstdio>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include <fcl/broadphase/broadphase_SSaP.h>
#include <fcl/broadphase/broadphase_SaP.h>
#include <fcl/broadphase/broadphase_bruteforce.h>
#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/broadphase/broadphase_dynamic_AABB_tree_array.h>
#include <fcl/broadphase/broadphase_interval_tree.h>
#include <fcl/broadphase/default_broadphase_callbacks.h>

#include "fcl/fcl_test_support.h"
#include "fcl_quadric/fcl/collision.h"
#include "fcl_quadric/fcl/distance.h"
#include "fcl_quadric/geometry/signed_distance.h"

namespace fcl_quadric {
namespace broadphase_test {
namespace {

using PairSet = std::set<std::pair<int, int>>;

struct Scene {
  std::vector<test::PosedShape> shapes;
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects;
  std::map<const fcl::CollisionGeometryd*, int> index;

  void add(const test::PosedShape& s) {
    shapes.push_back(s);
    objects.push_back(std::make_unique<fcl::CollisionObjectd>(s.geometry(), s.pose()));
    index[objects.back()->collisionGeometry().get()] = static_cast<int>(objects.size()) - 1;
  }
  std::vector<fcl::CollisionObjectd*> pointers() const {
    std::vector<fcl::CollisionObjectd*> p;
    for (const auto& o : objects) p.push_back(o.get());
    return p;
  }
  std::pair<int, int> pairOf(const fcl::CollisionGeometryd* a, const fcl::CollisionGeometryd* b) const {
    const int i = index.at(a), j = index.at(b);
    return {std::min(i, j), std::max(i, j)};
  }
};

/// 200 ellipsoids: 160 from a random distribution in [-10, 10]^3 and 20 near-tangent pairs at
/// relative gap 1e-8 (alternately just overlapping and just separate).
Scene collisionScene() {
  std::mt19937_64 rng(4242);
  std::uniform_real_distribution<double> ur(0.5, 3.0), uc(-10.0, 10.0);
  Scene scene;
  for (int i = 0; i < 160; ++i) {
    Eigen::Vector3d r(ur(rng), ur(rng), ur(rng)), c(uc(rng), uc(rng), uc(rng));
    scene.add(test::PosedShape{Ellipsoid(r, test::randomRotation(rng), c), false, Eigen::Matrix3d::Identity()});
  }
  for (int i = 0; i < 20; ++i) {
    const std::vector<test::ShapePair> p = test::nearTangentPairs(rng, false, 1e-8);
    scene.add(p[i % 2].a);
    scene.add(p[i % 2].b);
  }
  return scene;
}

PairSet bruteForceCollisions(const Scene& scene) {
  PairSet pairs;
  const int n = static_cast<int>(scene.shapes.size());
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      if (classifyEllipsoids(scene.shapes[i].e, scene.shapes[j].e).status != Separation::Separated) pairs.insert({i, j});
  return pairs;
}

PairSet managerCollisions(fcl::BroadPhaseCollisionManagerd& manager, const Scene& scene, fcl::CollisionCallBack<double> callback) {
  manager.registerObjects(scene.pointers());
  manager.setup();
  fcl::DefaultCollisionData<double> data;
  data.request.num_max_contacts = 100000;  // collect every colliding pair
  manager.collide(&data, callback);
  PairSet pairs;
  for (std::size_t k = 0; k < data.result.numContacts(); ++k) {
    const fcl::Contactd& c = data.result.getContact(k);
    pairs.insert(scene.pairOf(c.o1, c.o2));
  }
  EXPECT_EQ(pairs.size(), data.result.numContacts()) << "a pair was reported twice";
  return pairs;
}

std::vector<std::pair<std::string, std::unique_ptr<fcl::BroadPhaseCollisionManagerd>>> managers() {
  std::vector<std::pair<std::string, std::unique_ptr<fcl::BroadPhaseCollisionManagerd>>> m;
  m.emplace_back("DynamicAABBTree", std::make_unique<fcl::DynamicAABBTreeCollisionManagerd>());
  m.emplace_back("DynamicAABBTree_Array", std::make_unique<fcl::DynamicAABBTreeCollisionManager_Arrayd>());
  m.emplace_back("SaP", std::make_unique<fcl::SaPCollisionManagerd>());
  m.emplace_back("SSaP", std::make_unique<fcl::SSaPCollisionManagerd>());
  m.emplace_back("IntervalTree", std::make_unique<fcl::IntervalTreeCollisionManagerd>());
  m.emplace_back("Naive", std::make_unique<fcl::NaiveCollisionManagerd>());
  return m;
}

TEST(BroadPhase, DynamicAabbTreeWithDefaultCollisionFunctionFindsExactlyTheBruteForcePairs) {
  const Scene scene = collisionScene();
  ASSERT_EQ(scene.objects.size(), 200u);
  const PairSet truth = bruteForceCollisions(scene);
  fcl::DynamicAABBTreeCollisionManagerd manager;
  const PairSet ours = managerCollisions(manager, scene, fcl_quadric::defaultCollisionFunction<double>);
  EXPECT_EQ(ours, truth);
  EXPECT_GT(truth.size(), 100u);
  // For the record: the same manager with FCL's callback (stock libccd narrow phase).
  fcl::DynamicAABBTreeCollisionManagerd stock_manager;
  const test::ScopedNoFpTraps no_traps;  // stock libccd code
  const PairSet stock = managerCollisions(stock_manager, scene, fcl::DefaultCollisionFunction<double>);
  std::vector<std::pair<int, int>> missed, extra;
  std::set_difference(truth.begin(), truth.end(), stock.begin(), stock.end(), std::back_inserter(missed));
  std::set_difference(stock.begin(), stock.end(), truth.begin(), truth.end(), std::back_inserter(extra));
  std::printf("[ info ] %zu colliding pairs; stock FCL missed %zu and added %zu\n", truth.size(), missed.size(),
              extra.size());
}

TEST(BroadPhase, EveryManagerTypeFindsTheBruteForcePairs) {
  const Scene scene = collisionScene();
  const PairSet truth = bruteForceCollisions(scene);
  for (auto& m : managers()) EXPECT_EQ(managerCollisions(*m.second, scene, fcl_quadric::defaultCollisionFunction<double>), truth) << m.first;
}

TEST(BroadPhase, DefaultDistanceFunctionFindsTheBruteForceMinimumDistance) {
  // 100 pairwise separate ellipsoids (rejection sampling), so the manager has to find the minimum.
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> ur(0.5, 3.0), uc(-15.0, 15.0);
  Scene scene;
  while (scene.shapes.size() < 100) {
    const Ellipsoid e(Eigen::Vector3d(ur(rng), ur(rng), ur(rng)), test::randomRotation(rng),
                      Eigen::Vector3d(uc(rng), uc(rng), uc(rng)));
    bool free = true;
    for (const test::PosedShape& s : scene.shapes) free = free && !ellipsoidsCollide(s.e, e);
    if (free) scene.add(test::PosedShape{e, false, Eigen::Matrix3d::Identity()});
  }
  double truth = std::numeric_limits<double>::max();
  for (std::size_t i = 0; i < scene.shapes.size(); ++i)
    for (std::size_t j = i + 1; j < scene.shapes.size(); ++j)
      truth = std::min(truth, signedDistance(scene.shapes[i].e, scene.shapes[j].e).distance);
  for (auto& m : managers()) {
    m.second->registerObjects(scene.pointers());
    m.second->setup();
    fcl::DefaultDistanceData<double> data;
    m.second->distance(&data, fcl_quadric::defaultDistanceFunction<double>);
    EXPECT_NEAR(data.result.min_distance, truth, 1e-12 * (1.0 + truth)) << m.first;
  }
}

TEST(BroadPhase, CallbacksRejectNullData) {
  fcl::CollisionObjectd a(std::make_shared<fcl::Sphered>(1.0)), b(std::make_shared<fcl::Sphered>(1.0));
  double dist = 0;
  EXPECT_THROW(fcl_quadric::defaultCollisionFunction<double>(&a, &b, nullptr), std::invalid_argument);
  EXPECT_THROW(fcl_quadric::defaultDistanceFunction<double>(&a, &b, nullptr, dist), std::invalid_argument);
}

}  // namespace
}  // namespace broadphase_test
}  // namespace fcl_quadric
