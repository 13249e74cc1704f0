// `fcl_quadric render` and the demo's pictures: every example scene renders to SVG and PNG, the
// outputs parse back (well-formed XML with an <svg> root; a PNG of the documented size that Cairo
// reads), colliding objects are drawn red and separated ones not, bad input exits with status 2.

#include <cairo.h>
#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "cli/picture_check.h"
#include "fcl_quadric/cli.h"
#include "fcl_quadric/render_command.h"
#include "fcl_quadric/scene.h"

namespace fcl_quadric {
namespace cli {
namespace {

namespace fs = std::filesystem;
using namespace test;  // NOLINT: the picture helpers of cli/picture_check.h

TEST(XmlCheck, AcceptsWellFormedAndRejectsBrokenDocuments) {
  EXPECT_EQ(xmlProblem("<?xml version=\"1.0\"?>\n<svg a=\"x>y\"><g><path d='M 0 0'/></g><!-- c --></svg>", "svg"), "");
  EXPECT_NE(xmlProblem("<svg></svg>", "svg"), "");                                  // no prolog
  EXPECT_NE(xmlProblem("<?xml version=\"1.0\"?><svg><g></svg>", "svg"), "");         // unclosed g
  EXPECT_NE(xmlProblem("<?xml version=\"1.0\"?><svg></svg><svg></svg>", "svg"), "");  // two roots
  EXPECT_NE(xmlProblem("<?xml version=\"1.0\"?><svg><g></svg></g>", "svg"), "");     // crossed
  EXPECT_NE(xmlProblem("<?xml version=\"1.0\"?><svg", "svg"), "");                   // truncated
  EXPECT_NE(xmlProblem("<?xml version=\"1.0\"?><html></html>", "svg"), "");          // wrong root
}

/// Checks an SVG output and a PNG output of a scene of the given dimension.
void expectValidPictures(const fs::path& svg, const fs::path& png, int dimension) {
  const std::string text = readFile(svg);
  ASSERT_FALSE(text.empty()) << svg;
  EXPECT_NE(text.find("<svg"), std::string::npos) << svg;
  EXPECT_EQ(xmlProblem(text, "svg"), "") << svg;
  const ImageSize size = renderImageSize(dimension);
  EXPECT_NE(text.find("width=\"" + std::to_string(size.width) + "pt\""), std::string::npos) << svg;

  cairo_surface_t* image = readPng(png);
  ASSERT_EQ(cairo_surface_status(image), CAIRO_STATUS_SUCCESS) << png;
  EXPECT_EQ(cairo_image_surface_get_width(image), size.width) << png;
  EXPECT_EQ(cairo_image_surface_get_height(image), size.height) << png;
  const double ink = inkFraction(image);
  EXPECT_GT(ink, 0.05) << png << " looks blank";
  EXPECT_LT(ink, 0.95) << png << " looks flooded";
  cairo_surface_destroy(image);
}

TEST(Render, EveryExampleSceneRendersToValidSvgAndPng) {
  const fs::path dir = scratchDir("examples");
  int rendered = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(FCL_QUADRIC_SOURCE_DIR) / "examples")) {
    const fs::path path = entry.path();
    if (path.extension() != ".json" || path.filename().string().rfind("scene", 0) != 0) continue;
    const Scene scene = readSceneFile(path.string());
    bool moving = scene.dimension == 2;
    for (const SceneObject& o : scene.objects) moving = moving || o.motion.has_value();
    const std::vector<std::string> times = moving ? std::vector<std::string>{"0", "0.5"} : std::vector<std::string>{"0"};
    for (const std::string& t : times) {
      SCOPED_TRACE(path.filename().string() + " at t = " + t);
      const std::string stem = path.stem().string() + "_t" + t;
      const fs::path svg = dir / (stem + ".svg"), png = dir / (stem + ".png");
      for (const fs::path& out : {svg, png}) {
        const RunResult r = runCli({"render", path.string(), "-o", out.string(), "--time", t});
        EXPECT_EQ(r.status, kExitOk) << r.err;
        EXPECT_EQ(r.err, "");
      }
      expectValidPictures(svg, png, scene.dimension);
      ++rendered;
    }
  }
  EXPECT_GE(rendered, 6);  // scene_basic, scene_quadrics, scene_ccd x2, scene_ccd_2d x2
}

TEST(Render, SceneAtTimeFollowsTheMotions) {
  const Scene scene = readSceneFile(std::string(FCL_QUADRIC_SOURCE_DIR) + "/examples/scene_ccd.json");
  const Scene at0 = sceneAtTime(scene, 0.0), at1 = sceneAtTime(scene, 1.0), half = sceneAtTime(scene, 0.5);
  // "arm": linear from (-3, 0, 0) to (3, 0, 0), quarter turn about z; "swing": keyframes via (0, 1, 0.1).
  EXPECT_TRUE(at0.objects[0].pose.translation().isApprox(Eigen::Vector3d(-3, 0, 0), 1e-12));
  EXPECT_TRUE(at1.objects[0].pose.translation().isApprox(Eigen::Vector3d(3, 0, 0), 1e-12));
  EXPECT_TRUE(half.objects[2].pose.translation().isApprox(Eigen::Vector3d(0, 1.0, 0.1), 1e-12));
  EXPECT_NEAR(half.objects[1].pose.translation()[1], 0.2, 1e-15);  // "post" has no motion
  // The arm's long axis (radius 1) lies along x at t = 0 and along y at t = 1.
  const auto longAxis = [](const SceneObject& o) {
    int k;
    o.shape.dimensions.maxCoeff(&k);
    return Eigen::Vector3d(o.pose.linear().col(k).cwiseAbs());
  };
  EXPECT_NEAR(at0.objects[0].shape.dimensions.maxCoeff(), 1.0, 1e-9);
  EXPECT_TRUE(longAxis(at0.objects[0]).isApprox(Eigen::Vector3d::UnitX(), 1e-9));
  EXPECT_TRUE(longAxis(at1.objects[0]).isApprox(Eigen::Vector3d::UnitY(), 1e-9));
  EXPECT_FALSE(at0.objects[0].motion.has_value());
  EXPECT_THROW(sceneAtTime(scene, 1.5), SceneError);
  EXPECT_THROW(sceneAtTime(scene, std::numeric_limits<double>::quiet_NaN()), SceneError);
}

/// Two ellipsoids A at the origin and B at (x, 0, 0), rendered to PNG; returns the colour at the
/// projection of A's centre in each of the three views.
std::vector<std::array<int, 3>> coloursAtCentreOfA(double x, const fs::path& dir) {
  const fs::path scene_path = dir / "pair.json", png = dir / "pair.png";
  std::ofstream(scene_path) << "{\"objects\": [{\"name\": \"A\", \"shape\": {\"type\": \"ellipsoid\", \"radii\": [1, 0.6, 0.5]}},"
                               " {\"name\": \"B\", \"shape\": {\"type\": \"ellipsoid\", \"radii\": [0.8, 0.5, 0.4]},"
                               " \"pose\": {\"translation\": [" << x << ", 0, 0]}}]}";
  const RunResult r = runCli({"render", scene_path.string(), "-o", png.string()});
  EXPECT_EQ(r.status, kExitOk) << r.err;
  const Scene scene = readSceneFile(scene_path.string());
  cairo_surface_t* image = readPng(png);
  EXPECT_EQ(cairo_surface_status(image), CAIRO_STATUS_SUCCESS);
  std::vector<std::array<int, 3>> colours;
  for (int view = 0; view < 3; ++view) {
    const Eigen::Vector2d p = pixelOf(scene, view, Eigen::Vector3d::Zero());
    colours.push_back(pixel(image, static_cast<int>(p[0]), static_cast<int>(p[1])));
  }
  cairo_surface_destroy(image);
  return colours;
}

bool reddish(const std::array<int, 3>& c) { return c[0] > c[1] + 60 && c[0] > c[2] + 60; }

TEST(Render, CollidingObjectsAreHighlightedRed) {
  const fs::path dir = scratchDir("colour");
  for (const auto& c : coloursAtCentreOfA(1.5, dir)) {  // overlap along x (1 + 0.8 > 1.5)
    EXPECT_TRUE(reddish(c)) << c[0] << "," << c[1] << "," << c[2];
    EXPECT_LT(c[1], 235);  // filled, not background
  }
  for (const auto& c : coloursAtCentreOfA(2.5, dir)) {  // separated
    EXPECT_FALSE(reddish(c)) << c[0] << "," << c[1] << "," << c[2];
    EXPECT_GT(c[2], c[0]);  // the first palette colour is blue
    EXPECT_LT(c[0], 235);   // filled, not background
  }
}

// A CSG solid is drawn by its exact shadow, not its bounding box: a ring (ellipsoid (1.2, 1.2, 0.6)
// minus a bore of radius 0.6 along z), alone. Seen from the top the bore is a hole and the box
// corner (1, 1) is outside the disk; seen from the front the line through the centre crosses the
// ring's material (|y| in [0.6, 1.2]), and (x, z) = (1, 0.5) is outside the ellipse
// x^2/1.44 + z^2/0.36 <= 1 though inside the box.
TEST(Render, CsgSolidsAreDrawnByTheirExactShadow) {
  const fs::path dir = scratchDir("csg_shadow");
  const fs::path scene_path = dir / "ring.json", png = dir / "ring.png";
  std::ofstream(scene_path) << R"({"objects": [{"name": "ring", "shape": {"type": "csg", "op": "difference",
      "children": [{"type": "ellipsoid", "radii": [1.2, 1.2, 0.6]}, {"type": "cylinder", "radius": 0.6, "length": 3}]}}]})";
  const RunResult r = runCli({"render", scene_path.string(), "-o", png.string()});
  ASSERT_EQ(r.status, kExitOk) << r.err;
  const Scene scene = readSceneFile(scene_path.string());
  cairo_surface_t* image = readPng(png);
  ASSERT_EQ(cairo_surface_status(image), CAIRO_STATUS_SUCCESS);
  auto colourAt = [&](int view, const Eigen::Vector3d& world) {
    const Eigen::Vector2d p = pixelOf(scene, view, world);
    return pixel(image, static_cast<int>(p[0]), static_cast<int>(p[1]));
  };
  auto filled = [](const std::array<int, 3>& c) { return c[2] > c[0] + 20; };  // the blue of the palette
  EXPECT_FALSE(filled(colourAt(0, {0.0, 0.0, 0.0})));   // top view: the bore
  EXPECT_TRUE(filled(colourAt(0, {0.9, 0.0, 0.0})));    // top view: material
  EXPECT_FALSE(filled(colourAt(0, {1.0, 1.0, 0.0})));   // top view: box corner outside the disk
  EXPECT_TRUE(filled(colourAt(1, {0.0, 0.0, 0.0})));    // front view: through the material
  EXPECT_FALSE(filled(colourAt(1, {1.0, 0.0, 0.5})));   // front view: outside the ellipse
  EXPECT_TRUE(filled(colourAt(1, {1.0, 0.0, 0.2})));    // front view: inside it
  cairo_surface_destroy(image);
}

