// Composite quadric models (issue 5): static queries of the certified region engine
// (geometry/quadric_region.h) against FCL 0.7's GJK (libccd) on the same capped circular cylinder
// poses, and CSG pairs (ring = ellipsoid minus bore, wedge = elliptic cylinder minus half-space
// minus cylinder; quadric_shapes_scene.h). One iteration = one pair, the pair set walked
// cyclically; `--pairs N` (default 2,000). `Cylinders/fcl_quadric` is the front door's collide on
// EllipticCylinder pairs made once (GJK's screening, the engine near contact; session 30). After
// the timed runs the program prints the agreement on the cylinder pairs: FCL's boolean and the
// front door's against the engine's certified answers (Touching pairs counted apart: within the
// engine's tolerance band, neither answer is wrong).
//
// Continuous (continuous/region_ccd.h): the second cylinder of each of the first `--motions N`
// pairs (default 32) translates from p + d to p - d (|d| = 2.5, random direction, rotation
// fixed: an fcl::TranslationMotion, the one motion both libraries run exactly alike) against
// FCL's continuousCollide on fcl::Cylinder with CCDC_NAIVE (10 time samples, FCL's default) and
// CCDC_CONSERVATIVE_ADVANCEMENT (GJK distances); afterwards their misses against the certified
// answers. CSG ring-wedge pairs under motions of degree 1 (translation), 2 (from two poses:
// rotation by quaternion interpolation) and 4 (two such motions composed).
//
// Small ellipsoids (geometry/ellipsoid_quadric.h): fcl::Ellipsoid (radii U(0.1, 0.35), random
// rotation, centre in the shape's AABB grown by 0.5 and within ~0.5 of the quadric surface) against
// three clipped quadrics (a
// paraboloid cup, a hyperboloid waist, a capped elliptic cylinder) through fcl_quadric::collide,
// which screens with GJK when the quadric is convex and then tries the seed paper's filter,
// against the region engine alone on the same pairs (the path before both); afterwards their
// agreement.
//
// Distance (geometry/convex_distance.h): fcl_quadric::distance on EllipticCylinder pairs (GJK on
// exact support mappings) against fcl::distance on the same fcl::Cylinder poses (libccd GJK,
// FCL's default solver and distance_tolerance); afterwards FCL's relative error on the separated
// pairs, against ours.
//
// Terrain: a capped circular cylinder (r 0.3, length 1) at 200 random poses over a 40,000-triangle
// height-field mesh (BVHModel<OBBRSS>): fcl_quadric::collide / distance on an EllipticCylinder
// (our traversal of the mesh's BVH, exact per triangle) against fcl::collide / fcl::distance on
// fcl::Cylinder (FCL's traversal nodes, libccd per triangle); afterwards their disagreements.
//
// OcTree terrain: the same cylinder at 50 random poses over an fcl::OcTree of a height field
// (resolution 0.05, 82,686 occupied leaves): fcl_quadric::collide / distance / distanceLowerBound
// on the EllipticCylinder (best-first search of the cells, GJK per leaf box) against
// fcl::collide / fcl::distance on fcl::Cylinder (FCL's OcTree traversal, libccd per leaf);
// afterwards their disagreements and the lower bound against the distance.
//
// Non-convex distance (geometry/region_distance.h): a CSG ring against a ball at 64 separated
// poses, fcl_quadric::distance against fcl::distance on the ring tessellated (6,144 triangles);
// afterwards the certified bracket of ours and the mesh's error against it.
//
// Construction (session 42): the certified local box of four convex quadric solids (a clipped
// ellipsoid, a paraboloid cap, a cone nappe, a two-sheet hyperboloid's capped sheet) and of a
// union of three posed capped elliptic cylinders, as built (named constructors, unposed) and
// posed by a fixed rotation and offset (the region transformed, as a CSG child's is):
// ConvexSupport::treeBox (the support mapping's box, each face certified by duality or by the
// engine, a union's from its operands': what a QuadricShape's constructor uses since session 42)
// against regionAabb (the engine's bisections: what it used before, and still uses for the other
// regions); and the whole construction (box, support mapping). Boundary elements (session 58):
// what the dimension reduction computes once per shape, for a box, a turned box with four corners
// cut, a plus-shaped union and the CSG wedge, and the turned block's regionAabb.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <octomap/OcTree.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/octree/octree.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/halfspace.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/motion/translation_motion.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/detail/traversal/collision/mesh_shape_collision_traversal_node.h>
#include <fcl/narrowphase/detail/traversal/collision_node.h>
#include <fcl/narrowphase/detail/traversal/distance/mesh_shape_distance_traversal_node.h>
#include <fcl/narrowphase/continuous_collision.h>
#include <fcl/narrowphase/distance.h>

#include "fcl_quadric/continuous/dimension_reduction_ccd.h"
#include "fcl_quadric/continuous/region_ccd.h"
#include "fcl_quadric/fcl/collision.h"
#include "fcl_quadric/fcl/distance.h"
#include "fcl_quadric/fcl/quadric_shapes.h"
#include "fcl_quadric/fcl/quadric_solver.h"
#include "fcl_quadric/geometry/convex_support.h"
#include "fcl_quadric/geometry/region_distance.h"

#include "bench_support.h"
#include "quadric_shapes_scene.h"

namespace {

using fcl_quadric::Box3;
using fcl_quadric::QuadricRegion;
using fcl_quadric::bench::CylinderPair;

std::vector<CylinderPair>& cylinderPairs() {
  static std::vector<CylinderPair> pairs;
  return pairs;
}

fcl_quadric::RegionRelation regionQuery(const CylinderPair& c) { return fcl_quadric::bench::cylinderPairRelation(c); }

bool fclQuery(const CylinderPair& c) {
  fcl::Cylinderd a(c.r1, c.L1), b(c.r2, c.L2);
  fcl::Transform3d ta = fcl::Transform3d::Identity(), tb = fcl::Transform3d::Identity();
  tb.linear() = c.R;
  tb.translation() = c.p;
  fcl::CollisionRequestd req;
  fcl::CollisionResultd res;
  return fcl::collide(&a, ta, &b, tb, req, res) > 0;
}

void BM_CylindersRegionEngine(benchmark::State& state) {
  const auto& pairs = cylinderPairs();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(regionQuery(pairs[i]));
    i = (i + 1) % pairs.size();
  }
}
void BM_CylindersFclGjkLibccd(benchmark::State& state) {
  const auto& pairs = cylinderPairs();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(fclQuery(pairs[i]));
    i = (i + 1) % pairs.size();
  }
}

void BM_CsgRingWedge(benchmark::State& state) {
  const QuadricRegion ring = fcl_quadric::bench::ringRegion(), wedge = fcl_quadric::bench::wedgeRegion();
  const Box3 rb = fcl_quadric::regionAabb(ring), wb = fcl_quadric::regionAabb(wedge);
  const auto poses = fcl_quadric::bench::makeRingWedgePoses(256);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(fcl_quadric::collideRegions(ring, rb, wedge, wb, poses[i].first, poses[i].second));
    i = (i + 1) % poses.size();
  }
}

// --- Continuous -----------------------------------------------------------------------------

struct CylinderMotion {
  CylinderPair pair;
  Eigen::Vector3d d;  // the second cylinder moves from p + d to p - d
};

std::vector<CylinderMotion>& cylinderMotions() {
  static std::vector<CylinderMotion> motions;
  return motions;
}
// The same translations with the moving cylinder 20 times smaller (a pin passing a post): the
// pair is close over a short part of the motion only.
std::vector<CylinderMotion>& smallCylinderMotions() {
  static std::vector<CylinderMotion> motions;
  return motions;
}
const std::vector<CylinderMotion>& motionSet(bool small) { return small ? smallCylinderMotions() : cylinderMotions(); }

// The pair of MovingRegions of a cylinder motion; with `elements`, each carries its boundary
// elements (computed once, as fcl_quadric's shapes cache them).
std::pair<fcl_quadric::MovingRegion, fcl_quadric::MovingRegion> cylinderRegions(const CylinderMotion& m, bool elements) {
  using fcl_quadric::MotionMatrix;
  using fcl_quadric::PiecewiseMotion;
  const CylinderPair& c = m.pair;
  fcl_quadric::MovingRegion a{fcl_quadric::bench::cappedCylinderRegion(c.r1, c.r1, c.L1),
                              Box3{Eigen::Vector3d(-c.r1, -c.r1, -0.5 * c.L1), Eigen::Vector3d(c.r1, c.r1, 0.5 * c.L1)},
                              PiecewiseMotion(MotionMatrix())};
  fcl_quadric::MovingRegion b{fcl_quadric::bench::cappedCylinderRegion(c.r2, c.r2, c.L2),
                              Box3{Eigen::Vector3d(-c.r2, -c.r2, -0.5 * c.L2), Eigen::Vector3d(c.r2, c.r2, 0.5 * c.L2)},
                              PiecewiseMotion(MotionMatrix::fromPoses(c.R, c.p + m.d, c.R, c.p - m.d))};
  if (elements) {
    a.elements = std::make_shared<const fcl_quadric::BoundaryElements>(fcl_quadric::boundaryElements(a.region, *a.box));
    b.elements = std::make_shared<const fcl_quadric::BoundaryElements>(fcl_quadric::boundaryElements(b.region, *b.box));
  }
  return {a, b};
}

fcl_quadric::RegionCcdResult regionCcd(const CylinderMotion& m) {
  const auto [a, b] = cylinderRegions(m, false);
  return fcl_quadric::continuousCollideRegions(a, b);
}

