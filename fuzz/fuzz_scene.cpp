// libFuzzer target: the fcl_quadric program's input paths (docs/reliability.md): the scene JSON
// reader and every subcommand (check, ccd, demo, render, plot, bench), driven through cli::run as
// the program runs them. The first byte (mod 6) picks the command:
//   0: check SCENE   1: ccd SCENE   (the rest of the input is the scene file's content)
//   2: the rest is a command line: arguments separated by '\n' (demo options mostly; numbers other
//      than a --seed value are capped at 20 to keep each execution short; demo's pictures go to a
//      scratch directory, and render / plot / bench have their own modes so that no file is
//      written where the input says);
//   3: render, 4: plot (fuzzPicture: an options byte, an argument byte, the scene file);
//   5: bench --size tiny (fuzzBench: "SIZE\nONLY").
// Properties:
//  - the exit status is 0 or 2 (bad input), never 1 (internal error: a library exception that the
//    scene reader should have prevented, or a bug); on 2, exactly one line "fcl_quadric: error: ..."
//    on stderr and nothing on stdout;
//  - on success the output is JSON without NaN (a NaN would print as null where a number is due):
//    check: status, collide and signed_distance agree; ccd: first_contact_time is null exactly for
//    collision-free pairs and inside [0, 1];
//  - render / plot: on success the picture exists and reads back (well-formed SVG with an <svg>
//    root, or a PNG Cairo decodes); bench: bench.json parses, its rows are well formed, its charts
//    are readable PNGs;
//  - symmetry: checkScene with every pair reversed gives the same collide flags (pairs with an
//    ellipsoid or sphere; box-box pairs are FCL's).
#include <unistd.h>

#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <cairo.h>

#include "fcl_quadric/bench_command.h"
#include "fcl_quadric/check_command.h"
#include "fcl_quadric/cli.h"
#include "fcl_quadric/scene.h"
#include "fuzz_common.h"
#include "support/picture_files.h"

using namespace fcl_quadric;

namespace {

/// A scratch file or directory of this process under $TMPDIR (never the working directory).
std::string scratchPath(const std::string& name) {
  const char* dir = std::getenv("TMPDIR");
  return std::string(dir && *dir ? dir : "/tmp") + "/fcl_quadric_fuzz_scene." + std::to_string(getpid()) + "." + name;
}

std::string scenePath() {
  static const std::string path = scratchPath("json");
  return path;
}

/// True if some run of digits in `s` is a number above `limit`.
bool hasNumberAbove(const std::string& s, unsigned long limit) {
  for (std::size_t i = 0; i < s.size();) {
    if (!std::isdigit(static_cast<unsigned char>(s[i]))) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j < s.size() && std::isdigit(static_cast<unsigned char>(s[j]))) ++j;
    if (j - i > 6 || std::stoul(s.substr(i, j - i)) > limit) return true;
    i = j;
  }
  return false;
}

