#include "fcl_quadric/cli.h"

#include <unistd.h>

#include <cstdint>
#include <exception>
#include <iostream>
#include <limits>
#include <optional>
#include <sstream>

#include <CLI/CLI.hpp>

#include "fcl_quadric/bench_command.h"
#include "fcl_quadric/ccd_command.h"
#include "fcl_quadric/check_command.h"
#include "fcl_quadric/demo_command.h"
#include "fcl_quadric/plot_command.h"
#include "fcl_quadric/render_command.h"
#include "fcl_quadric/scene.h"
#include "fcl_quadric/version.h"

namespace fcl_quadric {
namespace cli {

std::string errorLine(const std::string& message) {
  std::string line = "fcl_quadric: error: " + message;
  for (char& c : line) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = ' ';
  }
  while (!line.empty() && line.back() == ' ') line.pop_back();
  return line + "\n";
}

namespace {

/// A decimal integer in [0, 2^64), or nothing.
std::optional<std::uint64_t> parseSeed(const std::string& text) {
  if (text.empty() || text.size() > 20 || text.find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
  std::uint64_t value = 0;
  for (char c : text) {
    const auto digit = static_cast<std::uint64_t>(c - '0');
    if (value > (std::numeric_limits<std::uint64_t>::max() - digit) / 10) return std::nullopt;
    value = 10 * value + digit;
  }
  return value;
}

}  // namespace

int run(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
  CLI::App app{"fcl_quadric: exact collision detection of ellipsoids (with FCL).", "fcl_quadric"};
  app.set_version_flag("--version", std::string("fcl_quadric ") + FCL_QUADRIC_VERSION_STRING);
  app.require_subcommand(1);
  app.footer(
      "Exit status: 0 success, 1 internal error, 2 bad scene or usage.\n"
      "Run 'fcl_quadric COMMAND --help' for the options of a command.");

  std::string scene_path;
  CLI::App* check = app.add_subcommand(
      "check", "Classify the object pairs of a JSON scene and print status, signed distance, witness "
               "points and normal of each pair as JSON (objects with a motion at t = 0).");
  check->add_option("SCENE", scene_path, "Scene file (JSON; see examples/README.md)")->required();

  std::string ccd_scene_path;
  CLI::App* ccd = app.add_subcommand(
      "ccd", "Continuous collision over t in [0, 1] of the scene's moving objects (objects with a "
             "\"motion\"): first contact time, contact point and every overlap interval of each ellipsoid pair; "
             "first contact and the contacting boundary elements for pairs with quadric shapes or boxes; as JSON.");
  ccd->add_option("SCENE", ccd_scene_path, "Scene file (JSON with motions; see examples/README.md)")->required();
  std::string ccd_solver = "space-time";
  ccd->add_option("--solver", ccd_solver,
                  "Method for pairs with quadric shapes or boxes: space-time (the certified space-time search) or "
                  "reduction (thesis 6.2 dimension reduction first, the space-time search where it is undecided; "
                  "entries add \"method\")")
      ->check(CLI::IsMember({"space-time", "reduction"}))
      ->capture_default_str();

  std::string render_scene_path, render_output;
  double render_time = 0.0;
  CLI::App* render = app.add_subcommand(
      "render", "Draw a JSON scene to SVG or PNG in three orthographic views (top XY, front XZ, side YZ), "
                "colliding objects in red, contact points and separating planes marked.");
  render->add_option("SCENE", render_scene_path, "Scene file (JSON; see examples/README.md)")->required();
  render->add_option("-o,--output", render_output, "Picture to write: a .svg or .png file")->required();
  render->add_option("--time", render_time, "For scenes with motions: draw the poses at this time in [0, 1]")
      ->capture_default_str();

  std::string plot_kind, plot_scene_path, plot_pair, plot_output;
  CLI::App* plot = app.add_subcommand(
      "plot", "Plots that explain the continuous-collision algorithms, to SVG or PNG: ccd-function (zero set "
              "of the CCD function F(u, t) of a moving ellipsoid pair, contact instants marked), discriminant "
              "(Delta(t) of a moving ellipse pair of a planar scene), timeline (overlap intervals of every moving pair).");
  plot->add_option("KIND", plot_kind, "ccd-function, discriminant or timeline")
      ->required()
      ->check(CLI::IsMember({"ccd-function", "discriminant", "timeline"}));
  plot->add_option("SCENE", plot_scene_path, "Scene file (JSON with motions; see examples/README.md)")->required();
  plot->add_option("--pair", plot_pair, "The pair I,J to plot (object indices from 0, or names); ccd-function and discriminant");
  plot->add_option("-o,--output", plot_output, "Picture to write: a .svg or .png file")->required();

  DemoOptions demo_options;
  CLI::App* demo = app.add_subcommand(
      "demo", "Simulate spinning ellipsoids and compare classification with and without "
              "inter-frame coherence (PairCoherence).");
  demo->add_option("--frames", demo_options.frames, "Frames to simulate")
      ->check(CLI::Range(1, 100000000))
      ->capture_default_str();
  demo->add_option("--objects", demo_options.objects, "Number of ellipsoids")
      ->check(CLI::Range(2, 1000))
      ->capture_default_str();
  // The seed is read as text: CLI11 would wrap "-1" and saturate values beyond 2^64 - 1.
  std::string seed_text = std::to_string(demo_options.seed);
  demo->add_option("--seed", seed_text, "Seed of the scene generator (integer in [0, 2^64))")
      ->type_name("UINT")
      ->check([](const std::string& s) { return parseSeed(s) ? std::string() : "must be an integer in [0, 2^64), got " + s; })
      ->capture_default_str();
  std::string demo_pictures = "fcl_quadric_demo";
  demo->add_option("--pictures", demo_pictures,
                   "Directory for the pictures of the first and last frame (created if missing; \"\" for none)")
      ->capture_default_str();

  BenchOptions bench_options;
  CLI::App* bench = app.add_subcommand(
      "bench", "Benchmark suite: fcl_quadric against stock FCL 0.7 and Bullet on the same inputs in this process "
               "(random pairs, near-tangent pairs, the separating-planes paper's tables, the thesis' boxing and robot "
               "arm, a broad-phase scene, an OcTree, capped cylinders and CSG pairs); prints a table per experiment, writes DIR/bench.json and a bar chart per "
               "experiment.");
  bench->add_option("--size", bench_options.size, "tiny (seconds), small (about a minute) or full (the papers' sizes)")
      ->check([](const std::string& s) {
        return s == "tiny" || s == "small" || s == "full" ? std::string()
                                                          : "unknown size '" + s + "' (known: tiny, small, full)";
      })
      ->capture_default_str();
  bench->add_option("--out", bench_options.out, "Directory for bench.json and the charts (created if missing)")
      ->capture_default_str();
  bench->add_option("--only", bench_options.only,
                    "Comma-separated experiments to run (random, near_tangent, separating_planes, boxing, arm, "
                    "broadphase, octree, quadric_shapes); default all")
      ->check([](const std::string& s) {
        try {
          parseBenchOnly(s);
          return std::string();
        } catch (const SceneError& e) {
          return e.message();
        }
      });

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    out << app.help();
    return kExitOk;
  } catch (const CLI::CallForAllHelp&) {
    out << app.help("", CLI::AppFormatMode::All);
    return kExitOk;
  } catch (const CLI::CallForVersion& e) {
    out << e.what() << '\n';
    return kExitOk;
  } catch (const CLI::ParseError& e) {
    err << errorLine(std::string(e.what()) + " (run 'fcl_quadric --help' for usage)");
    return kExitBadInput;
  }

