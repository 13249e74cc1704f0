// `fcl_quadric ccd`: the scene's motions reach the continuous solver unchanged (checked against the
// closed form for spheres on straight lines and against the static classifier at the reported
// times), and bad input gives exit status 2 with the JSON pointer.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "fcl_quadric/ccd_command.h"
#include "fcl_quadric/cli.h"
#include "fcl_quadric/continuous/ellipsoid_ccd.h"
#include "fcl_quadric/geometry/ellipsoid_separation.h"
#include "fcl_quadric/geometry/signed_distance.h"

namespace fcl_quadric {
namespace cli {
namespace {

struct RunResult {
  int status;
  std::string out;
  std::string err;
};

RunResult runCcdText(const std::string& text, const std::string& name) {
  const std::string path = ::testing::TempDir() + name + ".json";
  std::ofstream(path) << text;
  const char* argv[] = {"fcl_quadric", "ccd", path.c_str()};
  std::ostringstream out, err;
  const int status = run(3, argv, out, err);
  return {status, out.str(), err.str()};
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

TEST(CcdCommand, BoxesAreRejectedWithTheObjectPointer) {
  const std::string text = R"({"objects":[
    {"name":"A","shape":{"type":"sphere","radius":1}},
    {"name":"B","shape":{"type":"box","size":[1,1,1]}}]})";
  const RunResult r = runCcdText(text, "ccd_box");
  EXPECT_EQ(r.status, kExitBadInput);
  EXPECT_TRUE(r.out.empty());
  EXPECT_NE(r.err.find("/objects/1/shape"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1);
}

TEST(CcdCommand, SingularMotionExitsWithStatusTwoAndThePath) {
  const std::string text = R"({"objects":[{"name":"A","shape":{"type":"sphere","radius":1},
    "motion":{"type":"polynomial","matrix":[[1,0,0,0],[0,1,0,0],[0,0,[1,-4],0],[0,0,0,1]]}}]})";
  const RunResult r = runCcdText(text, "ccd_singular");
  EXPECT_EQ(r.status, kExitBadInput);
  EXPECT_NE(r.err.find("/objects/0/motion/matrix"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("0.25"), std::string::npos) << "names where det L(t) vanishes: " << r.err;
}

}  // namespace
}  // namespace cli
}  // namespace fcl_quadric
