// The two experiments of Wang et al. 2004 §5 (separating planes for moving ellipsoids), with FCL
// 0.7 as the polygonal/GJK peer (docs/benchmarks.md).
//
// Table 1: two ellipsoids with half-axes (3, 3, 5), centres 8 apart, each rotating about its own
//   random axis by omega = 0.1, 0.5, 1.0 rad per frame for 10,000 frames. One pair of axes decides
//   the collision rate (from 0 % to about a third of the frames across seeds; about 16 % for
//   uniformly random orientations), so the program runs 16 sequences (seeds 2004..2019;
//   `--table1_seeds N`) and reports seed 2004 and the mean. Peers: classifyEllipsoids every frame
//   (baseline "fcl_quadric"), PairCoherence (EECD: cached plane first), fcl::collide libccd on
//   fcl::Ellipsoid.
// Table 2: a unit sphere orbiting the ellipsoid (4.5, 4, 2) in the plane of its two longest axes,
//   orbit radius 5.49, 0.01 rad per frame, 13,746 frames; an AABB test first, the narrow phase
//   only where the boxes overlap. Peers: classifyEllipsoids, PairCoherence, fcl::collide libccd on
//   fcl::Ellipsoid, on fcl::Convex of sqrt(3)-tessellations (488 / 1,460 / 4,376 / 13,124
//   vertices, both bodies) and on fcl::BVHModel<OBBRSS> of the same meshes.
// One benchmark iteration is a whole sequence; t_frame = CPU time / frames (Table 1: 10,000 per
// sequence; Table 2: the frames whose boxes overlap, as in the paper). Motions are built explicitly per
// frame (FCL 0.7's InterpMotion is not used).
// At the end the program prints the "Summary" (median CPU time per frame), "Table 1" and "Table 2"
// blocks, each beside the paper's numbers; benchmarks/update_docs.sh copies them into
// docs/benchmarks.md.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <Eigen/Geometry>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/math/bv/OBBRSS.h>

#include "bench_support.h"
#include "fcl_peers.h"
#include "fcl_quadric/geometry/ellipsoid_separation.h"
#include "fcl_quadric/geometry/pair_coherence.h"
#include "separating_planes_scenes.h"
#include "sqrt3_tessellation.h"