TEST(Render, BadInputExitsWithStatusTwoAndWritesNothing) {
  const fs::path dir = scratchDir("bad");
  const std::string good = std::string(FCL_QUADRIC_SOURCE_DIR) + "/examples/scene_basic.json";
  const fs::path bad_json = dir / "bad.json";
  std::ofstream(bad_json) << "{\"objects\": [";
  const std::string png = (dir / "out.png").string();
  const std::vector<std::vector<std::string>> cases = {
      {"render", (dir / "missing.json").string(), "-o", png},   // missing scene
      {"render", bad_json.string(), "-o", png},                  // malformed JSON
      {"render", good, "-o", (dir / "out.jpg").string()},        // unknown extension
      {"render", good, "-o", (dir / "out").string()},            // no extension
      {"render", good, "-o", png, "--time", "nan"},              // non-finite time
      {"render", good, "-o", png, "--time", "inf"},
      {"render", good, "-o", png, "--time", "1.5"},              // outside [0, 1]
      {"render", good, "-o", png, "--time", "soon"},             // not a number
      {"render", good},                                          // no output
      {"render", good, "-o", (dir / "no" / "such" / "dir.png").string()},  // unwritable
  };
  for (const auto& args : cases) expectBadInput(args);
  EXPECT_FALSE(fs::exists(png));
  EXPECT_FALSE(fs::exists(dir / "out.jpg"));
}