void checkOutput(int status, const std::string& out, const std::string& err, const std::string& command) {
  FUZZ_CHECK(status == cli::kExitOk || status == cli::kExitBadInput, "%s: exit status %d, stderr: %s",
             command.c_str(), status, err.c_str());
  if (status != cli::kExitOk) {
    FUZZ_CHECK(out.empty(), "%s: output on failure", command.c_str());
    FUZZ_CHECK(err.rfind("fcl_quadric: error: ", 0) == 0 && err.find('\n') == err.size() - 1,
               "%s: diagnostic is not one line: %s", command.c_str(), err.c_str());
    return;
  }
  if (command != "check" && command != "ccd") return;
  if (out.rfind('{', 0) != 0) {
    // A command line with -h among its arguments (alone or in a group of short flags) prints the
    // subcommand's help and exits 0: CLI11's help wins over every other problem of the command
    // line (found by fuzz_scene in session 51: `check -h...` after three junk arguments; corpus
    // file regression_check_help). Anything else that is not JSON fails below.
    if (out.find("Usage: fcl_quadric " + command) != std::string::npos) return;
  }
  const auto doc = nlohmann::json::parse(out);  // must be valid JSON (throws -> crash otherwise)
  for (const auto& pair : doc.at("pairs")) {
    const bool collide = pair.at("collide").get<bool>();
    if (command == "check") {
      const std::string status = pair.at("status").get<std::string>();
      FUZZ_CHECK(collide == (status != "separate"), "check: collide %d with status %s", collide, status.c_str());
      // Quadric shapes (method quadric_region): a signed distance for convex pairs, else null and
      // a witness point only on contact (examples/README.md). Every other pair has both.
      const bool region = pair.at("method") == "quadric_region";
      const auto& sd = pair.at("signed_distance");
      FUZZ_CHECK((region && sd.is_null()) || sd.is_number(), "check: signed_distance is %s (method %s)",
                 sd.dump().c_str(), pair.at("method").dump().c_str());
      if ((pair.at("method") == "exact" || region) && sd.is_number()) {
        // The sign of FCL's own box-box answers is FCL's business; ours must match the status (a
        // quadric pair's distance is given only when it certifies the engine's status; touching: 0).
        const double d = sd.get<double>();
        if (status == "separate") FUZZ_CHECK(d >= 0, "check: separated at distance %g", d);
        if (status == "overlapping") FUZZ_CHECK(d <= 0, "check: overlapping at distance %g", d);
        if (region && status == "touching") FUZZ_CHECK(d == 0, "check: touching at distance %g", d);
      }
      const auto& points = pair.at("points");
      FUZZ_CHECK(!points.is_null() || (region && !collide && sd.is_null()), "check: no witness points (method %s, collide %d)",
                 pair.at("method").dump().c_str(), collide);
      if (!points.is_null())
        for (const auto& p : points)
          for (const auto& x : p) FUZZ_CHECK(x.is_number(), "check: witness coordinate %s", x.dump().c_str());
    } else {
      const auto& t = pair.at("first_contact_time");
      FUZZ_CHECK(collide == !t.is_null(), "ccd: collide %d, first_contact_time %s", collide, t.dump().c_str());
      if (collide) {
        FUZZ_CHECK(t.is_number() && t.get<double>() >= 0 && t.get<double>() <= 1, "ccd: time %s", t.dump().c_str());
        for (const auto& x : pair.at("contact_point"))
          FUZZ_CHECK(x.is_number(), "ccd: contact point coordinate %s", x.dump().c_str());
      }
    }
  }
}

void checkSymmetry(const std::string& text) {
  cli::Scene scene;
  try {
    scene = cli::parseSceneText(text);
  } catch (const cli::SceneError&) {
    return;
  }
  if (scene.dimension != 3 || scene.pairs.size() > 16) return;
  nlohmann::ordered_json forward, backward;
  try {
    forward = cli::checkScene(scene);
  } catch (const cli::SceneError&) {
    return;  // same as the program's exit status 2, already checked through cli::run
  }
  for (auto& p : scene.pairs) std::swap(p.first, p.second);
  backward = cli::checkScene(scene);
  for (std::size_t i = 0; i < scene.pairs.size(); ++i) {
    // Box-box pairs are FCL's (libccd), not ours: only the exact pairs must be symmetric.
    const auto [p, q] = scene.pairs[i];
    if (!cli::isEllipsoidal(scene.objects[p].shape) && !cli::isEllipsoidal(scene.objects[q].shape)) continue;
    const bool f = forward["pairs"][i]["collide"].get<bool>(), b = backward["pairs"][i]["collide"].get<bool>();
    FUZZ_CHECK(f == b, "pair %zu: collide %d forward, %d reversed", i, f, b);
  }
}


enum Mode { kCheck, kCcd, kCommandLine, kRender, kPlot, kBench, kModes };

/// Keeps each execution short: small scene files with at most 28 pairs.
bool shortScene(const std::string& body) {
  if (body.size() > 4096) return false;
  try {
    if (cli::parseSceneText(body).pairs.size() > 28) return false;
  } catch (const cli::SceneError&) {
  }
  return true;
}