  // Each command writes to a buffer first, so that a failure leaves `out` untouched.
  std::ostringstream result;
  try {
    if (check->parsed()) {
      runCheck(scene_path, result);
    } else if (ccd->parsed()) {
      runCcd(ccd_scene_path, result,
             ccd_solver == "reduction" ? RegionCcdSolver::DimensionReduction : RegionCcdSolver::SpaceTime);
    } else if (demo->parsed()) {
      demo_options.seed = *parseSeed(seed_text);
      const DemoSummary summary = simulateDemo(demo_options);
      printDemoSummary(summary, result);
      if (!demo_pictures.empty()) {
        result << "  pictures: " << writeDemoPictures(summary, demo_pictures) << "\n";
        // The demo's frames have no motions over [0, 1]: the CCD plots show the built-in example scenes.
        result << "  plots: " << writeDemoPlots(demo_pictures) << "\n";
      }
    } else if (bench->parsed()) {
      runBench(bench_options, result, err, &err == &std::cerr && isatty(STDERR_FILENO) != 0);
    } else if (render->parsed()) {
      runRender(render_scene_path, render_output, render_time);
    } else if (plot->parsed()) {
      runPlot(plot_kind, plot_scene_path, plot_pair, plot_output);
    }
  } catch (const SceneError& e) {
    err << errorLine(e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    err << errorLine(std::string("internal error: ") + e.what());
    return kExitInternalError;
  }
  out << result.str();
  out.flush();
  return kExitOk;
}

}  // namespace cli
}  // namespace fcl_quadric