TEST(Render, DemoWritesItsPicturesAndSaysWhere) {
  const fs::path dir = scratchDir("demo") / "pictures";
  const RunResult r = runCli({"demo", "--frames", "20", "--objects", "6", "--pictures", dir.string()});
  ASSERT_EQ(r.status, kExitOk) << r.err;
  const fs::path first = dir / "demo_first_frame.png", last = dir / "demo_last_frame.png";
  EXPECT_NE(r.out.find("  pictures: " + first.string() + ", " + last.string() + "\n"), std::string::npos) << r.out;
  for (const fs::path& p : {first, last}) {
    cairo_surface_t* image = readPng(p);
    ASSERT_EQ(cairo_surface_status(image), CAIRO_STATUS_SUCCESS) << p;
    EXPECT_EQ(cairo_image_surface_get_width(image), renderImageSize(3).width);
    EXPECT_GT(inkFraction(image), 0.05);
    cairo_surface_destroy(image);
  }
  // --pictures "" turns them off (and says nothing about pictures).
  const RunResult off = runCli({"demo", "--frames", "5", "--objects", "3", "--pictures", ""});
  EXPECT_EQ(off.status, kExitOk) << off.err;
  EXPECT_EQ(off.out.find("pictures:"), std::string::npos);
}

}  // namespace
}  // namespace cli
}  // namespace fcl_quadric
