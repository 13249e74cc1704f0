// `fcl_quadric ccd`: the scene's motions reach the continuous solver unchanged (checked against the
// closed form for spheres on straight lines and against the static classifier at the reported
// times), and bad input gives exit status 2 with the JSON pointer.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "fcl_quadric/ccd_command.h"
#include "fcl_quadric/cli.h"
#include "fcl_quadric/continuous/ellipsoid_ccd.h"
#include "fcl_quadric/geometry/ellipsoid_separation.h"
#include "fcl_quadric/geometry/signed_distance.h"
#include "fcl_quadric/scene.h"
#include "support/picture_files.h"

namespace fcl_quadric {
namespace cli {
namespace {

using test::RunResult;

RunResult runCcdText(const std::string& text, const std::string& name) {
  const std::string path = ::testing::TempDir() + name + ".json";
  std::ofstream(path) << text;
  return test::runCli({"ccd", path});
}

TEST(CcdCommand, SpheresOnStraightLinesGiveTheClosedFormTimes) {
  // A (r = 1) moves from x = -4 to x = 4 through B (r = 0.5) at rest: contact when the centre
  // distance is 1.5, i.e. x = -1.5 at t = 2.5 / 8 and x = 1.5 at t = 5.5 / 8.
  const std::string text = R"({"objects":[
    {"name":"A","shape":{"type":"sphere","radius":1},
     "motion":{"type":"linear","from":{"translation":[-4,0,0]},"to":{"translation":[4,0,0]}}},
    {"name":"B","shape":{"type":"sphere","radius":0.5}}]})";
  const RunResult r = runCcdText(text, "ccd_spheres");
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  const nlohmann::json& p = j["pairs"][0];
  EXPECT_TRUE(p["collide"].get<bool>());
  EXPECT_NEAR(p["first_contact_time"].get<double>(), 2.5 / 8, 1e-10);
  ASSERT_EQ(p["overlap_intervals"].size(), 1u);
  EXPECT_NEAR(p["overlap_intervals"][0][0].get<double>(), 2.5 / 8, 1e-10);
  EXPECT_NEAR(p["overlap_intervals"][0][1].get<double>(), 5.5 / 8, 1e-10);
  EXPECT_NEAR(p["contact_point"][0].get<double>(), -0.5, 1e-8);  // B's surface facing A
  EXPECT_FALSE(p["near_tangent"].get<bool>());
  EXPECT_FALSE(p["unresolved"].get<bool>());
}

TEST(CcdCommand, ExampleSceneTimesAreContactsOfTheStaticTest) {
  const Scene scene = readSceneFile(std::string(FCL_QUADRIC_SOURCE_DIR) + "/examples/scene_ccd.json");
  const nlohmann::ordered_json out = ccdScene(scene);
  ASSERT_EQ(out["pairs"].size(), scene.pairs.size());
  int colliding = 0;
  for (std::size_t k = 0; k < scene.pairs.size(); ++k) {
    const auto& p = out["pairs"][k];
    SCOPED_TRACE(p.dump());
    const SceneObject& a = scene.objects[scene.pairs[k].first];
    const SceneObject& b = scene.objects[scene.pairs[k].second];
    auto at = [&](const SceneObject& o, double t) {
      const Eigen::Matrix4d T = o.motion ? o.motion->evaluate(t) : o.pose.matrix();
      return Ellipsoid(o.shape.dimensions, Eigen::Matrix3d(T.topLeftCorner<3, 3>()), Eigen::Vector3d(T.block<3, 1>(0, 3)));
    };
    // Sampled static test: overlapping instants lie in reported intervals.
    for (int i = 0; i <= 400; ++i) {
      const double t = i / 400.0;
      if (classifyEllipsoids(at(a, t), at(b, t)).status != Separation::Overlapping) continue;
      bool inside = false;
      for (const auto& iv : p["overlap_intervals"]) inside = inside || (t >= iv[0].get<double>() && t <= iv[1].get<double>());
      EXPECT_TRUE(inside) << "t=" << t;
    }
    if (!p["collide"].get<bool>()) continue;
    ++colliding;
    const double t = p["first_contact_time"].get<double>();
    if (t > 0.0) {
      const SignedDistanceResult d = signedDistance(at(a, t), at(b, t));
      EXPECT_LT(std::abs(d.distance), 1e-7);
      EXPECT_EQ(classifyEllipsoids(at(a, t * (1 - 1e-6)), at(b, t * (1 - 1e-6))).status, Separation::Separated);
    }
  }
  EXPECT_GE(colliding, 3);
}

