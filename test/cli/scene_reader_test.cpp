// In-process tests of the scene reader (fcl_quadric/scene.h): valid scenes are read as written,
// every invalid scene is rejected with a SceneError naming the JSON pointer of the bad value.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <nlohmann/json.hpp>

#include "cli/bad_scenes.h"
#include "fcl_quadric/scene.h"
#include "fcl_quadric/tolerances.h"

namespace fcl_quadric {
namespace cli {
namespace {

using nlohmann::json;

/// The SceneError thrown by parseSceneText(text); fails the test if none is thrown.
SceneError errorOf(const std::string& text) {
  try {
    parseSceneText(text);
  } catch (const SceneError& e) {
    return e;
  }
  ADD_FAILURE() << "no SceneError for: " << text;
  return SceneError("<none>", "<none>");
}

SceneError errorOf(const json& document) {
  try {
    parseScene(document);
  } catch (const SceneError& e) {
    return e;
  }
  ADD_FAILURE() << "no SceneError for: " << document.dump();
  return SceneError("<none>", "<none>");
}

TEST(SceneReader, EveryBadSceneIsRejectedWithItsPointer) {
  const auto cases = test::badScenes();
  ASSERT_GE(cases.size(), 50u);
  for (const test::BadScene& c : cases) {
    SCOPED_TRACE(c.name);
    const SceneError e = errorOf(c.text);
    EXPECT_EQ(e.pointer(), c.pointer);
    EXPECT_NE(e.message().find(c.message), std::string::npos) << "message: " << e.message();
    // what() is "<pointer>: <message>" (just the message for document-level errors).
    EXPECT_EQ(std::string(e.what()), c.pointer.empty() ? e.message() : c.pointer + ": " + e.message());
    EXPECT_EQ(e.message().find('\n'), std::string::npos);
  }
}

TEST(SceneReader, ReadsShapesPosesAndPairsAsWritten) {
  const double s = std::sqrt(0.5);
  const json document = {
      {"objects",
       {{{"name", "E"},
         {"shape", {{"type", "ellipsoid"}, {"radii", {3, 2, 1}}}},
         {"pose", {{"translation", {1.5, -2, 4}}, {"quaternion", {s, 0, 0, s}}}}},
        {{"name", "S"}, {"shape", {{"type", "sphere"}, {"radius", 0.25}}}},
        {{"name", "X"}, {"shape", {{"type", "box"}, {"size", {1, 2, 3}}}}, {"pose", {{"translation", {0, 0, 9}}}}}}},
      {"pairs", json::array({json::array({"X", "E"}), json::array({"S", "E"})})}};
  const Scene scene = parseScene(document);
  ASSERT_EQ(scene.objects.size(), 3u);
  const SceneObject& e = scene.objects[0];
  EXPECT_EQ(e.name, "E");
  EXPECT_EQ(e.shape.type, ShapeType::Ellipsoid);
  EXPECT_EQ(e.shape.dimensions, Eigen::Vector3d(3, 2, 1));
  EXPECT_EQ(e.pose.translation(), Eigen::Vector3d(1.5, -2, 4));
  // 90 degrees about z: body x maps to world y.
  EXPECT_TRUE((e.pose.linear() * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY(), 1e-15));
  EXPECT_EQ(scene.objects[1].shape.type, ShapeType::Sphere);
  EXPECT_EQ(scene.objects[1].shape.dimensions, Eigen::Vector3d::Constant(0.25));
  EXPECT_TRUE(scene.objects[1].pose.matrix().isIdentity(0.0));
  EXPECT_EQ(scene.objects[2].shape.type, ShapeType::Box);
  EXPECT_EQ(scene.objects[2].shape.dimensions, Eigen::Vector3d(1, 2, 3));
  EXPECT_TRUE(scene.objects[2].pose.linear().isIdentity(0.0));
  EXPECT_EQ(scene.objects[2].pose.translation(), Eigen::Vector3d(0, 0, 9));
  // Pairs keep the order and orientation written.
  ASSERT_EQ(scene.pairs.size(), 2u);
  EXPECT_EQ(scene.pairs[0], std::make_pair(std::size_t{2}, std::size_t{0}));
  EXPECT_EQ(scene.pairs[1], std::make_pair(std::size_t{1}, std::size_t{0}));
  // The ellipsoid handed to the library is the one described.
  const Ellipsoid ell = toEllipsoid(e);
  EXPECT_EQ(ell.radii(), Eigen::Vector3d(3, 2, 1));
  EXPECT_NEAR(ell.implicit(Eigen::Vector3d(1.5, -2 + 3, 4)), 0.0, 1e-15);  // end of the rotated a axis
  EXPECT_THROW(toEllipsoid(scene.objects[2]), std::invalid_argument);
}

TEST(SceneReader, DefaultPairsAreAllUnorderedPairsInObjectOrder) {
  json objects = json::array();
  for (const char* name : {"p", "q", "r", "s"}) {
    objects.push_back({{"name", name}, {"shape", {{"type", "sphere"}, {"radius", 1}}}});
  }
  const Scene scene = parseScene({{"objects", objects}});
  const std::vector<std::pair<std::size_t, std::size_t>> expected = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  EXPECT_EQ(scene.pairs, expected);
  EXPECT_TRUE(parseScene(json{{"objects", json::array()}}).pairs.empty());
  // An explicit empty list means no pairs, not the default.
  EXPECT_TRUE(parseScene({{"objects", objects}, {"pairs", json::array()}}).pairs.empty());
}

TEST(SceneReader, QuaternionWithinToleranceIsNormalised) {
  const double f = 1.0 + 0.5 * tolerance::kQuaternionNorm;
  const json document = {
      {"objects", {{{"name", "A"}, {"shape", {{"type", "ellipsoid"}, {"radii", {1, 2, 3}}}},
                    {"pose", {{"quaternion", {f * 0.6, 0.0, f * 0.8, 0.0}}}}}}}};
  const Scene scene = parseScene(document);
  const Eigen::Matrix3d R = scene.objects[0].pose.linear();
  EXPECT_LT((R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-15);
  const Eigen::Matrix3d expected = Eigen::Quaterniond(0.6, 0.0, 0.8, 0.0).toRotationMatrix();
  EXPECT_TRUE(R.isApprox(expected, 1e-15));
  // Just outside the tolerance, on both sides of 1.
  for (double g : {1.0 + 2.0 * tolerance::kQuaternionNorm, 1.0 - 2.0 * tolerance::kQuaternionNorm}) {
    json bad = document;
    bad["objects"][0]["pose"]["quaternion"] = {g * 0.6, 0.0, g * 0.8, 0.0};
    EXPECT_EQ(errorOf(bad).pointer(), "/objects/0/pose/quaternion");
  }
}

TEST(SceneReader, NonFiniteNumbersBuiltInProcessAreRejected) {
  // JSON text cannot spell inf (see RadiusOverflow etc. in bad_scenes.h); a document built in
  // code can, and parseScene() must catch it too.
  const double inf = std::numeric_limits<double>::infinity();
  json document = {{"objects", {{{"name", "A"}, {"shape", {{"type", "ellipsoid"}, {"radii", {1, 2, 3}}}}}}}};
  json bad = document;
  bad["objects"][0]["shape"]["radii"][1] = inf;
  SceneError e = errorOf(bad);
  EXPECT_EQ(e.pointer(), "/objects/0/shape/radii/1");
  EXPECT_NE(e.message().find("got inf"), std::string::npos) << e.message();
  bad = document;
  bad["objects"][0]["pose"] = {{"translation", {0.0, -inf, 0.0}}};
  e = errorOf(bad);
  EXPECT_EQ(e.pointer(), "/objects/0/pose/translation/1");
  EXPECT_NE(e.message().find("translation must be finite, got -inf"), std::string::npos) << e.message();
  bad = document;
  bad["objects"][0]["pose"] = {{"quaternion", {1.0, 0.0, inf, 0.0}}};
  EXPECT_EQ(errorOf(bad).pointer(), "/objects/0/pose/quaternion/2");
}

TEST(SceneReader, FirstProblemInDocumentOrderIsReported) {
  // Two bad radii and a bad pair: the reader stops at the first in document order.
  const std::string text =
      R"({"objects":[{"name":"A","shape":{"type":"ellipsoid","radii":[1,2,3]}},)"
      R"({"name":"B","shape":{"type":"ellipsoid","radii":[1,0,-3]}}],"pairs":[["A","Q"]]})";
  EXPECT_EQ(errorOf(text).pointer(), "/objects/1/shape/radii/1");
}

TEST(SceneReader, UnreadableFilesAreSceneErrorsWithoutPointer) {
  for (const std::string& path : {std::string("/nonexistent/fcl_quadric/scene.json"), std::string("/")}) {
    try {
      readSceneFile(path);
      ADD_FAILURE() << "no error for " << path;
    } catch (const SceneError& e) {
      EXPECT_EQ(e.pointer(), "");
      EXPECT_NE(e.message().find("\"" + path + "\""), std::string::npos) << e.message();
    }
  }
}

TEST(SceneReader, ExampleSceneIsValid) {
  const Scene scene = readSceneFile(std::string(FCL_QUADRIC_SOURCE_DIR) + "/examples/scene_basic.json");
  ASSERT_EQ(scene.objects.size(), 5u);
  int boxes = 0, spheres = 0, ellipsoids = 0;
  for (const SceneObject& o : scene.objects) {
    boxes += o.shape.type == ShapeType::Box;
    spheres += o.shape.type == ShapeType::Sphere;
    ellipsoids += o.shape.type == ShapeType::Ellipsoid;
  }
  EXPECT_EQ(boxes, 1);
  EXPECT_EQ(spheres, 1);
  EXPECT_EQ(ellipsoids, 3);
  EXPECT_EQ(scene.pairs.size(), 7u);
}

}  // namespace
}  // namespace cli
}  // namespace fcl_quadric
