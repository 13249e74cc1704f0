#include "fcl_quadric/bench_command.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "benchmarks/bench_support.h"
#include "fcl_quadric/bench_chart.h"
#include "fcl_quadric/scene.h"

namespace fcl_quadric {
namespace cli {

const std::vector<std::string>& benchExperimentNames() {
  static const std::vector<std::string> names = {"random", "near_tangent", "separating_planes", "boxing",
                                                 "arm",    "broadphase",   "octree",            "quadric_shapes"};
  return names;
}

BenchExperiment runBenchExperiment(const std::string& name, BenchSize size, const BenchProgress& progress) {
  if (name == "random") return runRandomPairsExperiment(size, progress);
  if (name == "near_tangent") return runNearTangentExperiment(size, progress);
  if (name == "separating_planes") return runSeparatingPlanesExperiment(size, progress);
  if (name == "boxing") return runBoxingExperiment(size, progress);
  if (name == "arm") return runArmExperiment(size, progress);
  if (name == "broadphase") return runBroadphaseExperiment(size, progress);
  if (name == "octree") return runOcTreeExperiment(size, progress);
  if (name == "quadric_shapes") return runQuadricShapesExperiment(size, progress);
  throw SceneError("", "unknown experiment '" + name + "'");
}

namespace {

std::string knownNames() {
  std::string s;
  for (const std::string& n : benchExperimentNames()) s += (s.empty() ? "" : ", ") + n;
  return s;
}

const char* sizeName(BenchSize s) { return s == BenchSize::kTiny ? "tiny" : s == BenchSize::kSmall ? "small" : "full"; }

/// Fills the ratios: time / the fcl_quadric row of the same case.
void fillRatios(BenchExperiment* e) {
  for (BenchRow& r : e->rows) {
    r.ratio = 0.0;
    for (const BenchRow& base : e->rows) {
      if (base.case_name == r.case_name && base.peer == "fcl_quadric" && base.ns_per_query > 0.0) {
        r.ratio = r.ns_per_query / base.ns_per_query;
      }
    }
  }
}

using bench::strprintf;

void printTable(const BenchExperiment& e, std::ostream& out) {
  out << "\n== " << e.name << ": " << e.title << " ==\n";
  std::size_t case_width = 4, peer_width = 4;
  for (const BenchRow& r : e.rows) {
    case_width = std::max(case_width, r.case_name.size());
    peer_width = std::max(peer_width, r.peer.size());
  }
  const int cw = static_cast<int>(case_width), pw = static_cast<int>(peer_width);
  out << strprintf("%-*s  %-*s %9s %14s %14s %8s\n", cw, "case", pw, "peer", "n", ("ns/" + e.unit).c_str(),
                      "x fcl_quadric", "wrong");
  for (const BenchRow& r : e.rows) {
    const std::string ratio = r.ratio > 0.0 ? strprintf("%.2f", r.ratio) : "-";
    const std::string wrong = r.wrong >= 0 ? std::to_string(r.wrong) : "-";
    out << strprintf("%-*s  %-*s %9zu %14.1f %14s %8s\n", cw, r.case_name.c_str(), pw, r.peer.c_str(), r.n,
                        r.ns_per_query, ratio.c_str(), wrong.c_str());
  }
  for (const std::string& note : e.notes) out << "  " << note << "\n";
  out << "  wrong: answers that differ from the exact answer: " << e.truth << "\n";
}

nlohmann::ordered_json rowJson(const BenchExperiment& e, const BenchRow& r) {
  nlohmann::ordered_json j;
  j["experiment"] = e.name;
  j["case"] = r.case_name;
  j["peer"] = r.peer;
  j["n"] = r.n;
  j["ns_per_query"] = r.ns_per_query;
  j["ratio"] = r.ratio;
  j["wrong"] = r.wrong >= 0 ? nlohmann::ordered_json(r.wrong) : nlohmann::ordered_json(nullptr);
  return j;
}

std::string utcNow() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

/// Progress on stderr: a bar redrawn in place on a terminal, else one line per experiment.
class ProgressBar {
 public:
  ProgressBar(std::ostream& err, bool tty, std::size_t index, std::size_t count, const std::string& name)
      : err_(err), tty_(tty), prefix_(strprintf("[%zu/%zu] %-18s", index, count, name.c_str())) {
    start_ = std::chrono::steady_clock::now();
    if (tty_) {
      update(0.0);
    } else {
      err_ << "fcl_quadric bench: " << prefix_ << " running\n";
      err_.flush();
    }
  }
  void update(double fraction) {
    if (!tty_) return;
    fraction = std::min(1.0, std::max(0.0, fraction));
    const int width = 30, filled = static_cast<int>(std::lround(fraction * width));
    err_ << "\r" << prefix_ << " [" << std::string(static_cast<std::size_t>(filled), '#')
         << std::string(static_cast<std::size_t>(width - filled), '.') << "] "
         << strprintf("%3d%%  %5.1f s", static_cast<int>(std::lround(100 * fraction)), seconds());
    err_.flush();
  }
  void done() {
    if (tty_) {
      update(1.0);
      err_ << "\n";
    } else {
      err_ << "fcl_quadric bench: " << prefix_ << strprintf(" done in %.1f s\n", seconds());
    }
    err_.flush();
  }

