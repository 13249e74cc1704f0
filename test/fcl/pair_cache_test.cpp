// PairCache / coherentCollisionFunction: inter-frame coherence across broad-phase calls gives
// exactly the brute-force answer every frame, and actually uses its planes.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/shape/box.h>

#include "fcl_quadric/fcl/collision.h"
#include "fcl_quadric/fcl/pair_cache.h"
#include "fcl_quadric/geometry/ellipsoid_polytope.h"
#include "support/random_ellipsoids.h"

namespace fcl_quadric {
namespace pair_cache_test {
namespace {

using PairSet = std::set<std::pair<const void*, const void*>>;

std::pair<const void*, const void*> ordered(const void* a, const void* b) { return a < b ? std::make_pair(a, b) : std::make_pair(b, a); }

PairSet contactPairs(const fcl::CollisionResultd& r) {
  PairSet s;
  for (std::size_t i = 0; i < r.numContacts(); ++i) s.insert(ordered(r.getContact(i).o1, r.getContact(i).o2));
  return s;
}

struct Body {
  std::shared_ptr<fcl::CollisionGeometryd> geometry;
  std::unique_ptr<fcl::CollisionObjectd> object;
  Eigen::Vector3d radii;  // sphere: all equal
  Eigen::Vector3d axis;
  double spin;
  Eigen::Vector3d velocity;
  Eigen::Matrix3d R0;
  Eigen::Vector3d p0;
};

TEST(PairCache, AnimationMatchesBruteForceEveryFrameAndHitsItsPlanes) {
  std::mt19937_64 rng(121);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Body> bodies(300);
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    Body& b = bodies[i];
    const bool sphere = i % 5 == 0;
    b.radii = sphere ? Eigen::Vector3d::Constant(0.3 + 0.5 * u(rng)) : test::randomRadii(rng, 0.9, 4.0);
    if (sphere) b.geometry = std::make_shared<fcl::Sphered>(b.radii[0]);
    else b.geometry = std::make_shared<fcl::Ellipsoidd>(b.radii[0], b.radii[1], b.radii[2]);
    b.R0 = test::randomRotation(rng);
    b.p0 = Eigen::Vector3d(20 * u(rng), 20 * u(rng), 20 * u(rng));
    b.axis = test::randomUnitVector(rng);
    b.spin = 0.05 * u(rng);
    b.velocity = 0.02 * test::randomUnitVector(rng);
    b.object = std::make_unique<fcl::CollisionObjectd>(b.geometry, fcl::Transform3d::Identity());
  }
  fcl::DynamicAABBTreeCollisionManagerd manager;
  for (auto& b : bodies) manager.registerObject(b.object.get());
  PairCache cache;
  std::uint64_t collisions = 0;
  for (int frame = 0; frame < 60; ++frame) {
    std::vector<Ellipsoid> es;
    for (auto& b : bodies) {
      fcl::Transform3d tf = fcl::Transform3d::Identity();
      tf.linear() = Eigen::AngleAxisd(b.spin * frame, b.axis).toRotationMatrix() * b.R0;
      tf.translation() = b.p0 + frame * b.velocity;
      b.object->setTransform(tf);
      b.object->computeAABB();
      const bool sphere = b.geometry->getNodeType() == fcl::GEOM_SPHERE;
      es.push_back(sphere ? Ellipsoid::sphere(b.radii[0], tf.translation()) : Ellipsoid(b.radii, tf.linear(), tf.translation()));
    }
    manager.update();
    CoherentCollisionData data(&cache);
    data.request.num_max_contacts = 1000000;
    manager.collide(&data, coherentCollisionFunction);
    PairSet expected;
    for (std::size_t i = 0; i < es.size(); ++i)
      for (std::size_t j = i + 1; j < es.size(); ++j)
        if (ellipsoidsCollide(es[i], es[j])) expected.insert(ordered(bodies[i].geometry.get(), bodies[j].geometry.get()));
    ASSERT_EQ(contactPairs(data.result), expected) << "frame " << frame;
    collisions += expected.size();
  }
  EXPECT_GT(collisions, 50u);
  EXPECT_GT(cache.queries(), 1000u);
  EXPECT_GT(cache.planeHits(), cache.queries() / 2);  // slow motion: most planes stay valid
  // invalidate() drops every entry of an object.
  const std::size_t before = cache.size();
  for (auto& b : bodies) cache.invalidate(b.object.get());
  EXPECT_GT(before, 0u);
  EXPECT_EQ(cache.size(), 0u);
}

TEST(PairCache, ChangedGeometryIsNeverAnsweredFromAStalePlane) {
  PairCache cache;
  auto small = std::make_shared<fcl::Sphered>(1.0);
  fcl::CollisionObjectd a(small, fcl::Transform3d::Identity());
  fcl::Transform3d tb = fcl::Transform3d::Identity();
  tb.translation() << 3.0, 0, 0;
  fcl::CollisionObjectd b(std::make_shared<fcl::Ellipsoidd>(1.0, 1.0, 1.0), tb);
  fcl::CollisionRequestd req;
  fcl::CollisionResultd res;
  EXPECT_EQ(cache.collide(&a, &b, req, res), 0u);
  EXPECT_EQ(cache.size(), 1u);
  // Grow a's geometry in place (FCL 0.7 has no setter for an object's geometry; users edit the
  // shape): the cached plane is re-certified against the current radius and fails.
  small->radius = 2.5;
  a.computeAABB();
  fcl::CollisionResultd res2;
  EXPECT_GT(cache.collide(&a, &b, req, res2), 0u);
  EXPECT_TRUE(res2.isCollision());
  EXPECT_EQ(cache.planeHits(), 0u);
  // Move b away: a new plane, then hits.
  tb.translation() << 10.0, 0, 0;
  b.setTransform(tb);
  fcl::CollisionResultd r3, r4;
  cache.collide(&a, &b, req, r3);
  cache.collide(&b, &a, req, r4);  // either order shares the entry
  EXPECT_EQ(cache.planeHits(), 1u);
  EXPECT_FALSE(r4.isCollision());
}

TEST(PairCache, OtherPairsGoThroughTheFrontDoorAndBadDataThrows) {
  PairCache cache;
  fcl::Transform3d t = fcl::Transform3d::Identity();
  fcl::CollisionObjectd e(std::make_shared<fcl::Ellipsoidd>(1.0, 2.0, 3.0), t);
  t.translation() << 1.2, 0, 0;
  fcl::CollisionObjectd box(std::make_shared<fcl::Boxd>(1.0, 1.0, 1.0), t);
  fcl::CollisionRequestd req;
  fcl::CollisionResultd r1, r2;
  cache.collide(&e, &box, req, r1);
  fcl_quadric::collide(&e, &box, req, r2);
  EXPECT_EQ(r1.isCollision(), r2.isCollision());
  EXPECT_EQ(cache.queries(), 0u);
  EXPECT_THROW(coherentCollisionFunction(&e, &box, nullptr), std::invalid_argument);
  CoherentCollisionData no_cache(nullptr);
  EXPECT_THROW(coherentCollisionFunction(&e, &box, &no_cache), std::invalid_argument);
  EXPECT_THROW(cache.collide(nullptr, &box, req, r1), std::invalid_argument);
}

}  // namespace
}  // namespace pair_cache_test
}  // namespace fcl_quadric
