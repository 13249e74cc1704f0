// Issue 4's benchmarks of continuous collision (docs/benchmarks.md, "Continuous collision"):
// continuousCollideEllipsoids on the thesis' two experiments (Choi 2008, §5.4), rebuilt
// synthetically, and against FCL 0.7's fcl::continuousCollide on the same moving pairs.
//
//  (1) Boxing (thesis §5.4.1, Table 5): two characters of 20 ellipsoids each (head, jaw, neck,
//      chest, abdomen, pelvis, shoulders, upper arms, forearms, gloves, thighs, shins, feet; radii
//      0.04-0.2 m), animated procedurally over --frames frames (default 1,000) with fast periodic
//      jabs, torso twist and lean, sway, bobbing and a slow approach/retreat (seed kBoxingSeed
//      draws each character's periods and phases). Between consecutive frames every ellipsoid
//      moves by MotionMatrix::fromPoses (the thesis' rigid motion of rational degree 2), and the
//      400 cross pairs are tested for the first contact (all_intervals = false) in a fixed order:
//        setup1  culling on (bounding spheres, separating plane), rigid, t_max = the running
//                minimum t-bar of the frame (floored at kTbarFloor, see below)
//        setup2  culling off, rigid, t_max = 1
//        setup3  culling off, affine interpolation (CcdInterpolation::Affine), t_max = 1
//      The thesis' setup 2 kept the sphere test; the core's `culling` switch controls both culls,
//      so setup2 here has none. A frame's t-bar reaches 0 when a pair already touches at the
//      frame's start; CcdOptions::t_max must be positive, so the rest of that frame runs with
//      t_max = kTbarFloor (in effect a static test at t = 0), counted in the output.
//      One benchmark iteration is the whole sequence: motions built (40 fromPoses + MovingEllipsoid
//      per frame) and the 400 pairs solved; t_frame = CPU time / frames. Boxing/motions times the
//      motion construction alone. The per-pair breakdown (all / collision-free / colliding / worst /
//      close pairs) comes from a separate pass that times every pair with steady_clock (wall
//      time, so each pair is solved twice in a row and the faster call kept: on a shared machine a
//      preempted call measures the scheduler); the worst pair is re-timed (minimum of
//      kWorstRetimes calls) for the same reason.
//  (2) FCL (fcl::continuousCollide, CCDC_NAIVE, ContinuousCollisionRequest defaults: 10 samples)
//      on (a) the close pairs of setup 1 (those not culled) with the rotations frozen at the
//      frame's start (pure translation: fromPoses with equal rotations is exactly FCL's
//      TranslationMotion, CCDM_TRANS), (b) --random_pairs random translating pairs, and (c) the
//      same close pairs with their full rigid motions against FCL's CCDM_LINEAR (InterpMotion: a
//      different interpolation of the rotation, so only times and counts, no misses). Ours runs
//      with CcdOptions defaults except all_intervals = false (culling on, t_max = 1). Both peers
//      build their motions inside the timed call. Misses = pairs where the exact solver finds a
//      contact in [0, 1] and NAIVE none; lag = NAIVE's time of contact minus the exact first
//      contact time. CCDC_CONSERVATIVE_ADVANCEMENT is called once, untimed, to report what FCL
//      does for ellipsoids (its look-up table has no ellipsoid entry). A sampled static oracle
//      (classifyEllipsoids at kOracleSamples + 1 instants) checks ours on sets (a) and (b).
//  (3) Robot arm (thesis §5.4.2, Table 6): a 3-joint arm of 10 ellipsoids (base 0; links 1-3 on
//      joint 1, 4-5 on joint 2, 6-9 on joint 3) whose joint angles follow tan(theta/2) linear in t,
//      so each joint is a rotation of rational degree 2 and link k's motion, the product of the
//      PolynomialMatrix4's of its joints and the constant offsets, has degree 0, 2, 4 or 6
//      (MotionMatrix::fromPolynomialMatrix); 3 constant obstacle ellipsoids U, V, W (an I-beam).
//      All collision intervals (all_intervals = true, culling off) of the 30 pairs; t_pair per
//      pair, and "obtain F" = movingQuadric() of both + ccdFunction() (the construction of
//      F(u, t) through the public API; the solver additionally balances and scales), each timed
//      by Google Benchmark. The intervals are checked against the sampled static oracle.
//
// Options (removed from argv before Google Benchmark sees it):
//   --smoke            tiny sizes, for the test suite (or FCL_QUADRIC_BENCH_SMOKE=1)
//   --frames N         boxing frames (FCL_QUADRIC_BENCH_CCD_FRAMES, default 1000; smoke 12)
//   --random_pairs N   random translating pairs of (2b) (FCL_QUADRIC_BENCH_CCD_RANDOM, default 2000)
// At the end the program prints the blocks "== CCD summary", "== CCD boxing", "== CCD vs FCL",
// "== CCD robot arm" and "== CCD aim" that benchmarks/update_docs.sh copies into
// docs/benchmarks.md.

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <benchmark/benchmark.h>
#include <Eigen/Geometry>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/math/motion/interp_motion.h>
#include <fcl/math/motion/translation_motion.h>
#include <fcl/narrowphase/continuous_collision.h>

#include "bench_support.h"
#include "boxing_scene.h"
#include "robot_arm_scene.h"
#include "fcl_quadric/continuous/ccd_function.h"
#include "fcl_quadric/continuous/ellipsoid_ccd.h"
#include "fcl_quadric/continuous/motion_matrix.h"
#include "fcl_quadric/geometry/ellipsoid_separation.h"

