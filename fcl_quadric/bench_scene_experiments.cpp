// Experiments (5) broad-phase scene and (6) OcTree environment of `fcl_quadric bench`, on the
// scenes of benchmarks/bench_fcl_support.h (shared with bench_fcl_scenes): fcl_quadric's narrow
// phase inside FCL's own machinery (the fcl_quadric_fcl front doors) against stock FCL 0.7, and
// for the broad phase Bullet's own pipeline (btCollisionWorld with btDbvtBroadphase). Bullet has no
// voxel-map shape, so the OcTree experiment has no Bullet row.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <BulletCollision/BroadphaseCollision/btDbvtBroadphase.h>
#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/CollisionDispatch/btCollisionObject.h>
#include <BulletCollision/CollisionDispatch/btCollisionWorld.h>
#include <BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h>
#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>
#include <fcl/narrowphase/collision.h>

#include "benchmarks/bench_fcl_support.h"
#include "benchmarks/bullet_peers.h"
#include "fcl_quadric/bench_experiments.h"
#include "fcl_quadric/fcl/collision.h"

namespace fcl_quadric {
namespace cli {

namespace {

/// The scene as a Bullet user would set it up: one btCollisionObject per ellipsoid (the scaled
/// multisphere of bullet_peers.h) in a btCollisionWorld with a btDbvtBroadphase. Members are
/// declared so that the world is destroyed first, while its objects still exist.
class BulletScene {
 public:
  explicit BulletScene(bench::MovingEllipsoids& s) : world_(&dispatcher_, &broadphase_, &config_) {
    s.setFrame(0);
    for (std::size_t i = 0; i < s.size(); ++i) {
      shapes_.push_back(bench::bulletShape(s.ellipsoid(i).radii()));
      auto o = std::make_unique<btCollisionObject>();
      o->setCollisionShape(shapes_.back().get());
      o->setUserIndex(static_cast<int>(i));
      world_.addCollisionObject(o.get());
      objects_.push_back(std::move(o));
    }
  }

  /// Frame k: new poses, then Bullet's broad and narrow phase; returns the number of colliding
  /// pairs (a contact point at distance <= 0) and, if asked, the pairs (i < j, sorted).
  std::size_t runFrame(const bench::MovingEllipsoids& s, int k, bench::IndexPairs* pairs = nullptr) {
    for (std::size_t i = 0; i < objects_.size(); ++i) {
      const fcl::Transform3d X = s.poseAt(i, k);
      objects_[i]->setWorldTransform(bench::bulletPose(X.linear(), X.translation()));
    }
    world_.performDiscreteCollisionDetection();
    std::size_t colliding = 0;
    for (int m = 0; m < dispatcher_.getNumManifolds(); ++m) {
      const btPersistentManifold* manifold = dispatcher_.getManifoldByIndexInternal(m);
      bool contact = false;
      for (int c = 0; c < manifold->getNumContacts(); ++c) contact = contact || manifold->getContactPoint(c).getDistance() <= 0;
      if (!contact) continue;
      ++colliding;
      if (pairs) {
        const std::size_t a = static_cast<std::size_t>(manifold->getBody0()->getUserIndex());
        const std::size_t b = static_cast<std::size_t>(manifold->getBody1()->getUserIndex());
        pairs->emplace_back(std::min(a, b), std::max(a, b));
      }
    }
    if (pairs) std::sort(pairs->begin(), pairs->end());
    return colliding;
  }

