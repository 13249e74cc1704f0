#pragma once
/// \file bench_support.h
/// Shared pieces of the benchmark programs: the ANCHORS.md pair generator, the `--pairs` option,
/// per-item timing counters, and a console reporter that adds the ratio to fcl_quadric and prints
/// a summary table at the end (docs/benchmarks.md). No FCL here (see fcl_peers.h).
///
/// The end-of-run blocks ("== Title ==" followed by lines, ended by a blank line) are copied
/// verbatim into docs/benchmarks.md by benchmarks/update_docs.sh: keep them free of blank lines.

#include <algorithm>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

#include <benchmark/benchmark.h>
#include <Eigen/Geometry>

#include "fcl_quadric/geometry/ellipsoid.h"

namespace fcl_quadric {
namespace bench {

/// Name suffix of the benchmark every other member of its group is compared with.
constexpr const char* kOursSuffix = "/fcl_quadric";

/// One ellipsoid of the ANCHORS.md generator, drawn in this order: radii 3x U(0.5, 3), centre
/// 3x U(-3, 3), quaternion (w, x, y, z) from 4x N(0, 1), normalised. A normal distribution is
/// created per quaternion; libstdc++ draws normals in pairs, so 4 draws leave no cached value and
/// a long-lived distribution would give the same stream.
inline Ellipsoid anchorEllipsoid(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u_radius(0.5, 3.0), u_centre(-3.0, 3.0);
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Vector3d radii, p_WE;
  for (int i = 0; i < 3; ++i) radii[i] = u_radius(rng);
  for (int i = 0; i < 3; ++i) p_WE[i] = u_centre(rng);
  const double w = n(rng), x = n(rng), y = n(rng), z = n(rng);
  const Eigen::Quaterniond q = Eigen::Quaterniond(w, x, y, z).normalized();
  return Ellipsoid(radii, q.toRotationMatrix(), p_WE);
}

/// The ANCHORS.md pair set: std::mt19937_64(42), per pair ellipsoid A then B.
struct PairSet {
  std::vector<Ellipsoid> a, b;
  std::size_t size() const { return a.size(); }
};

inline PairSet anchorPairs(std::size_t n, std::uint64_t seed = 42) {
  std::mt19937_64 rng(seed);
  PairSet s;
  s.a.reserve(n);
  s.b.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    s.a.push_back(anchorEllipsoid(rng));
    s.b.push_back(anchorEllipsoid(rng));
  }
  return s;
}

/// Reads `--<name> N` or `--<name>=N` from argv and removes it (before benchmark::Initialize);
/// else the environment variable `env`; else `fallback`.
/// Removes `--name` from argv; true if it was there or the environment variable is set (not "0").
inline bool takeFlag(int* argc, char** argv, const char* name, const char* env) {
  bool value = false;
  if (const char* e = std::getenv(env)) value = e[0] != '\0' && std::strcmp(e, "0") != 0;
  const std::string flag = std::string("--") + name;
  int out = 1;
  for (int i = 1; i < *argc; ++i) {
    if (flag == argv[i]) {
      value = true;
    } else {
      argv[out++] = argv[i];
    }
  }
  *argc = out;
  argv[out] = nullptr;
  return value;
}

/// The 1, 5 and 15 minute load averages ("unknown" if /proc/loadavg cannot be read).
inline std::string loadAverage() {
  std::ifstream f("/proc/loadavg");
  double a = 0, b = 0, c = 0;
  if (!(f >> a >> b >> c)) return "unknown";
  char text[64];
  std::snprintf(text, sizeof text, "%.2f %.2f %.2f", a, b, c);
  return text;
}

inline std::size_t takeSizeOption(int* argc, char** argv, const char* name, const char* env,
                                  std::size_t fallback) {
  std::size_t value = fallback;
  if (const char* e = std::getenv(env)) value = std::strtoull(e, nullptr, 10);
  const std::string flag = std::string("--") + name;
  int out = 1;
  for (int i = 1; i < *argc; ++i) {
    const char* arg = argv[i];
    if (flag == arg && i + 1 < *argc) {
      value = std::strtoull(argv[++i], nullptr, 10);
    } else if (std::strncmp(arg, (flag + "=").c_str(), flag.size() + 1) == 0) {
      value = std::strtoull(arg + flag.size() + 1, nullptr, 10);
    } else {
      argv[out++] = argv[i];
    }
  }
  *argc = out;
  argv[out] = nullptr;
  return std::max<std::size_t>(value, 1);
}

/// printf into a std::string (at most 511 characters).
__attribute__((format(printf, 1, 2))) inline std::string strprintf(const char* fmt, ...) {
  char buf[512];
  va_list args;
  va_start(args, fmt);
  std::vsnprintf(buf, sizeof buf, fmt, args);
  va_end(args);
  return buf;
}

/// Console options for SummaryReporter, from `--benchmark_color` in argv (read before
/// benchmark::Initialize, which consumes the flag). A reporter passed to RunSpecifiedBenchmarks is
/// not configured by Google Benchmark, so without this the flag would be ignored and saved outputs
/// would carry colour escapes. Like Google Benchmark: "auto" (the default) means colour only on a
/// terminal. Counters are always printed as table columns.
inline benchmark::ConsoleReporter::OutputOptions consoleOutputOptions(int argc, char** argv) {
  std::string color = "auto";
  const std::string flag = "--benchmark_color";
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == flag) {
      color = "true";
    } else if (arg.compare(0, flag.size() + 1, flag + "=") == 0) {
      color = arg.substr(flag.size() + 1);
    }
  }
  bool use_color = false;
  if (color == "auto") {
    use_color = isatty(STDOUT_FILENO) != 0;
  } else {
    use_color = color == "true" || color == "yes" || color == "1" || color == "on";
  }
  return use_color ? benchmark::ConsoleReporter::OO_ColorTabular : benchmark::ConsoleReporter::OO_Tabular;
}