// Dimension reduction (thesis §6.2) with the engine as fallback, as fcl_quadric::continuousCollide
// does under CCDC_POLYNOMIAL_SOLVER: {collide, time, decided by the reduction}.
struct ReductionAnswer {
  bool collide;
  double time;
  bool decided;
};
ReductionAnswer reductionCcd(const std::pair<fcl_quadric::MovingRegion, fcl_quadric::MovingRegion>& ab) {
  const fcl_quadric::ReductionCcdResult r = fcl_quadric::continuousCollideRegionsByReduction(ab.first, ab.second);
  if (r.status == fcl_quadric::ReductionStatus::Decided) return {r.collide, r.time, true};
  const fcl_quadric::RegionCcdResult e = fcl_quadric::continuousCollideRegions(ab.first, ab.second);
  return {e.collide, e.time, false};
}

std::vector<std::pair<fcl_quadric::MovingRegion, fcl_quadric::MovingRegion>>& cylinderRegionPairs(bool small) {
  static std::vector<std::pair<fcl_quadric::MovingRegion, fcl_quadric::MovingRegion>> pairs[2];
  if (pairs[small].empty())
    for (const CylinderMotion& m : motionSet(small)) pairs[small].push_back(cylinderRegions(m, true));
  return pairs[small];
}

/// FCL's continuousCollide on the same translation: {collide, time of contact}.
std::pair<bool, double> fclCcd(const CylinderMotion& m, fcl::CCDSolverType solver) {
  const CylinderPair& c = m.pair;
  const auto a = std::make_shared<fcl::Cylinderd>(c.r1, c.L1);
  const auto b = std::make_shared<fcl::Cylinderd>(c.r2, c.L2);
  fcl::Transform3d t2a = fcl::Transform3d::Identity(), t2b = fcl::Transform3d::Identity();
  t2a.linear() = c.R;
  t2b.linear() = c.R;
  t2a.translation() = c.p + m.d;
  t2b.translation() = c.p - m.d;
  fcl::ContinuousCollisionRequestd req;
  req.ccd_motion_type = fcl::CCDM_TRANS;
  req.ccd_solver_type = solver;
  req.gjk_solver_type = fcl::GST_LIBCCD;
  fcl::ContinuousCollisionResultd res;
  fcl::continuousCollide(a.get(), fcl::Transform3d::Identity(), fcl::Transform3d::Identity(), b.get(), t2a, t2b, req,
                         res);
  return {res.is_collide, res.time_of_contact};
}

void BM_CylindersCcdRegion(benchmark::State& state, bool small) {
  const auto& motions = motionSet(small);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(regionCcd(motions[i]));
    i = (i + 1) % motions.size();
  }
}
void BM_CylindersCcdReduction(benchmark::State& state, bool small) {
  const auto& pairs = cylinderRegionPairs(small);  // boundary elements computed once, outside the timing
  std::size_t i = 0, decided = 0, runs = 0;
  for (auto _ : state) {
    const ReductionAnswer r = reductionCcd(pairs[i]);
    benchmark::DoNotOptimize(r);
    decided += r.decided;
    ++runs;
    i = (i + 1) % pairs.size();
  }
  state.counters["decided"] = static_cast<double>(decided) / runs;
}
void BM_CylindersCcdFcl(benchmark::State& state, fcl::CCDSolverType solver, bool small) {
  const auto& motions = motionSet(small);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(fclCcd(motions[i], solver));
    i = (i + 1) % motions.size();
  }
}

// Ring (fixed) against the wedge moving from pose k to pose k + 1 of makeRingWedgePoses, shifted
// so that the motion sweeps through the ring: degree 1 keeps the rotation, degree 2 interpolates
// it, degree 4 composes the degree-2 motion with a rotation of the whole path about z.
void BM_CsgRingWedgeCcd(benchmark::State& state) {
  using fcl_quadric::MotionMatrix;
  using fcl_quadric::PiecewiseMotion;
  const int degree = static_cast<int>(state.range(0));
  const QuadricRegion ring = fcl_quadric::bench::ringRegion(), wedge = fcl_quadric::bench::wedgeRegion();
  const Box3 rb = fcl_quadric::regionAabb(ring), wb = fcl_quadric::regionAabb(wedge);
  const auto poses = fcl_quadric::bench::makeRingWedgePoses(9);
  std::vector<fcl_quadric::MovingRegion> moving;
  for (std::size_t k = 0; k + 1 < poses.size(); ++k) {
    const Eigen::Matrix3d R0 = poses[k].first, R1 = degree == 1 ? R0 : poses[k + 1].first;
    const Eigen::Vector3d p0 = poses[k].second + Eigen::Vector3d(2.5, 0, 0), p1 = poses[k].second - Eigen::Vector3d(2.5, 0, 0);
    MotionMatrix m = MotionMatrix::fromPoses(R0, p0, R1, p1);
    if (degree == 4) {
      const Eigen::Matrix3d Rz = Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      m = MotionMatrix::compose(MotionMatrix::fromPoses(Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(), Rz,
                                                        Eigen::Vector3d::Zero()),
                                m);
    }
    moving.push_back({wedge, wb, PiecewiseMotion(m)});
  }
  const fcl_quadric::MovingRegion still{ring, rb, PiecewiseMotion(MotionMatrix())};
  std::size_t i = 0, collide = 0, boxes = 0, runs = 0;
  for (auto _ : state) {
    const fcl_quadric::RegionCcdResult r = fcl_quadric::continuousCollideRegions(still, moving[i]);
    collide += r.collide;
    boxes += r.boxes;
    ++runs;
    i = (i + 1) % moving.size();
  }
  state.counters["colliding"] = static_cast<double>(collide) / runs;
  state.counters["boxes"] = static_cast<double>(boxes) / runs;
}

BENCHMARK_CAPTURE(BM_CylindersCcdRegion, same, false)
    ->Name("QuadricShapes/CylindersCcd/RegionCcd")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_CylindersCcdReduction, same, false)
    ->Name("QuadricShapes/CylindersCcd/DimensionReduction")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_CylindersCcdFcl, naive, fcl::CCDC_NAIVE, false)
    ->Name("QuadricShapes/CylindersCcd/FclNaive")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_CylindersCcdFcl, ca, fcl::CCDC_CONSERVATIVE_ADVANCEMENT, false)
    ->Name("QuadricShapes/CylindersCcd/FclConservativeAdvancement")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_CylindersCcdRegion, small, true)
    ->Name("QuadricShapes/SmallCylinderCcd/RegionCcd")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_CylindersCcdReduction, small, true)
    ->Name("QuadricShapes/SmallCylinderCcd/DimensionReduction")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_CylindersCcdFcl, small_naive, fcl::CCDC_NAIVE, true)
    ->Name("QuadricShapes/SmallCylinderCcd/FclNaive")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_CylindersCcdFcl, small_ca, fcl::CCDC_CONSERVATIVE_ADVANCEMENT, true)
    ->Name("QuadricShapes/SmallCylinderCcd/FclConservativeAdvancement")
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CsgRingWedgeCcd)
    ->Name("QuadricShapes/CsgCcd/RingWedge")
    ->ArgName("degree")
    ->Arg(1)
    ->Arg(2)
    ->Arg(4)
    ->Unit(benchmark::kMillisecond);

BENCHMARK(BM_CylindersRegionEngine)->Name("QuadricShapes/Cylinders/RegionEngine")->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CylindersFclGjkLibccd)->Name("QuadricShapes/Cylinders/FclGjkLibccd")->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CsgRingWedge)->Name("QuadricShapes/Csg/RingWedge")->Unit(benchmark::kMicrosecond);
/// The cylinder pairs as prebuilt shapes (both libraries' shapes are built once, outside the
/// timed loops: an EllipticCylinder computes its AABB and mass properties on construction).
struct DistancePair {
  std::shared_ptr<fcl_quadric::EllipticCylinder<double>> a, b;
  std::shared_ptr<fcl::Cylinderd> fa, fb;
  fcl::Transform3d tb;
};
std::vector<DistancePair>& distancePairs() {
  static std::vector<DistancePair> pairs;
  return pairs;
}
std::vector<DistancePair> makeDistancePairs(const std::vector<CylinderPair>& cylinders) {
  std::vector<DistancePair> out;
  for (const CylinderPair& c : cylinders) {
    DistancePair d;
    d.a = std::make_shared<fcl_quadric::EllipticCylinder<double>>(c.r1, c.r1, c.L1);
    d.b = std::make_shared<fcl_quadric::EllipticCylinder<double>>(c.r2, c.r2, c.L2);
    d.fa = std::make_shared<fcl::Cylinderd>(c.r1, c.L1);
    d.fb = std::make_shared<fcl::Cylinderd>(c.r2, c.L2);
    d.tb = fcl::Transform3d::Identity();
    d.tb.linear() = c.R;
    d.tb.translation() = c.p;
    out.push_back(d);
  }
  return out;
}
double quadricDistance(const DistancePair& c) {
  fcl::DistanceRequestd req;
  fcl::DistanceResultd res;
  return fcl_quadric::distance(c.a.get(), fcl::Transform3d::Identity(), c.b.get(), c.tb, req, res);
}
double fclDistance(const DistancePair& c) {
  fcl::DistanceRequestd req;
  fcl::DistanceResultd res;
  return fcl::distance(c.fa.get(), fcl::Transform3d::Identity(), c.fb.get(), c.tb, req, res);
}
/// The front door's collide on the same cylinder pairs (GJK's screening, then the region engine
/// near contact), on shapes made once, as for the distance.
bool quadricCollide(const DistancePair& c) {
  fcl::CollisionRequestd req;
  fcl::CollisionResultd res;
  return fcl_quadric::collide(c.a.get(), fcl::Transform3d::Identity(), c.b.get(), c.tb, req, res) > 0;
}
/// One query per iteration over distancePairs(), walked cyclically.
template <auto Query>
void BM_DistancePairs(benchmark::State& state) {
  const auto& pairs = distancePairs();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(Query(pairs[i]));
    i = (i + 1) % pairs.size();
  }
}
BENCHMARK(BM_DistancePairs<quadricCollide>)->Name("QuadricShapes/Cylinders/fcl_quadric")->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_DistancePairs<quadricDistance>)
    ->Name("QuadricShapes/CylindersDistance/fcl_quadric")
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_DistancePairs<fclDistance>)
    ->Name("QuadricShapes/CylindersDistance/FclGjkLibccd")
    ->Unit(benchmark::kMicrosecond);