 private:
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  std::ostream& err_;
  bool tty_;
  std::string prefix_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace

BenchSize parseBenchSize(const std::string& text) {
  if (text == "tiny") return BenchSize::kTiny;
  if (text == "small") return BenchSize::kSmall;
  if (text == "full") return BenchSize::kFull;
  throw SceneError("", "unknown --size '" + text + "' (known: tiny, small, full)");
}

std::vector<std::string> parseBenchOnly(const std::string& list) {
  if (list.empty()) return benchExperimentNames();
  std::vector<std::string> wanted;
  std::stringstream in(list);
  std::string name;
  while (std::getline(in, name, ',')) {
    bool known = false;
    for (const std::string& n : benchExperimentNames()) known = known || n == name;
    if (!known) throw SceneError("", "unknown experiment '" + name + "' in --only (known: " + knownNames() + ")");
    wanted.push_back(name);
  }
  if (wanted.empty()) throw SceneError("", "empty --only list (known: " + knownNames() + ")");
  // Run order, each once.
  std::vector<std::string> ordered;
  for (const std::string& n : benchExperimentNames()) {
    for (const std::string& w : wanted) {
      if (w == n) {
        ordered.push_back(n);
        break;
      }
    }
  }
  return ordered;
}

void runBench(const BenchOptions& options, std::ostream& out, std::ostream& err, bool progress_tty) {
  const BenchSize size = parseBenchSize(options.size);
  const std::vector<std::string> names = parseBenchOnly(options.only);
  // The output directory must be writable before anything runs.
  const std::filesystem::path dir(options.out.empty() ? "." : options.out);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  const std::filesystem::path json_path = dir / "bench.json";
  {
    std::ofstream probe(json_path);
    if (ec || !probe) {
      throw SceneError("", "cannot write to --out '" + options.out + "'" + (ec ? ": " + ec.message() : std::string()));
    }
  }

  nlohmann::ordered_json document;
  document["command"] = "fcl_quadric bench --size " + std::string(sizeName(size)) +
                        (options.only.empty() ? std::string() : " --only " + options.only);
  document["date"] = utcNow();
  nlohmann::ordered_json experiments = nlohmann::ordered_json::array();
  nlohmann::ordered_json results = nlohmann::ordered_json::array();
  out << "fcl_quadric bench --size " << sizeName(size) << " (" << document["date"].get<std::string>()
      << "; CPU time of this thread per query; same inputs for every peer)\n";
  for (std::size_t i = 0; i < names.size(); ++i) {
    ProgressBar bar(err, progress_tty, i + 1, names.size(), names[i]);
    BenchExperiment e = runBenchExperiment(names[i], size, [&](double f) { bar.update(f); });
    fillRatios(&e);
    const std::string chart = "bench_" + e.name + ".png";
    writeBenchChart(e, (dir / chart).string());
    bar.done();
    printTable(e, out);
    nlohmann::ordered_json x;
    x["name"] = e.name;
    x["title"] = e.title;
    x["unit"] = e.unit;
    x["chart"] = chart;
    x["notes"] = e.notes;
    x["exact_answer"] = e.truth;
    experiments.push_back(std::move(x));
    for (const BenchRow& r : e.rows) results.push_back(rowJson(e, r));
  }
  document["experiments"] = std::move(experiments);
  document["results"] = std::move(results);
  std::ofstream json(json_path);
  json << document.dump(2) << "\n";
  if (!json) throw SceneError("", "cannot write " + json_path.string());
  out << "\nwrote " << json_path.string() << " and " << names.size() << " chart(s) bench_<experiment>.png in "
      << dir.string() << "\n";
}

}  // namespace cli
}  // namespace fcl_quadric
