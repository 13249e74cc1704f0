// Thread safety as documented (collision.h, distance.h, pair_cache.h): the front doors and the
// solver are stateless and may be called from several threads on the same objects at once; a
// PairCache is per thread. Two threads query one shared scene at the same time and must get
// exactly the answers of a sequential run. The CI runs this suite under ThreadSanitizer
// (scripts/ci-sanitizers.sh), which reports any data race on the way, including on the
// function-local static tables (FCL's CollisionFunctionMatrix / DistanceFunctionMatrix for
// QuadricSolver) that the first test initialises from both threads at once.
#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <random>
#include <set>
#include <thread>
#include <utility>
#include <vector>

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/sphere.h>

#include "fcl_quadric/continuous/ellipsoid_ccd.h"
#include "fcl_quadric/fcl/collision.h"
#include "fcl_quadric/fcl/distance.h"
#include "fcl_quadric/fcl/pair_cache.h"
#include "fcl_quadric/fcl/quadric_shapes.h"
#include "fcl_quadric/geometry/quadric_region.h"
#include "support/random_ellipsoids.h"

namespace fcl_quadric {
namespace {

struct Scene {
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects;
  std::vector<std::pair<int, int>> pairs;  // every pair with at least one fcl::Ellipsoid (exact paths)
};

// 24 objects in a 6^3 box: ellipsoids, spheres, boxes and (with `all_kinds`) capsules and a
// cylinder, dense enough that many pairs touch. Without `all_kinds` every pair that has no
// ellipsoid is one of FCL's closed forms (sphere/box), never libccd's GJK, which raises the test
// main's floating-point traps internally.
Scene makeScene(bool all_kinds) {
  Scene s;
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<bool> ellipsoid;
  for (int i = 0; i < 24; ++i) {
    std::shared_ptr<fcl::CollisionGeometryd> g;
    switch (i % 6) {
      case 0:
      case 1:
      case 2: {
        const Eigen::Vector3d r = test::randomRadii(rng, 1.5, 5.0);
        g = std::make_shared<fcl::Ellipsoidd>(r[0], r[1], r[2]);
        break;
      }
      case 3: g = std::make_shared<fcl::Sphered>(0.4 + u(rng)); break;
      case 4: g = std::make_shared<fcl::Boxd>(0.5 + u(rng), 0.5 + u(rng), 0.5 + u(rng)); break;
      default:
        if (all_kinds) g = std::make_shared<fcl::Capsuled>(0.3 + 0.5 * u(rng), 0.5 + u(rng));
        else g = std::make_shared<fcl::Sphered>(0.4 + u(rng));
        break;
    }
    if (i == 23 && all_kinds) g = std::make_shared<fcl::Cylinderd>(0.6, 1.5);
    ellipsoid.push_back(i % 6 < 3);
    fcl::Transform3d X = fcl::Transform3d::Identity();
    X.linear() = test::randomRotation(rng);
    X.translation() = Eigen::Vector3d(6 * u(rng), 6 * u(rng), 6 * u(rng));
    s.objects.push_back(std::make_unique<fcl::CollisionObjectd>(g, X));
    s.objects.back()->computeAABB();  // before the threads: the only mutation of an object
  }
  for (int i = 0; i < 24; ++i)
    for (int j = i + 1; j < 24; ++j)
      if (ellipsoid[i] || ellipsoid[j]) s.pairs.emplace_back(i, j);
  return s;
}

struct Answer {
  bool collide;
  std::size_t contacts;
  double distance;
  bool operator==(const Answer& o) const { return collide == o.collide && contacts == o.contacts && distance == o.distance; }
};

std::vector<Answer> queryAll(const Scene& s) {
  std::vector<Answer> answers;
  fcl::CollisionRequestd creq(4, true);
  fcl::DistanceRequestd dreq(true);
  dreq.enable_signed_distance = true;
  for (const auto& [i, j] : s.pairs) {
    fcl::CollisionResultd cres;
    fcl::DistanceResultd dres;
    fcl_quadric::collide(s.objects[i].get(), s.objects[j].get(), creq, cres);
    const double d = fcl_quadric::distance(s.objects[i].get(), s.objects[j].get(), dreq, dres);
    answers.push_back({cres.isCollision(), cres.numContacts(), d});
  }
  return answers;
}

/// Runs f(thread index) on two threads that start together.
template <typename F>
void onTwoThreads(F f) {
  std::atomic<int> ready{0};
  auto body = [&](int k) {
    ready.fetch_add(1);
    while (ready.load() < 2) std::this_thread::yield();
    f(k);
  };
  std::thread t0(body, 0), t1(body, 1);
  t0.join();
  t1.join();
}

// Must stay the first test of this executable: the two threads make the first calls of the
// front doors, so the static dispatch tables are initialised concurrently.
TEST(ConcurrentQueries, TwoThreadsOnOneSceneGetTheSequentialAnswers) {
  const Scene scene = makeScene(true);
  std::vector<Answer> results[2];
  onTwoThreads([&](int k) {
    for (int rep = 0; rep < 3; ++rep) results[k] = queryAll(scene);
  });
  const std::vector<Answer> sequential = queryAll(scene);
  ASSERT_EQ(sequential.size(), scene.pairs.size());
  int collisions = 0;
  for (std::size_t p = 0; p < sequential.size(); ++p) {
    EXPECT_TRUE(results[0][p] == sequential[p]) << "thread 0, pair " << p;
    EXPECT_TRUE(results[1][p] == sequential[p]) << "thread 1, pair " << p;
    collisions += sequential[p].collide;
    EXPECT_EQ(sequential[p].collide, sequential[p].distance <= 0) << "pair " << p;
  }
  // The scene exercises both answers.
  EXPECT_GT(collisions, 5);
  EXPECT_LT(collisions, static_cast<int>(sequential.size()) - 5);
}

using PairSet = std::set<std::pair<const void*, const void*>>;

PairSet contactPairs(const fcl::CollisionResultd& r) {
  PairSet s;
  for (std::size_t i = 0; i < r.numContacts(); ++i) {
    const void *a = r.getContact(i).o1, *b = r.getContact(i).o2;
    s.insert(a < b ? std::make_pair(a, b) : std::make_pair(b, a));
  }
  return s;
}

// pair_cache.h: "a PairCache is not thread-safe; use one per thread". Two threads, each with its
// own manager and cache over the same shared objects, three frames each (frames 2 and 3 are
// answered by cached planes), agree with a brute-force pass over the geometry pairs.
TEST(ConcurrentQueries, OnePairCachePerThreadOverSharedObjects) {
  const Scene scene = makeScene(false);
  fcl::CollisionRequestd request(1000, false);
  // Brute force over every pair of objects.
  PairSet expected;  // contacts name the geometries (fcl::Contact::o1, o2)
  for (std::size_t i = 0; i < scene.objects.size(); ++i)
    for (std::size_t j = i + 1; j < scene.objects.size(); ++j) {
      fcl::CollisionResultd r;
      if (fcl_quadric::collide(scene.objects[i].get(), scene.objects[j].get(), request, r) > 0) {
        const void *a = scene.objects[i]->collisionGeometry().get(), *b = scene.objects[j]->collisionGeometry().get();
        expected.insert(a < b ? std::make_pair(a, b) : std::make_pair(b, a));
      }
    }
  ASSERT_FALSE(expected.empty());
  PairSet found[2][3];
  std::uint64_t hits[2] = {0, 0};
  onTwoThreads([&](int k) {
    fcl::DynamicAABBTreeCollisionManagerd manager;
    std::vector<fcl::CollisionObjectd*> raw;
    for (const auto& o : scene.objects) raw.push_back(o.get());
    manager.registerObjects(raw);
    manager.setup();
    PairCache cache;
    for (int frame = 0; frame < 3; ++frame) {
      CoherentCollisionData data(&cache);
      data.request = request;
      manager.collide(&data, coherentCollisionFunction);
      found[k][frame] = contactPairs(data.result);
    }
    hits[k] = cache.planeHits();
  });
  for (int k = 0; k < 2; ++k) {
    for (int frame = 0; frame < 3; ++frame) EXPECT_EQ(found[k][frame], expected) << "thread " << k << " frame " << frame;
    EXPECT_GT(hits[k], 0u) << "thread " << k;
  }
}

// The continuous layer's static tables (Bernstein binomials, interpolation inverses) are shared by
// all threads: two threads solving the same moving pairs get the sequential answers.
TEST(ConcurrentQueries, TwoThreadsSolveTheSameMovingPairs) {
  std::mt19937_64 rng(88);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  std::vector<std::pair<MovingEllipsoid, MovingEllipsoid>> pairs;
  for (int k = 0; k < 12; ++k) {
    auto body = [&] { return Ellipsoid(test::randomRadii(rng, 1.0, 4.0), Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()); };
    const MotionMatrix ma = MotionMatrix::fromPoses(test::randomRotation(rng), Eigen::Vector3d(-2.5, U(rng), U(rng)),
                                                    test::randomRotation(rng), Eigen::Vector3d(2.5, U(rng), U(rng)));
    const MotionMatrix mb = MotionMatrix::fromPoses(test::randomRotation(rng), Eigen::Vector3d(U(rng), -2.5, U(rng)),
                                                    test::randomRotation(rng), Eigen::Vector3d(U(rng), 2.5, U(rng)));
    pairs.push_back({MovingEllipsoid{body(), PiecewiseMotion(ma)}, MovingEllipsoid{body(), PiecewiseMotion(mb)}});
  }
  auto solveAll = [&](CcdInterpolation interpolation) {
    std::vector<double> times;
    CcdOptions options;
    options.interpolation = interpolation;
    for (const auto& [a, b] : pairs) {
      const EllipsoidCcdResult r = continuousCollideEllipsoids(a, b, options);
      times.push_back(r.collide ? *r.first_contact_time : 2.0);
    }
    return times;
  };
  const std::vector<double> rigid = solveAll(CcdInterpolation::Rigid), affine = solveAll(CcdInterpolation::Affine);
  std::vector<double> results[2][2];
  onTwoThreads([&](int k) {
    results[k][0] = solveAll(CcdInterpolation::Rigid);
    results[k][1] = solveAll(CcdInterpolation::Affine);
  });
  int collisions = 0;
  for (double t : rigid) collisions += t <= 1.0;
  EXPECT_GT(collisions, 2);
  for (int k = 0; k < 2; ++k) {
    EXPECT_EQ(results[k][0], rigid) << "thread " << k;
    EXPECT_EQ(results[k][1], affine) << "thread " << k;
  }
}

/// A Quadric's mass properties are computed on first use (session 41: they took 2.5-29 ms of its
/// construction). Two threads asking at once, one through the shape and one through a copy
/// (which shares the computation), get the same values, those of regionMassProperties on the
/// same region and box; under TSan (scripts/ci-sanitizers.sh) the lazy computation is checked
/// for races.
TEST(ConcurrentQueries, TwoThreadsAskingAQuadricsMassPropertiesGetTheSameValues) {
  const Quadric<double> shape = Quadric<double>::ellipsoid(0.5, 0.7, 1.1, {{Eigen::Vector3d(0, 0, 1), 0.5}});
  const Quadric<double> copy = shape;
  double volume[2] = {0.0, 0.0};
  Eigen::Vector3d com[2];
  onTwoThreads([&](int k) {
    const Quadric<double>& q = k == 0 ? shape : copy;
    volume[k] = q.computeVolume();
    com[k] = q.computeCOM();
  });
  const MassProperties direct = regionMassProperties(shape.region(), shape.localBox());
  EXPECT_EQ(volume[0], direct.volume);
  EXPECT_EQ(volume[1], direct.volume);
  EXPECT_EQ(com[0], direct.centroid);
  EXPECT_EQ(com[1], direct.centroid);
  EXPECT_EQ(&shape.massProperties(), &copy.massProperties());  // one computation, shared
}

}  // namespace
}  // namespace fcl_quadric