/// One query of the cylinder posed tf against an environment (mesh or octree) at the identity:
/// fcl_quadric on `ours` or FCL on `theirs`; the distance, or the number of contacts.
template <bool Ours, bool Distance>
double cylinderQuery(const fcl_quadric::EllipticCylinder<double>& ours, const fcl::Cylinderd& theirs,
                     const fcl::CollisionGeometryd* environment, const fcl::Transform3d& tf) {
  const fcl::CollisionGeometryd* g = Ours ? static_cast<const fcl::CollisionGeometryd*>(&ours) : &theirs;
  const fcl::Transform3d I = fcl::Transform3d::Identity();
  if constexpr (Distance) {
    fcl::DistanceRequestd req;
    fcl::DistanceResultd res;
    return Ours ? fcl_quadric::distance(g, tf, environment, I, req, res) : fcl::distance(g, tf, environment, I, req, res);
  } else {
    fcl::CollisionRequestd req;
    fcl::CollisionResultd res;
    return static_cast<double>(Ours ? fcl_quadric::collide(g, tf, environment, I, req, res)
                                    : fcl::collide(g, tf, environment, I, req, res));
  }
}
/// n cylinder poses: a random rotation and a centre drawn from (ux, uy, uz), in that order.
std::vector<fcl::Transform3d> cylinderPoses(std::mt19937_64& rng, int n, std::uniform_real_distribution<double>& ux,
                                            std::uniform_real_distribution<double>& uy,
                                            std::uniform_real_distribution<double>& uz) {
  std::vector<fcl::Transform3d> poses;
  for (int q = 0; q < n; ++q) {
    fcl::Transform3d tf = fcl::Transform3d::Identity();
    tf.linear() = fcl_quadric::bench::quadricSceneRotation(rng);
    const double x = ux(rng), y = uy(rng), z = uz(rng);
    tf.translation() = Eigen::Vector3d(x, y, z);
    poses.push_back(tf);
  }
  return poses;
}
struct TerrainScene {
  std::shared_ptr<fcl::BVHModel<fcl::OBBRSS<double>>> mesh;
  std::shared_ptr<fcl_quadric::EllipticCylinder<double>> ours;
  std::shared_ptr<fcl::Cylinderd> theirs;
  std::vector<fcl::Transform3d> poses;
};
TerrainScene& terrain() {
  static TerrainScene t;
  return t;
}
TerrainScene makeTerrain() {
  TerrainScene t;
  t.mesh = std::make_shared<fcl::BVHModel<fcl::OBBRSS<double>>>();
  t.mesh->beginModel();
  auto h = [](double x, double y) { return 0.2 * std::sin(x) * std::cos(y); };
  for (int i = 0; i < 200; ++i)
    for (int j = 0; j < 100; ++j) {
      const double x0 = 0.1 * i, y0 = 0.1 * j, x1 = x0 + 0.1, y1 = y0 + 0.1;
      const Eigen::Vector3d a(x0, y0, h(x0, y0)), b(x1, y0, h(x1, y0)), c(x1, y1, h(x1, y1)), d(x0, y1, h(x0, y1));
      t.mesh->addTriangle(a, b, c);
      t.mesh->addTriangle(a, c, d);
    }
  t.mesh->endModel();
  t.ours = std::make_shared<fcl_quadric::EllipticCylinder<double>>(0.3, 0.3, 1.0);
  t.theirs = std::make_shared<fcl::Cylinderd>(0.3, 1.0);
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> ux(1, 19), uy(1, 9), uz(-0.2, 1.0);
  t.poses = cylinderPoses(rng, 200, ux, uy, uz);
  return t;
}
template <bool Ours, bool Distance>
double terrainQuery(const fcl::Transform3d& tf) {
  const TerrainScene& t = terrain();
  return cylinderQuery<Ours, Distance>(*t.ours, *t.theirs, t.mesh.get(), tf);
}
// The same query through FCL's own traversal node template instantiated with the quadric shape
// and QuadricSolver (what a user assembling FCL's nodes gets): FCL's OBBRSS tests, then one
// QuadricSolver::shapeTriangleIntersect per leaf (for this convex shape, the front door's
// per-triangle steps run directly; since session 32).
bool terrainNodeCollides(const fcl::Transform3d& tf) {
  const TerrainScene& t = terrain();
  static const fcl_quadric::QuadricSolverd solver;
  fcl::CollisionRequestd req;
  fcl::CollisionResultd res;
  fcl::detail::MeshShapeCollisionTraversalNodeOBBRSS<fcl_quadric::EllipticCylinder<double>, fcl_quadric::QuadricSolverd>
      node;
  fcl::detail::initialize(node, *t.mesh, fcl::Transform3d::Identity(), *t.ours, tf, &solver, req, res);
  fcl::detail::collide(&node);
  return res.isCollision();
}
void BM_TerrainFclNode(benchmark::State& state) {
  const auto& poses = terrain().poses;
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(terrainNodeCollides(poses[i]));
    i = (i + 1) % poses.size();
  }
}
BENCHMARK(BM_TerrainFclNode)->Name("QuadricShapes/TerrainCollide/FclTraversalNode")->Unit(benchmark::kMicrosecond);
// The distance through FCL's distance node: FCL's OBBRSS distance bounds, then one
// QuadricSolver::shapeTriangleDistance per leaf it cannot prune.
double terrainNodeDistance(const fcl::Transform3d& tf) {
  const TerrainScene& t = terrain();
  static const fcl_quadric::QuadricSolverd solver;
  fcl::DistanceRequestd req;
  fcl::DistanceResultd res;
  fcl::detail::MeshShapeDistanceTraversalNodeOBBRSS<fcl_quadric::EllipticCylinder<double>, fcl_quadric::QuadricSolverd>
      node;
  fcl::detail::initialize(node, *t.mesh, fcl::Transform3d::Identity(), *t.ours, tf, &solver, req, res);
  fcl::detail::distance(&node);
  return res.min_distance;
}
void BM_TerrainFclNodeDistance(benchmark::State& state) {
  const auto& poses = terrain().poses;
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(terrainNodeDistance(poses[i]));
    i = (i + 1) % poses.size();
  }
}
BENCHMARK(BM_TerrainFclNodeDistance)
    ->Name("QuadricShapes/TerrainDistance/FclTraversalNode")
    ->Unit(benchmark::kMicrosecond);

template <bool Ours, bool Distance>
void BM_Terrain(benchmark::State& state) {
  const auto& poses = terrain().poses;
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(terrainQuery<Ours, Distance>(poses[i]));
    i = (i + 1) % poses.size();
  }
}
BENCHMARK(BM_Terrain<true, false>)->Name("QuadricShapes/TerrainCollide/fcl_quadric")->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Terrain<false, false>)->Name("QuadricShapes/TerrainCollide/FclGjkLibccd")->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Terrain<true, true>)->Name("QuadricShapes/TerrainDistance/fcl_quadric")->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Terrain<false, true>)->Name("QuadricShapes/TerrainDistance/FclGjkLibccd")->Unit(benchmark::kMicrosecond);

// Certified distance lower bounds (distanceLowerBound, what the OMPL layer advances on): an
// fcl::Cylinder and the same circular EllipticCylinder over the terrain (GJK's bound per
// triangle), against FCL's own distance of the fcl::Cylinder (libccd GJK: not a bound); and a
// ring (ellipsoid minus bore, non-convex) threaded on a thin 6-triangle pole, where the ring's
// convex cover contains the pole and the region engine certifies each triangle's delta-prism.
template <bool Quadric>
void BM_TerrainLowerBound(benchmark::State& state) {
  const TerrainScene& t = terrain();
  const fcl::CollisionGeometryd* g = Quadric ? static_cast<const fcl::CollisionGeometryd*>(t.ours.get()) : t.theirs.get();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(fcl_quadric::distanceLowerBound(g, t.poses[i], t.mesh.get(), fcl::Transform3d::Identity(), 1e3));
    i = (i + 1) % t.poses.size();
  }
}
BENCHMARK(BM_TerrainLowerBound<false>)->Name("QuadricShapes/TerrainLowerBound/fcl_Cylinder")->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_TerrainLowerBound<true>)->Name("QuadricShapes/TerrainLowerBound/EllipticCylinder")->Unit(benchmark::kMicrosecond);

