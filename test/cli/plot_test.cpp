// `fcl_quadric plot`: every example scene with motions gives each plot kind that applies to it as
// SVG and PNG that parse back; the sampled zero set of the CCD function is the zero set of F (its
// vertices are zeros of F, the grid signs are the signs of F) and it closes exactly at the
// contact instants found by continuousCollideEllipsoids; the real roots of Delta bound the 2D
// collision intervals; bad input exits with status 2 and one error line; the demo writes the plots.

#include <cairo.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "cli/picture_check.h"
#include "fcl_quadric/ccd_command.h"
#include "fcl_quadric/cli.h"
#include "fcl_quadric/plot_command.h"
#include "fcl_quadric/scene.h"

namespace fcl_quadric {
namespace cli {
namespace {

namespace fs = std::filesystem;
using namespace test;  // NOLINT: the picture helpers of cli/picture_check.h

const std::string kExamples = std::string(FCL_QUADRIC_SOURCE_DIR) + "/examples/";

void expectValidSvg(const fs::path& svg) {
  const std::string text = readFile(svg);
  ASSERT_FALSE(text.empty()) << svg;
  EXPECT_EQ(xmlProblem(text, "svg"), "") << svg;
}

void expectValidPng(const fs::path& png) {
  cairo_surface_t* image = readPng(png);
  ASSERT_EQ(cairo_surface_status(image), CAIRO_STATUS_SUCCESS) << png;
  EXPECT_GT(cairo_image_surface_get_width(image), 0) << png;
  EXPECT_GT(cairo_image_surface_get_height(image), 0) << png;
  const double ink = inkFraction(image);
  EXPECT_GT(ink, 0.05) << png << " looks blank";
  EXPECT_LT(ink, 0.95) << png << " looks flooded";
  cairo_surface_destroy(image);
}

/// Runs one plot to SVG and PNG and checks both outputs.
void expectPlot(const fs::path& dir, const std::string& stem, std::vector<std::string> args) {
  SCOPED_TRACE(stem);
  for (const std::string ext : {".svg", ".png"}) {
    const fs::path out = dir / (stem + ext);
    std::vector<std::string> full = args;
    full.insert(full.end(), {"-o", out.string()});
    const RunResult r = runCli(full);
    ASSERT_EQ(r.status, kExitOk) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_EQ(r.out, "");
    if (ext == std::string(".svg")) {
      expectValidSvg(out);
    } else {
      expectValidPng(out);
    }
  }
}

TEST(Plot, EveryExampleSceneWithMotionsGivesValidPlots) {
  const fs::path dir = scratchDir("plot_examples");
  int timelines = 0, functions = 0, discriminants = 0;
  for (const auto& entry : fs::directory_iterator(kExamples)) {
    const fs::path path = entry.path();
    if (path.extension() != ".json" || path.filename().string().rfind("scene", 0) != 0) continue;
    const Scene scene = readSceneFile(path.string());
    bool any = false;
    for (const auto& [i, j] : scene.pairs) {
      if (!isMoving(scene, i) && !isMoving(scene, j)) continue;
      any = true;
      const std::string pair = std::to_string(i) + "," + std::to_string(j);
      const std::string stem = path.stem().string() + "_" + std::to_string(i) + "_" + std::to_string(j);
      if (scene.dimension == 3) {
        // F(u, t) is the ellipsoid pencil's CCD function: pairs with other shapes have none.
        if (!isEllipsoidal(scene.objects[i].shape) || !isEllipsoidal(scene.objects[j].shape)) continue;
        expectPlot(dir, stem + "_ccd_function", {"plot", "ccd-function", path.string(), "--pair", pair});
        ++functions;
      } else {
        expectPlot(dir, stem + "_discriminant", {"plot", "discriminant", path.string(), "--pair", pair});
        ++discriminants;
      }
    }
    if (any) {
      expectPlot(dir, path.stem().string() + "_timeline", {"plot", "timeline", path.string()});
      ++timelines;
    }
  }
  EXPECT_GE(timelines, 2);       // scene_ccd, scene_ccd_2d
  EXPECT_GE(functions, 6);       // the pairs of scene_ccd
  EXPECT_GE(discriminants, 3);   // the pairs of scene_ccd_2d
}

CcdFunctionPlot samplePair(const std::string& scene_file, const std::string& pair) {
  const Scene scene = readSceneFile(kExamples + scene_file);
  const auto [i, j] = parsePair(scene, pair);
  return sampleCcdFunction(movingEllipsoid(scene.objects[i], i), movingEllipsoid(scene.objects[j], j),
                           CcdInterpolation::Rigid, 120, 240);
}

/// Sign changes of F along grid row j (the zero set's crossings of the line t = t_j).
int crossings(const CcdFunctionGrid& g, int j) {
  int n = 0;
  for (int i = 0; i < g.nu; ++i) n += (g.value(i, j) > 0.0) != (g.value(i + 1, j) > 0.0);
  return n;
}

TEST(Plot, SampledSignsAndZeroSetAreThoseOfF) {
  for (const std::string pair : {"arm,post", "arm,swing", "post,drifter"}) {
    SCOPED_TRACE(pair);
    const CcdFunctionPlot plot = samplePair("scene_ccd.json", pair);
    ASSERT_EQ(plot.grids.size(), plot.segments.size());
    // Grid values (row polynomials) agree with direct evaluation of F at the nodes.
    std::mt19937 rng(7);
    for (const CcdFunctionGrid& g : plot.grids) {
      std::uniform_int_distribution<int> ui(0, g.nu), tj(0, g.nt - 1);  // last row: the next segment's
      for (int k = 0; k < 500; ++k) {
        const int i = ui(rng), j = tj(rng);
        const double direct = ccdFunctionValue(plot.segments, static_cast<double>(i) / g.nu, g.t(j));
        EXPECT_NEAR(g.value(i, j), direct, 1e-12) << "node " << i << "," << j;
        if (std::fabs(direct) > 1e-12) {
          EXPECT_EQ(g.value(i, j) > 0.0, direct > 0.0);
        }
      }
    }
    // Every vertex of the drawn zero set is a zero of F (normalised to max |coefficient| 1).
    ASSERT_FALSE(plot.zero_set.empty());
    for (const auto& run : plot.zero_set) {
      for (const Eigen::Vector2d& p : run) {
        ASSERT_GE(p[0], 0.0);
        ASSERT_LE(p[0], 1.0);
        ASSERT_GE(p[1], 0.0);
        ASSERT_LE(p[1], 1.0);
        // At a segment's last row the point belongs to that segment, not to the next one.
        const bool at_break = std::any_of(plot.segments.begin(), plot.segments.end(),
                                          [&](const CcdFunctionSegment& s) { return s.t_end == p[1] && s.t_end < 1.0; });
        if (!at_break) {
          EXPECT_LE(std::fabs(ccdFunctionValue(plot.segments, p[0], p[1])), 1e-10) << p.transpose();
        }
      }
    }
    // Theorem 5.1 on the grid: two crossings per row while separate, none while overlapping.
    for (const CcdFunctionGrid& g : plot.grids) {
      for (int j = 0; j <= g.nt; ++j) {
        const double t = g.t(j);
        bool inside = false, near = false;
        for (const CcdInterval& c : plot.result.collision_intervals) {
          inside = inside || (t > c.begin + 0.01 && t < c.end - 0.01);
          near = near || (t > c.begin - 0.01 && t < c.end + 0.01);
        }
        if (inside) {
          EXPECT_EQ(crossings(g, j), 0) << "t = " << t;
        }
        if (!near) {
          EXPECT_EQ(crossings(g, j), 2) << "t = " << t;
        }
      }
    }
  }
}

TEST(Plot, ZeroSetClosesAtTheContactInstants) {
  // arm - post: one collision interval [t0, t1] inside (0, 1) (`ccd` reports it).
  const CcdFunctionPlot plot = samplePair("scene_ccd.json", "arm,post");
  ASSERT_EQ(plot.result.collision_intervals.size(), 1u);
  const double t0 = plot.result.collision_intervals[0].begin, t1 = plot.result.collision_intervals[0].end;
  ASSERT_GT(t0, 0.1);
  ASSERT_LT(t1, 0.9);
  const double h = 1.0 / plot.grids[0].nt;
  double below = 0.0, above = 1.0;  // the zero set's extent next to the interval
  for (const auto& run : plot.zero_set) {
    for (const Eigen::Vector2d& p : run) {
      EXPECT_FALSE(p[1] > t0 + h && p[1] < t1 - h) << "zero set inside the overlap interval at t = " << p[1];
      if (p[1] <= t0 + h) below = std::max(below, p[1]);
      if (p[1] >= t1 - h) above = std::min(above, p[1]);
    }
  }
  EXPECT_NEAR(below, t0, h);  // the lens of separate instants closes at the first contact
  EXPECT_NEAR(above, t1, h);  // and reopens at the last
  // The marked contacts are double roots: F(u*, t*) ~ 0 and the maximum of u -> F there.
  ASSERT_EQ(plot.contacts.size(), 2u);
  for (const Eigen::Vector2d& c : plot.contacts) {
    const double f = ccdFunctionValue(plot.segments, c[0], c[1]);
    EXPECT_LE(std::fabs(f), 1e-8) << c.transpose();
    for (const double du : {-0.02, 0.02}) EXPECT_LT(ccdFunctionValue(plot.segments, c[0] + du, c[1]), f);
  }
  EXPECT_NEAR(plot.contacts[0][1], t0, 0.0);
  EXPECT_NEAR(plot.contacts[1][1], t1, 0.0);
}

TEST(Plot, DiscriminantRootsBoundTheCollisionIntervals) {
  const Scene scene = readSceneFile(kExamples + "scene_ccd_2d.json");
  const auto [i, j] = parsePair(scene, "A,C");
  const DiscriminantPlot plot = sampleDiscriminant(movingEllipse2(scene.objects[i]), movingEllipse2(scene.objects[j]));
  ASSERT_EQ(plot.result.collision_intervals.size(), 1u);
  for (const double r : plot.roots) {
    ASSERT_GE(r, 0.0);
    ASSERT_LE(r, 1.0);
  }
  for (const double t : {plot.result.collision_intervals[0].first, plot.result.collision_intervals[0].second}) {
    const bool found = std::any_of(plot.roots.begin(), plot.roots.end(), [&](double r) { return std::fabs(r - t) < 1e-6; });
    EXPECT_TRUE(found) << "no root of Delta at the interval end " << t;
  }
  // A transversal root: Delta changes sign across it.
  const double r = plot.roots.front();
  EXPECT_LT(plot.delta.evaluate(r - 1e-3) * plot.delta.evaluate(r + 1e-3), 0.0);
}

TEST(Plot, BadInputExitsWithStatusTwoAndWritesNothing) {
  const fs::path dir = scratchDir("plot_bad");
  const std::string ccd = kExamples + "scene_ccd.json", ccd2 = kExamples + "scene_ccd_2d.json",
                    basic = kExamples + "scene_basic.json";
  const std::string png = (dir / "out.png").string();
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"plot", "ccd-function", ccd, "-o", png}, "--pair"},                           // missing pair
      {{"plot", "ccd-function", ccd, "--pair", "0,7", "-o", png}, "7"},               // index out of range
      {{"plot", "ccd-function", ccd, "--pair", "arm,ghost", "-o", png}, "ghost"},     // unknown name
      {{"plot", "ccd-function", ccd, "--pair", "1,1", "-o", png}, "1,1"},             // the same object
      {{"plot", "ccd-function", ccd, "--pair", "1", "-o", png}, "\"1\""},             // not a pair
      {{"plot", "ccd-function", basic, "--pair", "0,1", "-o", png}, "motion"},        // nothing moves
      {{"plot", "ccd-function", ccd2, "--pair", "0,1", "-o", png}, "3D"},             // planar scene
      {{"plot", "discriminant", ccd, "--pair", "0,1", "-o", png}, "planar"},          // 3D scene
      {{"plot", "discriminant", ccd2, "-o", png}, "--pair"},                          // missing pair
      {{"plot", "timeline", basic, "-o", png}, "moving"},                             // no moving pair
      {{"plot", "timeline", ccd, "-o", (dir / "out.jpg").string()}, "out.jpg"},       // unknown extension
      {{"plot", "timeline", ccd, "-o", (dir / "no" / "dir.png").string()}, "dir.png"},  // unwritable
      {{"plot", "ccd-function", ccd, "--pair", "0,1", "-o", (dir / "no" / "dir.svg").string()}, "dir.svg"},
      {{"plot", "histogram", ccd, "-o", png}, "histogram"},                           // unknown kind
      {{"plot", "timeline", (dir / "missing.json").string(), "-o", png}, "missing.json"},
  };
  for (const auto& [args, named] : cases) expectBadInput(args, named);
  EXPECT_FALSE(fs::exists(png));
  EXPECT_FALSE(fs::exists(dir / "out.jpg"));
}

TEST(Plot, DemoWritesThePlotsOfTheExampleScenes) {
  const fs::path dir = scratchDir("plot_demo") / "pictures";
  const RunResult r = runCli({"demo", "--frames", "5", "--objects", "3", "--pictures", dir.string()});
  ASSERT_EQ(r.status, kExitOk) << r.err;
  const fs::path f = dir / "ccd_function.png", d = dir / "discriminant.png", t = dir / "timeline.png";
  EXPECT_NE(r.out.find("  plots: " + f.string() + ", " + d.string() + ", " + t.string() + "\n"), std::string::npos)
      << r.out;
  for (const fs::path& p : {f, d, t}) expectValidPng(p);
}

}  // namespace
}  // namespace cli
}  // namespace fcl_quadric