namespace fcl_quadric {
namespace bench {
namespace {

constexpr std::uint64_t kRandomPairSeed = 54;
constexpr double kTbarFloor = 1e-6;  ///< t_max once a frame's t-bar is 0 (t_max must be > 0)
constexpr int kWorstRetimes = 20;
constexpr int kOracleSamples = 400;

struct Settings {
  bool smoke = false;
  std::size_t frames = 1000;
  std::size_t random_pairs = 2000;
};

double nowUs() {
  return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double mean(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

// ------------------------------------------------------------------------------------------------
// (1) Boxing (the scene: boxing_scene.h)

using Motions = std::array<std::vector<MovingEllipsoid>, 2>;

/// The 40 moving ellipsoids of frame k -> k + 1.
void buildMotions(const BoxingScene& s, int k, Motions* m) {
  for (int c = 0; c < 2; ++c) {
    (*m)[c].clear();
    for (int p = 0; p < kParts; ++p)
      (*m)[c].push_back(MovingEllipsoid{
          s.bodies[p], PiecewiseMotion(MotionMatrix::fromPoses(s.poses[c][k][p], s.poses[c][k + 1][p]))});
  }
}

enum class Setup { kCulled, kNoCull, kAffine };
const char* setupName(Setup s) {
  switch (s) {
    case Setup::kCulled: return "setup1_rigid_culled_tbar";
    case Setup::kNoCull: return "setup2_rigid_no_cull";
    case Setup::kAffine: return "setup3_affine_no_cull";
  }
  return "?";
}

CcdOptions setupOptions(Setup s) {
  CcdOptions o;
  o.all_intervals = false;
  o.culling = s == Setup::kCulled;
  o.interpolation = s == Setup::kAffine ? CcdInterpolation::Affine : CcdInterpolation::Rigid;
  return o;
}

struct PairRecord {
  int frame = 0, a = 0, b = 0;
  double us = 0.0;
  double t_max = 1.0;
  bool collide = false, at_start = false, near_tangent = false, unresolved = false;
  int culled_by = 0, degree_t = 0, work = 0;
  double toc = 1.0;
};

/// One frame's 400 pairs; returns the frame's first contact time (1 if none). With `records`,
/// every call is timed and recorded.
double solveFrame(const Motions& m, Setup setup, int frame, std::vector<PairRecord>* records) {
  CcdOptions opt = setupOptions(setup);
  double tbar = 1.0;
  for (int i = 0; i < kParts; ++i) {
    for (int j = 0; j < kParts; ++j) {
      if (setup == Setup::kCulled) opt.t_max = std::max(tbar, kTbarFloor);
      double us = 0.0;
      if (records) {  // min of two calls: wall-clock time, and a preempted call is not the solver's
        const double t0 = nowUs();
        benchmark::DoNotOptimize(continuousCollideEllipsoids(m[0][i], m[1][j], opt).collide);
        us = nowUs() - t0;
      }
      const double t0 = records ? nowUs() : 0.0;
      const EllipsoidCcdResult r = continuousCollideEllipsoids(m[0][i], m[1][j], opt);
      if (records) us = std::min(us, nowUs() - t0);
      if (r.collide) tbar = std::min(tbar, *r.first_contact_time);
      if (records) {
        PairRecord p;
        p.frame = frame;
        p.a = i;
        p.b = j;
        p.us = us;
        p.t_max = opt.t_max;
        p.collide = r.collide;
        p.toc = r.collide ? *r.first_contact_time : 1.0;
        p.at_start = r.collide && *r.first_contact_time == 0.0;
        p.near_tangent = r.near_tangent;
        p.unresolved = r.unresolved;
        p.culled_by = r.culled_by;
        p.degree_t = r.degree_t;
        p.work = r.work;
        records->push_back(p);
      }
    }
  }
  return tbar;
}

struct SetupReport {
  Setup setup = Setup::kCulled;
  std::vector<PairRecord> pairs;
  std::vector<double> frame_toc;  ///< per frame: first contact time (1 = none)
  std::size_t culled[3] = {0, 0, 0};
  std::size_t colliding = 0, at_start = 0, near_tangent = 0, unresolved = 0, floor_pairs = 0;
  std::size_t frames_with_contact = 0;
  int max_degree = 0;
  double worst_us = 0.0, worst_retimed_us = 0.0;
  std::size_t worst = 0;  ///< index of the slowest pair in `pairs`
  double f_build_us = 0.0;  ///< mean time to build F via the public API on the close pairs
  std::size_t f_build_n = 0;
};

/// Times building F(u, t) the way the solver does through the public API (movingQuadric of both
/// and ccdFunction), for a rigid pair.
double timeFConstruction(const MovingEllipsoid& a, const MovingEllipsoid& b, int reps) {
  const MotionMatrix& ma = a.motion.pieces().front();
  const MotionMatrix& mb = b.motion.pieces().front();
  double best = 1e30;
  for (int r = 0; r < reps; ++r) {
    const double t0 = nowUs();
    const PolynomialMatrix4 A = movingQuadric(a.body.quadricMatrix(), ma);
    const PolynomialMatrix4 B = movingQuadric(b.body.quadricMatrix(), mb);
    const BivariateBernstein F = ccdFunction(A, B);
    benchmark::DoNotOptimize(F.coefficients().data());
    best = std::min(best, nowUs() - t0);
  }
  return best;
}

SetupReport recordSetup(const BoxingScene& s, Setup setup) {
  SetupReport rep;
  rep.setup = setup;
  Motions m;
  rep.pairs.reserve(static_cast<std::size_t>(s.frames) * kParts * kParts);
  for (int k = 0; k < s.frames; ++k) {
    buildMotions(s, k, &m);
    const std::size_t first = rep.pairs.size();
    rep.frame_toc.push_back(solveFrame(m, setup, k, &rep.pairs));
    bool contact = false;
    for (std::size_t i = first; i < rep.pairs.size(); ++i) contact = contact || rep.pairs[i].collide;
    rep.frames_with_contact += contact;
  }
  for (std::size_t i = 0; i < rep.pairs.size(); ++i) {
    const PairRecord& p = rep.pairs[i];
    rep.culled[p.culled_by] += 1;
    rep.colliding += p.collide;
    rep.at_start += p.at_start;
    rep.near_tangent += p.near_tangent;
    rep.unresolved += p.unresolved;
    rep.floor_pairs += p.t_max == kTbarFloor;
    rep.max_degree = std::max(rep.max_degree, p.degree_t);
    if (p.us > rep.worst_us) {
      rep.worst_us = p.us;
      rep.worst = i;
    }
  }
  if (!rep.pairs.empty()) {  // re-time the worst pair: minimum of kWorstRetimes calls
    const PairRecord& w = rep.pairs[rep.worst];
    buildMotions(s, w.frame, &m);
    CcdOptions opt = setupOptions(setup);
    opt.t_max = w.t_max;
    double best = 1e30;
    for (int r = 0; r < kWorstRetimes; ++r) {
      const double t0 = nowUs();
      const EllipsoidCcdResult res = continuousCollideEllipsoids(m[0][w.a], m[1][w.b], opt);
      benchmark::DoNotOptimize(res.collide);
      best = std::min(best, nowUs() - t0);
    }
    rep.worst_retimed_us = best;
  }
  if (setup != Setup::kAffine) {  // F construction on the close (not culled) pairs, sampled
    std::size_t n = 0;
    double sum = 0.0;
    int last_frame = -1;
    const std::size_t stride = std::max<std::size_t>(1, rep.pairs.size() / 4000);
    for (std::size_t i = 0; i < rep.pairs.size(); i += (setup == Setup::kCulled ? 1 : stride)) {
      const PairRecord& p = rep.pairs[i];
      if (p.culled_by != 0) continue;
      if (p.frame != last_frame) buildMotions(s, p.frame, &m);
      last_frame = p.frame;
      sum += timeFConstruction(m[0][p.a], m[1][p.b], 3);
      ++n;
    }
    rep.f_build_us = n ? sum / static_cast<double>(n) : 0.0;
    rep.f_build_n = n;
  }
  return rep;
}

void benchBoxing(benchmark::State& state, const BoxingScene* s, Setup setup) {
  Motions m;
  double sum = 0.0;
  for (auto _ : state) {
    for (int k = 0; k < s->frames; ++k) {
      buildMotions(*s, k, &m);
      sum += solveFrame(m, setup, k, nullptr);
    }
  }
  benchmark::DoNotOptimize(sum);
  setPerItemTime(state, s->frames, "t_frame");
}

void benchMotions(benchmark::State& state, const BoxingScene* s) {
  Motions m;
  for (auto _ : state) {
    for (int k = 0; k < s->frames; ++k) {
      buildMotions(*s, k, &m);
      benchmark::DoNotOptimize(m[0].data());
    }
  }
  setPerItemTime(state, s->frames, "t_frame");
}

// ------------------------------------------------------------------------------------------------
// (2) Against fcl::continuousCollide

/// A moving pair given by its poses at t = 0 and t = 1.
struct PosePair {
  Eigen::Vector3d ra, rb;
  Eigen::Isometry3d a0, a1, b0, b1;
};

struct PairSetReport {
  std::string name;
  std::vector<PosePair> pairs;
  bool translation = true;
  std::size_t exact_hits = 0, naive_hits = 0, misses = 0, false_hits = 0;
  std::size_t oracle_hits = 0, oracle_missed_by_exact = 0;  ///< sampled static oracle
  std::vector<double> lag;                                   ///< NAIVE toc - exact toc, both hit
};

MovingEllipsoid movingOf(const Eigen::Vector3d& r, const Eigen::Isometry3d& X0, const Eigen::Isometry3d& X1) {
  return MovingEllipsoid{Ellipsoid(r, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()),
                         PiecewiseMotion(MotionMatrix::fromPoses(X0, X1))};
}

EllipsoidCcdResult oursOn(const PosePair& p) {
  CcdOptions opt;
  opt.all_intervals = false;
  return continuousCollideEllipsoids(movingOf(p.ra, p.a0, p.a1), movingOf(p.rb, p.b0, p.b1), opt);
}

fcl::Transform3d fclOf(const Eigen::Isometry3d& X) {
  fcl::Transform3d T = fcl::Transform3d::Identity();
  T.linear() = X.linear();
  T.translation() = X.translation();
  return T;
}

/// NAIVE with the request's defaults; CCDM_TRANS through the transform overload, CCDM_LINEAR
/// through InterpMotion objects built with an explicit reference point (the transform overload's
/// InterpMotion(tf1, tf2) leaves it uninitialised in FCL 0.7).
fcl::ContinuousCollisionResultd naiveOn(const PosePair& p, bool linear,
                                        fcl::CCDSolverType solver = fcl::CCDC_NAIVE, double* ret = nullptr) {
  const fcl::Ellipsoidd ga(p.ra), gb(p.rb);
  fcl::ContinuousCollisionRequestd request;
  request.ccd_solver_type = solver;
  fcl::ContinuousCollisionResultd result;
  double r = 0.0;
  if (!linear) {
    request.ccd_motion_type = fcl::CCDM_TRANS;
    r = fcl::continuousCollide(&ga, fclOf(p.a0), fclOf(p.a1), &gb, fclOf(p.b0), fclOf(p.b1), request, result);
  } else {
    request.ccd_motion_type = fcl::CCDM_LINEAR;
    const Eigen::Vector3d O = Eigen::Vector3d::Zero();
    const fcl::InterpMotion<double> ma(p.a0.linear(), p.a0.translation(), p.a1.linear(), p.a1.translation(), O);
    const fcl::InterpMotion<double> mb(p.b0.linear(), p.b0.translation(), p.b1.linear(), p.b1.translation(), O);
    r = fcl::continuousCollide(&ga, &ma, &gb, &mb, request, result);
  }
  if (ret) *ret = r;
  return result;
}

/// Sampled static oracle on [0, 1] with our interpolation: first sampled contact or nothing.
bool oracleHit(const PosePair& p) {
  const MovingEllipsoid a = movingOf(p.ra, p.a0, p.a1), b = movingOf(p.rb, p.b0, p.b1);
  for (int k = 0; k <= kOracleSamples; ++k) {
    const double t = static_cast<double>(k) / kOracleSamples;
    if (ellipsoidsCollide(ellipsoidAt(a, t), ellipsoidAt(b, t))) return true;
  }
  return false;
}

void countPairSet(PairSetReport* s) {
  for (const PosePair& p : s->pairs) {
    const EllipsoidCcdResult ours = oursOn(p);
    const fcl::ContinuousCollisionResultd naive = naiveOn(p, !s->translation);
    s->exact_hits += ours.collide;
    s->naive_hits += naive.is_collide;
    if (s->translation) {
      s->misses += ours.collide && !naive.is_collide;
      s->false_hits += naive.is_collide && !ours.collide;
      if (ours.collide && naive.is_collide) s->lag.push_back(naive.time_of_contact - *ours.first_contact_time);
      const bool oracle = oracleHit(p);
      s->oracle_hits += oracle;
      s->oracle_missed_by_exact += oracle && !ours.collide;
    }
  }
}

void benchPairSet(benchmark::State& state, const PairSetReport* s, bool ours) {
  std::size_t hits = 0;
  for (auto _ : state) {
    for (const PosePair& p : s->pairs) hits += ours ? oursOn(p).collide : naiveOn(p, !s->translation).is_collide;
  }
  benchmark::DoNotOptimize(hits);
  setPerItemTime(state, static_cast<double>(s->pairs.size()), "t_pair");
}

/// Random translating pairs: radii U(0.05, 0.3) per axis, random fixed orientations; each centre
/// crosses the origin region on a straight line of length U(0.2, 1.5) m with a random offset.
std::vector<PosePair> randomPairs(std::size_t n) {
  std::mt19937_64 rng(kRandomPairSeed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> g(0.0, 1.0);
  auto unit = [&]() {
    Eigen::Vector3d v(g(rng), g(rng), g(rng));
    return v.normalized();
  };
  auto rot = [&]() { return Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix(); };
  std::vector<PosePair> out;
  for (std::size_t i = 0; i < n; ++i) {
    PosePair p;
    for (int k = 0; k < 3; ++k) {
      p.ra[k] = 0.05 + 0.25 * u(rng);
      p.rb[k] = 0.05 + 0.25 * u(rng);
    }
    const Eigen::Matrix3d Ra = rot(), Rb = rot();
    const Eigen::Vector3d da = (0.2 + 1.3 * u(rng)) * unit(), db = (0.2 + 1.3 * u(rng)) * unit();
    const Eigen::Vector3d oa = 0.25 * unit() * u(rng), ob = 0.25 * unit() * u(rng);
    const double sa = u(rng), sb = u(rng);  // where along its path each one is at the crossing
    p.a0 = pose(Ra, oa - sa * da);
    p.a1 = pose(Ra, oa + (1 - sa) * da);
    p.b0 = pose(Rb, ob - sb * db + Eigen::Vector3d(0.0, 0.0, 0.0));
    p.b1 = pose(Rb, ob + (1 - sb) * db);
    out.push_back(p);
  }
  return out;
}

// ------------------------------------------------------------------------------------------------
// (3) Robot arm

struct ArmPair : ArmScenePair {
  explicit ArmPair(ArmScenePair p) : ArmScenePair(std::move(p)) {}
  EllipsoidCcdResult result;
  int oracle_outside = 0;       ///< sampled colliding instants outside the reported intervals
  double oracle_end_gap = 0.0;  ///< largest distance of a reported interval end from a sampled transition
};

struct Arm {
  std::vector<ArmPair> pairs;
};

Arm makeArm() {
  Arm arm;
  for (ArmScenePair& p : makeArmScene()) arm.pairs.emplace_back(std::move(p));
  return arm;
}

CcdOptions armOptions() { return armCcdOptions(); }

void checkArmPair(ArmPair* p) {
  p->result = continuousCollideEllipsoids(p->obstacle, p->link_e, armOptions());
  const int n = 4000;
  bool prev = false;
  std::vector<double> transitions;
  for (int k = 0; k <= n; ++k) {
    const double t = static_cast<double>(k) / n;
    const bool hit = ellipsoidsCollide(ellipsoidAt(p->obstacle, t), ellipsoidAt(p->link_e, t));
    if (hit) {
      bool inside = false;
      for (const CcdInterval& i : p->result.collision_intervals) inside = inside || (t >= i.begin && t <= i.end);
      p->oracle_outside += !inside;
    }
    if (k > 0 && hit != prev) transitions.push_back(t - 0.5 / n);
    prev = hit;
  }
  for (const CcdInterval& i : p->result.collision_intervals) {
    for (double e : {i.begin, i.end}) {
      if (e == 0.0 || e == 1.0) continue;
      double best = 1.0;
      for (double x : transitions) best = std::min(best, std::abs(x - e));
      p->oracle_end_gap = std::max(p->oracle_end_gap, best);
    }
  }
}

void benchArmSolve(benchmark::State& state, const ArmPair* p) {
  const CcdOptions opt = armOptions();
  std::size_t n = 0;
  for (auto _ : state) n += continuousCollideEllipsoids(p->obstacle, p->link_e, opt).collision_intervals.size();
  benchmark::DoNotOptimize(n);
  setPerItemTime(state, 1.0, "t_pair");
}

void benchArmF(benchmark::State& state, const ArmPair* p) {
  const MotionMatrix& ma = p->obstacle.motion.pieces().front();
  const MotionMatrix& mb = p->link_e.motion.pieces().front();
  for (auto _ : state) {
    const PolynomialMatrix4 A = movingQuadric(p->obstacle.body.quadricMatrix(), ma);
    const PolynomialMatrix4 B = movingQuadric(p->link_e.body.quadricMatrix(), mb);
    const BivariateBernstein F = ccdFunction(A, B);
    benchmark::DoNotOptimize(F.coefficients().data());
  }
  setPerItemTime(state, 1.0, "t_pair");
}

// ------------------------------------------------------------------------------------------------
// Report

std::string intervalsText(const std::vector<CcdInterval>& v) {
  if (v.empty()) return "-";
  std::string s;
  char buf[64];
  for (const CcdInterval& i : v) {
    std::snprintf(buf, sizeof buf, "%s[%.3f,%.3f]", s.empty() ? "" : " ", i.begin, i.end);
    s += buf;
  }
  return s;
}

struct PairStats {
  double all = 0, free = 0, colliding = 0, close = 0, close_free = 0, close_colliding = 0, p99 = 0;
  std::size_t n = 0, n_free = 0, n_coll = 0, n_close = 0, n_close_free = 0, n_close_coll = 0;
};

PairStats pairStats(const std::vector<PairRecord>& v) {
  PairStats s;
  std::vector<double> all;
  for (const PairRecord& p : v) {
    all.push_back(p.us);
    s.all += p.us;
    (p.collide ? s.colliding : s.free) += p.us;
    (p.collide ? s.n_coll : s.n_free) += 1;
    if (p.culled_by == 0) {
      s.close += p.us;
      ++s.n_close;
      (p.collide ? s.close_colliding : s.close_free) += p.us;
      (p.collide ? s.n_close_coll : s.n_close_free) += 1;
    }
  }
  auto div = [](double x, std::size_t n) { return n ? x / static_cast<double>(n) : 0.0; };
  s.n = v.size();
  s.all = div(s.all, s.n);
  s.free = div(s.free, s.n_free);
  s.colliding = div(s.colliding, s.n_coll);
  s.close = div(s.close, s.n_close);
  s.close_free = div(s.close_free, s.n_close_free);
  s.close_colliding = div(s.close_colliding, s.n_close_coll);
  s.p99 = quantiles(all).p99;
  return s;
}

void printBoxing(const SummaryReporter& r, const Settings& cfg, const BoxingScene& scene,
                 const std::vector<SetupReport>& reps, const std::string& load_start) {
  std::printf("\n== CCD boxing (thesis 5.4.1, Table 5): two characters of 20 ellipsoids, %d frames, 400 cross pairs "
              "per frame, first contact ==\n",
              scene.frames);
  if (cfg.smoke) std::printf("  NOTE: smoke run (--smoke): tiny sizes, not the documented ones\n");
  std::printf("  load average (1, 5, 15 min): %s at the start, %s at the end\n", load_start.c_str(),
              loadAverage().c_str());
  std::printf("  scene: procedural, seed %llu (bench_ccd.cpp); setup1 culling + t_max = running t-bar (floor %.0e), "
              "setup2 no culling, setup3 affine, no culling\n",
              static_cast<unsigned long long>(kBoxingSeed), kTbarFloor);
  const double mot_ms = r.nsPerItem("Boxing/motions") / 1e6;
  std::printf("  times: t_frm = CPU ms per frame (Google Benchmark, whole sequence, motions included); t_mot = "
              "building the 40 motions of a frame; us per pair: steady_clock pass, faster of two consecutive calls per pair\n");
  std::printf("%-28s %8s %8s | %8s %8s %8s %8s %8s %10s\n", "setup", "t_frm ms", "t_mot ms", "all us", "free us",
              "coll. us", "p99 us", "worst us", "worst re-t");
  for (const SetupReport& s : reps) {
    const PairStats p = pairStats(s.pairs);
    std::printf("%-28s %8.3f %8.3f | %8.2f %8.2f %8.2f %8.2f %8.1f %10.1f\n", setupName(s.setup),
                r.nsPerItem(std::string("Boxing/") + setupName(s.setup)) / 1e6, mot_ms, p.all, p.free, p.colliding,
                p.p99, s.worst_us, s.worst_retimed_us);
    if (s.setup == Setup::kCulled)
      std::printf("%-28s %8s %8s | %8.2f %8.2f %8.2f %8s %8s %10s\n", "  close pairs (not culled)", "", "", p.close,
                  p.close_free, p.close_colliding, "", "", "");
  }
  {  // setup1 by path: which part of the pipeline answered the pair
    const SetupReport& s1 = reps[0];
    struct Path {
      const char* name;
      std::vector<double> us;
    } paths[5] = {{"culled by spheres", {}},
                  {"culled by the plane", {}},
                  {"close, touching at t = 0", {}},
                  {"close, CCD proper, free", {}},
                  {"close, CCD proper, contact", {}}};
    for (const PairRecord& p : s1.pairs) {
      const int k = p.culled_by == 1 ? 0 : p.culled_by == 2 ? 1 : p.at_start ? 2 : p.collide ? 4 : 3;
      paths[k].us.push_back(p.us);
    }
    std::printf("  setup1 by path:");
    for (const Path& q : paths)
      std::printf("  %s %zu pairs, mean %.2f us, max %.1f us;", q.name, q.us.size(), mean(q.us), quantiles(q.us).max);
    std::printf("\n");
  }
  std::printf("  thesis (2008 hardware): setup1 1.33 ms, t_mot 0.20 ms, all 2.8 / 2.5 / 17.8 us, worst 73.9 us; "
              "close pairs 55.2 / 54.7 / 65.4; setup2 1.90 ms, 4.2 / 4.0 / 13.8, worst 100.1; setup3 affine 1.19 ms, "
              "2.6 / 2.5 / 6.6, worst 39.4\n");
  std::printf("%-28s %9s %9s %9s %9s %9s %9s %9s %7s %6s %6s\n", "counts", "pairs", "sphere", "plane", "close",
              "colliding", "at t=0", "floor", "deg(t)", "tang.", "unres.");
  for (const SetupReport& s : reps) {
    std::printf("%-28s %9zu %9zu %9zu %9zu %9zu %9zu %9zu %7d %6zu %6zu\n", setupName(s.setup), s.pairs.size(),
                s.culled[1], s.culled[2], s.culled[0], s.colliding, s.at_start, s.floor_pairs, s.max_degree,
                s.near_tangent, s.unresolved);
  }
  const SetupReport& s1 = reps[0];
  const PairStats p1 = pairStats(s1.pairs);
  std::printf("  setup1: %.1f %% culled by spheres, %.1f %% of the rest by the plane, %zu close pairs (%.3f %% of all) "
              "of which %zu colliding (%zu already at t = 0) and %zu collision-free; thesis: 93.8 %%, 62.6 %% "
              "(34.1 %% colliding at t = 0), 780 close pairs (0.195 %%), 38 colliding / 742 free\n",
              100.0 * s1.culled[1] / std::max<std::size_t>(1, s1.pairs.size()),
              100.0 * s1.culled[2] / std::max<std::size_t>(1, s1.pairs.size() - s1.culled[1]), s1.culled[0],
              100.0 * s1.culled[0] / std::max<std::size_t>(1, s1.pairs.size()), p1.n_close_coll, s1.at_start,
              p1.n_close_free);
  // Consistency: the frame's first contact from setup1 (t-bar) and setup2 (all pairs on [0, 1]).
  if (reps.size() >= 3) {
    std::size_t frames_differ = 0, decisions_differ = 0, n_dt = 0;
    double max_tbar_diff = 0.0;
    std::vector<double> dt;
    for (std::size_t k = 0; k < s1.frame_toc.size(); ++k) {
      const double d = std::abs(s1.frame_toc[k] - reps[1].frame_toc[k]);
      max_tbar_diff = std::max(max_tbar_diff, d);
      frames_differ += d > 1e-6;
    }
    for (std::size_t i = 0; i < reps[1].pairs.size(); ++i) {
      const PairRecord &a = reps[1].pairs[i], &b = reps[2].pairs[i];
      decisions_differ += a.collide != b.collide;
      if (a.collide && b.collide && !a.at_start && !b.at_start) dt.push_back(std::abs(a.toc - b.toc));
    }
    n_dt = dt.size();
    const double m = mean(dt);
    double var = 0.0;
    for (double x : dt) var += (x - m) * (x - m);
    const double sd = n_dt > 1 ? std::sqrt(var / static_cast<double>(n_dt - 1)) : 0.0;
    std::printf("  frames with a contact: setup1 %zu, setup2 %zu of %d; frame first-contact time setup1 vs setup2: "
                "%zu frames differ by > 1e-6 (max %.2e)\n",
                s1.frames_with_contact, reps[1].frames_with_contact, scene.frames, frames_differ, max_tbar_diff);
    std::printf("  rigid (setup2) vs affine (setup3): %zu of %zu pairs differ in collide / free; |toc difference| "
                "over %zu pairs colliding after t = 0 in both: mean %.4f, sd %.4f, max %.4f (thesis 0.008, 0.03, 0.49)\n",
                decisions_differ, reps[1].pairs.size(), n_dt, m, sd, quantiles(dt).max);
  }
  std::printf("  where the time goes: building F(u, t) via the public API (movingQuadric x2 + ccdFunction, min of 3) "
              "on close pairs: setup1 %.2f us (%zu pairs, %.0f %% of their %.2f us)",
              s1.f_build_us, s1.f_build_n, p1.close > 0 ? 100.0 * s1.f_build_us / p1.close : 0.0, p1.close);
  if (reps.size() >= 2) {
    const PairStats p2 = pairStats(reps[1].pairs);
    std::printf(", setup2 %.2f us (%zu sampled pairs, %.0f %% of %.2f us)", reps[1].f_build_us, reps[1].f_build_n,
                p2.all > 0 ? 100.0 * reps[1].f_build_us / p2.all : 0.0, p2.all);
  }
  std::printf("\n  columns: all / free / coll. = mean us per pair over all / collision-free / colliding pairs (in setup1 "
              "within [0, t_max]); worst re-t = the worst pair re-timed, min of %d calls; close = neither cull "
              "applied; floor = pairs run with t_max = %.0e after t-bar reached 0; tang. / unres. = near_tangent / "
              "unresolved flags\n",
              kWorstRetimes, kTbarFloor);
  std::fflush(stdout);
}

void printFcl(const SummaryReporter& r, const std::vector<PairSetReport>& sets, const std::string& ca_text) {
  std::printf("\n== CCD vs FCL: continuousCollideEllipsoids (first contact, culling on) vs fcl::continuousCollide "
              "(CCDC_NAIVE, request defaults: 10 samples), same moving pairs ==\n");
  std::printf("%-30s %6s | %9s %9s %8s | %6s %6s %7s %7s | %9s %9s | %7s %7s\n", "pair set", "pairs", "ours us",
              "naive us", "nv/ours", "exact", "naive", "misses", "false", "lag mean", "lag max", "oracle", "ex.miss");
  for (const PairSetReport& s : sets) {
    const double ours = r.nsPerItem("Fcl/" + s.name + "/fcl_quadric") / 1e3;
    const double naive = r.nsPerItem("Fcl/" + s.name + "/fcl_naive") / 1e3;
    if (s.translation) {
      std::printf("%-30s %6zu | %9.2f %9.2f %8.2f | %6zu %6zu %7zu %7zu | %9.4f %9.4f | %7zu %7zu\n", s.name.c_str(),
                  s.pairs.size(), ours, naive, ours > 0 ? naive / ours : 0.0, s.exact_hits, s.naive_hits, s.misses,
                  s.false_hits, mean(s.lag), quantiles(s.lag).max, s.oracle_hits, s.oracle_missed_by_exact);
    } else {
      std::printf("%-30s %6zu | %9.2f %9.2f %8.2f | %6zu %6zu %7s %7s | %9s %9s | %7s %7s\n", s.name.c_str(),
                  s.pairs.size(), ours, naive, ours > 0 ? naive / ours : 0.0, s.exact_hits, s.naive_hits, "-", "-",
                  "-", "-", "-", "-");
    }
  }
  std::printf("  translation sets: fromPoses with equal rotations vs CCDM_TRANS (the same motion); misses = exact "
              "contact in [0, 1] that NAIVE reports as none; false = NAIVE contact the exact solver rejects; lag = "
              "NAIVE time of contact - exact first contact time, pairs both report; oracle = pairs with a contact "
              "among %d + 1 sampled instants (classifyEllipsoids), ex.miss = of those, pairs the exact solver "
              "reports free\n",
              kOracleSamples);
  std::printf("  rigid set: our fromPoses (linear quaternion, rational degree 2) vs CCDM_LINEAR (InterpMotion: "
              "constant angular velocity), different motions: times and contact counts only\n");
  std::printf("  times: CPU us per pair (Google Benchmark, median of the repetitions), motion construction included "
              "for both peers\n");
  std::printf("  CCDC_CONSERVATIVE_ADVANCEMENT on ellipsoids: %s\n", ca_text.c_str());
  std::fflush(stdout);
}

void printArm(const SummaryReporter& r, const Arm& arm) {
  std::printf("\n== CCD robot arm (thesis 5.4.2, Table 6): 10 link ellipsoids on 3 joints (tan(theta/2) linear in t), "
              "3 obstacle ellipsoids, all collision intervals, culling off ==\n");
  std::printf("%-5s %6s %6s | %10s %10s %10s | %6s | %-30s | %8s %8s\n", "pair", "motion", "deg F", "obtain F",
              "total", "solve", "work", "collision intervals in [0,1]", "oracle", "end gap");
  double total_ms = 0.0;
  for (const ArmPair& p : arm.pairs) {
    const double f = r.nsPerItem("ArmF/" + p.name) / 1e6, t = r.nsPerItem("Arm/" + p.name) / 1e6;
    total_ms += t;
    std::printf("%-5s %6d %6d | %10.3f %10.3f %10.3f | %6d | %-30s | %8d %8.4f\n", p.name.c_str(), p.motion_degree,
                p.result.degree_t, f, t, t - f, p.result.work, intervalsText(p.result.collision_intervals).c_str(),
                p.oracle_outside, p.oracle_end_gap);
  }
  std::printf("  by motion degree (mean ms per pair: obtain F / total):");
  for (int d = 0; d <= 6; d += 2) {
    double f = 0, t = 0;
    int n = 0;
    for (const ArmPair& p : arm.pairs) {
      if (p.motion_degree != d) continue;
      f += r.nsPerItem("ArmF/" + p.name) / 1e6;
      t += r.nsPerItem("Arm/" + p.name) / 1e6;
      ++n;
    }
    if (n) std::printf("  deg %d: %.3f / %.3f", d, f / n, t / n);
  }
  std::printf("\n  all 30 pairs: %.2f ms (thesis 43.8 ms; F degrees there 0 / 32 / 64 / 96 for motion degrees 0 / 2 / "
              "4 / 6)\n",
              total_ms);
  std::printf("  times: CPU ms per pair (Google Benchmark, median of the repetitions); obtain F = movingQuadric x2 + "
              "ccdFunction; solve = total - obtain F; oracle = sampled colliding instants (4001, classifyEllipsoids) "
              "outside the reported intervals; end gap = largest distance from a reported interval end to a "
              "sampled transition (resolution 2.5e-4)\n");
  std::fflush(stdout);
}

void printAim(const SummaryReporter& r, const std::vector<SetupReport>& reps, const std::vector<PairSetReport>& sets,
              const Arm& arm) {
  std::printf("\n== CCD aim (issue 4), judged on the results above ==\n");
  const double ms = r.nsPerItem(std::string("Boxing/") + setupName(Setup::kCulled)) / 1e6;
  std::printf("  %-8s boxing setup1 <= 0.2 ms per frame: %.3f ms per frame\n", ms > 0 && ms <= 0.2 ? "met" : "not met",
              ms);
  std::size_t misses = 0, oracle_missed = 0;
  for (const PairSetReport& s : sets) {
    misses += s.misses;
    oracle_missed += s.oracle_missed_by_exact;
  }
  std::printf("  %-8s exact solver misses no contact of the sampled oracle: %zu missed\n",
              oracle_missed == 0 ? "met" : "not met", oracle_missed);
  int outside = 0;
  for (const ArmPair& p : arm.pairs) outside += p.oracle_outside;
  std::printf("  %-8s robot arm intervals contain every sampled contact: %d sampled instants outside\n",
              outside == 0 ? "met" : "not met", outside);
  std::printf("  (info)   NAIVE (10 samples) misses on the translation sets: %zu\n", misses);
  std::size_t unresolved = 0;
  for (const SetupReport& s : reps) unresolved += s.unresolved;
  for (const ArmPair& p : arm.pairs) unresolved += p.result.unresolved;
  std::printf("  %-8s no pair left unresolved (work cap): %zu\n", unresolved == 0 ? "met" : "not met", unresolved);
  std::fflush(stdout);
}

}  // namespace
}  // namespace bench
}  // namespace fcl_quadric

int main(int argc, char** argv) {
  using namespace fcl_quadric;
  using namespace fcl_quadric::bench;
  Settings cfg;
  cfg.smoke = takeFlag(&argc, argv, "smoke", "FCL_QUADRIC_BENCH_SMOKE");
  cfg.frames = takeSizeOption(&argc, argv, "frames", "FCL_QUADRIC_BENCH_CCD_FRAMES", cfg.smoke ? 12 : 1000);
  cfg.random_pairs = takeSizeOption(&argc, argv, "random_pairs", "FCL_QUADRIC_BENCH_CCD_RANDOM", cfg.smoke ? 50 : 2000);
  const benchmark::ConsoleReporter::OutputOptions console = consoleOutputOptions(argc, argv);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  const std::string load_start = loadAverage();
  std::printf("fcl_quadric continuous-collision benchmarks (issue 4)%s: computing scenes and counts (untimed)...\n",
              cfg.smoke ? ", smoke run" : "");
  std::fflush(stdout);

  // (1)
  static const BoxingScene scene = makeBoxing(cfg.frames);
  static std::vector<SetupReport> reps;
  for (Setup s : {Setup::kCulled, Setup::kNoCull, Setup::kAffine}) reps.push_back(recordSetup(scene, s));
  // (2): close pairs of setup 1 (untimed list), their translation-only and rigid versions; random pairs.
  static std::vector<PairSetReport> sets(3);
  sets[0].name = "boxing_close_translation";
  sets[1].name = "random_translation";
  sets[2].name = "boxing_close_rigid";
  sets[2].translation = false;
  for (const PairRecord& p : reps[0].pairs) {
    if (p.culled_by != 0) continue;
    PosePair q;
    q.ra = partRadii()[p.a];
    q.rb = partRadii()[p.b];
    q.a0 = scene.poses[0][p.frame][p.a];
    q.a1 = scene.poses[0][p.frame + 1][p.a];
    q.b0 = scene.poses[1][p.frame][p.b];
    q.b1 = scene.poses[1][p.frame + 1][p.b];
    sets[2].pairs.push_back(q);
    q.a1.linear() = q.a0.linear();
    q.b1.linear() = q.b0.linear();
    sets[0].pairs.push_back(q);
  }
  sets[1].pairs = randomPairs(cfg.random_pairs);
  for (PairSetReport& s : sets) countPairSet(&s);
  std::string ca_text = "no pair to try";
  if (!sets[0].pairs.empty()) {
    double ret = 0.0;
    std::fflush(stdout);
    const fcl::ContinuousCollisionResultd ca =
        naiveOn(sets[0].pairs.front(), false, fcl::CCDC_CONSERVATIVE_ADVANCEMENT, &ret);
    char text[200];
    std::snprintf(text, sizeof text, "returns %.3g, is_collide %s (exact solver on that pair: %s); FCL prints a "
                  "warning (node types not supported)",
                  ret, ca.is_collide ? "true" : "false", oursOn(sets[0].pairs.front()).collide ? "contact" : "free");
    ca_text = text;
  }
  // (3)
  static Arm arm = makeArm();
  for (ArmPair& p : arm.pairs) checkArmPair(&p);

  registerBenchmark("Boxing/motions", benchMotions, &scene);
  for (Setup s : {Setup::kCulled, Setup::kNoCull, Setup::kAffine})
    registerBenchmark((std::string("Boxing/") + setupName(s)).c_str(), benchBoxing, &scene, s);
  for (const PairSetReport& s : sets) {
    if (s.pairs.empty()) continue;
    registerBenchmark(("Fcl/" + s.name + "/fcl_quadric").c_str(), benchPairSet, &s, true);
    registerBenchmark(("Fcl/" + s.name + "/fcl_naive").c_str(), benchPairSet, &s, false);
  }
  for (const ArmPair& p : arm.pairs) {
    registerBenchmark(("ArmF/" + p.name).c_str(), benchArmF, &p);
    registerBenchmark(("Arm/" + p.name).c_str(), benchArmSolve, &p);
  }

  SummaryReporter reporter(console);
  benchmark::RunSpecifiedBenchmarks(&reporter);
  reporter.printSummary("CCD summary: CPU time per frame (Boxing), per pair (Fcl, Arm, ArmF)", "item");
  printBoxing(reporter, cfg, scene, reps, load_start);
  printFcl(reporter, sets, ca_text);
  printArm(reporter, arm);
  printAim(reporter, reps, sets, arm);
  benchmark::Shutdown();
  return 0;
}
