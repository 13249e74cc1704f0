// Experiment (4) of `fcl_quadric bench`: the thesis' boxing set-up (Choi 2008, Table 5;
// benchmarks/boxing_scene.h) for continuous collision: continuousCollideEllipsoids against
// fcl::continuousCollide (CCDC_NAIVE) and Bullet's btContinuousConvexCollision on the same moving
// pairs. Every peer sees the same motion: between frames k and k + 1 each part translates from
// its pose at k to its position at k + 1 with the orientation of frame k (fromPoses with equal
// rotations is a pure translation, FCL's CCDM_TRANS, and Bullet's cast between two transforms
// with the same basis), so the peers' answers can be compared pair by pair.
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/narrowphase/continuous_collision.h>

#include "benchmarks/boxing_scene.h"
#include "benchmarks/bullet_peers.h"
#include "fcl_quadric/bench_experiments.h"
#include "fcl_quadric/continuous/ellipsoid_ccd.h"
#include "fcl_quadric/continuous/motion_matrix.h"
#include "fcl_quadric/geometry/ellipsoid_separation.h"

namespace fcl_quadric {
namespace cli {

namespace {

struct MovingPair {
  int part_a = 0, part_b = 0;
  Eigen::Isometry3d a0, a1, b0, b1;
};

fcl::Transform3d fclOf(const Eigen::Isometry3d& X) {
  fcl::Transform3d T = fcl::Transform3d::Identity();
  T.linear() = X.linear();
  T.translation() = X.translation();
  return T;
}

/// Pose at k + 1's position with k's orientation.
Eigen::Isometry3d translated(const Eigen::Isometry3d& X0, const Eigen::Isometry3d& X1) {
  Eigen::Isometry3d X = X0;
  X.translation() = X1.translation();
  return X;
}

}  // namespace

BenchExperiment runBoxingExperiment(BenchSize size, const BenchProgress& progress) {
  const std::size_t frames = size == BenchSize::kTiny ? 5 : size == BenchSize::kSmall ? 300 : 1000;
  BenchExperiment e;
  e.name = "boxing";
  e.title = "Boxing (thesis Table 5): continuous collision of 2 x 20 ellipsoids, 400 cross pairs per frame";
  e.unit = "pair";
  const bench::BoxingScene scene = bench::makeBoxing(frames);
  std::vector<MovingPair> pairs;
  for (int k = 0; k < scene.frames; ++k) {
    for (int pa = 0; pa < bench::kParts; ++pa) {
      for (int pb = 0; pb < bench::kParts; ++pb) {
        MovingPair m;
        m.part_a = pa;
        m.part_b = pb;
        m.a0 = scene.poses[0][k][pa];
        m.a1 = translated(m.a0, scene.poses[0][k + 1][pa]);
        m.b0 = scene.poses[1][k][pb];
        m.b1 = translated(m.b0, scene.poses[1][k + 1][pb]);
        pairs.push_back(m);
      }
    }
  }
  const std::size_t n = pairs.size();
  std::vector<fcl::Ellipsoidd> fcl_shapes;
  std::vector<std::unique_ptr<btMultiSphereShape>> bt_shapes;
  for (int p = 0; p < bench::kParts; ++p) {
    fcl_shapes.emplace_back(bench::partRadii()[p]);
    bt_shapes.push_back(bench::bulletShape(bench::partRadii()[p]));
  }
  std::vector<char> truth(n), hit(n);
  CcdOptions options;
  options.all_intervals = false;
  auto ours = [&](const MovingPair& m) {
    const MovingEllipsoid a{scene.bodies[m.part_a], PiecewiseMotion(MotionMatrix::fromPoses(m.a0, m.a1))};
    const MovingEllipsoid b{scene.bodies[m.part_b], PiecewiseMotion(MotionMatrix::fromPoses(m.b0, m.b1))};
    return continuousCollideEllipsoids(a, b, options).collide;
  };
  auto overlapAtStart = [&](const MovingPair& m) {
    const Ellipsoid& a = scene.bodies[m.part_a];
    const Ellipsoid& b = scene.bodies[m.part_b];
    return ellipsoidsCollide(Ellipsoid(a.radii(), m.a0.linear(), m.a0.translation()),
                             Ellipsoid(b.radii(), m.b0.linear(), m.b0.translation()));
  };
  auto row = [&](const char* peer, auto&& f) {
    BenchRow r;
    r.case_name = "boxing";
    r.peer = peer;
    r.n = n;
    r.ns_per_query = nsPerQuery(n, [&] {
      for (std::size_t i = 0; i < n; ++i) hit[i] = f(pairs[i]);
    });
    std::size_t misses = 0, misses_at_start = 0, false_hits = 0;
    for (std::size_t i = 0; i < n; ++i) {
      misses += truth[i] && !hit[i];
      misses_at_start += truth[i] && !hit[i] && overlapAtStart(pairs[i]);
      false_hits += hit[i] && !truth[i];
    }
    r.wrong = static_cast<long>(misses + false_hits);
    if (r.wrong > 0) {
      char line[160];
      std::snprintf(line, sizeof line, "%s: %zu missed contacts (%zu of them touching or overlapping at t = 0), %zu false hits",
                    peer, misses, misses_at_start, false_hits);
      e.notes.push_back(line);
    }
    return r;
  };
  std::size_t colliding = 0;
  for (std::size_t i = 0; i < n; ++i) colliding += truth[i] = ours(pairs[i]);
  progress(0.1);
  e.rows.push_back(row("fcl_quadric", ours));
  progress(0.3);
  e.rows.push_back(row("fcl_naive", [&](const MovingPair& m) {
    fcl::ContinuousCollisionRequestd request;
    request.ccd_solver_type = fcl::CCDC_NAIVE;
    request.ccd_motion_type = fcl::CCDM_TRANS;
    fcl::ContinuousCollisionResultd result;
    fcl::continuousCollide(&fcl_shapes[m.part_a], fclOf(m.a0), fclOf(m.a1), &fcl_shapes[m.part_b], fclOf(m.b0),
                           fclOf(m.b1), request, result);
    return result.is_collide;
  }));
  progress(0.6);
  e.rows.push_back(row("bullet", [&](const MovingPair& m) {
    return bench::bulletTimeOfImpact(bt_shapes[m.part_a].get(), bench::bulletPose(m.a0), bench::bulletPose(m.a1),
                                     bt_shapes[m.part_b].get(), bench::bulletPose(m.b0), bench::bulletPose(m.b1))
        .has_value();
  }));
  progress(0.9);
  // Conservative advancement, once (untimed): FCL 0.7 has no ellipsoid entry for it.
  double ca = 0.0;
  {
    const MovingPair& m = pairs.front();
    fcl::ContinuousCollisionRequestd request;
    request.ccd_solver_type = fcl::CCDC_CONSERVATIVE_ADVANCEMENT;
    request.ccd_motion_type = fcl::CCDM_TRANS;
    fcl::ContinuousCollisionResultd result;
    ca = fcl::continuousCollide(&fcl_shapes[m.part_a], fclOf(m.a0), fclOf(m.a1), &fcl_shapes[m.part_b], fclOf(m.b0),
                                fclOf(m.b1), request, result);
  }
  progress(1.0);
  char line[256];
  std::snprintf(line, sizeof line,
                "%zu frames x 400 moving pairs (parts translate between frames, orientation of the frame's start), %zu "
                "collide in [0, 1]",
                frames, colliding);
  e.notes.push_back(line);
  e.notes.push_back("fcl_naive: fcl::continuousCollide CCDC_NAIVE, CCDM_TRANS, request defaults (10 samples)");
  std::snprintf(line, sizeof line,
                "fcl::continuousCollide CCDC_CONSERVATIVE_ADVANCEMENT returned %g for ellipsoids (not supported), so "
                "it has no row",
                ca);
  e.notes.push_back(line);
  return e;
}

}  // namespace cli
}  // namespace fcl_quadric
