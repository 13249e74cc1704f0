// Quadric shapes in scenes (elliptic_cylinder, cylinder, halfspace, quadric, csg): the example
// scene's pairs have hand-checked answers; the circular cylinder agrees with the exact
// ellipsoid-cylinder kernel; bad quadric shapes are rejected with their JSON pointers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "fcl_quadric/check_command.h"
#include "fcl_quadric/geometry/ellipsoid_cylinder.h"
#include "fcl_quadric/scene.h"

namespace fcl_quadric {
namespace cli {
namespace {

using nlohmann::json;

TEST(QuadricScene, ExampleSceneHasTheHandCheckedStatuses) {
  const Scene scene = readSceneFile(std::string(FCL_QUADRIC_SOURCE_DIR) + "/examples/scene_quadrics.json");
  const nlohmann::ordered_json out = checkScene(scene);
  // pillar-rod: the rod passes through the pillar's axis; pillar-floor: bottom cap on the plane;
  // dish-floor: the paraboloid's apex on the plane; ring-pin: the pin sits in the bore;
  // the others are far apart.
  const std::vector<std::pair<std::string, std::string>> expected = {
      {"overlapping", "quadric_region"}, {"touching", "quadric_region"}, {"touching", "quadric_region"},
      {"separate", "quadric_region"},  {"separate", "quadric_region"}, {"separate", "quadric_region"},
      {"separate", "quadric_region"}};
  ASSERT_EQ(out["pairs"].size(), expected.size());
  int with_distance = 0;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const auto& p = out["pairs"][i];
    EXPECT_EQ(p["status"], expected[i].first) << p.dump();
    EXPECT_EQ(p["method"], expected[i].second) << p.dump();
    // Bounded pairs carry a signed distance whose sign is the status's, except an overlapping
    // pair with a non-convex shape (a ring or wedge: they subtract cylinders), whose depth is not
    // computed. The floor is a half-space (unbounded): no distance.
    auto convexShape = [](const std::string& n) { return n != "ring" && n != "wedge"; };
    const bool bounded = p["a"] != "floor" && p["b"] != "floor";
    const bool convex = convexShape(p["a"]) && convexShape(p["b"]);
    EXPECT_EQ(p["signed_distance"].is_null(), !bounded || (!convex && p["status"] == "overlapping")) << p.dump();
    if (!p["signed_distance"].is_null()) {
      ++with_distance;
      const double d = p["signed_distance"];
      const std::string st = p["status"];
      EXPECT_TRUE(st == "separate" ? d > 0 : (st == "touching" ? d == 0 : d < 0)) << p.dump();
      EXPECT_FALSE(p["points"].is_null()) << p.dump();
    } else {
      EXPECT_EQ(p["points"].is_null(), p["status"] == "separate") << p.dump();
    }
  }
  EXPECT_GT(with_distance, 0);
}

TEST(QuadricScene, CylinderAgreesWithTheExactEllipsoidCylinderKernel) {
  for (double x : {1.2, 1.45, 1.55, 2.0}) {
    const json doc = {{"objects",
                       {{{"name", "c"}, {"shape", {{"type", "cylinder"}, {"radius", 0.5}, {"length", 2.0}}}},
                        {{"name", "e"},
                         {"shape", {{"type", "ellipsoid"}, {"radii", {1.0, 0.5, 0.7}}}},
                         {"pose", {{"translation", {x, 0.2, 0.3}}, {"quaternion", {0.9, 0.3, 0.3, 0.1}}}}}}}};
    json d = doc;
    // Normalise the quaternion in the document (the reader accepts only unit norm).
    const double n = std::sqrt(0.81 + 0.09 + 0.09 + 0.01);
    d["objects"][1]["pose"]["quaternion"] = {0.9 / n, 0.3 / n, 0.3 / n, 0.1 / n};
    const Scene scene = parseScene(d);
    const PairReport r = evaluatePair(scene.objects[0], scene.objects[1]);
    const SceneObject& e = scene.objects[1];
    const SignedDistanceResult ref =
        signedDistanceEllipsoidCylinder(toEllipsoid(e), 0.5, 2.0, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
    ASSERT_GT(std::fabs(ref.distance), 1e-6);
    EXPECT_EQ(r.collide, ref.distance < 0) << "x = " << x << " d = " << ref.distance;
  }
}

// A union of two balls (an exact convex cover) against a ball: the signed distance is the nearer
// ball's, |c - c_i| - r_i - r, computed by hand; overlapping, the deeper ball's.
TEST(QuadricScene, UnionOfBallsGetsTheNearestBallsSignedDistance) {
  for (double x : {3.0, 2.2, 1.5}) {
    const json ball = {{"type", "quadric"}, {"matrix", {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, -1}}}};
    json shifted = ball;  // a child may carry a pose
    shifted["pose"] = {{"translation", {0.5, 1.2, 0}}, {"quaternion", {1, 0, 0, 0}}};
    const json doc = {
        {"objects",
         {{{"name", "pair"},
           {"shape",
            {{"type", "csg"},
             {"op", "union"},
             {"children", {ball, shifted}}}}},
          {{"name", "s"}, {"shape", {{"type", "sphere"}, {"radius", 0.5}}}, {"pose", {{"translation", {x, 0.3, 0}}, {"quaternion", {1, 0, 0, 0}}}}}}}};
    const Scene scene = parseScene(doc);
    const PairReport r = evaluatePair(scene.objects[0], scene.objects[1]);
    const Eigen::Vector3d c(x, 0.3, 0);
    const double expected = std::min(c.norm(), (c - Eigen::Vector3d(0.5, 1.2, 0)).norm()) - 1.5;
    ASSERT_FALSE(std::isnan(r.signed_distance)) << "x = " << x;
    EXPECT_NEAR(r.signed_distance, expected, 1e-8) << "x = " << x;
    EXPECT_EQ(r.collide, expected < 0) << "x = " << x;
  }
}

// A ring (ellipsoid minus a cylinder) against a ball: outside it the nearest point is on the outer
// face, inside the bore on the bore wall; both by hand.
TEST(QuadricScene, RingGetsItsDistanceOutsideAndInsideTheBore) {
  const json ellipsoid = {{"type", "ellipsoid"}, {"radii", {2.0, 2.0, 1.0}}};
  const json bore = {{"type", "cylinder"}, {"radius", 1.0}, {"length", 3.0}};
  for (const auto& [q, expected] : {std::pair(Eigen::Vector3d(3.5, 0, 0), 1.5 - 0.25),
                                    std::pair(Eigen::Vector3d(0.2, 0.1, 0), 1.0 - std::hypot(0.2, 0.1) - 0.25)}) {
    const json doc = {{"objects",
                       {{{"name", "ring"}, {"shape", {{"type", "csg"}, {"op", "difference"}, {"children", {ellipsoid, bore}}}}},
                        {{"name", "s"},
                         {"shape", {{"type", "sphere"}, {"radius", 0.25}}},
                         {"pose", {{"translation", {q.x(), q.y(), q.z()}}, {"quaternion", {1, 0, 0, 0}}}}}}}};
    const Scene scene = parseScene(doc);
    const PairReport r = evaluatePair(scene.objects[0], scene.objects[1]);
    EXPECT_EQ(r.status, Separation::Separated);
    EXPECT_NEAR(r.signed_distance, expected, 1e-9) << q.transpose();
    EXPECT_NEAR((r.point_b - r.point_a).norm(), r.signed_distance, 1e-12);
    EXPECT_NEAR((r.point_b - q).norm(), 0.25, 1e-9);
    EXPECT_NEAR(r.normal.norm(), 1.0, 1e-12);
  }
}

TEST(QuadricScene, BadQuadricShapesAreRejectedWithTheirPointers) {
  auto pointerOf = [](const json& shape) {
    const json doc = {{"objects", {{{"name", "q"}, {"shape", shape}}}}};
    try {
      parseScene(doc);
    } catch (const SceneError& e) {
      return e.pointer();
    }
    return std::string("<none>");
  };
  EXPECT_EQ(pointerOf({{"type", "elliptic_cylinder"}, {"radii", {1.0, -1.0}}, {"length", 1.0}}),
            "/objects/0/shape/radii/1");
  EXPECT_EQ(pointerOf({{"type", "cylinder"}, {"radius", 1.0}}), "/objects/0/shape/length");
  EXPECT_EQ(pointerOf({{"type", "halfspace"}, {"normal", {0, 0, 0}}, {"offset", 1.0}}), "/objects/0/shape/normal");
  const json asym = {{1, 0.5, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, -1}};
  EXPECT_EQ(pointerOf({{"type", "quadric"}, {"matrix", asym}}), "/objects/0/shape/matrix");
  const json paraboloid = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 0, -0.5}, {0, 0, -0.5, 0}};
  EXPECT_EQ(pointerOf({{"type", "quadric"}, {"matrix", paraboloid}}), "/objects/0/shape");  // unbounded
  EXPECT_EQ(pointerOf({{"type", "quadric"},
                       {"matrix", paraboloid},
                       {"clip", {{{"type", "halfspace"}, {"normal", {0, 0, 1}}, {"offset", -1.0}}}}}),
            "/objects/0/shape");  // empty
  EXPECT_EQ(pointerOf({{"type", "csg"}, {"op", "xor"}, {"children", json::array()}}), "/objects/0/shape/op");
  EXPECT_EQ(pointerOf({{"type", "csg"}, {"op", "union"}, {"children", json::array()}}), "/objects/0/shape/children");
  EXPECT_EQ(pointerOf({{"type", "csg"},
                       {"op", "union"},
                       {"children", {{{"type", "sphere"}, {"radius", 1.0}, {"pose", {{"translation", {0, 0}}}}}}}}),
            "/objects/0/shape/children/0/pose/translation");
  EXPECT_EQ(pointerOf({{"type", "sphere"}, {"radius", 1.0}, {"pose", json::object()}}), "/objects/0/shape/pose");
}

}  // namespace
}  // namespace cli
}  // namespace fcl_quadric
