// Experiments (1) random pairs, (2) near-tangent pairs and (3) the separating-planes paper's
// set-ups of `fcl_quadric bench` (bench_experiments.h). The only translation unit of the static
// experiments that instantiates FCL's entry points (through benchmarks/fcl_peers.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "benchmarks/bench_support.h"
#include "benchmarks/bullet_peers.h"
#include "benchmarks/fcl_peers.h"
#include "benchmarks/separating_planes_scenes.h"
#include "benchmarks/sqrt3_tessellation.h"
#include "fcl_quadric/bench_experiments.h"
#include "fcl_quadric/geometry/ellipsoid_separation.h"
#include "fcl_quadric/geometry/pair_coherence.h"
#include "fcl_quadric/geometry/signed_distance.h"

namespace fcl_quadric {
namespace cli {

namespace {

using bench::bulletCollide;
using bench::bulletPose;
using bench::bulletShape;
using bench::bulletSignedDistance;
using bench::fclCollide;
using bench::fclPose;
using bench::fclShape;
using bench::fclSignedDistance;

std::string format(const char* fmt, double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, x);
  return buf;
}

/// Ellipsoid pairs with their FCL and Bullet twins, built once outside the timed loops.
struct PeerPairs {
  std::vector<Ellipsoid> a, b;
  std::vector<fcl::Ellipsoidd> fcl_a, fcl_b;
  std::vector<fcl::Transform3d> X_WA, X_WB;
  std::vector<std::unique_ptr<btMultiSphereShape>> bt_a, bt_b;
  std::vector<btTransform> bt_X_WA, bt_X_WB;

