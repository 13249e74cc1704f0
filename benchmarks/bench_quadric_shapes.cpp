// Composite quadric models (issue 5): static queries of the certified region engine
// (geometry/quadric_region.h) against FCL 0.7's GJK (libccd) on the same capped circular cylinder
// poses, and CSG pairs (ring = ellipsoid minus bore, wedge = elliptic cylinder minus half-space
// minus cylinder; quadric_shapes_scene.h). One iteration = one pair, the pair set walked
// cyclically; `--pairs N` (default 2,000). After the timed runs the program prints the agreement on the
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

BENCHMARK(BM_CylindersRegionEngine)->Name("QuadricShapes/Cylinders/RegionEngine")->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CylindersFclGjkLibccd)->Name("QuadricShapes/Cylinders/FclGjkLibccd")->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CsgRingWedge)->Name("QuadricShapes/Csg/RingWedge")->Unit(benchmark::kMicrosecond);

}  // namespace

int main(int argc, char** argv) {
  const std::size_t n = fcl_quadric::bench::takeSizeOption(&argc, argv, "pairs", "FCL_QUADRIC_BENCH_PAIRS", 2000);
  cylinderPairs() = fcl_quadric::bench::makeCylinderPairs(n);
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
