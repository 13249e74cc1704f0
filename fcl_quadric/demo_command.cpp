#include "fcl_quadric/demo_command.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <sstream>

#include <Eigen/Geometry>

#include "fcl_quadric/geometry/ellipsoid.h"
#include "fcl_quadric/geometry/pair_coherence.h"
#include "fcl_quadric/geometry/signed_distance.h"

namespace fcl_quadric {
namespace cli {

namespace {

constexpr double kFrameTime = 1.0 / 60.0;  // seconds per frame
constexpr std::size_t kExampleContacts = 5;

/// One body of the demo: an ellipsoid spinning at a constant rate about its own axis while its
/// centre drifts in a straight line, reflected at the walls of the box [-half, half]^3 and
/// deflected by contacts (bounce()).
struct Body {
  Eigen::Vector3d radii;
  Eigen::Matrix3d initial_rotation;
  Eigen::Vector3d spin_axis;
  double spin_rate = 0.0;  // rad/s
  Eigen::Vector3d position;
  Eigen::Vector3d velocity;  // units/s
};

Eigen::Vector3d randomUnitVector(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Vector3d v;
  do {
    v = Eigen::Vector3d(n(rng), n(rng), n(rng));
  } while (!(v.norm() > 1e-6));
  return v.normalized();
}

/// Half the side of the box: the bounding spheres of the ellipsoids fill about a quarter of it,
/// so close encounters (where the two classifications do real work) are frequent.
double boxHalfSide(int objects) { return 0.9 * std::cbrt(static_cast<double>(objects)); }

std::vector<Body> makeBodies(const DemoOptions& options) {
  std::mt19937_64 rng(options.seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double half = boxHalfSide(options.objects);
  std::vector<Body> bodies(static_cast<std::size_t>(options.objects));
  for (Body& body : bodies) {
    // Largest semi-axis 0.35..1, the others down to a quarter of it, in random order.
    const double scale = 0.35 + 0.65 * u(rng);
    Eigen::Vector3d r(scale, scale * (0.25 + 0.75 * u(rng)), scale * (0.25 + 0.75 * u(rng)));
    std::shuffle(r.data(), r.data() + 3, rng);
    body.radii = r;
    std::normal_distribution<double> g(0.0, 1.0);
    body.initial_rotation = Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
    body.spin_axis = randomUnitVector(rng);
    body.spin_rate = 0.5 + 2.5 * u(rng);
    body.velocity = (0.2 + 0.6 * u(rng)) * randomUnitVector(rng);
  }
  // Start without bounding-sphere overlaps where possible (a bounded number of attempts each), so
  // contacts happen during the run rather than at frame 0.
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    Body& body = bodies[i];
    for (int attempt = 0; attempt < 100; ++attempt) {
      for (int k = 0; k < 3; ++k) body.position[k] = half * (2.0 * u(rng) - 1.0);
      bool free = true;
      for (std::size_t j = 0; j < i && free; ++j) {
        const double reach = body.radii.maxCoeff() + bodies[j].radii.maxCoeff();
        free = (body.position - bodies[j].position).squaredNorm() > reach * reach;
      }
      if (free) break;
    }
  }
  return bodies;
}

Ellipsoid poseAt(const Body& body, double t) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(body.spin_rate * t, body.spin_axis).toRotationMatrix() *
                            body.initial_rotation;
  return Ellipsoid(body.radii, R, body.position);
}

void drift(Body* body, double half) {
  body->position += kFrameTime * body->velocity;
  for (int k = 0; k < 3; ++k) {
    if (body->position[k] > half) {
      body->position[k] = 2.0 * half - body->position[k];
      body->velocity[k] = -body->velocity[k];
    } else if (body->position[k] < -half) {
      body->position[k] = -2.0 * half - body->position[k];
      body->velocity[k] = -body->velocity[k];
    }
  }
}

/// Crude collision response so that contacts are brief events rather than long interpenetrations:
/// if the centres approach, exchange the velocity components along the line of centres (an
/// elastic collision of equal masses). Spin is unaffected.
void bounce(Body* a, Body* b) {
  const Eigen::Vector3d d = b->position - a->position;
  const double length = d.norm();
  if (!(length > 0.0)) return;
  const Eigen::Vector3d n = d / length;
  const double approach = (a->velocity - b->velocity).dot(n);
  if (approach <= 0.0) return;
  a->velocity -= approach * n;
  b->velocity += approach * n;
}

struct Candidate {
  int a;
  int b;
  std::size_t pair;  // index of the unordered pair (a, b)
};

std::string formatDouble(const char* format, double v) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, v);
  return buffer;
}

