// In-process tests of the commands (check, demo) and of cli::run()'s output contract.
#include <gtest/gtest.h>

#include <sstream>

#include <nlohmann/json.hpp>

#include "fcl_quadric/check_command.h"
#include "fcl_quadric/cli.h"
#include "fcl_quadric/demo_command.h"
#include "fcl_quadric/geometry/signed_distance.h"
#include "fcl_quadric/version.h"

namespace fcl_quadric {
namespace cli {
namespace {

struct RunResult {
  int status;
  std::string out;
  std::string err;
};

RunResult runCli(std::vector<std::string> args) {
  args.insert(args.begin(), "fcl_quadric");
  std::vector<const char*> argv;
  for (const std::string& a : args) argv.push_back(a.c_str());
  std::ostringstream out, err;
  const int status = run(static_cast<int>(argv.size()), argv.data(), out, err);
  return {status, out.str(), err.str()};
}

SceneObject ellipsoidObject(const std::string& name, const Eigen::Vector3d& radii, const Eigen::Vector3d& p,
                            const Eigen::Quaterniond& q) {
  SceneObject o;
  o.name = name;
  o.shape.type = ShapeType::Ellipsoid;
  o.shape.dimensions = radii;
  o.pose.linear() = q.toRotationMatrix();
  o.pose.translation() = p;
  return o;
}

TEST(CheckCommand, ReportsExactlyWhatTheLibraryComputes) {
  Scene scene;
  scene.objects.push_back(ellipsoidObject("a", {2, 1, 0.5}, {0, 0, 0}, Eigen::Quaterniond::Identity()));
  scene.objects.push_back(ellipsoidObject("b", {1, 1, 1}, {2.5, 0, 0}, Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()))));
  scene.objects.push_back(ellipsoidObject("c", {0.5, 0.7, 0.9}, {0, 4, 0}, Eigen::Quaterniond(Eigen::AngleAxisd(1.0, Eigen::Vector3d(1, 1, 0).normalized()))));
  scene.pairs = {{0, 1}, {1, 0}, {0, 2}, {2, 1}};
  const nlohmann::ordered_json out = checkScene(scene);
  ASSERT_EQ(out.at("pairs").size(), 4u);
  for (std::size_t k = 0; k < scene.pairs.size(); ++k) {
    const auto [i, j] = scene.pairs[k];
    const nlohmann::ordered_json& p = out["pairs"][k];
    SCOPED_TRACE(p.dump());
    const Ellipsoid a = toEllipsoid(scene.objects[i]), b = toEllipsoid(scene.objects[j]);
    const Separation s = classifyEllipsoids(a, b).status;
    const SignedDistanceResult sd = signedDistance(a, b);
    EXPECT_EQ(p["a"], scene.objects[i].name);
    EXPECT_EQ(p["b"], scene.objects[j].name);
    EXPECT_EQ(p["status"], toString(s));
    EXPECT_EQ(p["collide"], s != Separation::Separated);
    EXPECT_EQ(p["signed_distance"].get<double>(), sd.distance);
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(p["points"][0][c].get<double>(), sd.point_a[c]);
      EXPECT_EQ(p["points"][1][c].get<double>(), sd.point_b[c]);
      EXPECT_EQ(p["normal"][c].get<double>(), sd.normal[c]);
    }
    EXPECT_EQ(p["method"], "exact");
  }
  // a-b overlap (2 + 1 > 2.5 along x); a-c are separate; reversing a pair flips the normal.
  EXPECT_EQ(out["pairs"][0]["status"], "overlapping");
  EXPECT_EQ(out["pairs"][2]["status"], "separate");
  EXPECT_NEAR(out["pairs"][0]["signed_distance"].get<double>(), out["pairs"][1]["signed_distance"].get<double>(), 1e-12);
  EXPECT_NEAR(out["pairs"][0]["normal"][0].get<double>(), -out["pairs"][1]["normal"][0].get<double>(), 1e-9);
  // Keys in the documented order.
  std::vector<std::string> keys;
  for (const auto& item : out["pairs"][0].items()) keys.push_back(item.key());
  EXPECT_EQ(keys, (std::vector<std::string>{"a", "b", "status", "collide", "signed_distance", "points", "normal", "method"}));
}

TEST(Cli, ErrorLineIsOneLine) {
  EXPECT_EQ(errorLine("a\nb\r\tc"), "fcl_quadric: error: a b  c\n");
  EXPECT_EQ(errorLine("trailing\n"), "fcl_quadric: error: trailing\n");
}

TEST(Cli, BadSceneWritesNothingToStdout) {
  const RunResult r = runCli({"check", "/nonexistent/scene.json"});
  EXPECT_EQ(r.status, kExitBadInput);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err, "fcl_quadric: error: cannot open scene file \"/nonexistent/scene.json\": No such file or directory\n");
}

TEST(Cli, VersionInProcess) {
  const RunResult r = runCli({"--version"});
  EXPECT_EQ(r.status, kExitOk);
  EXPECT_EQ(r.out, std::string("fcl_quadric ") + FCL_QUADRIC_VERSION_STRING + "\n");
  EXPECT_EQ(r.err, "");
}