namespace fcl_quadric {
namespace bench {
namespace {

// ------------------------------------------------------------------------------------------------
// Table 1: rotating ellipsoids

constexpr std::size_t kDefaultTable1Sequences = 16;
/// Paper values (Pentium 4, 2.26 GHz) in the order of kTable1Omegas.
constexpr int kPaperCollisions[] = {1202, 1554, 1622};
constexpr int kPaperPlaneHits[] = {8310, 6029, 4502};
constexpr double kPaperEecdUs[] = {2.474, 3.985, 4.982};
constexpr double kPaperPlainUs[] = {7.906, 7.951, 7.899};

/// One 10,000-frame sequence: poses precomputed, counts taken once (untimed).
struct RotatingSequence {
  std::vector<Ellipsoid> a, b;
  std::vector<fcl::Transform3d> X_WA, X_WB;
  int collisions = 0, separations = 0, plane_hits = 0, coherence_mismatches = 0;
  int fcl_found = 0, fcl_misses = 0, fcl_false_hits = 0;
};

/// The sequences of one angular speed (seeds kTable1FirstSeed, +1, ...; the same seeds, hence the
/// same initial orientations and axes, for every speed).
struct RotatingScene {
  double omega = 0.0;
  std::vector<RotatingSequence> sequences;
  fcl::Ellipsoidd fcl_a{3.0, 3.0, 5.0}, fcl_b{3.0, 3.0, 5.0};
  std::string group() const {
    char g[32];
    std::snprintf(g, sizeof g, "Table1/omega_%.1f", omega);
    return g;
  }
  double frames() const { return static_cast<double>(kTable1Frames) * static_cast<double>(sequences.size()); }
};

/// The sequence of rotatingFrames(omega, seed) with its FCL poses and counts.
RotatingSequence makeRotatingSequence(double omega, std::uint64_t seed, const fcl::Ellipsoidd& fcl_shape) {
  RotatingSequence s;
  RotatingFrames frames = rotatingFrames(omega, seed);
  s.a = std::move(frames.a);
  s.b = std::move(frames.b);
  for (int k = 0; k < kTable1Frames; ++k) {
    s.X_WA.push_back(fclPose(s.a[k]));
    s.X_WB.push_back(fclPose(s.b[k]));
  }
  PairCoherence coherence;
  for (int k = 0; k < kTable1Frames; ++k) {
    const Separation plain = classifyEllipsoids(s.a[k], s.b[k]).status;
    const Separation eecd = coherence.query(s.a[k], s.b[k]);
    s.coherence_mismatches += plain != eecd;
    const bool collide = plain != Separation::Separated;
    s.collisions += collide;
    const bool fcl_hit = fclCollide(&fcl_shape, s.X_WA[k], &fcl_shape, s.X_WB[k], fcl::GST_LIBCCD);
    s.fcl_found += fcl_hit;
    s.fcl_misses += collide && !fcl_hit;
    s.fcl_false_hits += fcl_hit && !collide;
  }
  s.separations = kTable1Frames - s.collisions;
  s.plane_hits = static_cast<int>(coherence.planeHits());
  return s;
}

RotatingScene makeRotatingScene(double omega, std::size_t n_sequences) {
  RotatingScene s;
  s.omega = omega;
  for (std::size_t i = 0; i < n_sequences; ++i) {
    s.sequences.push_back(makeRotatingSequence(omega, kTable1FirstSeed + i, s.fcl_a));
  }
  return s;
}

/// Mean, min and max of a per-sequence count.
struct CountStats {
  double mean = 0.0;
  int min = 0, max = 0;
};

template <class Field>
CountStats countStats(const RotatingScene& s, Field field) {
  CountStats c;
  c.min = c.max = field(s.sequences.front());
  for (const RotatingSequence& q : s.sequences) {
    const int v = field(q);
    c.mean += v;
    c.min = std::min(c.min, v);
    c.max = std::max(c.max, v);
  }
  c.mean /= static_cast<double>(s.sequences.size());
  return c;
}

void setTable1Counters(benchmark::State& state, const RotatingScene& s) {
  setPerItemTime(state, s.frames(), "t_frame");
  state.counters["collisions"] =
      countStats(s, [](const RotatingSequence& q) { return q.collisions; }).mean;
}

void benchTable1Plain(benchmark::State& state, const RotatingScene* s) {
  for (auto _ : state) {
    for (const RotatingSequence& q : s->sequences) {
      int collisions = 0;
      for (int k = 0; k < kTable1Frames; ++k) {
        collisions += classifyEllipsoids(q.a[k], q.b[k]).status != Separation::Separated;
      }
      benchmark::DoNotOptimize(collisions);
    }
  }
  setTable1Counters(state, *s);
}

void benchTable1Coherence(benchmark::State& state, const RotatingScene* s) {
  for (auto _ : state) {
    for (const RotatingSequence& q : s->sequences) {
      PairCoherence coherence;
      int collisions = 0;
      for (int k = 0; k < kTable1Frames; ++k) {
        collisions += coherence.query(q.a[k], q.b[k]) != Separation::Separated;
      }
      benchmark::DoNotOptimize(collisions);
      benchmark::DoNotOptimize(coherence);
    }
  }
  setTable1Counters(state, *s);
  state.counters["plane_hits"] = countStats(*s, [](const RotatingSequence& q) { return q.plane_hits; }).mean;
}

void benchTable1Fcl(benchmark::State& state, const RotatingScene* s) {
  for (auto _ : state) {
    for (const RotatingSequence& q : s->sequences) {
      int collisions = 0;
      for (int k = 0; k < kTable1Frames; ++k) {
        collisions += fclCollide(&s->fcl_a, q.X_WA[k], &s->fcl_b, q.X_WB[k], fcl::GST_LIBCCD);
      }
      benchmark::DoNotOptimize(collisions);
    }
  }
  setTable1Counters(state, *s);
  state.counters["misses"] = countStats(*s, [](const RotatingSequence& q) { return q.fcl_misses; }).mean;
  state.counters["false_hits"] =
      countStats(*s, [](const RotatingSequence& q) { return q.fcl_false_hits; }).mean;
}

// ------------------------------------------------------------------------------------------------
// Table 2: a sphere orbiting an ellipsoid

constexpr int kTessellations[] = {488, 1460, 4376, 13124};
/// Paper values: EECD and enhanced GJK on n = 488 ... 13,124 vertices.
constexpr int kPaperTable2Collisions[] = {1157, 0, 435, 971, 1111};
constexpr double kPaperTable2Us[] = {2.12, 15.2, 23.6, 36.8, 54.3};
constexpr int kPaperTable2PlaneHits = 8020;
constexpr int kPaperTable2BoxFrames = 10000;
constexpr double kPaperTable2PlainUs = 7.63;

struct OrbitScene {
  Ellipsoid b = orbitEllipsoid();
  std::vector<Ellipsoid> a;               ///< the sphere at each frame
  std::vector<fcl::Transform3d> X_WA;     ///< its pose (translation only)
  fcl::Transform3d X_WB = fcl::Transform3d::Identity();
  std::vector<char> box_overlap;          ///< AABB test result per frame
  std::vector<char> exact;                ///< classifyEllipsoids collides (box-overlap frames)
  int box_frames = 0, collisions = 0, plane_hits = 0;
};

OrbitScene makeOrbitScene() {
  OrbitScene s;
  for (int k = 0; k < kTable2Frames; ++k) {
    const Eigen::Vector3d p = orbitCentre(k);
    s.a.push_back(Ellipsoid::sphere(1.0, p));
    fcl::Transform3d X = fcl::Transform3d::Identity();
    X.translation() = p;
    s.X_WA.push_back(X);
    const bool overlap = orbitBoxesOverlap(p);
    s.box_overlap.push_back(overlap);
    s.box_frames += overlap;
    const bool hit = overlap && classifyEllipsoids(s.a[k], s.b).status != Separation::Separated;
    s.exact.push_back(hit);
    s.collisions += hit;
  }
  PairCoherence coherence;
  for (int k = 0; k < kTable2Frames; ++k) {
    if (s.box_overlap[k]) coherence.query(s.a[k], s.b);
  }
  s.plane_hits = static_cast<int>(coherence.planeHits());
  return s;
}

/// A narrow-phase peer of Table 2: the shapes FCL sees (null for fcl_quadric peers).
struct OrbitPeer {
  std::string name;
  std::shared_ptr<fcl::CollisionGeometryd> a, b;
  int vertices = 0;  ///< of the tessellation, 0 for exact shapes
  int found = 0, misses = 0, false_hits = 0;
};

/// Runs `collides(k)` on the box-overlap frames of the orbit, in order. `reset()` starts a run.
template <class Reset, class Collides>
int runOrbit(const OrbitScene& s, Reset&& reset, Collides&& collides) {
  reset();
  int found = 0;
  for (int k = 0; k < kTable2Frames; ++k) {
    if (s.box_overlap[k]) found += collides(k);
  }
  return found;
}

template <class Reset, class Collides>
void countOrbit(const OrbitScene& s, OrbitPeer* peer, Reset&& reset, Collides&& collides) {
  reset();
  for (int k = 0; k < kTable2Frames; ++k) {
    if (!s.box_overlap[k]) continue;
    const bool hit = collides(k);
    peer->found += hit;
    peer->misses += s.exact[k] && !hit;
    peer->false_hits += hit && !s.exact[k];
  }
}

template <class Reset, class Collides>
void benchOrbit(benchmark::State& state, const OrbitScene& s, const OrbitPeer& peer, Reset&& reset,
                Collides&& collides) {
  for (auto _ : state) {
    // Each sequence runs the box test on all 13,746 frames, the narrow phase on the others.
    const int found = runOrbit(s, reset, collides);
    benchmark::DoNotOptimize(found);
  }
  setPerItemTime(state, s.box_frames, "t_frame");
  state.counters["found"] = peer.found;
  state.counters["misses"] = peer.misses;
  state.counters["false_hits"] = peer.false_hits;
  if (peer.vertices > 0) state.counters["vertices"] = peer.vertices;
}

/// Table 1 laid out like the paper's: one row per quantity, per angular speed this run's value
/// beside the paper's.
void printTable1(const std::vector<RotatingScene>& scenes, const SummaryReporter& r) {
  const std::size_t n_seq = scenes.front().sequences.size();
  const unsigned long long first_seed = kTable1FirstSeed;
  const unsigned long long last_seed = kTable1FirstSeed + n_seq - 1;
  std::printf("\n== Table 1 (Wang et al. 2004): ellipsoids (3,3,5), centres 8 apart, %d frames per sequence, "
              "%zu seeded sequences (%llu..%llu) per speed ==\n",
              kTable1Frames, n_seq, first_seed, last_seed);
  std::printf("%-52s", "");
  for (const RotatingScene& s : scenes) std::printf(" | %17s %.1f %7s", "omega", s.omega, "paper");
  std::printf("\n");
  // One row: a label and, per speed, this run's value and the paper's ("-" if none).
  const auto row = [&](const std::string& label, auto ours, auto paper) {
    std::printf("%-52s", label.c_str());
    for (std::size_t i = 0; i < scenes.size(); ++i) {
      std::printf(" | %21s %7s", ours(scenes[i]).c_str(), paper(i).c_str());
    }
    std::printf("\n");
  };
  const auto none = [](std::size_t) { return std::string("-"); };
  const auto text = [](const char* fmt, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, fmt, v);
    return std::string(buf);
  };
  const auto range = [](const CountStats& c) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.1f [%d..%d]", c.mean, c.min, c.max);
    return std::string(buf);
  };
  const std::string seed = "seed " + std::to_string(first_seed);
  const std::string mean = "mean [min..max] of " + std::to_string(n_seq) + " seeds";