TEST(CcdCommand, FirstContactOnlyReportsOneInstant) {
  const std::string text = R"({"objects":[
    {"name":"A","shape":{"type":"sphere","radius":1},
     "motion":{"type":"linear","from":{"translation":[-4,0,0]},"to":{"translation":[4,0,0]}}},
    {"name":"B","shape":{"type":"ellipsoid","radii":[0.5,0.4,0.3]}}],
    "ccd":{"all_intervals":false,"interpolation":"affine"}})";
  const RunResult r = runCcdText(text, "ccd_first");
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json p = nlohmann::json::parse(r.out)["pairs"][0];
  ASSERT_EQ(p["overlap_intervals"].size(), 1u);
  EXPECT_EQ(p["overlap_intervals"][0][0], p["overlap_intervals"][0][1]);
  EXPECT_NEAR(p["first_contact_time"].get<double>(), 2.5 / 8, 1e-10);
}

TEST(CcdCommand, BoxPairsUseTheRegionCcdAtTheClosedFormTime) {
  // A sphere (r = 0.5) falls from z = 4 to z = -4 onto a unit box at rest: contact when z = 1 at
  // t = 3 / 8, on the box's top face.
  const std::string text = R"({"objects":[
    {"name":"A","shape":{"type":"sphere","radius":0.5},
     "motion":{"type":"linear","from":{"translation":[0.1,0.2,4]},"to":{"translation":[0.1,0.2,-4]}}},
    {"name":"B","shape":{"type":"box","size":[1,1,1]}}]})";
  const RunResult r = runCcdText(text, "ccd_box");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto doc = nlohmann::json::parse(r.out);
  const auto& p = doc["pairs"][0];
  EXPECT_TRUE(p["collide"].get<bool>());
  EXPECT_NEAR(p["first_contact_time"].get<double>(), 3.0 / 8, 1e-7);
  EXPECT_LE(p["first_contact_time"].get<double>(), 3.0 / 8 + 1e-12);
  EXPECT_NEAR(p["contact_point"][2].get<double>(), 0.5, 1e-6);
  EXPECT_TRUE(p["overlap_intervals"].is_null());
  ASSERT_EQ(p["elements"].size(), 2u);
  EXPECT_EQ(p["elements"][0], "F0");
  EXPECT_EQ(p["elements"][1].get<std::string>().substr(0, 1), "F") << "a face of the box";
}

TEST(CcdCommand, TwoHalfspacesAreABadPair) {
  const std::string text = R"({"objects":[
    {"name":"A","shape":{"type":"halfspace","normal":[0,0,1],"offset":0}},
    {"name":"B","shape":{"type":"halfspace","normal":[1,0,0],"offset":0}}]})";
  const RunResult r = runCcdText(text, "ccd_halfspaces");
  EXPECT_EQ(r.status, kExitBadInput);
  EXPECT_TRUE(r.out.empty());
  EXPECT_NE(r.err.find("unbounded"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1);
}

TEST(CcdCommand, QuadricExampleSceneHasTheHandCheckedRimContactAndMiss) {
  // examples/scene_quadrics_ccd.json: a ball (r = 0.3) falls along x = 0.3 through a ring
  // (ellipsoid (1, 1, 0.5) minus a cylinder of radius 0.4): it first touches the rim circle
  // (radius 0.4, z_rim = 0.5 sqrt(0.84)) at (0.4, 0, z_rim) when its centre is at
  // z_rim + sqrt(0.3^2 - 0.1^2); the probe passes the pillar's vertex 0.01 away.
  const std::string path = std::string(FCL_QUADRIC_SOURCE_DIR) + "/examples/scene_quadrics_ccd.json";
  const nlohmann::ordered_json doc = ccdScene(readSceneFile(path));
  const double z_rim = 0.5 * std::sqrt(0.84), z = z_rim + std::sqrt(0.08);
  const auto& rim = doc["pairs"][0];
  ASSERT_TRUE(rim["collide"].get<bool>());
  EXPECT_NEAR(rim["first_contact_time"].get<double>(), (3.0 - z) / 6.0, 1e-7);
  EXPECT_NEAR(rim["contact_point"][0].get<double>(), 0.4, 1e-5);
  EXPECT_NEAR(rim["contact_point"][2].get<double>(), z_rim, 1e-5);
  // The ring's element is the edge between its outer face (the ellipsoid) and the bore.
  EXPECT_EQ(rim["elements"][0], "E0");
  EXPECT_EQ(rim["elements"][1], "F0");
  const auto& miss = doc["pairs"][1];
  EXPECT_FALSE(miss["collide"].get<bool>());
  EXPECT_TRUE(miss["first_contact_time"].is_null());
  EXPECT_TRUE(miss["elements"].empty());
}