struct OcTreeTerrainScene {
  std::shared_ptr<fcl::OcTree<double>> tree;
  std::shared_ptr<fcl_quadric::EllipticCylinder<double>> ours;
  std::shared_ptr<fcl::Cylinderd> theirs;
  std::vector<fcl::Transform3d> poses;
};
OcTreeTerrainScene& octreeTerrain() {
  static OcTreeTerrainScene t;
  return t;
}
OcTreeTerrainScene makeOcTreeTerrain() {
  OcTreeTerrainScene t;
  auto octo = std::make_shared<octomap::OcTree>(0.05);
  for (int i = 0; i < 400; ++i)
    for (int j = 0; j < 400; ++j) {
      const double x = -10 + 0.05 * i, y = -10 + 0.05 * j, z = 0.3 * std::sin(0.5 * x) * std::cos(0.7 * y);
      octo->updateNode(octomap::point3d(float(x), float(y), float(z)), true);
    }
  t.tree = std::make_shared<fcl::OcTree<double>>(octo);
  t.ours = std::make_shared<fcl_quadric::EllipticCylinder<double>>(0.3, 0.3, 1.0);
  t.theirs = std::make_shared<fcl::Cylinderd>(0.3, 1.0);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-8, 8), h(-0.2, 1.0);
  t.poses = cylinderPoses(rng, 50, u, u, h);
  return t;
}
template <bool Ours, bool Distance>
double octreeTerrainQuery(const fcl::Transform3d& tf) {
  const OcTreeTerrainScene& t = octreeTerrain();
  return cylinderQuery<Ours, Distance>(*t.ours, *t.theirs, t.tree.get(), tf);
}
template <bool Ours, bool Distance>
void BM_OcTreeTerrain(benchmark::State& state) {
  const auto& poses = octreeTerrain().poses;
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(octreeTerrainQuery<Ours, Distance>(poses[i]));
    i = (i + 1) % poses.size();
  }
}
BENCHMARK(BM_OcTreeTerrain<true, false>)->Name("QuadricShapes/OcTreeCollide/fcl_quadric")->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_OcTreeTerrain<false, false>)->Name("QuadricShapes/OcTreeCollide/FclGjkLibccd")->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_OcTreeTerrain<true, true>)->Name("QuadricShapes/OcTreeDistance/fcl_quadric")->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_OcTreeTerrain<false, true>)->Name("QuadricShapes/OcTreeDistance/FclGjkLibccd")->Unit(benchmark::kMicrosecond);
void BM_OcTreeTerrainLowerBound(benchmark::State& state) {
  const OcTreeTerrainScene& t = octreeTerrain();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        fcl_quadric::distanceLowerBound(t.ours.get(), t.poses[i], t.tree.get(), fcl::Transform3d::Identity(), 1e3));
    i = (i + 1) % t.poses.size();
  }
}
BENCHMARK(BM_OcTreeTerrainLowerBound)->Name("QuadricShapes/OcTreeLowerBound/EllipticCylinder")->Unit(benchmark::kMicrosecond);

struct RingPoleScene {
  std::shared_ptr<fcl_quadric::QuadricCSG<double>> ring;
  std::shared_ptr<fcl::BVHModel<fcl::OBBRSS<double>>> pole;
  std::vector<fcl::Transform3d> poses;  // the ring's centre within 0.3 of the pole's axis, tilted up to 0.3 rad
};
RingPoleScene makeRingPole() {
  RingPoleScene s;
  auto outer = std::make_shared<fcl_quadric::Quadric<double>>(fcl_quadric::Quadric<double>::ellipsoid(1.0, 1.0, 0.4));
  auto bore = std::make_shared<fcl_quadric::Quadric<double>>(fcl_quadric::Quadric<double>::ellipticCylinder(0.5, 0.5));
  s.ring = std::make_shared<fcl_quadric::QuadricCSG<double>>(
      fcl_quadric::QuadricRegion::Op::Difference,
      std::vector<fcl_quadric::QuadricCSG<double>::Child>{{outer, fcl::Transform3d::Identity()},
                                                          {bore, fcl::Transform3d::Identity()}});
  s.pole = std::make_shared<fcl::BVHModel<fcl::OBBRSS<double>>>();
  s.pole->beginModel();
  Eigen::Vector3d rim[3];
  for (int k = 0; k < 3; ++k) rim[k] = 0.1 * Eigen::Vector3d(std::cos(2 * M_PI * k / 3), std::sin(2 * M_PI * k / 3), 0);
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d a = rim[k], b = rim[(k + 1) % 3], up(0, 0, 2);
    s.pole->addTriangle(a - up, b - up, b + up);
    s.pole->addTriangle(a - up, b + up, a + up);
  }
  s.pole->endModel();
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  while (s.poses.size() < 32) {
    const Eigen::Vector3d c(0.3 * u(rng), 0.3 * u(rng), 0.5 * u(rng));
    if (c.head<2>().norm() > 0.3) continue;
    fcl::Transform3d tf = fcl::Transform3d::Identity();
    tf.linear() = Eigen::AngleAxisd(0.3 * u(rng), Eigen::Vector3d(u(rng), u(rng), 0).normalized()).toRotationMatrix();
    tf.translation() = c;
    s.poses.push_back(tf);
  }
  return s;
}
RingPoleScene& ringPole() {
  static RingPoleScene s = makeRingPole();
  return s;
}
void BM_RingPoleLowerBound(benchmark::State& state) {
  const RingPoleScene& s = ringPole();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        fcl_quadric::distanceLowerBound(s.ring.get(), s.poses[i], s.pole.get(), fcl::Transform3d::Identity(), 1e3));
    i = (i + 1) % s.poses.size();
  }
}
BENCHMARK(BM_RingPoleLowerBound)->Name("QuadricShapes/RingPoleLowerBound/fcl_quadric")->Unit(benchmark::kMillisecond);
// The distance itself on the same poses (region_distance.h per triangle of the pole).
void BM_RingPoleDistance(benchmark::State& state) {
  const RingPoleScene& s = ringPole();
  std::size_t i = 0;
  for (auto _ : state) {
    fcl::DistanceRequestd req;
    fcl::DistanceResultd res;
    benchmark::DoNotOptimize(
        fcl_quadric::distance(s.ring.get(), s.poses[i], s.pole.get(), fcl::Transform3d::Identity(), req, res));
    i = (i + 1) % s.poses.size();
  }
}
BENCHMARK(BM_RingPoleDistance)->Name("QuadricShapes/RingPoleDistance/fcl_quadric")->Unit(benchmark::kMillisecond);

// Ring (the ring-pole scene's) against a ball of radius 0.15 at 64 separated random poses around
// it, in its bore and above it: fcl_quadric::distance on the CSG ring (branch and bound,
// geometry/region_distance.h) against fcl::distance on the ring's surface tessellated into
// 96 x (24 + 8) quads (a BVHModel<OBBRSS>, libccd per triangle: what FCL offers for this shape).
struct RingBallScene {
  std::shared_ptr<fcl::BVHModel<fcl::OBBRSS<double>>> mesh;
  std::shared_ptr<fcl::Sphered> ball = std::make_shared<fcl::Sphered>(0.15);
  std::vector<fcl::Transform3d> poses;
};
RingBallScene makeRingBall() {
  RingBallScene s;
  const int nt = 96, no = 24, nb = 8;
  const double phi_rim = M_PI / 6, z_rim = 0.4 * std::cos(phi_rim);  // sin(phi_rim) = 0.5 / 1
  // Rows of points from the top rim over the outer face to the bottom rim, then up the bore.
  std::vector<std::vector<Eigen::Vector3d>> rows;
  for (int j = 0; j <= no; ++j) {
    const double phi = phi_rim + (M_PI - 2 * phi_rim) * j / no;
    std::vector<Eigen::Vector3d> row;
    for (int i = 0; i < nt; ++i) {
      const double th = 2 * M_PI * i / nt;
      row.emplace_back(std::sin(phi) * std::cos(th), std::sin(phi) * std::sin(th), 0.4 * std::cos(phi));
    }
    rows.push_back(row);
  }
  for (int j = 1; j < nb; ++j) {
    std::vector<Eigen::Vector3d> row;
    for (int i = 0; i < nt; ++i) {
      const double th = 2 * M_PI * i / nt;
      row.emplace_back(0.5 * std::cos(th), 0.5 * std::sin(th), -z_rim + 2 * z_rim * j / nb);
    }
    rows.push_back(row);
  }
  rows.push_back(rows.front());  // back to the top rim
  s.mesh = std::make_shared<fcl::BVHModel<fcl::OBBRSS<double>>>();
  s.mesh->beginModel();
  for (std::size_t j = 0; j + 1 < rows.size(); ++j)
    for (int i = 0; i < nt; ++i) {
      const int k = (i + 1) % nt;
      s.mesh->addTriangle(rows[j][i], rows[j + 1][i], rows[j + 1][k]);
      s.mesh->addTriangle(rows[j][i], rows[j + 1][k], rows[j][k]);
    }
  s.mesh->endModel();
  const auto& ring = *ringPole().ring;
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  while (s.poses.size() < 64) {
    fcl::Transform3d tf = fcl::Transform3d::Identity();
    tf.translation() = Eigen::Vector3d(1.5 * u(rng), 1.5 * u(rng), 0.9 * u(rng));
    fcl::CollisionRequestd req;
    fcl::CollisionResultd res;
    if (fcl_quadric::collide(&ring, fcl::Transform3d::Identity(), s.ball.get(), tf, req, res) > 0) continue;
    s.poses.push_back(tf);
  }
  return s;
}
RingBallScene& ringBall() {
  static RingBallScene s = makeRingBall();
  return s;
}
template <bool Ours>
double ringBallDistance(const fcl::Transform3d& tf, fcl::DistanceResultd* out = nullptr) {
  fcl::DistanceRequestd req(true);
  fcl::DistanceResultd res;
  const double d = Ours ? fcl_quadric::distance(ringPole().ring.get(), fcl::Transform3d::Identity(), ringBall().ball.get(),
                                                tf, req, res)
                        : fcl::distance(ringBall().mesh.get(), fcl::Transform3d::Identity(), ringBall().ball.get(), tf,
                                        req, res);
  if (out) *out = res;
  return d;
}
template <bool Ours>
void BM_RingBallDistance(benchmark::State& state) {
  const RingBallScene& s = ringBall();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(ringBallDistance<Ours>(s.poses[i]));
    i = (i + 1) % s.poses.size();
  }
}
BENCHMARK(BM_RingBallDistance<true>)->Name("QuadricShapes/RingBallDistance/fcl_quadric")->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RingBallDistance<false>)->Name("QuadricShapes/RingBallDistance/FclMeshLibccd")->Unit(benchmark::kMicrosecond);