std::string percent(std::uint64_t part, std::uint64_t whole) {
  return whole == 0 ? std::string("-") : formatDouble("%.1f%%", 100.0 * static_cast<double>(part) / static_cast<double>(whole));
}

}  // namespace

std::string demoObjectName(int index, int count) {
  int digits = 1;
  for (int n = count - 1; n >= 10; n /= 10) ++digits;
  std::string number = std::to_string(index);
  if (static_cast<int>(number.size()) < digits) number.insert(0, static_cast<std::size_t>(digits) - number.size(), '0');
  return "E" + number;
}

DemoSummary simulateDemo(const DemoOptions& options) {
  if (options.frames < 1) throw std::invalid_argument("demo needs at least 1 frame");
  if (options.objects < 2) throw std::invalid_argument("demo needs at least 2 objects");
  using Clock = std::chrono::steady_clock;

  DemoSummary summary;
  summary.options = options;
  std::vector<Body> bodies = makeBodies(options);
  const double half = boxHalfSide(options.objects);
  const int n = options.objects;
  const std::size_t pair_count = static_cast<std::size_t>(n) * static_cast<std::size_t>(n - 1) / 2;
  std::vector<PairCoherence> coherence(pair_count);
  std::vector<char> was_colliding(pair_count, 0);
  std::vector<Ellipsoid> ellipsoids;
  ellipsoids.reserve(static_cast<std::size_t>(n));
  std::vector<Candidate> candidates;
  std::vector<Separation> coherent, direct;

  for (int frame = 0; frame < options.frames; ++frame) {
    const double t = frame * kFrameTime;
    ellipsoids.clear();
    for (const Body& body : bodies) ellipsoids.push_back(poseAt(body, t));
    if (frame == 0) summary.first_frame = ellipsoids;
    if (frame == options.frames - 1) summary.last_frame = ellipsoids;

    // Broad phase: bounding spheres.
    candidates.clear();
    std::vector<char> colliding_now(pair_count, 0);
    std::size_t pair = 0;
    for (int a = 0; a < n; ++a) {
      for (int b = a + 1; b < n; ++b, ++pair) {
        const double reach = ellipsoids[static_cast<std::size_t>(a)].maxRadius() +
                             ellipsoids[static_cast<std::size_t>(b)].maxRadius();
        const Eigen::Vector3d d = ellipsoids[static_cast<std::size_t>(b)].center() -
                                  ellipsoids[static_cast<std::size_t>(a)].center();
        if (d.squaredNorm() <= reach * reach) candidates.push_back({a, b, pair});
      }
    }

    // Narrow phase, twice; the order alternates between frames so neither pass always runs on a
    // warm cache.
    coherent.assign(candidates.size(), Separation::Touching);
    direct.assign(candidates.size(), Separation::Touching);
    auto run_coherent = [&] {
      const auto start = Clock::now();
      for (std::size_t k = 0; k < candidates.size(); ++k) {
        const Candidate& c = candidates[k];
        coherent[k] = coherence[c.pair].query(ellipsoids[static_cast<std::size_t>(c.a)],
                                              ellipsoids[static_cast<std::size_t>(c.b)]);
      }
      summary.coherent_ns += std::chrono::duration<double, std::nano>(Clock::now() - start).count();
    };
    auto run_direct = [&] {
      const auto start = Clock::now();
      for (std::size_t k = 0; k < candidates.size(); ++k) {
        const Candidate& c = candidates[k];
        direct[k] = classifyEllipsoids(ellipsoids[static_cast<std::size_t>(c.a)],
                                       ellipsoids[static_cast<std::size_t>(c.b)]).status;
      }
      summary.direct_ns += std::chrono::duration<double, std::nano>(Clock::now() - start).count();
    };
    if (frame % 2 == 0) {
      run_coherent();
      run_direct();
    } else {
      run_direct();
      run_coherent();
    }

    for (std::size_t k = 0; k < candidates.size(); ++k) {
      const Candidate& c = candidates[k];
      if (coherent[k] != direct[k]) {
        std::ostringstream os;
        os << "coherent and direct classification disagree for pair " << demoObjectName(c.a, n) << "-"
           << demoObjectName(c.b, n) << " at frame " << frame << ": " << toString(coherent[k]) << " vs "
           << toString(direct[k]) << " (seed " << options.seed << ")";
        throw DemoMismatch(os.str());
      }
      ++summary.pair_tests;
      if (direct[k] == Separation::Separated) {
        ++summary.separated;
        continue;
      }
      ++summary.colliding;
      summary.touching += direct[k] == Separation::Touching;
      colliding_now[c.pair] = 1;
      bounce(&bodies[static_cast<std::size_t>(c.a)], &bodies[static_cast<std::size_t>(c.b)]);
      if (frame > 0 && !was_colliding[c.pair]) {
        ++summary.contact_starts;
        if (summary.examples.size() < kExampleContacts) {
          const SignedDistanceResult sd = signedDistance(ellipsoids[static_cast<std::size_t>(c.a)],
                                                         ellipsoids[static_cast<std::size_t>(c.b)]);
          summary.examples.push_back({c.a, c.b, frame, sd.distance, direct[k]});
        }
      }
    }
    was_colliding.swap(colliding_now);
    for (Body& body : bodies) drift(&body, half);
  }

  summary.pair_frames = static_cast<std::uint64_t>(options.frames) * pair_count;
  for (const PairCoherence& c : coherence) summary.plane_hits += c.planeHits();
  return summary;
}