  const auto first = [](int RotatingSequence::*field) {
    return [field](const RotatingScene& s) { return std::to_string(s.sequences.front().*field); };
  };
  const auto stats = [&range](int RotatingSequence::*field) {
    return [field, &range](const RotatingScene& s) {
      return range(countStats(s, [field](const RotatingSequence& q) { return q.*field; }));
    };
  };
  const auto per_frame = [&](const char* peer) {
    return [&r, peer, &text](const RotatingScene& s) { return text("%.3f", 1e-3 * r.nsPerItem(s.group() + peer)); };
  };
  const auto paper_int = [](const int* values) {
    return [values](std::size_t i) { return std::to_string(values[i]); };
  };
  const auto paper_us = [&text](const double* values) {
    return [values, &text](std::size_t i) { return text("%.3f", values[i]); };
  };

  row("collisions, " + seed, first(&RotatingSequence::collisions), paper_int(kPaperCollisions));
  row("collisions, " + mean, stats(&RotatingSequence::collisions), none);
  row("separations, " + seed, first(&RotatingSequence::separations),
      [](std::size_t i) { return std::to_string(kTable1Frames - kPaperCollisions[i]); });
  row("separations, " + mean, stats(&RotatingSequence::separations), none);
  row("separations reported by the plane, " + seed, first(&RotatingSequence::plane_hits),
      paper_int(kPaperPlaneHits));
  row("separations reported by the plane, mean [min..max]", stats(&RotatingSequence::plane_hits), none);
  row("EECD (PairCoherence), us/frame", per_frame("/pair_coherence"), paper_us(kPaperEecdUs));
  row("plain classifyEllipsoids, us/frame", per_frame("/fcl_quadric"), paper_us(kPaperPlainUs));
  row("EECD time / plain time",
      [&](const RotatingScene& s) {
        return text("%.2f", r.ratio(s.group() + "/pair_coherence", s.group() + "/fcl_quadric"));
      },
      [&](std::size_t i) { return text("%.2f", kPaperEecdUs[i] / kPaperPlainUs[i]); });
  row("FCL libccd on fcl::Ellipsoid, us/frame", per_frame("/fcl_libccd"), none);
  row("FCL libccd misses / false hits, mean",
      [&](const RotatingScene& s) {
        const CountStats mis = countStats(s, [](const RotatingSequence& q) { return q.fcl_misses; });
        const CountStats fal = countStats(s, [](const RotatingSequence& q) { return q.fcl_false_hits; });
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.1f / %.1f", mis.mean, fal.mean);
        return std::string(buf);
      },
      none);
  std::printf("  times: CPU us per frame over all %zu x %d frames of a speed; paper: one sequence per speed, "
              "Pentium 4 2.26 GHz\n",
              n_seq, kTable1Frames);
  for (const RotatingScene& s : scenes) {
    int mismatches = 0;
    for (const RotatingSequence& q : s.sequences) mismatches += q.coherence_mismatches;
    if (mismatches != 0) {
      std::printf("  WARNING: omega %.1f: PairCoherence disagreed with classifyEllipsoids on %d frames\n", s.omega,
                  mismatches);
    }
  }
  std::fflush(stdout);
}

void printTable2(const OrbitScene& s, const std::vector<OrbitPeer>& peers, const SummaryReporter& r) {
  std::printf("\n== Table 2 (Wang et al. 2004): unit sphere orbiting (4.5,4,2), radius %.2f, %d frames, "
              "%d with overlapping boxes (paper %d), %d collisions (paper %d) ==\n",
              kOrbitRadius, kTable2Frames, s.box_frames, kPaperTable2BoxFrames, s.collisions,
              kPaperTable2Collisions[0]);
  std::printf("  separations reported by the cached plane: %d of %d (paper %d of %d)\n", s.plane_hits,
              s.box_frames - s.collisions, kPaperTable2PlaneHits,
              kPaperTable2BoxFrames - kPaperTable2Collisions[0]);
  std::printf("%-36s %9s %8s %8s %10s %12s  %s\n", "peer", "found", "misses", "false", "separated",
              "us/frame", "paper (found, us/frame)");
  for (const OrbitPeer& p : peers) {
    const double us = 1e-3 * r.nsPerItem("Table2/" + p.name);
    std::string paper = "-";
    char buf[64];
    if (p.name == "pair_coherence") {
      std::snprintf(buf, sizeof buf, "EECD %d, %.2f", kPaperTable2Collisions[0], kPaperTable2Us[0]);
      paper = buf;
    } else if (p.name == "fcl_quadric") {
      std::snprintf(buf, sizeof buf, "no planes %d, %.2f", kPaperTable2Collisions[0], kPaperTable2PlainUs);
      paper = buf;
    } else if (p.name.rfind("fcl_libccd_convex_", 0) == 0) {
      for (int i = 0; i < 4; ++i) {
        if (p.vertices == kTessellations[i]) {
          std::snprintf(buf, sizeof buf, "GJK n=%d: %d, %.1f", kTessellations[i], kPaperTable2Collisions[i + 1],
                        kPaperTable2Us[i + 1]);
          paper = buf;
        }
      }
    }
    std::printf("%-36s %9d %8d %8d %10d %12.3f  %s\n", p.name.c_str(), p.found, p.misses, p.false_hits,
                s.box_frames - p.found, us, paper.c_str());
  }
  std::printf("  EECD time / plain time: %.2f (paper %.2f); us/frame: CPU time of the whole orbit (box tests "
              "included) / box-overlap frames\n",
              r.ratio("Table2/pair_coherence", "Table2/fcl_quadric"), kPaperTable2Us[0] / kPaperTable2PlainUs);
  std::fflush(stdout);
}

}  // namespace
}  // namespace bench
}  // namespace fcl_quadric