TEST(CcdCommand, ReductionSolverAgreesWithTheSpaceTimeSearchAndSaysWhichAnswered) {
  // The sphere onto the box (above) and the quadric example scene, with `--solver reduction`:
  // thesis 6.2's reduction answers the box (a sphere face against a planar face) and the pillar
  // pair; the ring's bore meets its ellipsoid in a quartic edge, which the reduction leaves to the
  // space-time search (reported with the reason). Times and verdicts are those of the default run.
  auto run3 = [](const std::string& path, bool reduction) {
    const char* plain[] = {"fcl_quadric", "ccd", path.c_str()};
    const char* with[] = {"fcl_quadric", "ccd", "--solver", "reduction", path.c_str()};
    std::ostringstream out, err;
    const int status = reduction ? run(5, with, out, err) : run(3, plain, out, err);
    EXPECT_EQ(status, 0) << err.str();
    return nlohmann::json::parse(out.str());
  };
  const std::string box_path = ::testing::TempDir() + "ccd_box_reduction.json";
  // (At (0.1, 0.2) the ball's path stays exactly tangent to the vertical edge through (0.5, 0.5):
  // an identically degenerate quadric-line subproblem, whose contact begins on bounding elements.)
  std::ofstream(box_path) << R"({"objects":[
    {"name":"A","shape":{"type":"sphere","radius":0.5},
     "motion":{"type":"linear","from":{"translation":[0.1,0.2,4]},"to":{"translation":[0.1,0.2,-4]}}},
    {"name":"B","shape":{"type":"box","size":[1,1,1]}}]})";
  const auto box = run3(box_path, true)["pairs"][0];
  EXPECT_EQ(box["method"], "dimension_reduction") << box.dump();
  ASSERT_TRUE(box["collide"].get<bool>());
  EXPECT_NEAR(box["first_contact_time"].get<double>(), 3.0 / 8, 1e-9);
  EXPECT_NEAR(box["contact_point"][0].get<double>(), 0.1, 1e-8);
  EXPECT_NEAR(box["contact_point"][2].get<double>(), 0.5, 1e-8);
  ASSERT_EQ(box["elements"].size(), 2u);
  EXPECT_EQ(box["elements"][1].get<std::string>().substr(0, 1), "F") << "a face of the box";

  const std::string path = std::string(FCL_QUADRIC_SOURCE_DIR) + "/examples/scene_quadrics_ccd.json";
  const auto engine = run3(path, false)["pairs"], reduced = run3(path, true)["pairs"];
  ASSERT_EQ(reduced.size(), 2u);
  EXPECT_FALSE(engine[0].contains("method"));  // the default output is unchanged
  EXPECT_EQ(reduced[0]["method"], "space_time");
  EXPECT_FALSE(reduced[0]["undecided_reason"].get<std::string>().empty());
  EXPECT_EQ(reduced[0]["first_contact_time"], engine[0]["first_contact_time"]);
  EXPECT_EQ(reduced[1]["method"], "dimension_reduction");
  EXPECT_EQ(reduced[1]["collide"], engine[1]["collide"]);

  // A bad solver name: exit status 2, one line on stderr, nothing on stdout.
  const char* bad[] = {"fcl_quadric", "ccd", "--solver", "guess", path.c_str()};
  std::ostringstream out, err;
  EXPECT_EQ(run(5, bad, out, err), kExitBadInput);
  EXPECT_TRUE(out.str().empty());
  const std::string message = err.str();
  EXPECT_NE(message.find("guess"), std::string::npos) << message;
  EXPECT_EQ(std::count(message.begin(), message.end(), '\n'), 1) << message;
}