void printDemoSummary(const DemoSummary& s, std::ostream& out) {
  const int n = s.options.objects;
  const double tests = static_cast<double>(s.pair_tests);
  const double coherent_mean = s.pair_tests > 0 ? s.coherent_ns / tests : 0.0;
  const double direct_mean = s.pair_tests > 0 ? s.direct_ns / tests : 0.0;
  out << "fcl_quadric demo: " << n << " spinning, drifting ellipsoids in a box, " << s.options.frames
      << " frames (seed " << s.options.seed << ")\n";
  out << "  pair tests (bounding spheres overlap):  " << s.pair_tests << " of " << s.pair_frames << " pair-frames ("
      << percent(s.pair_tests, s.pair_frames) << ")\n";
  out << "  colliding pair-frames:                  " << s.colliding << " (touching: " << s.touching
      << "), contacts begun: " << s.contact_starts << "\n";
  out << "  separations:                            " << s.separated << ", of which " << s.plane_hits << " ("
      << percent(s.plane_hits, s.separated) << ") certified by the cached separating plane\n";
  out << "  mean time per pair test, coherence:     " << formatDouble("%.1f", coherent_mean) << " ns\n";
  out << "  mean time per pair test, direct:        " << formatDouble("%.1f", direct_mean) << " ns\n";
  out << "  speed-up from coherence:                "
      << (coherent_mean > 0.0 ? formatDouble("%.2fx", direct_mean / coherent_mean) : std::string("-")) << "\n";
  out << "  coherent and direct answers agree on all " << s.pair_tests << " pair tests\n";
  if (s.examples.empty()) {
    out << "  no contact began during the run\n";
    return;
  }
  out << "  example contacts (first frame of a new contact):\n";
  for (const DemoContact& c : s.examples) {
    out << "    " << demoObjectName(c.a, n) << "-" << demoObjectName(c.b, n) << "  frame " << c.frame
        << "  signed distance " << formatDouble("%.6g", c.signed_distance) << " (" << toString(c.status) << ")\n";
  }
}

void runDemo(const DemoOptions& options, std::ostream& out) { printDemoSummary(simulateDemo(options), out); }

}  // namespace cli
}  // namespace fcl_quadric