 private:
  btDefaultCollisionConfiguration config_;
  btCollisionDispatcher dispatcher_{&config_};
  btDbvtBroadphase broadphase_;
  std::vector<std::unique_ptr<btMultiSphereShape>> shapes_;
  std::vector<std::unique_ptr<btCollisionObject>> objects_;
  btCollisionWorld world_;
};

}  // namespace

BenchExperiment runBroadphaseExperiment(BenchSize size, const BenchProgress& progress) {
  const std::size_t n = size == BenchSize::kTiny ? 50 : 1000;
  const int frames = size == BenchSize::kTiny ? 5 : size == BenchSize::kSmall ? 300 : 1000;
  BenchExperiment e;
  e.name = "broadphase";
  char title[160];
  std::snprintf(title, sizeof title,
                "Broad phase: %zu spinning, drifting ellipsoids in a DynamicAABBTreeCollisionManager, %d frames", n,
                frames);
  e.title = title;
  e.unit = "frame";
  bench::MovingEllipsoids scene(n, frames, bench::kMovingSeed + n);
  const bench::MovingReport report = bench::countMoving(scene);
  progress(0.2);
  const bench::Peer peers[] = {bench::Peer::kOurs, bench::Peer::kPairCache, bench::Peer::kStock,
                               bench::Peer::kBroadphaseOnly};
  int done = 0;
  for (bench::Peer peer : peers) {
    PairCache cache;
    std::size_t total = 0;
    BenchRow row;
    row.case_name = "broadphase";
    row.peer = bench::peerName(peer);
    row.n = static_cast<std::size_t>(frames);
    row.ns_per_query = nsPerQuery(row.n, [&] {
      for (int k = 0; k < frames; ++k) total += bench::runFrame(scene, k, peer, &cache);
    });
    const int p = peer == bench::Peer::kOurs ? 0 : peer == bench::Peer::kPairCache ? 1 : 2;
    row.wrong = peer == bench::Peer::kBroadphaseOnly
                    ? -1
                    : static_cast<long>(report.misses[p] + report.false_hits[p]);
    e.rows.push_back(row);
    progress(0.2 + 0.15 * ++done);
  }
  {
    // Bullet: its own broad phase and narrow phase. Timed on a fresh world (manifolds persist
    // between frames, as in a Bullet simulation); its wrong pairs are counted on a second one.
    BulletScene timed(scene);
    BenchRow row;
    row.case_name = "broadphase";
    row.peer = "bullet";
    row.n = static_cast<std::size_t>(frames);
    std::size_t total = 0;
    row.ns_per_query = nsPerQuery(row.n, [&] {
      for (int k = 0; k < frames; ++k) total += timed.runFrame(scene, k);
    });
    BulletScene counted(scene);
    std::size_t misses = 0, false_hits = 0;
    for (int k = 0; k < frames; ++k) {
      bench::IndexPairs found;
      counted.runFrame(scene, k, &found);
      const bench::IndexPairs exact = bench::exactCollidingPairs(scene, k);
      misses += bench::countMissing(exact, found);
      false_hits += bench::countMissing(found, exact);
    }
    row.wrong = static_cast<long>(misses + false_hits);
    e.rows.push_back(row);
    char note[200];
    std::snprintf(note, sizeof note,
                  "bullet: btCollisionWorld + btDbvtBroadphase, scaled btMultiSphereShape; a pair collides when its "
                  "manifold has a point at distance <= 0; %zu missed, %zu false",
                  misses, false_hits);
    e.notes.push_back(note);
    progress(1.0);
  }
  char line[256];
  std::snprintf(line, sizeof line,
                "%zu candidate pairs (overlapping AABBs) and %zu colliding pairs over all frames; wrong = pairs missed "
                "or falsely reported, summed over frames",
                report.candidates, report.colliding);
  e.notes.push_back(line);
  e.notes.push_back("broadphase_only: the callback only counts candidates (the part every peer shares)");
  return e;
}

BenchExperiment runOcTreeExperiment(BenchSize size, const BenchProgress& progress) {
  const std::size_t queries = size == BenchSize::kTiny ? 100 : size == BenchSize::kSmall ? 2000 : 10000;
  const double half = size == BenchSize::kTiny ? 3.0 : 8.0;
  BenchExperiment e;
  e.name = "octree";
  e.unit = "query";
  const std::shared_ptr<octomap::OcTree> tree = bench::terrainOcTree(half, 0.05);
  auto fcl_tree = std::make_shared<fcl::OcTreed>(std::shared_ptr<const octomap::OcTree>(tree));
  const bench::LeafBoxes boxes(*fcl_tree);
  const fcl::CollisionObjectd environment(fcl_tree, fcl::Transform3d::Identity());
  char title[200];
  std::snprintf(title, sizeof title,
                "OcTree: one ellipsoid against a terrain fcl::OcTree (%.0f x %.0f m, resolution 0.05, %zu occupied "
                "leaves)",
                2 * half, 2 * half, boxes.size());
  e.title = title;
  progress(0.3);
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects;
  std::vector<char> truth;
  std::size_t colliding = 0;
  for (const Ellipsoid& q : bench::terrainQueries(half, queries)) {
    objects.push_back(std::make_unique<fcl::CollisionObjectd>(std::make_shared<fcl::Ellipsoidd>(q.radii()),
                                                              bench::makePose(q.rotation(), q.center())));
    truth.push_back(boxes.collides(q));
    colliding += truth.back();
  }
  progress(0.5);
  std::vector<char> hit(objects.size());
  for (int ours = 1; ours >= 0; --ours) {
    BenchRow row;
    row.case_name = "octree";
    row.peer = ours ? "fcl_quadric" : "fcl_libccd";
    row.n = objects.size();
    row.ns_per_query = nsPerQuery(row.n, [&] {
      for (std::size_t i = 0; i < objects.size(); ++i) {
        fcl::CollisionRequestd request;  // boolean: one contact, no contact details
        fcl::CollisionResultd result;
        hit[i] = (ours ? fcl_quadric::collide(objects[i].get(), &environment, request, result)
                       : fcl::collide(objects[i].get(), &environment, request, result)) > 0;
      }
    });
    row.wrong = 0;
    for (std::size_t i = 0; i < hit.size(); ++i) row.wrong += (hit[i] != 0) != (truth[i] != 0);
    e.rows.push_back(row);
    progress(ours ? 0.75 : 1.0);
  }
  char line[256];
  std::snprintf(line, sizeof line,
                "%zu query ellipsoids near the surface, %zu collide (exact: classifyEllipsoidBox over the occupied leaf "
                "boxes; touching counts as collision)",
                objects.size(), colliding);
  e.notes.push_back(line);
  return e;
}

}  // namespace cli
}  // namespace fcl_quadric