TEST(CcdCommand, SingularMotionExitsWithStatusTwoAndThePath) {
  const std::string text = R"({"objects":[{"name":"A","shape":{"type":"sphere","radius":1},
    "motion":{"type":"polynomial","matrix":[[1,0,0,0],[0,1,0,0],[0,0,[1,-4],0],[0,0,0,1]]}}]})";
  const RunResult r = runCcdText(text, "ccd_singular");
  EXPECT_EQ(r.status, kExitBadInput);
  EXPECT_NE(r.err.find("/objects/0/motion/matrix"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("0.25"), std::string::npos) << "names where det L(t) vanishes: " << r.err;
}

// A motion beyond the condition the CCD decides (a shear of 1e7 on an ellipsoid of aspect 4:
// kCcdMaxCondition) gets the conservative answer, colliding throughout, and says so.
TEST(CcdCommand, ConservativeAnswersAreFlaggedUnresolved) {
  const RunResult r = runCcdText(R"({"objects":[{"name":"A","shape":{"type":"ellipsoid","radii":[1,0.25,0.25]},
    "motion":{"type":"polynomial","matrix":[[1,1e7,0,[0,1]],[0,1,0,0],[0,0,1,0],[0,0,0,1]]}},
    {"name":"B","shape":{"type":"sphere","radius":0.5},"pose":{"translation":[10,0,0]}}]})",
                                 "ccd_unresolved");
  ASSERT_EQ(r.status, kExitOk) << r.err;
  const nlohmann::json p = nlohmann::json::parse(r.out)["pairs"][0];
  EXPECT_TRUE(p["collide"].get<bool>());
  EXPECT_TRUE(p["unresolved"].get<bool>());
  EXPECT_TRUE(p["near_tangent"].get<bool>());
  EXPECT_EQ(p["overlap_intervals"], nlohmann::json::parse("[[0.0, 1.0]]"));
}

// A pair whose motions exceed a solver's degree limit is a bad scene, not an internal error:
// exit 2 naming the motion (session 34; before, exit 1 from deep inside the CCD function, and
// above degree 511 a silent "no collision").
TEST(CcdCommand, MotionsAboveTheDegreeLimitExitWithStatusTwoAndThePath) {
  auto translation = [](int k) {
    std::string x = "[";
    for (int i = 0; i < k; ++i) x += "0,";
    return x + "3]";
  };
  const std::string ellipsoids = R"({"objects":[{"name":"B","shape":{"type":"sphere","radius":0.5},"pose":{"translation":[3,0,0]}},
    {"name":"A","shape":{"type":"ellipsoid","radii":[1,0.5,0.5]},
     "motion":{"type":"polynomial","matrix":[[1,0,0,)" + translation(201) + R"(],[0,1,0,0],[0,0,1,0],[0,0,0,1]]}}]})";
  RunResult r = runCcdText(ellipsoids, "ccd_degree");
  EXPECT_EQ(r.status, kExitBadInput);
  EXPECT_TRUE(r.out.empty());
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("/objects/1/motion/matrix"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("degree 402"), std::string::npos) << r.err;
  // The region CCD's own limit (kRegionCcdMaxDegree = 60: a translation of degree 31).
  const std::string region = R"({"objects":[{"name":"ball","shape":{"type":"sphere","radius":0.5},
     "motion":{"type":"polynomial","matrix":[[1,0,0,)" + translation(31) + R"(],[0,1,0,0],[0,0,1,0],[0,0,0,1]]}},
    {"name":"pillar","shape":{"type":"cylinder","radius":0.5,"length":1},"pose":{"translation":[3,0,0]}}]})";
  r = runCcdText(region, "ccd_region_degree");
  EXPECT_EQ(r.status, kExitBadInput);
  EXPECT_TRUE(r.out.empty());
  EXPECT_NE(r.err.find("/objects/0/motion/matrix"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("kRegionCcdMaxDegree"), std::string::npos) << r.err;
  // Degree 30 is within it: the ball (radius 0.5, centre 3 t^30) meets the pillar's side at x = 2.
  nlohmann::json doc;
  const RunResult ok = runCcdText(R"({"objects":[{"name":"ball","shape":{"type":"sphere","radius":0.5},
     "motion":{"type":"polynomial","matrix":[[1,0,0,)" + translation(30) + R"(],[0,1,0,0],[0,0,1,0],[0,0,0,1]]}},
    {"name":"pillar","shape":{"type":"cylinder","radius":0.5,"length":1},"pose":{"translation":[3,0,0]}}]})",
                                  "ccd_region_degree_ok");
  ASSERT_EQ(ok.status, kExitOk) << ok.err;
  doc = nlohmann::json::parse(ok.out);
  EXPECT_NEAR(doc["pairs"][0]["first_contact_time"].get<double>(), std::pow(2.0 / 3.0, 1.0 / 30.0), 1e-8);
}