  void add(const Ellipsoid& ea, const Ellipsoid& eb) {
    a.push_back(ea);
    b.push_back(eb);
    fcl_a.push_back(fclShape(ea));
    fcl_b.push_back(fclShape(eb));
    X_WA.push_back(fclPose(ea));
    X_WB.push_back(fclPose(eb));
    bt_a.push_back(bulletShape(ea));
    bt_b.push_back(bulletShape(eb));
    bt_X_WA.push_back(bulletPose(ea));
    bt_X_WB.push_back(bulletPose(eb));
  }
  std::size_t size() const { return a.size(); }
};

/// Times a boolean peer over all pairs and counts its answers that differ from `truth`.
template <class Peer>
BenchRow collideRow(const std::string& case_name, const std::string& peer_name, const PeerPairs& p,
                    const std::vector<char>& truth, Peer&& peer) {
  std::vector<char> hit(p.size());
  BenchRow row;
  row.case_name = case_name;
  row.peer = peer_name;
  row.n = p.size();
  row.ns_per_query = nsPerQuery(p.size(), [&] {
    for (std::size_t i = 0; i < p.size(); ++i) hit[i] = peer(i);
  });
  row.wrong = 0;
  for (std::size_t i = 0; i < p.size(); ++i) row.wrong += (hit[i] != 0) != (truth[i] != 0);
  return row;
}

bool oursCollide(const PeerPairs& p, std::size_t i) {  // the boolean query, as fcl::collide's
  return ellipsoidsCollide(p.a[i], p.b[i]);
}
bool libccdCollide(const PeerPairs& p, std::size_t i) {
  return fclCollide(&p.fcl_a[i], p.X_WA[i], &p.fcl_b[i], p.X_WB[i], fcl::GST_LIBCCD);
}
bool indepCollide(const PeerPairs& p, std::size_t i) {
  return fclCollide(&p.fcl_a[i], p.X_WA[i], &p.fcl_b[i], p.X_WB[i], fcl::GST_INDEP);
}
bool btCollide(const PeerPairs& p, std::size_t i) {
  return bulletCollide(p.bt_a[i].get(), p.bt_X_WA[i], p.bt_b[i].get(), p.bt_X_WB[i]);
}

/// The four boolean peers of a pair set.
void collideRows(const std::string& case_name, const PeerPairs& p, const std::vector<char>& truth,
                 std::vector<BenchRow>* rows, const std::function<void()>& step) {
  rows->push_back(collideRow(case_name, "fcl_quadric", p, truth, [&](std::size_t i) { return oursCollide(p, i); }));
  step();
  rows->push_back(collideRow(case_name, "fcl_libccd", p, truth, [&](std::size_t i) { return libccdCollide(p, i); }));
  step();
  rows->push_back(collideRow(case_name, "fcl_indep", p, truth, [&](std::size_t i) { return indepCollide(p, i); }));
  step();
  rows->push_back(collideRow(case_name, "bullet", p, truth, [&](std::size_t i) { return btCollide(p, i); }));
  step();
}

/// The peers of the separating-planes set-ups on frames that form sequences of `sequence`
/// frames: classification every frame, PairCoherence (one per sequence: the cached plane is the
/// point of the paper), FCL libccd and Bullet.
void sequenceRows(const std::string& case_name, const PeerPairs& p, const std::vector<char>& truth, std::size_t sequence,
                  std::vector<BenchRow>* rows, const std::function<void()>& step) {
  rows->push_back(collideRow(case_name, "fcl_quadric", p, truth, [&](std::size_t i) { return oursCollide(p, i); }));
  step();
  PairCoherence coherence;
  rows->push_back(collideRow(case_name, "pair_coherence", p, truth, [&](std::size_t i) {
    if (sequence > 0 && i % sequence == 0) coherence = PairCoherence();
    return coherence.query(p.a[i], p.b[i]) != Separation::Separated;
  }));
  step();
  rows->push_back(collideRow(case_name, "fcl_libccd", p, truth, [&](std::size_t i) { return libccdCollide(p, i); }));
  step();
  rows->push_back(collideRow(case_name, "bullet", p, truth, [&](std::size_t i) { return btCollide(p, i); }));
  step();
}

}  // namespace

// ------------------------------------------------------------------------------------------------
// (1) Random pairs

BenchExperiment runRandomPairsExperiment(BenchSize size, const BenchProgress& progress) {
  const std::size_t n = size == BenchSize::kTiny ? 2000 : size == BenchSize::kSmall ? 50000 : 100000;
  BenchExperiment e;
  e.name = "random";
  e.title = "Random ellipsoid pairs (ANCHORS generator, seed 42): static collide and signed distance";
  e.unit = "pair";
  const bench::PairSet set = bench::anchorPairs(n);
  PeerPairs p;
  for (std::size_t i = 0; i < n; ++i) p.add(set.a[i], set.b[i]);
  std::vector<char> truth(n);
  std::size_t overlapping = 0;
  for (std::size_t i = 0; i < n; ++i) overlapping += truth[i] = oursCollide(p, i);
  int done = 0;
  const int steps = 7;
  auto step = [&] { progress(static_cast<double>(++done) / steps); };
  collideRows("collide", p, truth, &e.rows, step);

  // Signed distance: wrong = the sign disagrees with the exact classification.
  std::vector<double> ours(n), libccd(n), bt(n);
  auto distanceRow = [&](const char* peer, std::vector<double>* out, auto&& f) {
    BenchRow row;
    row.case_name = "distance";
    row.peer = peer;
    row.n = n;
    row.ns_per_query = nsPerQuery(n, [&] {
      for (std::size_t i = 0; i < n; ++i) (*out)[i] = f(i);
    });
    row.wrong = 0;
    for (std::size_t i = 0; i < n; ++i) row.wrong += truth[i] ? ((*out)[i] > 0.0) : !((*out)[i] > 0.0);
    e.rows.push_back(row);
    step();
  };
  distanceRow("fcl_quadric", &ours, [&](std::size_t i) { return signedDistance(p.a[i], p.b[i]).distance; });
  distanceRow("fcl_libccd", &libccd, [&](std::size_t i) {
    return fclSignedDistance(&p.fcl_a[i], p.X_WA[i], &p.fcl_b[i], p.X_WB[i], fcl::GST_LIBCCD);
  });
  distanceRow("bullet", &bt, [&](std::size_t i) {
    return bulletSignedDistance(p.bt_a[i].get(), p.bt_X_WA[i], p.bt_b[i].get(), p.bt_X_WB[i]);
  });
  auto errors = [&](const std::vector<double>& d) {
    std::vector<double> err(n);
    for (std::size_t i = 0; i < n; ++i) err[i] = std::abs(d[i] - ours[i]) / std::max(std::abs(ours[i]), 1e-12);
    return bench::quantiles(err);
  };
  const bench::Quantiles el = errors(libccd), eb = errors(bt);
  char line[256];
  std::snprintf(line, sizeof line, "%zu pairs, %zu touching or overlapping. distance: wrong = sign disagrees with the classification", n,
                overlapping);
  e.notes.push_back(line);
  std::snprintf(line, sizeof line,
                "relative distance error vs fcl_quadric: fcl_libccd median %.1e max %.1e; bullet median %.1e max %.1e",
                el.median, el.max, eb.median, eb.max);
  e.notes.push_back(line);
  e.notes.push_back("fcl_indep has no distance row: FCL 0.7's indep signed distance asserts on overlaps (fcl_peers.h)");
  return e;
}

// ------------------------------------------------------------------------------------------------
// (2) Near-tangent pairs

BenchExperiment runNearTangentExperiment(BenchSize size, const BenchProgress& progress) {
  const std::size_t n = size == BenchSize::kTiny ? 100 : size == BenchSize::kSmall ? 5000 : 10000;
  const double gaps[] = {1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8};
  BenchExperiment e;
  e.name = "near_tangent";
  e.title = "Near-tangent pairs: B moved off the exact touching offset by a relative gap (+ separate, - overlap)";
  e.unit = "pair";
  e.chart_wrong = true;
  e.truth = "the construction (+ gaps separate, - gaps overlap)";
  // Base pairs: the ANCHORS generator (seed 43); B slides along the line of centres, and the
  // touching offset lam* is bracketed by bisection on the certified classifier to 4 ulp.
  const bench::PairSet base = bench::anchorPairs(n, 43);
  std::vector<Eigen::Vector3d> dir(n);
  std::vector<double> lam(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Ellipsoid& a = base.a[i];
    const Ellipsoid& b = base.b[i];
    Eigen::Vector3d u = b.center() - a.center();
    u = u.norm() > 0.0 ? Eigen::Vector3d(u.normalized()) : Eigen::Vector3d::UnitX();
    dir[i] = u;
    auto at = [&](double l) { return Ellipsoid(b.radii(), b.rotation(), a.center() + l * u); };
    double lo = 0.0, hi = a.radii().maxCoeff() + b.radii().maxCoeff() + 1.0;
    for (int it = 0; it < 200 && hi - lo > 4e-16 * hi; ++it) {
      const double mid = 0.5 * (lo + hi);
      (classifyEllipsoids(a, at(mid)).status == Separation::Separated ? hi : lo) = mid;
    }
    lam[i] = 0.5 * (lo + hi);
  }
  const int steps = 2 * static_cast<int>(std::size(gaps)) * 4;
  int done = 0;
  auto step = [&] { progress(static_cast<double>(++done) / steps); };
  std::size_t touching_outward = 0;
  for (double g : gaps) {
    for (int sign : {+1, -1}) {
      PeerPairs p;
      for (std::size_t i = 0; i < n; ++i) {
        const Ellipsoid& b = base.b[i];
        p.add(base.a[i], Ellipsoid(b.radii(), b.rotation(), base.a[i].center() + lam[i] * (1.0 + sign * g) * dir[i]));
      }
      const std::vector<char> truth(n, sign < 0);  // known by construction
      const std::string case_name = (sign > 0 ? "+" : "-") + format("%.0e", g);
      collideRows(case_name, p, truth, &e.rows, step);
      if (sign > 0) {
        for (std::size_t i = 0; i < n; ++i) touching_outward += classifyEllipsoids(p.a[i], p.b[i]).status == Separation::Touching;
      }
    }
  }
  char line[256];
  std::snprintf(line, sizeof line,
                "%zu pairs per gap and side; truth by construction (touching offset bracketed to 4 ulp by bisection on the "
                "certified classifier)",
                n);
  e.notes.push_back(line);
  std::snprintf(line, sizeof line,
                "fcl_quadric's Touching counts as contact: it answered Touching on %zu of the %zu separated (+) pairs",
                touching_outward, n * std::size(gaps));
  e.notes.push_back(line);
  return e;
}

// ------------------------------------------------------------------------------------------------
// (3) Separating-planes paper, Tables 1 and 2

BenchExperiment runSeparatingPlanesExperiment(BenchSize size, const BenchProgress& progress) {
  const int table1_frames = size == BenchSize::kTiny ? 1000 : bench::kTable1Frames;
  const std::size_t table1_sequences = size == BenchSize::kFull ? 16 : size == BenchSize::kSmall ? 4 : 1;
  std::vector<int> tessellations = {488};
  if (size != BenchSize::kTiny) tessellations.push_back(1460);
  if (size == BenchSize::kFull) tessellations.insert(tessellations.end(), {4376, 13124});
  BenchExperiment e;
  e.name = "separating_planes";
  e.title = "Separating-planes paper (Wang et al. 2004): Table 1 rotating ellipsoids, Table 2 sphere orbit";
  e.unit = "frame";
  const int steps = 3 * 5 + 5 + 2 * static_cast<int>(tessellations.size());
  int done = 0;
  auto step = [&] { progress(static_cast<double>(++done) / steps); };

  for (double omega : bench::kTable1Omegas) {
    PeerPairs p;
    for (std::size_t s = 0; s < table1_sequences; ++s) {
      const bench::RotatingFrames f = bench::rotatingFrames(omega, bench::kTable1FirstSeed + s, table1_frames);
      for (std::size_t k = 0; k < f.a.size(); ++k) p.add(f.a[k], f.b[k]);
    }
    std::vector<char> truth(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) truth[i] = oursCollide(p, i);
    step();
    sequenceRows("T1 omega " + format("%.1f", omega), p, truth, static_cast<std::size_t>(table1_frames), &e.rows, step);
  }
  char line[512];
  std::snprintf(line, sizeof line, "Table 1: %zu sequence(s) of %d frames per angular speed (paper: 10,000 frames)",
                table1_sequences, table1_frames);
  e.notes.push_back(line);

  // Table 2: the narrow phase on the frames whose boxes overlap (time per such frame).
  PeerPairs p;
  const Ellipsoid b = bench::orbitEllipsoid();
  for (int k = 0; k < bench::kTable2Frames; ++k) {
    const Eigen::Vector3d c = bench::orbitCentre(k);
    if (bench::orbitBoxesOverlap(c)) p.add(Ellipsoid::sphere(1.0, c), b);
  }
  std::vector<char> truth(p.size());
  std::size_t collisions = 0;
  for (std::size_t i = 0; i < p.size(); ++i) collisions += truth[i] = oursCollide(p, i);
  const std::string t2 = "T2 orbit";
  sequenceRows(t2, p, truth, p.size(), &e.rows, step);
  for (int v : tessellations) {
    const std::shared_ptr<fcl::Convexd> ca = bench::fclConvex(bench::sqrt3Ellipsoid(Eigen::Vector3d::Ones(), v));
    const std::shared_ptr<fcl::Convexd> cb = bench::fclConvex(bench::sqrt3Ellipsoid(b.radii(), v));
    e.rows.push_back(collideRow(t2, "fcl_convex_" + std::to_string(v), p, truth, [&](std::size_t i) {
      return fclCollide(ca.get(), p.X_WA[i], cb.get(), p.X_WB[i], fcl::GST_LIBCCD);
    }));
    step();
  }
  for (int v : tessellations) {
    const auto ma = bench::fclBvh(bench::sqrt3Ellipsoid(Eigen::Vector3d::Ones(), v));
    const auto mb = bench::fclBvh(bench::sqrt3Ellipsoid(b.radii(), v));
    e.rows.push_back(collideRow(t2, "fcl_bvh_" + std::to_string(v), p, truth, [&](std::size_t i) {
      return fclCollide(ma.get(), p.X_WA[i], mb.get(), p.X_WB[i], fcl::GST_LIBCCD);
    }));
    step();
  }
  std::snprintf(line, sizeof line,
                "Table 2: %zu of %d orbit frames with overlapping boxes, %zu collisions (paper: 10,000 and 1,157); "
                "fcl_convex_N / fcl_bvh_N: libccd on sqrt(3)-tessellations with N vertices as fcl::Convex / "
                "fcl::BVHModel<OBBRSS> (triangle against triangle: surfaces only)",
                p.size(), bench::kTable2Frames, collisions);
  e.notes.push_back(line);
  step();
  return e;
}

}  // namespace cli
}  // namespace fcl_quadric
