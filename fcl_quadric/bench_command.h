#pragma once
/// \file bench_command.h
/// `fcl_quadric bench [--size tiny|small|full] [--out DIR] [--only LIST]`: the benchmark suite of
/// issue 7. Runs the experiments of bench_experiments.h, each against its peers (stock FCL 0.7,
/// Bullet) in this process on the same inputs, with a progress bar on stderr (a plain line per
/// experiment when stderr is not a terminal); prints one table per experiment (time per query of
/// each peer, ratio to fcl_quadric, wrong answers against the exact answer) and writes
/// DIR/bench.json and one bar chart DIR/bench_<experiment>.png per experiment.

#include <ostream>
#include <string>
#include <vector>

#include "fcl_quadric/bench_experiments.h"

namespace fcl_quadric {
namespace cli {

struct BenchOptions {
  std::string size = "small";          ///< tiny (seconds; the test suite), small (about a minute), full (the papers')
  std::string out = "fcl_quadric_bench";  ///< directory for bench.json and the charts (created if missing)
  std::string only;                    ///< comma-separated experiment names; empty: all
};

/// The size named `text`, or throws SceneError naming it.
BenchSize parseBenchSize(const std::string& text);

/// The experiments named by a comma-separated list (empty: all, in run order); throws SceneError
/// naming the first unknown name.
std::vector<std::string> parseBenchOnly(const std::string& list);

/// Runs the suite: tables to `out`, progress to `err` (a bar when `progress_tty`).
/// \throws SceneError for bad options or an --out directory that cannot be written (before any
/// experiment runs).
void runBench(const BenchOptions& options, std::ostream& out, std::ostream& err, bool progress_tty);

}  // namespace cli
}  // namespace fcl_quadric