struct SmallEllipsoidPair {
  std::shared_ptr<fcl_quadric::Quadric<double>> shape;  // at the identity
  Eigen::Vector3d radii;
  fcl::Transform3d pose;  // of the ellipsoid, in the shape's frame
};

std::vector<SmallEllipsoidPair>& smallEllipsoidPairs() {
  static std::vector<SmallEllipsoidPair> pairs;
  return pairs;
}

std::vector<SmallEllipsoidPair> makeSmallEllipsoidPairs(std::size_t n) {
  using Q = fcl_quadric::Quadric<double>;
  const std::vector<std::shared_ptr<Q>> shapes = {
      std::make_shared<Q>(Q::ellipticParaboloid(1.0, 1.0, {{Eigen::Vector3d::UnitZ(), 3.0}})),
      std::make_shared<Q>(Q::hyperboloidOneSheet(1.0, 1.0, 1.0, {{Eigen::Vector3d::UnitZ(), 2.0}, {-Eigen::Vector3d::UnitZ(), 2.0}})),
      std::make_shared<Q>(Q::ellipticCylinder(1.2, 0.9, {{Eigen::Vector3d::UnitZ(), 1.5}, {-Eigen::Vector3d::UnitZ(), 1.5}})),
  };
  std::mt19937_64 rng(19);
  std::uniform_real_distribution<double> r(0.1, 0.35), u(0.0, 1.0);
  std::vector<SmallEllipsoidPair> pairs;
  for (std::size_t i = 0; i < n; ++i) {
    const auto& shape = shapes[i % shapes.size()];
    const double a = r(rng), b = r(rng), c = r(rng);
    fcl::Transform3d pose = fcl::Transform3d::Identity();
    pose.linear() = fcl_quadric::bench::quadricSceneRotation(rng);
    // Near the quadric surface (|f| / |grad f| <= 0.5 at the centre), where both answers are hard.
    const Box3& box = shape->localBox();
    const Eigen::Matrix4d& Qm = shape->matrix();
    for (;;) {
      Eigen::Vector4d X(0, 0, 0, 1);
      for (int k = 0; k < 3; ++k) X[k] = box.lo[k] - 0.5 + u(rng) * (box.hi[k] - box.lo[k] + 1.0);
      const double grad = 2.0 * (Qm * X).head<3>().norm();
      if (std::fabs(X.dot(Qm * X)) <= 0.5 * grad) {
        pose.translation() = X.head<3>();
        break;
      }
    }
    pairs.push_back({shape, Eigen::Vector3d(a, b, c), pose});
  }
  return pairs;
}

bool smallEllipsoidCollide(const SmallEllipsoidPair& s) {
  const fcl::Ellipsoidd e(s.radii);
  fcl::CollisionRequestd req;
  fcl::CollisionResultd res;
  return fcl_quadric::collide(&e, s.pose, s.shape.get(), fcl::Transform3d::Identity(), req, res) > 0;
}

fcl_quadric::RegionRelation smallEllipsoidEngine(const SmallEllipsoidPair& s) {
  const QuadricRegion e = QuadricRegion::atom(fcl_quadric::quadric::ellipsoid(s.radii));
  const Box3 eb{-s.radii, s.radii};
  return fcl_quadric::collideRegions(s.shape->region(), s.shape->localBox(), e, eb, s.pose.linear(),
                                     s.pose.translation())
      .relation;
}

void BM_SmallEllipsoidCollide(benchmark::State& state) {
  const auto& pairs = smallEllipsoidPairs();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(smallEllipsoidCollide(pairs[i]));
    i = (i + 1) % pairs.size();
  }
}
void BM_SmallEllipsoidEngine(benchmark::State& state) {
  const auto& pairs = smallEllipsoidPairs();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(smallEllipsoidEngine(pairs[i]));
    i = (i + 1) % pairs.size();
  }
}
BENCHMARK(BM_SmallEllipsoidCollide)->Name("QuadricShapes/SmallEllipsoid/SeedFilterThenEngine")->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SmallEllipsoidEngine)->Name("QuadricShapes/SmallEllipsoid/RegionEngine")->Unit(benchmark::kMicrosecond);

}  // namespace

