#pragma once
/// \file demo_command.h
/// `fcl_quadric demo`: spinning, drifting ellipsoids in a box (bouncing off the walls and, crudely,
/// off each other), every pair whose bounding spheres overlap classified each frame with and
/// without inter-frame coherence (PairCoherence), answers compared, times reported.

#include <cstdint>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "fcl_quadric/geometry/ellipsoid.h"
#include "fcl_quadric/geometry/ellipsoid_separation.h"

namespace fcl_quadric {
namespace cli {

struct DemoOptions {
  int frames = 2000;        ///< simulated frames (>= 1)
  int objects = 40;         ///< ellipsoids (>= 2)
  std::uint64_t seed = 1;   ///< seed of the scene generator (std::mt19937_64)
};

/// The first frame of a new contact of a pair, with the signed distance at that frame.
struct DemoContact {
  int a = 0;  ///< object index
  int b = 0;  ///< object index, a < b
  int frame = 0;
  double signed_distance = 0.0;
  Separation status = Separation::Touching;
};

struct DemoSummary {
  DemoOptions options;
  std::uint64_t pair_frames = 0;  ///< frames x all unordered pairs
  std::uint64_t pair_tests = 0;   ///< pair-frames whose bounding spheres overlap (classified)
  std::uint64_t colliding = 0;    ///< pair tests reported touching or overlapping
  std::uint64_t touching = 0;     ///< pair tests reported touching
  std::uint64_t separated = 0;    ///< pair tests reported separate
  std::uint64_t plane_hits = 0;   ///< separations certified by a cached plane (PairCoherence)
  std::uint64_t contact_starts = 0;  ///< pair-frames where a pair begins to collide
  double coherent_ns = 0.0;       ///< total time of the PairCoherence queries
  double direct_ns = 0.0;         ///< total time of the plain classifyEllipsoids() calls
  std::vector<DemoContact> examples;  ///< the first few contact starts
  std::vector<Ellipsoid> first_frame;  ///< the ellipsoids at the first frame (for the pictures)
  std::vector<Ellipsoid> last_frame;   ///< the ellipsoids at the last frame
};

/// Thrown when coherent and direct classification disagree (a library bug).
class DemoMismatch : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

/// Name of demo object i ("E00", "E01", ...).
std::string demoObjectName(int index, int count);

/// Runs the simulation. Deterministic for given options except for the timings.
/// \throws std::invalid_argument for frames < 1 or objects < 2; DemoMismatch on disagreement.
DemoSummary simulateDemo(const DemoOptions& options);

/// Human-readable summary of a run.
void printDemoSummary(const DemoSummary& summary, std::ostream& out);

/// simulateDemo() then printDemoSummary().
void runDemo(const DemoOptions& options, std::ostream& out);

}  // namespace cli
}  // namespace fcl_quadric