TEST(Demo, SummaryCountsAreConsistentAndDeterministic) {
  DemoOptions options;
  options.frames = 300;
  options.objects = 16;
  options.seed = 3;
  const DemoSummary s = simulateDemo(options);
  EXPECT_EQ(s.pair_frames, 300u * 120u);
  EXPECT_GT(s.pair_tests, 0u);
  EXPECT_LE(s.pair_tests, s.pair_frames);
  EXPECT_EQ(s.colliding + s.separated, s.pair_tests);
  EXPECT_LE(s.touching, s.colliding);
  EXPECT_LE(s.plane_hits, s.separated);
  // Coherence must actually work on a slowly moving scene: most separations come from planes.
  EXPECT_GT(s.plane_hits, s.separated / 2);
  EXPECT_GT(s.coherent_ns, 0.0);
  EXPECT_GT(s.direct_ns, 0.0);
  EXPECT_LE(s.examples.size(), 5u);
  EXPECT_LE(s.examples.size(), s.contact_starts);
  for (const DemoContact& c : s.examples) {
    EXPECT_LT(c.a, c.b);
    EXPECT_GT(c.frame, 0);
    EXPECT_NE(c.status, Separation::Separated);
    EXPECT_LE(c.signed_distance, 0.0);
  }
  const DemoSummary again = simulateDemo(options);
  EXPECT_EQ(again.pair_tests, s.pair_tests);
  EXPECT_EQ(again.colliding, s.colliding);
  EXPECT_EQ(again.plane_hits, s.plane_hits);
  EXPECT_EQ(again.contact_starts, s.contact_starts);

  std::ostringstream text;
  printDemoSummary(s, text);
  EXPECT_NE(text.str().find("16 spinning, drifting ellipsoids in a box, 300 frames (seed 3)"), std::string::npos) << text.str();
  EXPECT_NE(text.str().find(std::to_string(s.plane_hits) + " ("), std::string::npos) << text.str();
}

TEST(Demo, RejectsDegenerateOptions) {
  DemoOptions options;
  options.frames = 0;
  EXPECT_THROW(simulateDemo(options), std::invalid_argument);
  options.frames = 1;
  options.objects = 1;
  EXPECT_THROW(simulateDemo(options), std::invalid_argument);
  EXPECT_EQ(demoObjectName(7, 40), "E07");
  EXPECT_EQ(demoObjectName(7, 10), "E7");
  EXPECT_EQ(demoObjectName(123, 1000), "E123");
}

}  // namespace
}  // namespace cli
}  // namespace fcl_quadric

namespace fcl_quadric {
namespace cli {
namespace {

TEST(Check, EllipsoidBoxPairsAreExactInBothOrders) {
  // A box of side 1 whose face is at x = 1.5 + gap, an ellipsoid of radii (1.5, 1, 1) at the
  // origin: separate, touching and overlapping according to the gap, in either order.
  SceneObject e;
  e.name = "E";
  e.shape.type = ShapeType::Ellipsoid;
  e.shape.dimensions = Eigen::Vector3d(1.5, 1.0, 1.0);
  e.pose = Eigen::Isometry3d::Identity();
  for (const double gap : {0.25, 0.0, -0.25}) {
    SceneObject box;
    box.name = "B";
    box.shape.type = ShapeType::Box;
    box.shape.dimensions = Eigen::Vector3d(1.0, 1.0, 1.0);
    box.pose = Eigen::Isometry3d::Identity();
    box.pose.translation() = Eigen::Vector3d(2.0 + gap, 0.0, 0.0);
    const PairReport eb = evaluatePair(e, box), be = evaluatePair(box, e);
    const Separation expected = gap > 0 ? Separation::Separated : (gap < 0 ? Separation::Overlapping : Separation::Touching);
    EXPECT_EQ(eb.status, expected) << gap;
    EXPECT_EQ(be.status, expected) << gap;
    EXPECT_EQ(eb.method, PairMethod::Exact);
    EXPECT_NEAR(eb.signed_distance, expected == Separation::Touching ? 0.0 : gap, 1e-14);
    EXPECT_NEAR(be.signed_distance, eb.signed_distance, 0.0);
    EXPECT_NEAR((eb.normal - Eigen::Vector3d::UnitX()).norm(), 0.0, 1e-12);  // from E to the box
    EXPECT_NEAR((be.normal + Eigen::Vector3d::UnitX()).norm(), 0.0, 1e-12);  // from the box to E
    EXPECT_EQ(eb.point_a, be.point_b);
    EXPECT_EQ(eb.point_b, be.point_a);
  }
  // Box-box stays with FCL.
  SceneObject b1, b2;
  b1.shape.type = b2.shape.type = ShapeType::Box;
  b1.pose = b2.pose = Eigen::Isometry3d::Identity();
  b2.pose.translation() = Eigen::Vector3d(3.0, 0, 0);
  EXPECT_EQ(evaluatePair(b1, b2).method, PairMethod::Fcl);
}

}  // namespace
}  // namespace cli
}  // namespace fcl_quadric