/// A picture the CLI reported as written must be there and be a valid SVG / PNG: well-formed XML
/// with one <svg> root, or a PNG that Cairo reads back with a non-empty size.
void checkPicture(const std::string& path, bool png, const std::string& command) {
  namespace fs = std::filesystem;
  FUZZ_CHECK(fs::exists(path), "%s: exit 0 but no picture at %s", command.c_str(), path.c_str());
  if (png) {
    cairo_surface_t* image = cli::test::readPng(path);
    const bool ok = cairo_surface_status(image) == CAIRO_STATUS_SUCCESS &&
                    cairo_image_surface_get_width(image) > 0 && cairo_image_surface_get_height(image) > 0;
    cairo_surface_destroy(image);
    FUZZ_CHECK(ok, "%s: %s is not a readable PNG", command.c_str(), path.c_str());
  } else {
    const std::string problem = cli::test::xmlProblem(cli::test::readFile(path), "svg");
    FUZZ_CHECK(problem.empty(), "%s: %s is not well-formed SVG: %s", command.c_str(), path.c_str(), problem.c_str());
  }
}

/// Modes render and plot. Input: one options byte, one argument byte, then the scene file.
///  render SCENE -o OUT [--time T]: options bit 0 PNG (else SVG), bit 1 --time given, with
///    T = argument / 200 - 0.1 (so also outside [0, 1], a documented error);
///  plot KIND SCENE -o OUT [--pair I,J]: options bits 2-3 pick ccd-function, discriminant,
///    timeline or an unknown kind; bit 1 --pair given, I,J from the argument byte's two nibbles
///    (mod 5: an index past the scene's objects is a documented error).
int fuzzPicture(int mode, const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  const std::uint8_t options = data[0], argument = data[1];
  const std::string body(reinterpret_cast<const char*>(data) + 2, size - 2);
  if (!shortScene(body)) return 0;
  std::ofstream(scenePath(), std::ios::binary) << body;
  const bool png = options & 1;
  const std::string output = scratchPath(png ? "picture.png" : "picture.svg");
  std::filesystem::remove(output);
  std::vector<std::string> args;
  if (mode == kRender) {
    args = {"render", scenePath(), "-o", output};
    if (options & 2) args.insert(args.end(), {"--time", std::to_string(argument / 200.0 - 0.1)});
  } else {
    static const char* const kKinds[] = {"ccd-function", "discriminant", "timeline", "zero-set"};
    args = {"plot", kKinds[(options >> 2) & 3], scenePath(), "-o", output};
    if (options & 2)
      args.insert(args.end(), {"--pair", std::to_string((argument >> 4) % 5) + "," + std::to_string((argument & 15) % 5)});
  }
  const cli::test::RunResult r = cli::test::runCli(args);
  checkOutput(r.status, r.out, r.err, args[0]);  // exit status 0 or 2 with the one-line diagnostic
  if (r.status == cli::kExitOk) checkPicture(output, png, args[0]);
  return 0;
}