int main(int argc, char** argv) {
  using namespace fcl_quadric;
  using namespace fcl_quadric::bench;
  const std::size_t n_sequences = takeSizeOption(&argc, argv, "table1_seeds", "FCL_QUADRIC_BENCH_TABLE1_SEEDS",
                                                 kDefaultTable1Sequences);
  const benchmark::ConsoleReporter::OutputOptions console = consoleOutputOptions(argc, argv);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;

  // ---- Table 1
  static std::vector<RotatingScene> rotating;
  for (double omega : kTable1Omegas) rotating.push_back(makeRotatingScene(omega, n_sequences));
  for (const RotatingScene& s : rotating) {
    const std::string g = s.group();
    registerBenchmark((g + "/fcl_quadric").c_str(), benchTable1Plain, &s);
    registerBenchmark((g + "/pair_coherence").c_str(), benchTable1Coherence, &s);
    registerBenchmark((g + "/fcl_libccd").c_str(), benchTable1Fcl, &s);
  }

  // ---- Table 2
  static const OrbitScene orbit = makeOrbitScene();
  static std::vector<OrbitPeer> peers;
  static PairCoherence coherence;  // reset at the start of each orbit
  const auto no_reset = [] {};
  const auto reset_coherence = [] { coherence.reset(); };
  const auto plain = [](int k) {
    return classifyEllipsoids(orbit.a[k], orbit.b).status != Separation::Separated;
  };
  const auto eecd = [](int k) { return coherence.query(orbit.a[k], orbit.b) != Separation::Separated; };

  peers.push_back({"fcl_quadric", nullptr, nullptr, 0});
  countOrbit(orbit, &peers.back(), no_reset, plain);
  peers.push_back({"pair_coherence", nullptr, nullptr, 0});
  countOrbit(orbit, &peers.back(), reset_coherence, eecd);
  peers.push_back({"fcl_libccd_ellipsoid", std::make_shared<fcl::Ellipsoidd>(1.0, 1.0, 1.0),
                   std::make_shared<fcl::Ellipsoidd>(4.5, 4.0, 2.0), 0});
  for (int n : kTessellations) {
    const TriangleMesh mesh_a = sqrt3Ellipsoid(Eigen::Vector3d::Ones(), n);
    const TriangleMesh mesh_b = sqrt3Ellipsoid(orbit.b.radii(), n);
    const int v = static_cast<int>(mesh_a.vertices.size());
    peers.push_back({"fcl_libccd_convex_" + std::to_string(v), fclConvex(mesh_a), fclConvex(mesh_b), v});
    peers.push_back({"fcl_obbrss_mesh_" + std::to_string(v), fclBvh(mesh_a), fclBvh(mesh_b), v});
  }
  for (std::size_t i = 2; i < peers.size(); ++i) {
    OrbitPeer* p = &peers[i];
    countOrbit(orbit, p, no_reset, [p](int k) {
      return fclCollide(p->a.get(), orbit.X_WA[k], p->b.get(), orbit.X_WB, fcl::GST_LIBCCD);
    });
  }
  for (std::size_t i = 0; i < peers.size(); ++i) {
    const OrbitPeer* p = &peers[i];
    const std::string name = "Table2/" + p->name;
    if (i == 0) {
      registerBenchmark(name.c_str(), [=](benchmark::State& st) {
        benchOrbit(st, orbit, *p, no_reset, plain);
      });
    } else if (i == 1) {
      registerBenchmark(name.c_str(), [=](benchmark::State& st) {
        benchOrbit(st, orbit, *p, reset_coherence, eecd);
      });
    } else {
      registerBenchmark(name.c_str(), [=](benchmark::State& st) {
        benchOrbit(st, orbit, *p, no_reset, [p](int k) {
          return fclCollide(p->a.get(), orbit.X_WA[k], p->b.get(), orbit.X_WB, fcl::GST_LIBCCD);
        });
      });
    }
  }

  std::printf("fcl_quadric separating-plane benchmarks (Wang et al. 2004 §5)\n");
  std::fflush(stdout);
  SummaryReporter reporter(console);
  benchmark::RunSpecifiedBenchmarks(&reporter);
  reporter.printSummary("Summary: CPU time per frame", "frame");
  printTable1(rotating, reporter);
  printTable2(orbit, peers, reporter);
  benchmark::Shutdown();
  return 0;
}
