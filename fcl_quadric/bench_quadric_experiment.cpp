// Experiment (7) of `fcl_quadric bench`: composite quadric models (issue 5) on the pairs of
// benchmarks/quadric_shapes_scene.h. Capped circular cylinders: the certified region engine
// against stock FCL 0.7 (fcl::Cylinder, GJK libccd and indep) and Bullet (btCylinderShapeZ,
// GJK/EPA) on the same poses. Capped elliptic cylinders: against FCL on tessellated prisms
// (fcl::Convex), the only model a user of FCL has for them. CSG ring-versus-wedge pairs: fcl_quadric alone (no peer models a
// CSG solid of quadrics; a user would tessellate it).
#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <BulletCollision/CollisionShapes/btCylinderShape.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/narrowphase/collision.h>

#include "benchmarks/bullet_peers.h"
#include "benchmarks/fcl_peers.h"
#include "benchmarks/quadric_shapes_scene.h"
#include "fcl_quadric/bench_experiments.h"

namespace fcl_quadric {
namespace cli {

BenchExperiment runQuadricShapesExperiment(BenchSize size, const BenchProgress& progress) {
  const std::size_t n = size == BenchSize::kTiny ? 200 : size == BenchSize::kSmall ? 2000 : 20000;
  const std::size_t n_csg = size == BenchSize::kTiny ? 64 : size == BenchSize::kSmall ? 256 : 2048;
  BenchExperiment e;
  e.name = "quadric_shapes";
  e.title = "Composite quadric models: capped circular and elliptic cylinders, CSG ring-vs-wedge pairs";
  e.unit = "pair";
  e.truth =
      "the region engine's certified relation (Touching counts as contact; checked against sampling oracles in the "
      "test suite)";
  const std::vector<bench::CylinderPair> pairs = bench::makeCylinderPairs(n);
  std::vector<char> truth(n), hit(n);
  std::size_t colliding = 0, touching = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const RegionRelation r = bench::cylinderPairRelation(pairs[i]);
    truth[i] = r != RegionRelation::Separated;
    colliding += truth[i];
    touching += r == RegionRelation::Touching;
  }
  progress(0.2);
  auto row = [&](const std::string& case_name, const std::string& peer, std::size_t count, auto&& f) {
    BenchRow r;
    r.case_name = case_name;
    r.peer = peer;
    r.n = count;
    r.ns_per_query = nsPerQuery(count, [&] {
      for (std::size_t i = 0; i < count; ++i) hit[i] = f(i);
    });
    return r;
  };
  auto countWrong = [&](BenchRow* r) {
    long wrong = 0;
    for (std::size_t i = 0; i < n; ++i) wrong += (hit[i] != 0) != (truth[i] != 0);
    r->wrong = wrong;
  };
  {
    BenchRow r = row("cylinders", "fcl_quadric", n, [&](std::size_t i) {
      return bench::cylinderPairRelation(pairs[i]) != RegionRelation::Separated;
    });
    countWrong(&r);
    e.rows.push_back(r);
  }
  progress(0.4);
  for (const fcl::GJKSolverType solver : {fcl::GST_LIBCCD, fcl::GST_INDEP}) {
    BenchRow r = row("cylinders", solver == fcl::GST_LIBCCD ? "fcl_libccd" : "fcl_indep", n, [&](std::size_t i) {
      const bench::CylinderPair& c = pairs[i];
      const fcl::Cylinderd a(c.r1, c.L1), b(c.r2, c.L2);
      fcl::Transform3d tb = fcl::Transform3d::Identity();
      tb.linear() = c.R;
      tb.translation() = c.p;
      fcl::CollisionRequestd request;
      request.gjk_solver_type = solver;
      fcl::CollisionResultd result;
      return fcl::collide(&a, fcl::Transform3d::Identity(), &b, tb, request, result) > 0;
    });
    countWrong(&r);
    e.rows.push_back(r);
    progress(solver == fcl::GST_LIBCCD ? 0.5 : 0.6);
  }
  {
    // Bullet's cylinder along z, as a user builds it (half extents r, r, L/2; default margin).
    std::vector<std::unique_ptr<btCylinderShapeZ>> a, b;
    for (const bench::CylinderPair& c : pairs) {
      a.push_back(std::make_unique<btCylinderShapeZ>(btVector3(c.r1, c.r1, 0.5 * c.L1)));
      b.push_back(std::make_unique<btCylinderShapeZ>(btVector3(c.r2, c.r2, 0.5 * c.L2)));
    }
    const btTransform identity = btTransform::getIdentity();
    BenchRow r = row("cylinders", "bullet", n, [&](std::size_t i) {
      return bench::bulletCollide(a[i].get(), identity, b[i].get(), bench::bulletPose(pairs[i].R, pairs[i].p));
    });
    countWrong(&r);
    e.rows.push_back(r);
  }
  {
    char line[320];
    std::snprintf(line, sizeof line,
                  "cylinders: %zu pairs (radius U(0.3, 1), length U(0.6, 2), random poses in [-2, 2]^3), %zu in "
                  "contact, %zu of them Touching (the engine's tolerance band: counted as contact)",
                  n, colliding, touching);
    e.notes.push_back(line);
  }
  progress(0.7);
  {
    // Capped elliptic cylinders: no FCL or Bullet primitive; a user tessellates them (a prism over
    // an inscribed k-gon, as fcl::Convex: libccd GJK on its vertices).
    // The tessellated peers hold one fcl::Convex per body (~50 KB at 512 vertices): at most 5,000
    // pairs, so that the full size stays under a gigabyte.
    const std::size_t ne = std::min<std::size_t>(n, 5000);
    const std::vector<bench::EllipticCylinderPair> ep = bench::makeEllipticCylinderPairs(ne);
    std::vector<char> etruth(ne);
    std::size_t ecolliding = 0;
    for (std::size_t i = 0; i < ne; ++i) {
      etruth[i] = bench::ellipticCylinderPairRelation(ep[i]) != RegionRelation::Separated;
      ecolliding += etruth[i];
    }
    auto countEllipticWrong = [&](BenchRow* r) {
      long wrong = 0;
      for (std::size_t i = 0; i < ne; ++i) wrong += (hit[i] != 0) != (etruth[i] != 0);
      r->wrong = wrong;
    };
    BenchRow ours = row("elliptic cylinders", "fcl_quadric", ne, [&](std::size_t i) {
      return bench::ellipticCylinderPairRelation(ep[i]) != RegionRelation::Separated;
    });
    countEllipticWrong(&ours);
    e.rows.push_back(ours);
    for (const int k : {16, 64, 256}) {
      std::vector<std::shared_ptr<fcl::Convexd>> ca, cb;
      for (const bench::EllipticCylinderPair& c : ep) {
        ca.push_back(bench::fclConvex(bench::ellipticCylinderMesh(c.a1, c.b1, c.L1, k)));
        cb.push_back(bench::fclConvex(bench::ellipticCylinderMesh(c.a2, c.b2, c.L2, k)));
      }
      BenchRow r = row("elliptic cylinders", "fcl_convex_" + std::to_string(2 * k), ne, [&](std::size_t i) {
        fcl::Transform3d tb = fcl::Transform3d::Identity();
        tb.linear() = ep[i].R;
        tb.translation() = ep[i].p;
        return bench::fclCollide(ca[i].get(), fcl::Transform3d::Identity(), cb[i].get(), tb, fcl::GST_LIBCCD);
      });
      countEllipticWrong(&r);
      e.rows.push_back(r);
    }
    char note[240];
    std::snprintf(note, sizeof note,
                  "elliptic cylinders: %zu pairs (semi-axes U(0.3, 1), length U(0.6, 2), random poses), %zu in "
                  "contact; fcl_convex_N: libccd on a prism over an inscribed polygon, N vertices",
                  ne, ecolliding);
    e.notes.push_back(note);
  }
  progress(0.85);
  const QuadricRegion ring = bench::ringRegion(), wedge = bench::wedgeRegion();
  const Box3 ring_box = regionAabb(ring), wedge_box = regionAabb(wedge);
  const auto poses = bench::makeRingWedgePoses(n_csg);
  std::size_t csg_colliding = 0;
  if (hit.size() < n_csg) hit.resize(n_csg);
  BenchRow csg = row("csg ring-wedge", "fcl_quadric", n_csg, [&](std::size_t i) {
    return collideRegions(ring, ring_box, wedge, wedge_box, poses[i].first, poses[i].second).relation !=
           RegionRelation::Separated;
  });
  for (std::size_t i = 0; i < n_csg; ++i) csg_colliding += hit[i];
  csg.wrong = -1;  // no peer, no independent answer in this run (the test suite checks the engine)
  e.rows.push_back(csg);
  progress(1.0);
  char line[320];
  std::snprintf(line, sizeof line,
                "csg ring-wedge: ring = ellipsoid (1.2, 1.2, 0.6) minus a bore of radius 0.6; wedge = capped elliptic "
                "cylinder (1.0, 0.7, 0.8) minus the half-space y > 0 minus a bore of radius 0.3; %zu random poses, %zu "
                "in contact; no peer models these solids",
                n_csg, csg_colliding);
  e.notes.push_back(line);
  e.notes.push_back("bullet: btCylinderShapeZ (default collision margin, inside its half extents), GJK/EPA distance <= 0");
  return e;
}

}  // namespace cli
}  // namespace fcl_quadric