/// Mode bench: the rest is "SIZE\nONLY" (either may be empty: the defaults). Runs
/// `bench --size SIZE --out SCRATCH [--only ONLY]`. To keep executions short, sizes other than
/// tiny and lists naming the three slower experiments (random, near_tangent, separating_planes:
/// 0.1-0.3 s each in Release, ten times that under ASan) are not run when valid; invalid ones
/// always are (they must fail with status 2 before anything runs). On success bench.json must
/// parse, with a finite time >= 0, n > 0 and wrong null (not counted) or >= 0 in every row, and every chart it
/// names must be a readable PNG.
int fuzzBench(const std::uint8_t* data, std::size_t size) {
  const std::string body(reinterpret_cast<const char*>(data), size);
  const std::size_t newline = body.find('\n');
  // Arguments reach the CLI as C strings (runCli passes c_str()), cut at their first NUL: the
  // checks below must see what the CLI sees. (Checking the whole string once let "tiny" with an
  // --only of "\0..." pass as invalid while the CLI read an empty list, i.e. every experiment:
  // a 30 s timeout under ASan.)
  auto asArgument = [](std::string s) { return s.substr(0, s.find('\0')); };
  const std::string size_arg = asArgument(body.substr(0, newline));
  const std::string only = newline == std::string::npos ? std::string() : asArgument(body.substr(newline + 1));
  if (size_arg.size() > 16 || only.size() > 96) return 0;
  try {
    if (cli::parseBenchSize(size_arg.empty() ? "small" : size_arg) != cli::BenchSize::kTiny) return 0;
    for (const std::string& name : cli::parseBenchOnly(only))
      if (name == "random" || name == "near_tangent" || name == "separating_planes") return 0;
  } catch (const cli::SceneError&) {
    // Invalid: run it, it must be rejected cleanly.
  }
  const std::string dir = scratchPath("bench");
  std::filesystem::remove_all(dir);
  std::vector<std::string> args{"bench", "--out", dir};
  if (!size_arg.empty()) args.insert(args.end(), {"--size", size_arg});
  if (newline != std::string::npos) args.insert(args.end(), {"--only", only});
  const cli::test::RunResult r = cli::test::runCli(args);
  checkOutput(r.status, r.out, r.err, "bench");
  if (r.status != cli::kExitOk) return 0;
  const auto doc = nlohmann::json::parse(cli::test::readFile(dir + "/bench.json"));
  for (const auto& row : doc.at("results")) {
    const auto& ns = row.at("ns_per_query");
    FUZZ_CHECK(ns.is_number() && std::isfinite(ns.get<double>()) && ns.get<double>() >= 0, "bench: ns_per_query %s",
               ns.dump().c_str());
    const auto& wrong = row.at("wrong");  // null: not counted for that peer
    FUZZ_CHECK(row.at("n").get<long long>() > 0 && (wrong.is_null() || wrong.get<long long>() >= 0), "bench: row %s",
               row.dump().c_str());
  }
  for (const auto& e : doc.at("experiments")) checkPicture(dir + "/" + e.at("chart").get<std::string>(), true, "bench");
  return 0;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const int mode = data[0] % kModes;
  if (mode == kRender || mode == kPlot) return fuzzPicture(mode, data + 1, size - 1);
  if (mode == kBench) return fuzzBench(data + 1, size - 1);
  const std::string body(reinterpret_cast<const char*>(data) + 1, size - 1);
  std::vector<std::string> args{"fcl_quadric"};
  if (mode == kCommandLine) {
    std::istringstream lines(body);
    std::string arg;
    bool after_seed = false;
    while (std::getline(lines, arg) && args.size() < 8) {
      // The CLI sees each argument as a C string (runCli passes c_str()), cut at its first NUL:
      // judge what it sees ("bench\0..." is `bench`, which this mode must not run; finding 17).
      arg = arg.substr(0, arg.find('\0'));
      const bool is_seed = after_seed || arg.rfind("--seed=", 0) == 0;
      if (!is_seed && hasNumberAbove(arg, 20)) return 0;
      // Files are written only where this target says: the commands that write pictures or
      // results have their own modes, and demo's --pictures is set below.
      if (arg == "render" || arg == "plot" || arg == "bench" || arg.rfind("--pictures", 0) == 0) return 0;
      after_seed = arg == "--seed";
      args.push_back(arg);
    }
    if (args.size() > 1 && args[1] == "demo") {
      args.push_back("--pictures");
      args.push_back(scratchPath("demo"));
    }
  } else {
    if (!shortScene(body)) return 0;
    std::ofstream(scenePath(), std::ios::binary) << body;
    args.push_back(mode == kCheck ? "check" : "ccd");
    args.push_back(scenePath());
  }
  const cli::test::RunResult r = cli::test::runCli({args.begin() + 1, args.end()});
  checkOutput(r.status, r.out, r.err, args.size() > 1 ? args[1] : "");
  if (mode == kCheck && r.status == cli::kExitOk) checkSymmetry(body);
  return 0;
}