/// Marks `items` units of work (pairs or frames) done per iteration: Google Benchmark then reports
/// items_per_second and `counter_name` = CPU seconds per item (printed as e.g. "612n" = 612 ns).
inline void setPerItemTime(benchmark::State& state, double items_per_iteration,
                           const char* counter_name = "t_pair") {
  const double items = items_per_iteration * static_cast<double>(state.iterations());
  state.SetItemsProcessed(static_cast<std::int64_t>(items));
  state.counters[counter_name] =
      benchmark::Counter(items, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

/// The names given to registerBenchmark(), in registration order: the order of the summary table
/// whatever order the runs come in (--benchmark_enable_random_interleaving shuffles them).
inline std::vector<std::string>& registrationOrder() {
  static std::vector<std::string> names;
  return names;
}

/// benchmark::RegisterBenchmark(name, ...), remembering the name for the summary's order.
template <class... Args>
benchmark::internal::Benchmark* registerBenchmark(const char* name, Args&&... args) {
  registrationOrder().emplace_back(name);
  return benchmark::RegisterBenchmark(name, std::forward<Args>(args)...);
}

/// Console reporter that (1) adds `x_ours` = (time per item) / (time per item of the group's
/// "<group>/fcl_quadric" run) to every other member of the group whose baseline has already run
/// (with random interleaving it may run later: then the console line has no x_ours, the summary
/// still has the ratio), and (2) remembers every run for a summary table printed by
/// printSummary(), in registration order (registerBenchmark()). Group = name up to the last '/'.
/// With --benchmark_repetitions the summary keeps the median aggregate.
class SummaryReporter : public benchmark::ConsoleReporter {
 public:
  struct Row {
    std::string name;
    double ns_per_item = 0.0;
    double cv = -1.0;  ///< coefficient of variation of CPU time over repetitions; < 0: none
  };

  explicit SummaryReporter(OutputOptions options) : ConsoleReporter(options) {}

  void ReportRuns(const std::vector<Run>& reports) override {
    std::vector<Run> copy = reports;
    for (Run& run : copy) {
      if (run.run_type == Run::RT_Aggregate && run.aggregate_name == "cv" && !run.error_occurred) {
        // Google Benchmark stores the coefficient of variation (a fraction) in the time fields.
        const std::string name = run.run_name.str();
        for (Row& r : rows_) {
          if (r.name == name) r.cv = run.cpu_accumulated_time;
        }
        continue;
      }
      // With --benchmark_repetitions the median aggregate, reported last, is the one kept.
      const bool median = run.run_type == Run::RT_Aggregate && run.aggregate_name == "median";
      if ((run.run_type != Run::RT_Iteration && !median) || run.error_occurred) continue;
      const auto it = run.counters.find("items_per_second");
      if (it == run.counters.end() || !(it->second.value > 0.0)) continue;
      const double ns = 1e9 / it->second.value;
      const std::string name = run.run_name.str();
      const Row row{name, ns, -1.0};
      if (const double baseline = nsPerItem(baselineOf(name)); baseline > 0.0 && !isBaseline(name)) {
        run.counters["x_ours"] = benchmark::Counter(ns / baseline);
      }
      const auto same = std::find_if(rows_.begin(), rows_.end(), [&](const Row& r) { return r.name == name; });
      if (same != rows_.end()) {
        *same = row;
      } else {
        rows_.push_back(row);
      }
    }
    ConsoleReporter::ReportRuns(copy);
  }

  /// Time per item of the run with this exact name, or 0 if it did not run.
  double nsPerItem(const std::string& name) const {
    for (const Row& r : rows_) {
      if (r.name == name) return r.ns_per_item;
    }
    return 0.0;
  }

  /// Ratio of the times per item of two runs (numerator / denominator), or 0 if either is missing.
  double ratio(const std::string& numerator, const std::string& denominator) const {
    const double n = nsPerItem(numerator), d = nsPerItem(denominator);
    return n > 0.0 && d > 0.0 ? n / d : 0.0;
  }

  /// Prints "name | ns per item | x fcl_quadric | CV" for every run, in registration order (runs
  /// of names not registered through registerBenchmark() last, in run order).
  void printSummary(const char* title, const char* item) const {
    bool any_cv = false;
    for (const Row& r : rows_) any_cv = any_cv || r.cv >= 0.0;
    std::printf("\n== %s (%s) ==\n", title,
                any_cv ? "median of the repetitions; CV = coefficient of variation over them"
                       : "one run, no repetitions");
    std::printf("%-52s %14s %14s %8s\n", "benchmark", (std::string("ns/") + item).c_str(), "x fcl_quadric",
                "CV");
    std::vector<Row> rows = rows_;
    std::stable_sort(rows.begin(), rows.end(),
                     [](const Row& x, const Row& y) { return registrationIndex(x.name) < registrationIndex(y.name); });
    for (const Row& r : rows) {
      char ratio_text[32] = "-", cv_text[32] = "-";
      if (const double q = ratio(r.name, baselineOf(r.name)); q > 0.0 && !isBaseline(r.name)) {
        std::snprintf(ratio_text, sizeof ratio_text, "%.2f", q);
      }
      if (r.cv >= 0.0) std::snprintf(cv_text, sizeof cv_text, "%.1f %%", 100.0 * r.cv);
      std::printf("%-52s %14.1f %14s %8s\n", r.name.c_str(), r.ns_per_item, ratio_text, cv_text);
    }
    std::fflush(stdout);
  }

 private:
  /// "<group>/fcl_quadric" for a run "<group>/<peer>".
  static std::string baselineOf(const std::string& name) {
    return name.substr(0, name.rfind('/')) + kOursSuffix;
  }
  static bool isBaseline(const std::string& name) { return endsWith(name, kOursSuffix); }
  /// The position of the registered name a run's name is or starts with ("name/arg" for a
  /// benchmark with arguments); unregistered names sort last.
  static std::size_t registrationIndex(const std::string& run_name) {
    const std::vector<std::string>& order = registrationOrder();
    for (std::size_t i = 0; i < order.size(); ++i) {
      if (run_name == order[i] || run_name.compare(0, order[i].size() + 1, order[i] + "/") == 0) return i;
    }
    return order.size();
  }
  static bool endsWith(const std::string& s, const char* suffix) {
    const std::size_t n = std::strlen(suffix);
    return s.size() >= n && s.compare(s.size() - n, n, suffix) == 0;
  }
  std::vector<Row> rows_;
};

/// Median / 99th percentile / max of a sample (copied; empty sample gives zeros).
struct Quantiles {
  double median = 0.0, p99 = 0.0, max = 0.0;
  std::size_t count = 0;
};

inline Quantiles quantiles(std::vector<double> v) {
  Quantiles q;
  q.count = v.size();
  if (v.empty()) return q;
  std::sort(v.begin(), v.end());
  q.median = v[v.size() / 2];
  q.p99 = v[std::min(v.size() - 1, static_cast<std::size_t>(0.99 * static_cast<double>(v.size())))];
  q.max = v.back();
  return q;
}

}  // namespace bench
}  // namespace fcl_quadric
