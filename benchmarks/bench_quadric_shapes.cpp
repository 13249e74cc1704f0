// Composite quadric models (issue 5): static queries of the certified region engine
// (geometry/quadric_region.h) against FCL 0.7's GJK (libccd) on the same capped circular cylinder
// poses, and CSG pairs (ring = ellipsoid minus bore, wedge = elliptic cylinder minus half-space
// minus cylinder). One iteration = one pair, the pair set walked cyclically; std::mt19937_64(7),
// `--pairs N` (default 2,000). After the timed runs the program prints the agreement on the
// cylinder pairs: FCL's boolean against the engine's certified answers (Touching pairs counted
// apart: within the engine's tolerance band, neither answer is wrong).
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/narrowphase/collision.h>

#include "bench_support.h"
#include "fcl_quadric/algebra/quadric_matrix.h"
#include "fcl_quadric/geometry/quadric_region.h"

namespace {

using fcl_quadric::Box3;
using fcl_quadric::QuadricRegion;
using Op = QuadricRegion::Op;

struct CylinderPair {
  double r1, L1, r2, L2;
  Eigen::Matrix3d R;  // cylinder 2 in cylinder 1's frame (= world; cylinder 1 at the identity)
  Eigen::Vector3d p;
};

QuadricRegion capped(double a, double b, double L) {
  return QuadricRegion::combine(Op::Intersection, {QuadricRegion::atom(fcl_quadric::quadric::ellipticCylinder(a, b)),
                                                   QuadricRegion::halfspace({0, 0, 1}, 0.5 * L),
                                                   QuadricRegion::halfspace({0, 0, -1}, 0.5 * L)});
}

Eigen::Matrix3d randomRotation(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
  q.normalize();
  return q.toRotationMatrix();
}

std::vector<CylinderPair>& cylinderPairs() {
  static std::vector<CylinderPair> pairs;
  return pairs;
}

void makePairs(std::size_t n) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> r(0.3, 1.0), L(0.6, 2.0), u(-2.0, 2.0);
  auto& pairs = cylinderPairs();
  pairs.clear();
  for (std::size_t i = 0; i < n; ++i)
    pairs.push_back({r(rng), L(rng), r(rng), L(rng), randomRotation(rng), Eigen::Vector3d(u(rng), u(rng), u(rng))});
}

fcl_quadric::RegionRelation regionQuery(const CylinderPair& c) {
  const Box3 b1{Eigen::Vector3d(-c.r1, -c.r1, -0.5 * c.L1), Eigen::Vector3d(c.r1, c.r1, 0.5 * c.L1)};
  const Box3 b2{Eigen::Vector3d(-c.r2, -c.r2, -0.5 * c.L2), Eigen::Vector3d(c.r2, c.r2, 0.5 * c.L2)};
  return fcl_quadric::collideRegions(capped(c.r1, c.r1, c.L1), b1, capped(c.r2, c.r2, c.L2), b2, c.R, c.p).relation;
}

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
  const QuadricRegion ring = QuadricRegion::combine(
      Op::Difference, {QuadricRegion::atom(fcl_quadric::quadric::ellipsoid({1.2, 1.2, 0.6})),
                       QuadricRegion::atom(fcl_quadric::quadric::ellipticCylinder(0.6, 0.6))});
  const QuadricRegion wedge = QuadricRegion::combine(
      Op::Difference, {capped(1.0, 0.7, 0.8), QuadricRegion::halfspace({0, 1, 0}, 0.0),
                       QuadricRegion::atom(fcl_quadric::quadric::ellipticCylinder(0.3, 0.3))});
  const Box3 rb = fcl_quadric::regionAabb(ring), wb = fcl_quadric::regionAabb(wedge);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  std::vector<std::pair<Eigen::Matrix3d, Eigen::Vector3d>> poses;
  for (int k = 0; k < 256; ++k) poses.emplace_back(randomRotation(rng), Eigen::Vector3d(u(rng), u(rng), u(rng)));
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(fcl_quadric::collideRegions(ring, rb, wedge, wb, poses[i].first, poses[i].second));
    i = (i + 1) % poses.size();
  }
}

BENCHMARK(BM_CylindersRegionEngine)->Name("QuadricShapes/Cylinders/RegionEngine")->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CylindersFclGjkLibccd)->Name("QuadricShapes/Cylinders/FclGjkLibccd")->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CsgRingWedge)->Name("QuadricShapes/Csg/RingWedge")->Unit(benchmark::kMicrosecond);

}  // namespace

int main(int argc, char** argv) {
  const std::size_t n = fcl_quadric::bench::takeSizeOption(&argc, argv, "pairs", "FCL_QUADRIC_BENCH_PAIRS", 2000);
  makePairs(n);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  // Agreement (outside the timed loops).
  int touching = 0, disagree = 0, fcl_misses = 0, fcl_false = 0, hits = 0;
  for (const CylinderPair& c : cylinderPairs()) {
    const fcl_quadric::RegionRelation rel = regionQuery(c);
    const bool f = fclQuery(c);
    if (rel == fcl_quadric::RegionRelation::Touching) {
      ++touching;
      continue;
    }
    const bool ours = rel == fcl_quadric::RegionRelation::Overlapping;
    hits += ours;
    if (ours != f) {
      ++disagree;
      if (ours) ++fcl_misses;
      else ++fcl_false;
    }
  }
  std::printf("Agreement on %zu cylinder pairs: %d colliding (certified), %d touching (band), FCL GJK disagrees "
              "on %d (%d missed collisions, %d false collisions)\n",
              cylinderPairs().size(), hits, touching, disagree, fcl_misses, fcl_false);
  return 0;
}
