#pragma once
/// \file bench_experiments.h
/// The experiments of `fcl_quadric bench` (bench_command.h): each runs fcl_quadric and its peers
/// (stock FCL 0.7, Bullet) in this process on the same inputs and returns one row per
/// (case, peer): time per query and wrong answers against the exact answer (fcl_quadric's
/// certified classification, or the sign known by construction for near-tangent pairs).
/// The scenes come from the headers of benchmarks/ shared with the Google Benchmark programs.

#include <chrono>
#include <cstddef>
#include <ctime>
#include <functional>
#include <string>
#include <vector>

namespace fcl_quadric {
namespace cli {

enum class BenchSize { kTiny, kSmall, kFull };

/// One measured row: `peer` answered `n` queries of `case_name` in `ns_per_query` CPU ns each.
struct BenchRow {
  std::string case_name;
  std::string peer;
  std::size_t n = 0;
  double ns_per_query = 0.0;
  double ratio = 0.0;  ///< ns_per_query / the fcl_quadric row of the same case (filled by the command)
  long wrong = -1;     ///< wrong answers against the exact answer; -1: not counted
};

struct BenchExperiment {
  std::string name;   ///< as --only takes it
  std::string title;  ///< one line
  std::string unit;   ///< what one query is ("pair", "frame", ...)
  std::vector<BenchRow> rows;
  std::vector<std::string> notes;  ///< lines printed under the table
  bool chart_wrong = false;        ///< chart wrong answers (% of n) instead of time per query
  /// What `wrong` is counted against (table footer, chart footer and bench.json).
  std::string truth =
      "fcl_quadric's certified classification (verified against a GMP oracle in the test suite)";
};

/// Reports progress of the running experiment as a fraction in [0, 1].
using BenchProgress = std::function<void(double)>;

/// Names of the experiments, in run order.
const std::vector<std::string>& benchExperimentNames();

/// Runs the experiment `name` (one of benchExperimentNames()).
BenchExperiment runBenchExperiment(const std::string& name, BenchSize size, const BenchProgress& progress);

// The experiments, by translation unit.
BenchExperiment runRandomPairsExperiment(BenchSize size, const BenchProgress& progress);      // bench_static_experiments.cpp
BenchExperiment runNearTangentExperiment(BenchSize size, const BenchProgress& progress);      // bench_static_experiments.cpp
BenchExperiment runSeparatingPlanesExperiment(BenchSize size, const BenchProgress& progress); // bench_static_experiments.cpp
BenchExperiment runBoxingExperiment(BenchSize size, const BenchProgress& progress);           // bench_ccd_experiment.cpp
BenchExperiment runArmExperiment(BenchSize size, const BenchProgress& progress);              // bench_ccd_experiment.cpp
BenchExperiment runBroadphaseExperiment(BenchSize size, const BenchProgress& progress);       // bench_scene_experiments.cpp
BenchExperiment runOcTreeExperiment(BenchSize size, const BenchProgress& progress);           // bench_scene_experiments.cpp
BenchExperiment runQuadricShapesExperiment(BenchSize size, const BenchProgress& progress);    // bench_quadric_experiment.cpp

/// CPU time of this thread, in ns (what the experiments time: less sensitive to other processes
/// than wall time).
inline double threadCpuNs() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e9 * static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec);
}

/// Times `body()` run once over `n` queries: CPU ns per query (at least 1e-3 ns, never 0).
template <class Body>
double nsPerQuery(std::size_t n, Body&& body) {
  const double t0 = threadCpuNs();
  body();
  const double t1 = threadCpuNs();
  const double per = (t1 - t0) / static_cast<double>(n > 0 ? n : 1);
  return per > 1e-3 ? per : 1e-3;
}

}  // namespace cli
}  // namespace fcl_quadric