// Shape pairs (session 30): fcl_quadric::collide with a quadric shape first, against each FCL
// partner FCL 0.7 has (libccd on an fcl::Cylinder of the same size in place of the
// EllipticCylinder), and shapes FCL does not have (a clipped paraboloid, a union of two balls, a
// ring, the ring against the two balls, a link of three capped cylinders): 1,000 poses of the
// partner (random rotation, centre in [-1.5, 1.5]^3), the quadric shape at the identity. One
// iteration = one pose, walked cyclically.
struct ShapePairScene {
  std::string name;
  std::shared_ptr<fcl::CollisionGeometryd> ours, partner;
  std::shared_ptr<fcl::CollisionGeometryd> theirs;  // FCL's stand-in for `ours`, or null
};
const std::vector<fcl::Transform3d>& shapePairPoses() {
  static const std::vector<fcl::Transform3d> poses = [] {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(-1.5, 1.5);
    return cylinderPoses(rng, 1000, u, u, u);
  }();
  return poses;
}
std::vector<ShapePairScene> makeShapePairScenes() {
  using Q = fcl_quadric::Quadric<double>;
  using Csg = fcl_quadric::QuadricCSG<double>;
  const fcl::Transform3d I = fcl::Transform3d::Identity();
  fcl::Transform3d up = I, down = I;
  up.translation() = Eigen::Vector3d(0, 0, 0.6);
  down.translation() = Eigen::Vector3d(0, 0, -0.6);
  auto cylinder = std::make_shared<fcl_quadric::EllipticCylinder<double>>(0.5, 0.5, 1.2);
  auto fcl_cylinder = std::make_shared<fcl::Cylinderd>(0.5, 1.2);
  auto ball = std::make_shared<Q>(Q::ellipsoid(0.5, 0.5, 0.5));
  auto balls = std::make_shared<Csg>(fcl_quadric::QuadricRegion::Op::Union, std::vector<Csg::Child>{{ball, up}, {ball, down}});
  auto ring = std::make_shared<Csg>(fcl_quadric::QuadricRegion::Op::Difference,
                                    std::vector<Csg::Child>{{std::make_shared<Q>(Q::ellipsoid(1.2, 1.2, 0.6)), I},
                                                            {std::make_shared<Q>(Q::ellipticCylinder(0.6, 0.6)), I}});
  auto paraboloid = std::make_shared<Q>(Q::ellipticParaboloid(0.8, 0.5, {{Eigen::Vector3d::UnitZ(), 1.5}}));
  auto box = std::make_shared<fcl::Boxd>(0.8, 0.6, 1.0);
  auto sphere = std::make_shared<fcl::Sphered>(0.4);
  // fcl::Cone(0.5, 1.2) as a quadric: x^2 + y^2 <= k^2 (h - z)^2, k = r / L, between its base
  // z = -h and its apex z = h = L / 2 (the clip through the apex keeps one nappe: a convex shape
  // since session 37, before which the branch and bound answered it).
  const double cone_k = 0.5 / 1.2, cone_h = 0.6;
  Eigen::Matrix4d cone_q = Eigen::Matrix4d::Zero();
  cone_q(0, 0) = cone_q(1, 1) = 1.0;
  cone_q(2, 2) = -cone_k * cone_k;
  cone_q(2, 3) = cone_q(3, 2) = cone_k * cone_k * cone_h;
  cone_q(3, 3) = -cone_k * cone_k * cone_h * cone_h;
  auto cone = std::make_shared<Q>(cone_q, Q::Clips{{Eigen::Vector3d::UnitZ(), cone_h}, {-Eigen::Vector3d::UnitZ(), cone_h}});
  // A link of three posed capped elliptic cylinders (a union of convex operands, answered on its
  // convex cover: one piece per cylinder, since session 43 without the union box's faces).
  std::vector<Csg::Child> rods;
  const auto rod = std::make_shared<fcl_quadric::EllipticCylinder<double>>(0.3, 0.4, 2.0);
  for (int k = 0; k < 3; ++k) {
    fcl::Transform3d X = I;
    X.linear() = Eigen::AngleAxisd(0.4 + 0.45 * k, Eigen::Vector3d(1, k, 0.5).normalized()).toRotationMatrix();
    X.translation() = Eigen::Vector3d(0.3 * k, 0.1 * k, 0.0);
    rods.push_back({rod, X});
  }
  auto link = std::make_shared<Csg>(fcl_quadric::QuadricRegion::Op::Union, rods);
  return {
      {"CylinderSphere", cylinder, sphere, fcl_cylinder},
      {"CylinderBox", cylinder, box, fcl_cylinder},
      {"CylinderCone", cylinder, std::make_shared<fcl::Coned>(0.5, 1.0), fcl_cylinder},
      {"CylinderCapsule", cylinder, std::make_shared<fcl::Capsuled>(0.3, 1.0), fcl_cylinder},
      {"CylinderEllipsoid", cylinder, std::make_shared<fcl::Ellipsoidd>(0.3, 0.5, 0.7), fcl_cylinder},
      {"CylinderHalfspace", cylinder,
       std::make_shared<fcl::Halfspaced>(Eigen::Vector3d(0.3, 0.2, 1.0).normalized(), 0.1), fcl_cylinder},
      {"ConeSphere", cone, sphere, std::make_shared<fcl::Coned>(0.5, 1.2)},
      {"ParaboloidBox", paraboloid, box, nullptr},
      {"TwoBallsBox", balls, box, nullptr},
      {"RingSphere", ring, sphere, nullptr},
      {"RingTwoBalls", ring, balls, nullptr},
      {"LinkSphere", link, sphere, nullptr},
  };
}
std::vector<ShapePairScene>& shapePairScenes() {
  static std::vector<ShapePairScene> scenes;
  return scenes;
}
bool shapePairCollide(const fcl::CollisionGeometryd* a, const fcl::CollisionGeometryd* b, const fcl::Transform3d& tb,
                      bool ours) {
  fcl::CollisionRequestd req;
  fcl::CollisionResultd res;
  const fcl::Transform3d I = fcl::Transform3d::Identity();
  return (ours ? fcl_quadric::collide(a, I, b, tb, req, res) : fcl::collide(a, I, b, tb, req, res)) > 0;
}
/// The distance of the same pair (session 31): fcl_quadric::distance, or fcl::distance on FCL's
/// stand-in (libccd GJK, FCL's default; it reports -1 for an overlap where we give the depth).
double shapePairDistance(const fcl::CollisionGeometryd* a, const fcl::CollisionGeometryd* b, const fcl::Transform3d& tb,
                         bool ours) {
  fcl::DistanceRequestd req;
  fcl::DistanceResultd res;
  const fcl::Transform3d I = fcl::Transform3d::Identity();
  return ours ? fcl_quadric::distance(a, I, b, tb, req, res) : fcl::distance(a, I, b, tb, req, res);
}
/// The pairs whose distance is timed: FCL's stand-ins against a sphere and a capsule (the solids
/// GJK and EPA run as a grown core since session 31) and against a box (a solid that is its own
/// core, for comparison); a quadric cone (one nappe, convex since session 37) against a sphere.
bool distanceTimed(const ShapePairScene& s) {
  return s.theirs && (s.name == "CylinderSphere" || s.name == "CylinderCapsule" || s.name == "CylinderBox" ||
                      s.name == "ConeSphere");
}
/// The solids of the construction rows: each as a shape (built unposed), its region, and that
/// region posed.
struct ConstructionCase {
  std::string name;
  std::function<std::shared_ptr<fcl_quadric::QuadricShape<double>>()> make;
  QuadricRegion local, posed;
};
std::vector<ConstructionCase> makeConstructionCases() {
  using Q = fcl_quadric::Quadric<double>;
  using CSG = fcl_quadric::QuadricCSG<double>;
  const Eigen::Vector3d ez(0, 0, 1);
  std::vector<ConstructionCase> out;
  out.push_back({"ClippedEllipsoid", [ez] { return std::make_shared<Q>(Q::ellipsoid(0.5, 0.7, 1.1, {{ez, 0.5}})); }, {}, {}});
  out.push_back({"ParaboloidCap", [ez] { return std::make_shared<Q>(Q::ellipticParaboloid(0.5, 0.7, {{ez, 1.0}})); }, {}, {}});
  out.push_back(
      {"ConeNappe", [ez] { return std::make_shared<Q>(Q::ellipticCone(0.5, 0.7, 1.0, {{-ez, 0.0}, {ez, 1.1}})); }, {}, {}});
  out.push_back({"TwoSheetCap",
                 [ez] { return std::make_shared<Q>(Q::hyperboloidTwoSheets(1.0, 1.0, 1.0, {{-ez, 0.0}, {ez, 2.0}})); },
                 {},
                 {}});
  // A link made of three posed capped elliptic cylinders (a union of convex operands).
  const auto rod = std::make_shared<fcl_quadric::EllipticCylinder<double>>(0.3, 0.4, 2.0);
  out.push_back({"UnionOfThreeCylinders",
                 [rod] {
                   std::vector<CSG::Child> children;
                   for (int k = 0; k < 3; ++k) {
                     fcl::Transform3d X = fcl::Transform3d::Identity();
                     X.linear() = Eigen::AngleAxisd(0.4 + 0.45 * k, Eigen::Vector3d(1, k, 0.5).normalized()).toRotationMatrix();
                     X.translation() = Eigen::Vector3d(0.3 * k, 0.1 * k, 0.0);
                     children.push_back({rod, X});
                   }
                   return std::make_shared<CSG>(CSG::Op::Union, children);
                 },
                 {},
                 {}});
  // Not convex, so boxed by regionAabb's bisections: the ring of the CSG scenes (an ellipsoid
  // minus a bore) and a lens (two balls intersected).
  out.push_back({"Ring",
                 [] {
                   const fcl::Transform3d I = fcl::Transform3d::Identity();
                   const auto outer = std::make_shared<Q>(Q::ellipsoid(1.2, 1.2, 0.6));
                   const auto bore = std::make_shared<Q>(Q::ellipticCylinder(0.6, 0.6));
                   return std::make_shared<CSG>(CSG::Op::Difference, std::vector<CSG::Child>{{outer, I}, {bore, I}});
                 },
                 {},
                 {}});
  out.push_back({"Lens",
                 [] {
                   fcl::Transform3d up = fcl::Transform3d::Identity(), down = up;
                   up.translation() = Eigen::Vector3d(0, 0, 0.5);
                   down.translation() = Eigen::Vector3d(0, 0, -0.5);
                   const auto ball = std::make_shared<Q>(Q::ellipsoid(1.0, 1.0, 1.0));
                   return std::make_shared<CSG>(CSG::Op::Intersection,
                                                std::vector<CSG::Child>{{ball, up}, {ball, down}});
                 },
                 {},
                 {}});
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.9, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  for (ConstructionCase& c : out) {
    c.local = c.make()->region();
    c.posed = c.local.transformed(R, Eigen::Vector3d(1.5, -2.0, 3.0));
  }
  return out;
}
std::vector<ConstructionCase>& constructionCases() {
  static std::vector<ConstructionCase> cases;
  return cases;
}
void registerConstructionBenchmarks() {
  for (std::size_t k = 0; k < constructionCases().size(); ++k) {
    const std::string& name = constructionCases()[k].name;
    benchmark::RegisterBenchmark(("QuadricShapes/Construction/" + name + "/fcl_quadric").c_str(),
                                 [k](benchmark::State& state) {
                                   for (auto _ : state) benchmark::DoNotOptimize(constructionCases()[k].make());
                                 })
        ->Unit(benchmark::kMillisecond);
    for (const bool posed : {false, true}) {
      for (const bool support : {true, false}) {
        const std::string row = "QuadricShapes/ConstructionBox/" + name + (posed ? "Posed/" : "/") +
                                (support ? "SupportCertified" : "RegionEngineBisection");
        benchmark::RegisterBenchmark(row.c_str(),
                                     [k, posed, support](benchmark::State& state) {
                                       const ConstructionCase& c = constructionCases()[k];
                                       const QuadricRegion& r = posed ? c.posed : c.local;
                                       for (auto _ : state) {
                                         if (support) {
                                           const std::optional<Box3> b = fcl_quadric::ConvexSupport::treeBox(r);
                                           if (!b) {
                                             state.SkipWithError("treeBox left the region to regionAabb");
                                             break;
                                           }
                                           benchmark::DoNotOptimize(b);
                                         } else {
                                           benchmark::DoNotOptimize(fcl_quadric::regionAabb(r));
                                         }
                                       }
                                     })
            ->Unit(benchmark::kMillisecond);
      }
    }
  }
}

