// In-process tests of the commands (check, demo) and of cli::run()'s output contract.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include <nlohmann/json.hpp>

#include "fcl_quadric/check_command.h"
#include "fcl_quadric/cli.h"
#include "fcl_quadric/demo_command.h"
#include "fcl_quadric/geometry/signed_distance.h"
#include "fcl_quadric/version.h"
#include "support/picture_files.h"

namespace fcl_quadric {
namespace cli {
namespace {

using test::RunResult;
using test::runCli;

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

// A moving object is checked where its motion puts it at t = 0. Found by fuzz_scene (CI of
// f273df0): a sheared "polynomial" motion made `check` build an Ellipsoid from the non-rigid
// M(0) and exit 1 ("ellipsoid rotation is not a rotation"); a rigid one with w(0) != 1 did too.
TEST(CheckCommand, MovingObjectsAreCheckedAtTimeZero) {
  // "shear": the unit ball under x -> L x, L = [[1, 1, 0], [0, 1, 0], [0, 0, 1]] (x += y), whose
  // image reaches (1, 1, 0); "probe": a small sphere at (1, 1.05, 0), 0.071 from the sheared
  // surface (point L u for u = (-0.0476, 0.9989, 0)) and 1.45 from the unsheared one.
  // "scaled": w = 2 and L = 2 I, i.e. the rigid pose translation (3, 0, 0).
  const Scene scene = parseSceneText(R"({"objects": [
    {"name": "shear", "shape": {"type": "sphere", "radius": 1},
     "motion": {"type": "polynomial", "matrix": [[1, 1, 0, 0], [0, 1, 0, 0], [0, 0, 1, [0, 1]], [0, 0, 0, 1]]}},
    {"name": "probe", "shape": {"type": "sphere", "radius": 0.1}, "pose": {"translation": [1, 1.05, 0]}},
    {"name": "scaled", "shape": {"type": "ellipsoid", "radii": [1, 0.5, 0.5]},
     "motion": {"type": "polynomial", "matrix": [[2, 0, 0, 6], [0, 2, 0, 0], [0, 0, 2, 0], [0, 0, 0, 2]]}}],
    "pairs": [["shear", "probe"], ["probe", "scaled"]]})");
  EXPECT_FALSE(scene.objects[0].motion->isRigid());
  EXPECT_TRUE(scene.objects[2].motion->isRigid());
  EXPECT_TRUE(scene.objects[2].pose.isApprox(Eigen::Isometry3d(Eigen::Translation3d(3, 0, 0)), 1e-15));

  const nlohmann::ordered_json out = checkScene(sceneAtTime(scene, 0.0));
  ASSERT_EQ(out.at("pairs").size(), 2u);
  const nlohmann::ordered_json& sheared = out["pairs"][0];
  SCOPED_TRACE(sheared.dump());
  EXPECT_EQ(sheared["collide"], true);
  // Independent of the snapshot's eigen-decomposition: the witness on "shear" is on the sheared
  // unit sphere (|L^-1 p| = 1) and the one on "probe" on its sphere.
  Eigen::Matrix3d L;
  L << 1, 1, 0, 0, 1, 0, 0, 0, 1;
  const Eigen::Vector3d pa(sheared["points"][0][0].get<double>(), sheared["points"][0][1].get<double>(),
                           sheared["points"][0][2].get<double>());
  const Eigen::Vector3d pb(sheared["points"][1][0].get<double>(), sheared["points"][1][1].get<double>(),
                           sheared["points"][1][2].get<double>());
  EXPECT_NEAR((L.inverse() * pa).norm(), 1.0, 1e-9);
  EXPECT_NEAR((pb - Eigen::Vector3d(1, 1.05, 0)).norm(), 0.1, 1e-9);
  EXPECT_LT(sheared["signed_distance"].get<double>(), 0.0);
  EXPECT_GT(sheared["signed_distance"].get<double>(), -0.1);
  // probe-scaled (the ellipsoid at (3, 0, 0), not at the origin nor scaled by 2): the centres are
  // |d| apart, d = (2, -1.05); the gap of the supports along d is a lower bound of the distance
  // (ellipsoid support sqrt((2 * 1)^2 + (1.05 * 0.5)^2) / |d|), and the distance to the
  // ellipsoid's point (2, 0, 0) an upper bound.
  const Eigen::Vector2d d(2, -1.05);
  const double lower = d.norm() - 0.1 - std::hypot(2.0 * 1.0, 1.05 * 0.5) / d.norm();
  const double upper = std::hypot(1.0, 1.05) - 0.1;
  EXPECT_EQ(out["pairs"][1]["collide"], false);
  EXPECT_GE(out["pairs"][1]["signed_distance"].get<double>(), lower - 1e-12);
  EXPECT_LE(out["pairs"][1]["signed_distance"].get<double>(), upper + 1e-12);
}

// Only an ellipsoid's affine image is again a shape of its kind: a box may only move rigidly.
TEST(CheckCommand, AffineMotionOfABoxIsABadScene) {
  try {
    parseSceneText(R"({"objects": [{"name": "B", "shape": {"type": "box", "size": [1, 1, 1]},
      "motion": {"type": "polynomial", "matrix": [[1, 1, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}}]})");
    ADD_FAILURE() << "no SceneError";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.pointer(), "/objects/0/motion");
    EXPECT_NE(e.message().find("box may only move rigidly"), std::string::npos) << e.message();
  }
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
