// libFuzzer target: the fcl_quadric program's input paths (docs/reliability.md): the scene JSON
// reader and the `check`, `ccd` and `demo` subcommands, driven through cli::run as the program
// runs them. The first byte picks the command:
//   0: check SCENE   1: ccd SCENE   (the rest of the input is the scene file's content)
//   2: the rest is a command line: arguments separated by '\n' (demo options mostly; numbers other
//      than a --seed value are capped at 20 to keep each execution short).
// Properties:
//  - the exit status is 0 or 2 (bad input), never 1 (internal error: a library exception that the
//    scene reader should have prevented, or a bug); on 2, exactly one line "fcl_quadric: error: ..."
//    on stderr and nothing on stdout;
//  - on success the output is JSON without NaN (a NaN would print as null where a number is due):
//    check: status, collide and signed_distance agree; ccd: first_contact_time is null exactly for
//    collision-free pairs and inside [0, 1];
//  - symmetry: checkScene with every pair reversed gives the same collide flags (pairs with an
//    ellipsoid or sphere; box-box pairs are FCL's).
#include <unistd.h>

#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fcl_quadric/check_command.h"
#include "fcl_quadric/cli.h"
#include "fcl_quadric/scene.h"
#include "fuzz_common.h"

using namespace fcl_quadric;

namespace {

std::string scenePath() {
  static const std::string path = [] {
    const char* dir = std::getenv("TMPDIR");
    return std::string(dir && *dir ? dir : "/tmp") + "/fcl_quadric_fuzz_scene." + std::to_string(getpid()) + ".json";
  }();
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
  const auto doc = nlohmann::json::parse(out);  // must be valid JSON (throws -> crash otherwise)
  for (const auto& pair : doc.at("pairs")) {
    const bool collide = pair.at("collide").get<bool>();
    if (command == "check") {
      FUZZ_CHECK(pair.at("signed_distance").is_number(), "check: signed_distance is %s",
                 pair.at("signed_distance").dump().c_str());
      const double d = pair.at("signed_distance").get<double>();
      const std::string status = pair.at("status").get<std::string>();
      FUZZ_CHECK(collide == (status != "separate"), "check: collide %d with status %s", collide, status.c_str());
      if (pair.at("method") == "exact") {  // the sign of FCL's own box-box answers is FCL's business
        if (status == "separate") FUZZ_CHECK(d >= 0, "check: separated at distance %g", d);
        if (status == "overlapping") FUZZ_CHECK(d <= 0, "check: overlapping at distance %g", d);
      }
      for (const auto& p : pair.at("points"))
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

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const int mode = data[0] % 3;
  const std::string body(reinterpret_cast<const char*>(data) + 1, size - 1);
  std::vector<std::string> args{"fcl_quadric"};
  if (mode == 2) {
    std::istringstream lines(body);
    std::string arg;
    bool after_seed = false;
    while (std::getline(lines, arg) && args.size() < 8) {
      const bool is_seed = after_seed || arg.rfind("--seed=", 0) == 0;
      if (!is_seed && hasNumberAbove(arg, 20)) return 0;
      after_seed = arg == "--seed";
      args.push_back(arg);
    }
  } else {
    // Keep each execution short: small files, at most 28 pairs.
    if (body.size() > 4096) return 0;
    try {
      if (cli::parseSceneText(body).pairs.size() > 28) return 0;
    } catch (const cli::SceneError&) {
    }
    std::ofstream(scenePath(), std::ios::binary) << body;
    args.push_back(mode == 0 ? "check" : "ccd");
    args.push_back(scenePath());
  }
  std::vector<const char*> argv;
  for (const auto& a : args) argv.push_back(a.c_str());
  std::ostringstream out, err;
  const int status = cli::run(static_cast<int>(argv.size()), argv.data(), out, err);
  checkOutput(status, out.str(), err.str(), args.size() > 1 ? args[1] : "");
  if (mode == 0 && status == cli::kExitOk) checkSymmetry(body);
  return 0;
}