// Boundary elements (thesis §6.1-6.2), which the dimension reduction needs once per shape (the
// front door caches them): a box, a box with four corners cut and turned, a plus-shaped union of
// two boxes, the CSG wedge, a turned capped cylinder and a turned block with a bore; and the
// turned corner-cut box's regionAabb (ten planes in one and-node). No FCL counterpart: FCL has
// no CSG solids.
QuadricRegion cuboidRegion(const Eigen::Vector3d& h) {
  std::vector<QuadricRegion> faces;
  for (int i = 0; i < 3; ++i)
    for (const double s : {1.0, -1.0}) faces.push_back(QuadricRegion::halfspace(s * Eigen::Vector3d::Unit(i), h[i]));
  return QuadricRegion::combine(QuadricRegion::Op::Intersection, faces);
}
std::vector<std::pair<std::string, QuadricRegion>> makeElementCases() {
  using Op = QuadricRegion::Op;
  const Eigen::Vector3d h(0.7, 0.9, 1.1);
  std::vector<QuadricRegion> cut{cuboidRegion(h)};
  for (int corner = 0; corner < 4; ++corner) {  // planes through the corner's edges at 0.6 h
    const Eigen::Vector3d sign((corner & 1) ? -1.0 : 1.0, (corner & 2) ? -1.0 : 1.0, 1.0);
    const Eigen::Vector3d n = sign.cwiseQuotient(0.6 * h);
    cut.push_back(QuadricRegion::halfspace(n, n.dot(sign.cwiseProduct(h)) - 1.0));
  }
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.9, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  const Eigen::Vector3d p(1.5, -2.0, 3.0);
  const QuadricRegion bore = QuadricRegion::atom(fcl_quadric::quadric::ellipticCylinder(0.35, 0.45));
  return {{"Box", cuboidRegion(h)},
          {"CornerCutBlockTurned",
           QuadricRegion::combine(Op::Intersection, cut).transformed(R, p)},
          {"Plus", QuadricRegion::combine(Op::Union, {cuboidRegion(Eigen::Vector3d(0.7, 0.15, 0.6)),
                                                      cuboidRegion(Eigen::Vector3d(0.21, 0.5, 0.6))})},
          {"Wedge", fcl_quadric::bench::wedgeRegion()},
          {"CappedCylinderTurned", fcl_quadric::bench::cappedCylinderRegion(0.7, 0.5, 2.2).transformed(R, p)},
          {"DrilledBlockTurned", QuadricRegion::combine(Op::Difference, {cuboidRegion(h), bore}).transformed(R, p)}};
}
void registerElementBenchmarks() {
  static const std::vector<std::pair<std::string, QuadricRegion>> cases = makeElementCases();
  for (const auto& [name, region] : cases) {
    const QuadricRegion* r = &region;
    const Box3 box = fcl_quadric::regionAabb(region);
    benchmark::RegisterBenchmark(("QuadricShapes/BoundaryElements/" + name).c_str(),
                                 [r, box](benchmark::State& state) {
                                   for (auto _ : state) benchmark::DoNotOptimize(fcl_quadric::boundaryElements(*r, box));
                                 })
        ->Unit(benchmark::kMillisecond);
  }
  const QuadricRegion* turned = &cases[1].second;
  benchmark::RegisterBenchmark("QuadricShapes/ConstructionBox/CornerCutBlockTurned/RegionEngineBisection",
                               [turned](benchmark::State& state) {
                                 for (auto _ : state) benchmark::DoNotOptimize(fcl_quadric::regionAabb(*turned));
                               })
      ->Unit(benchmark::kMillisecond);
}

void registerShapePairBenchmarks() {
  for (std::size_t k = 0; k < shapePairScenes().size(); ++k) {
    const ShapePairScene& s = shapePairScenes()[k];
    if (distanceTimed(s)) {
      for (const bool ours : {true, false}) {
        benchmark::RegisterBenchmark(
            ("QuadricShapes/PairsDistance/" + s.name + (ours ? "/fcl_quadric" : "/FclGjkLibccd")).c_str(),
            [k, ours](benchmark::State& state) {
              const ShapePairScene& c = shapePairScenes()[k];
              const auto& poses = shapePairPoses();
              std::size_t i = 0;
              for (auto _ : state) {
                benchmark::DoNotOptimize(
                    shapePairDistance(ours ? c.ours.get() : c.theirs.get(), c.partner.get(), poses[i], ours));
                i = (i + 1) % poses.size();
              }
            })
            ->Unit(benchmark::kMicrosecond);
      }
    }
    for (const bool ours : {true, false}) {
      if (!ours && !s.theirs) continue;
      benchmark::RegisterBenchmark(("QuadricShapes/Pairs/" + s.name + (ours ? "/fcl_quadric" : "/FclGjkLibccd")).c_str(),
                                   [k, ours](benchmark::State& state) {
                                     const ShapePairScene& c = shapePairScenes()[k];
                                     const auto& poses = shapePairPoses();
                                     std::size_t i = 0;
                                     for (auto _ : state) {
                                       benchmark::DoNotOptimize(shapePairCollide(ours ? c.ours.get() : c.theirs.get(),
                                                                                 c.partner.get(), poses[i], ours));
                                       i = (i + 1) % poses.size();
                                     }
                                   })
          ->Unit(benchmark::kMicrosecond);
    }
  }
}