std::string readText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Thesis Example 2.2 (with the erratum of ../shared/seeds/README.md): the disks touch at t = 1/2 at
// the origin. Moving B (the lower disk at t = 1/2) down by d leaves a gap d: collision-free; up by
// d: overlapping.
TEST(CcdCommand, PlanarExample22TouchesAtOneHalfAndSeparatesAfterAShiftDown) {
  const std::string text = readText(std::string(FCL_QUADRIC_SOURCE_DIR) + "/examples/scene_ccd_2d.json");
  const RunResult r = runCcdText(text, "ccd_2d");
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json p = nlohmann::json::parse(r.out)["pairs"][0];
  ASSERT_TRUE(p["collide"].get<bool>());
  EXPECT_NEAR(p["first_contact_time"].get<double>(), 0.5, 1e-9);
  EXPECT_NEAR(p["contact_point"][0].get<double>(), 0.0, 1e-6);
  EXPECT_NEAR(p["contact_point"][1].get<double>(), 0.0, 1e-6);
  const std::string b_translation_y = "[-80, 400, -880, 960, -480]";
  ASSERT_NE(text.find(b_translation_y), std::string::npos);
  for (double d : {1e-7, 1e-5, 1e-3}) {
    for (double sign : {-1.0, 1.0}) {  // w(t) = 4 - 16t + 32t^2 - 32t^3 + 16t^4; shift y by sign d
      std::ostringstream shifted;
      shifted.precision(17);
      const double w[5] = {4, -16, 32, -32, 16}, y[5] = {-80, 400, -880, 960, -480};
      shifted << "[";
      for (int k = 0; k < 5; ++k) shifted << (k ? ", " : "") << y[k] + sign * d * w[k];
      shifted << "]";
      std::string moved = text;
      moved.replace(moved.find(b_translation_y), b_translation_y.size(), shifted.str());
      const RunResult m = runCcdText(moved, "ccd_2d_shift");
      ASSERT_EQ(m.status, 0) << m.err;
      const nlohmann::json q = nlohmann::json::parse(m.out)["pairs"][0];
      EXPECT_EQ(q["collide"].get<bool>(), sign > 0) << "d = " << sign * d;
    }
  }
}

TEST(CcdCommand, PlanarSceneErrorsNameTheirPointer) {
  struct Case {
    std::string text, pointer;
  };
  const std::vector<Case> cases = {
      {R"({"dimension":2,"objects":[{"name":"A","shape":{"type":"ellipsoid","radii":[1,1,1]}}]})", "/objects/0/shape/type"},
      {R"({"dimension":2,"objects":[{"name":"A","shape":{"type":"ellipse","radii":[1,1,1]}}]})", "/objects/0/shape/radii"},
      {R"({"dimension":4,"objects":[]})", "/dimension"},
      {R"({"dimension":2,"objects":[],"ccd":{"interpolation":"affine"}})", "/ccd/interpolation"},
      {R"({"dimension":2,"objects":[{"name":"A","shape":{"type":"ellipse","radii":[1,2]},
          "motion":{"type":"polynomial","matrix":[[1,0,0],[0,1,0],[0,0,[1,-2]]]}}]})", "/objects/0/motion/matrix"},
      {R"({"dimension":2,"objects":[{"name":"A","shape":{"type":"ellipse","radii":[1,2]},
          "motion":{"type":"linear","from":{"angle":"x"},"to":{}}}]})", "/objects/0/motion/from/angle"},
  };
  for (const Case& c : cases) {
    const RunResult r = runCcdText(c.text, "ccd_2d_bad");
    EXPECT_EQ(r.status, kExitBadInput) << c.text;
    EXPECT_NE(r.err.find(c.pointer + ":"), std::string::npos) << r.err;
  }
  // check does not take planar scenes.
  const std::string path = ::testing::TempDir() + "planar_for_check.json";
  std::ofstream(path) << R"({"dimension":2,"objects":[]})";
  const char* argv[] = {"fcl_quadric", "check", path.c_str()};
  std::ostringstream out, err;
  EXPECT_EQ(run(3, argv, out, err), kExitBadInput);
  EXPECT_NE(err.str().find("/dimension"), std::string::npos) << err.str();
}

}  // namespace
}  // namespace cli
}  // namespace fcl_quadric