int main(int argc, char** argv) {
  const std::size_t n = fcl_quadric::bench::takeSizeOption(&argc, argv, "pairs", "FCL_QUADRIC_BENCH_PAIRS", 2000);
  const std::size_t nm = fcl_quadric::bench::takeSizeOption(&argc, argv, "motions", "FCL_QUADRIC_BENCH_MOTIONS", 32);
  cylinderPairs() = fcl_quadric::bench::makeCylinderPairs(n);
  {
    std::mt19937_64 rng(17);
    std::normal_distribution<double> g(0.0, 1.0);
    for (std::size_t k = 0; k < nm && k < cylinderPairs().size(); ++k) {
      const double x = g(rng), y = g(rng), z = g(rng);
      cylinderMotions().push_back({cylinderPairs()[k], 2.5 * Eigen::Vector3d(x, y, z).normalized()});
      CylinderMotion small = cylinderMotions().back();
      small.pair.r2 *= 0.05;
      small.pair.L2 *= 0.05;
      smallCylinderMotions().push_back(small);
    }
  }
  smallEllipsoidPairs() = makeSmallEllipsoidPairs(n);
  distancePairs() = makeDistancePairs(cylinderPairs());
  terrain() = makeTerrain();
  octreeTerrain() = makeOcTreeTerrain();
  shapePairScenes() = makeShapePairScenes();
  registerShapePairBenchmarks();
  constructionCases() = makeConstructionCases();
  registerConstructionBenchmarks();
  registerElementBenchmarks();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  {
    int colliding = 0, band = 0, differ = 0;
    for (const SmallEllipsoidPair& s : smallEllipsoidPairs()) {
      const fcl_quadric::RegionRelation rel = smallEllipsoidEngine(s);
      const bool ours = smallEllipsoidCollide(s);
      if (rel == fcl_quadric::RegionRelation::Touching) {
        ++band;
        continue;
      }
      colliding += rel == fcl_quadric::RegionRelation::Overlapping;
      differ += ours != (rel == fcl_quadric::RegionRelation::Overlapping);
    }
    std::printf("Small ellipsoids, %zu pairs: %d colliding (certified), %d in the engine's band; fcl_quadric::collide "
                "(GJK screening and the filter first) differs from the engine on %d\n",
                smallEllipsoidPairs().size(), colliding, band, differ);
  }
  {
    // Distance: FCL's relative error on the pairs both call separated; sign disagreements.
    std::vector<double> err;
    int sign_differ = 0, separated = 0;
    for (const DistancePair& c : distancePairs()) {
      const double ours = quadricDistance(c), theirs = fclDistance(c);
      if ((ours > 0) != (theirs > 0)) ++sign_differ;
      if (ours > 0 && theirs > 0) {
        ++separated;
        err.push_back(std::fabs(theirs - ours) / ours);
      }
    }
    std::sort(err.begin(), err.end());
    std::printf("Distance, %zu cylinder pairs: %d separated for both; FCL libccd relative error median %.3g, max %.3g; "
                "sign differs on %d\n",
                cylinderPairs().size(), separated, err.empty() ? 0.0 : err[err.size() / 2],
                err.empty() ? 0.0 : err.back(), sign_differ);
  }
  {
    // Terrain: collide flags and distances of the two libraries on the same poses.
    int hits = 0, flags_differ = 0, node_differs = 0;
    double worst = 0.0, worst_node = 0.0;
    for (const fcl::Transform3d& tf : terrain().poses) {
      const bool ours = terrainQuery<true, false>(tf) > 0, theirs = terrainQuery<false, false>(tf) > 0;
      hits += ours;
      flags_differ += ours != theirs;
      node_differs += ours != terrainNodeCollides(tf);
      const double d1 = terrainQuery<true, true>(tf), d2 = terrainQuery<false, true>(tf);
      if (d1 > 0 && d2 > 0) worst = std::max(worst, std::fabs(d1 - d2) / d1);
      const double d3 = terrainNodeDistance(tf);
      if (d1 > 0) worst_node = std::max(worst_node, std::fabs(d3 - d1) / d1);
      else node_differs += d3 > 0;
    }
    std::printf("Terrain, %zu poses over 40,000 triangles: %d colliding (ours); FCL's collide flag differs on %d; "
                "FCL's traversal nodes with QuadricSolver differ from the front door on %d (distance: largest "
                "relative difference %.3g); largest relative distance difference on pairs both call separated "
                "%.3g\n",
                terrain().poses.size(), hits, flags_differ, node_differs, worst_node, worst);
  }
  {
    // OcTree terrain: collide flags and distances of the two libraries; our lower bound against
    // our distance.
    const OcTreeTerrainScene& t = octreeTerrain();
    int hits = 0, flags_differ = 0, bound_above = 0;
    double worst = 0.0, worst_bound = 0.0;
    for (const fcl::Transform3d& tf : t.poses) {
      const bool ours = octreeTerrainQuery<true, false>(tf) > 0, theirs = octreeTerrainQuery<false, false>(tf) > 0;
      hits += ours;
      flags_differ += ours != theirs;
      const double d1 = octreeTerrainQuery<true, true>(tf), d2 = octreeTerrainQuery<false, true>(tf);
      if (d1 > 0 && d2 > 0) worst = std::max(worst, std::fabs(d1 - d2) / d1);
      const double b = *fcl_quadric::distanceLowerBound(t.ours.get(), tf, t.tree.get(), fcl::Transform3d::Identity(), 1e3);
      if (d1 > 0) {
        bound_above += b > d1;
        worst_bound = std::max(worst_bound, (d1 - b) / d1);
      }
    }
    std::printf("OcTree terrain, %zu poses over %zu leaves: %d colliding (ours); FCL's collide flag differs on %d; "
                "largest relative distance difference on poses both call separated %.3g; lower bound above the "
                "distance on %d, largest (distance - bound) / distance %.3g\n",
                t.poses.size(), t.tree->toBoxes().size(), hits, flags_differ, worst, bound_above, worst_bound);
  }
  {
    // Lower bounds: the terrain bound against our exact distance (both cylinders), the ring's
    // bound against its poses (how many certified positive).
    double worst = 0.0;
    int below = 0, separated = 0, zero_on_contact = 0;
    for (const fcl::Transform3d& tf : terrain().poses) {
      const double d = terrainQuery<true, true>(tf);
      const double b = *fcl_quadric::distanceLowerBound(terrain().theirs.get(), tf, terrain().mesh.get(),
                                                        fcl::Transform3d::Identity(), 1e3);
      if (d > 0) {
        ++separated;
        worst = std::max(worst, (d - b) / d);
        below += b <= d;
      } else {
        zero_on_contact += b == 0.0;
      }
    }
    int positive = 0, bound_above = 0;
    for (const fcl::Transform3d& tf : ringPole().poses) {
      const double b = *fcl_quadric::distanceLowerBound(ringPole().ring.get(), tf, ringPole().pole.get(),
                                                        fcl::Transform3d::Identity(), 1e3);
      fcl::DistanceRequestd req;
      fcl::DistanceResultd res;
      const double d = fcl_quadric::distance(ringPole().ring.get(), tf, ringPole().pole.get(),
                                             fcl::Transform3d::Identity(), req, res);
      positive += b > 0.0;
      bound_above += b > d;
    }
    std::printf("Lower bounds: terrain, %d of %d separated poses at or below the exact distance (largest relative "
                "shortfall %.3g), %d of %zu colliding poses at 0; ring on pole, %d of %zu poses certified clear, "
                "bound above fcl_quadric::distance on %d\n",
                below, separated, worst, zero_on_contact, terrain().poses.size() - separated, positive,
                ringPole().poses.size(), bound_above);
  }
  {
    // Ring and ball: the certified bracket [lower bound, distance] of the branch and bound, and the
    // tessellated mesh's distance against it.
    std::vector<double> gaps, mesh_err;
    int outside_bracket = 0;
    const fcl_quadric::ConvexSupport ball = fcl_quadric::ConvexSupport::ellipsoid(Eigen::Vector3d::Constant(0.15));
    const auto& ring = *ringPole().ring;
    for (const fcl::Transform3d& tf : ringBall().poses) {
      const double ours = ringBallDistance<true>(tf), theirs = ringBallDistance<false>(tf);
      const fcl_quadric::RegionDistanceResult r = fcl_quadric::regionDistance(
          fcl_quadric::DistanceOperand::ofRegion(ring.region(), ring.localBox(), Eigen::Matrix3d::Identity(),
                                                 Eigen::Vector3d::Zero()),
          fcl_quadric::DistanceOperand::ofConvex(ball, Eigen::Matrix3d::Identity(), tf.translation()));
      gaps.push_back(r.distance - r.lower_bound);
      outside_bracket += ours < r.lower_bound || ours > r.distance + 1e-12;
      mesh_err.push_back(std::fabs(theirs - ours) / ours);
    }
    std::sort(gaps.begin(), gaps.end());
    std::sort(mesh_err.begin(), mesh_err.end());
    std::printf("Ring and ball, %zu separated poses: certified gap (distance - lower bound) median %.3g, max %.3g; "
                "front door outside its bracket on %d; FCL on the %d-triangle mesh: relative error median %.3g, "
                "max %.3g\n",
                ringBall().poses.size(), gaps[gaps.size() / 2], gaps.back(), outside_bracket,
                ringBall().mesh->num_tris, mesh_err[mesh_err.size() / 2], mesh_err.back());
  }
  {
    // Shape pairs: the colliding poses of each, and where FCL has the pair, the poses where its
    // flag differs from ours.
    std::printf("Shape pairs, %zu poses each (colliding; FCL differs):", shapePairPoses().size());
    for (const ShapePairScene& c : shapePairScenes()) {
      int hits = 0, differs = 0;
      for (const fcl::Transform3d& tb : shapePairPoses()) {
        const bool ours = shapePairCollide(c.ours.get(), c.partner.get(), tb, true);
        hits += ours;
        if (c.theirs) differs += shapePairCollide(c.theirs.get(), c.partner.get(), tb, false) != ours;
      }
      std::printf(" %s %d", c.name.c_str(), hits);
      if (c.theirs) std::printf(" (%d)", differs);
      std::printf(";");
    }
    std::printf("\n");
    // Their distances: separated poses (ours > 0), and the largest difference from FCL's where
    // both are positive (FCL stops at 1e-6; it gives -1 for an overlap).
    std::printf("Shape pair distances (separated; max |ours - FCL| where both > 0):");
    for (const ShapePairScene& c : shapePairScenes()) {
      if (!distanceTimed(c)) continue;
      int separated = 0;
      double worst = 0.0;
      for (const fcl::Transform3d& tb : shapePairPoses()) {
        const double ours = shapePairDistance(c.ours.get(), c.partner.get(), tb, true);
        const double theirs = shapePairDistance(c.theirs.get(), c.partner.get(), tb, false);
        separated += ours > 0.0;
        if (ours > 0.0 && theirs > 0.0) worst = std::max(worst, std::abs(ours - theirs));
      }
      std::printf(" %s %d %.2g;", c.name.c_str(), separated, worst);
    }
    std::printf("\n");
  }
  // Agreement (outside the timed loops).
  int touching = 0, disagree = 0, fcl_misses = 0, fcl_false = 0, hits = 0, front_door_differs = 0;
  for (std::size_t i = 0; i < cylinderPairs().size(); ++i) {
    const CylinderPair& c = cylinderPairs()[i];
    const fcl_quadric::RegionRelation rel = regionQuery(c);
    const bool f = fclQuery(c);
    if (rel == fcl_quadric::RegionRelation::Touching) {
      ++touching;
      continue;
    }
    const bool ours = rel == fcl_quadric::RegionRelation::Overlapping;
    front_door_differs += quadricCollide(distancePairs()[i]) != ours;
    hits += ours;
    if (ours != f) {
      ++disagree;
      if (ours) ++fcl_misses;
      else ++fcl_false;
    }
  }
  std::printf("Agreement on %zu cylinder pairs: %d colliding (certified), %d touching (band), FCL GJK disagrees "
              "on %d (%d missed collisions, %d false collisions); fcl_quadric::collide differs from the engine on "
              "%d\n",
              cylinderPairs().size(), hits, touching, disagree, fcl_misses, fcl_false, front_door_differs);
  // Continuous: FCL's answers against the certified first contacts. A miss: the pair collides
  // (certified) and FCL reports no collision; late: FCL's time exceeds the certified one by more
  // than 1e-3; false: FCL reports a collision where the region CCD certified none.
  for (const bool small : {false, true}) {
    const char* what = small ? "pin-and-post (the moving cylinder 1/20)" : "cylinder";
    int ccd_hits = 0, near = 0, red_decided = 0, red_disagree = 0;
    double red_worst = 0.0;
    int misses[2] = {0, 0}, late[2] = {0, 0}, falses[2] = {0, 0};
    double worst[2] = {0.0, 0.0};  // largest |FCL time - certified time| over pairs both call colliding
    const fcl::CCDSolverType solvers[2] = {fcl::CCDC_NAIVE, fcl::CCDC_CONSERVATIVE_ADVANCEMENT};
    for (const CylinderMotion& m : motionSet(small)) {
      const fcl_quadric::RegionCcdResult r = regionCcd(m);
      ccd_hits += r.collide;
      near += r.near_tangent;
      const ReductionAnswer d = reductionCcd(cylinderRegions(m, true));
      red_decided += d.decided;
      if (d.decided && d.collide != r.collide) ++red_disagree;
      if (d.decided && d.collide && r.collide) red_worst = std::max(red_worst, std::fabs(d.time - r.time));
      for (int s = 0; s < 2; ++s) {
        const auto [collide, toc] = fclCcd(m, solvers[s]);
        if (r.collide && !collide) ++misses[s];
        if (r.collide && collide && toc > r.time + 1e-3) ++late[s];
        if (r.collide && collide) worst[s] = std::max(worst[s], std::fabs(toc - r.time));
        if (!r.collide && collide) ++falses[s];
      }
    }
    std::printf("Continuous, %zu %s translations: %d colliding (certified; %d near-tangent); FCL CCDC_NAIVE: "
                "%d missed, %d late by > 1e-3, %d false, largest time error %.3g; FCL conservative advancement: %d "
                "missed, %d late, %d false, largest time error %.3g\n",
                motionSet(small).size(), what, ccd_hits, near, misses[0], late[0], falses[0], worst[0], misses[1],
                late[1], falses[1], worst[1]);
    std::printf("Dimension reduction on the same %zu translations: %d decided (the rest fall back to the engine), "
                "%d disagree with the engine on collide, largest |time - engine time| %.3g\n",
                motionSet(small).size(), red_decided, red_disagree, red_worst);
  }
  return 0;
}
