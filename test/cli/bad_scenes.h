#pragma once
// The catalogue of invalid scenes shared by the in-process reader tests and the end-to-end tests:
// each is the JSON text, the JSON pointer the error must name and a fragment of its message.
#include <string>
#include <vector>

namespace fcl_quadric {
namespace cli {
namespace test {

struct BadScene {
  const char* name;       // test label (identifier characters only)
  std::string text;       // file contents
  std::string pointer;    // expected SceneError::pointer()
  std::string message;    // expected substring of SceneError::message()
};

/// A valid object with the given name at x along the x axis (used to build larger scenes).
inline std::string sphereAt(const std::string& name, double x) {
  return R"({"name":")" + name + R"(","shape":{"type":"sphere","radius":0.5},"pose":{"translation":[)" +
         std::to_string(x) + ",0,0]}}";
}

inline std::vector<BadScene> badScenes() {
  const std::string a = sphereAt("A", 0), b = sphereAt("B", 2);
  auto withObject = [&](const std::string& object) { return R"({"objects":[)" + a + "," + b + "," + object + "]}"; };
  auto ellipsoid = [](const std::string& radii) {
    return R"({"name":"E","shape":{"type":"ellipsoid","radii":)" + radii + "}}";
  };
  auto posed = [](const std::string& pose) {
    return R"({"objects":[{"name":"P","shape":{"type":"sphere","radius":1},"pose":)" + pose + "}]}";
  };
  auto moving = [](const std::string& motion) {
    return R"({"objects":[{"name":"M","shape":{"type":"sphere","radius":1},"motion":)" + motion + "}]}";
  };
  auto paired = [&](const std::string& pairs) { return R"({"objects":[)" + a + "," + b + R"(],"pairs":)" + pairs + "}"; };
  return {
      // Document level.
      {"MalformedJson", "{\"objects\": [\n  {\"name\": \"A\",}\n]}", "", "line 2, column 16"},
      {"EmptyFile", "", "", "malformed JSON"},
      {"TrailingGarbage", R"({"objects":[]} x)", "", "malformed JSON"},
      {"RootNotObject", "[1, 2]", "", "must be a JSON object"},
      {"UnknownTopLevelField", R"({"objects":[],"pair":[]})", "/pair", "unknown field"},
      {"ObjectsMissing", R"({"pairs":[]})", "/objects", "required field is missing"},
      {"ObjectsNotArray", R"({"objects":{"A":1}})", "/objects", "must be an array, got object"},
      // Objects.
      {"ObjectNotObject", withObject("7"), "/objects/2", "must be an object, got number"},
      {"NameMissing", withObject(R"({"shape":{"type":"sphere","radius":1}})"), "/objects/2/name", "required field is missing"},
      {"NameNotString", withObject(R"({"name":3,"shape":{"type":"sphere","radius":1}})"), "/objects/2/name",
       "must be a string, got number"},
      {"NameEmpty", withObject(R"({"name":"","shape":{"type":"sphere","radius":1}})"), "/objects/2/name", "must not be empty"},
      {"DuplicateName", withObject(sphereAt("A", 5)), "/objects/2/name", "duplicate object name \"A\""},
      {"UnknownObjectField", withObject(R"({"name":"C","shape":{"type":"sphere","radius":1},"colour":"red"})"),
       "/objects/2/colour", "unknown field"},
      {"EscapedUnknownField", withObject(R"({"name":"C","shape":{"type":"sphere","radius":1},"a/b~c":0})"),
       "/objects/2/a~1b~0c", "unknown field"},
      // Shapes.
      {"ShapeMissing", withObject(R"({"name":"C"})"), "/objects/2/shape", "required field is missing"},
      {"ShapeNotObject", withObject(R"({"name":"C","shape":"sphere"})"), "/objects/2/shape", "must be an object, got string"},
      {"ShapeTypeMissing", withObject(R"({"name":"C","shape":{"radius":1}})"), "/objects/2/shape/type", "required field is missing"},
      {"ShapeTypeNotString", withObject(R"({"name":"C","shape":{"type":1}})"), "/objects/2/shape/type", "must be a string"},
      {"UnknownShapeType", withObject(R"({"name":"C","shape":{"type":"cone","radius":1}})"), "/objects/2/shape/type",
       "unknown shape type \"cone\""},
      {"RadiiMissing", withObject(R"({"name":"E","shape":{"type":"ellipsoid"}})"), "/objects/2/shape/radii", "required field is missing"},
      {"RadiiNotArray", withObject(ellipsoid("1")), "/objects/2/shape/radii", "must be an array of 3 numbers, got number"},
      {"RadiiTooShort", withObject(ellipsoid("[1,2]")), "/objects/2/shape/radii", "exactly 3 elements, got 2"},
      {"RadiiTooLong", withObject(ellipsoid("[1,2,3,4]")), "/objects/2/shape/radii", "exactly 3 elements, got 4"},
      {"RadiusNotNumber", withObject(ellipsoid(R"([1,2,"3"])")), "/objects/2/shape/radii/2", "must be a number, got string"},
      {"RadiusBoolean", withObject(ellipsoid("[true,2,3]")), "/objects/2/shape/radii/0", "must be a number, got boolean"},
      {"RadiusNegative", withObject(ellipsoid("[1,-1,3]")), "/objects/2/shape/radii/1", "radius must be finite and > 0, got -1"},
      {"RadiusZero", withObject(ellipsoid("[1,2,0.0]")), "/objects/2/shape/radii/2", "radius must be finite and > 0, got 0.0"},
      {"RadiusOverflow", withObject(ellipsoid("[1e999,2,3]")), "/objects/2/shape/radii/0", "1e999 is out of the range"},
      // Finite radii and translations outside the library's range (fuzz_scene found these as
      // internal errors, exit status 1).
      {"RadiusBelowLibraryRange", withObject(ellipsoid("[1,1e-300,3]")), "/objects/2/shape/radii/1",
       "radius must be in [1e-100, 1e+100], got 1e-300"},
      {"SphereRadiusAboveLibraryRange", withObject(R"({"name":"S","shape":{"type":"sphere","radius":1e200}})"),
       "/objects/2/shape/radius", "radius must be in [1e-100, 1e+100]"},
      {"EllipsoidWithRadius", withObject(R"({"name":"E","shape":{"type":"ellipsoid","radius":1}})"),
       "/objects/2/shape/radius", "unknown field (allowed here: type, radii)"},
      {"SphereRadiusMissing", withObject(R"({"name":"S","shape":{"type":"sphere"}})"), "/objects/2/shape/radius",
       "required field is missing"},
      {"SphereRadiusNegative", withObject(R"({"name":"S","shape":{"type":"sphere","radius":-0.5}})"),
       "/objects/2/shape/radius", "radius must be finite and > 0, got -0.5"},
      {"SphereRadiusArray", withObject(R"({"name":"S","shape":{"type":"sphere","radius":[1]}})"), "/objects/2/shape/radius",
       "must be a number, got array"},
      {"SphereRadiusOverflow", withObject(R"({"name":"S","shape":{"type":"sphere","radius":-2e400}})"),
       "/objects/2/shape/radius", "out of the range"},
      {"BoxSizeZero", withObject(R"({"name":"X","shape":{"type":"box","size":[1,1,0]}})"), "/objects/2/shape/size/2",
       "box size must be finite and > 0, got 0"},
      {"BoxSizeWrongLength", withObject(R"({"name":"X","shape":{"type":"box","size":[1,1]}})"), "/objects/2/shape/size",
       "exactly 3 elements"},
      {"BoxSizeOverflow", withObject(R"({"name":"X","shape":{"type":"box","size":[1,1e500,1]}})"), "/objects/2/shape/size/1",
       "out of the range"},
      // Poses.
      {"PoseNotObject", posed("[0,0,0]"), "/objects/0/pose", "must be an object, got array"},
      {"UnknownPoseField", posed(R"({"rotation":[1,0,0,0]})"), "/objects/0/pose/rotation", "unknown field"},
      {"TranslationWrongLength", posed(R"({"translation":[0,0]})"), "/objects/0/pose/translation", "exactly 3 elements"},
      {"TranslationNull", posed(R"({"translation":[null,0,0]})"), "/objects/0/pose/translation/0", "must be a number, got null"},
      {"TranslationOverflow", posed(R"({"translation":[0,0,1e309]})"), "/objects/0/pose/translation/2", "out of the range"},
      {"TranslationBeyondLibraryRange", posed(R"({"translation":[0,-1e150,0]})"), "/objects/0/pose/translation/1",
       "translation must be within +-1e+100"},
      {"QuaternionWrongLength", posed(R"({"quaternion":[1,0,0]})"), "/objects/0/pose/quaternion", "exactly 4 elements, got 3"},
      {"QuaternionNotUnit", posed(R"({"quaternion":[1,0,0,0.1]})"), "/objects/0/pose/quaternion", "unit norm"},
      {"QuaternionZero", posed(R"({"quaternion":[0,0,0,0]})"), "/objects/0/pose/quaternion", "got norm 0"},
      {"QuaternionJustBeyondTolerance", posed(R"({"quaternion":[1.000002,0,0,0]})"), "/objects/0/pose/quaternion", "unit norm"},
      {"QuaternionOverflow", posed(R"({"quaternion":[1,0,0,1e999]})"), "/objects/0/pose/quaternion/3", "out of the range"},
      {"QuaternionComponentString", posed(R"({"quaternion":[1,0,"0",0]})"), "/objects/0/pose/quaternion/2", "must be a number"},
      // Motions (fcl_quadric ccd).
      {"MotionUnknownType", moving(R"({"type":"spline"})"), "/objects/0/motion/type", "unknown motion type \"spline\""},
      {"MotionWithPose", R"({"objects":[{"name":"M","shape":{"type":"sphere","radius":1},"pose":{},"motion":{"type":"linear","from":{},"to":{}}}]})",
       "/objects/0/motion", "not both"},
      {"MotionLinearMissingTo", moving(R"({"type":"linear","from":{}})"), "/objects/0/motion/to", "required field is missing"},
      {"MotionLinearBadQuaternion", moving(R"({"type":"linear","from":{},"to":{"quaternion":[2,0,0,0]}})"),
       "/objects/0/motion/to/quaternion", "unit norm"},
      {"MotionKeyframesFirstTime", moving(R"({"type":"keyframes","times":[0.1,1],"poses":[{},{}]})"),
       "/objects/0/motion/times/0", "first time must be 0"},
      {"MotionKeyframesNotIncreasing", moving(R"({"type":"keyframes","times":[0,0.6,0.5,1],"poses":[{},{},{},{}]})"),
       "/objects/0/motion/times/2", "increase strictly"},
      {"MotionKeyframesPoseCount", moving(R"({"type":"keyframes","times":[0,1],"poses":[{}]})"),
       "/objects/0/motion/poses", "exactly 2 elements, got 1"},
      {"MotionMatrixRows", moving(R"({"type":"polynomial","matrix":[[1,0,0,0],[0,1,0,0],[0,0,1,0]]})"),
       "/objects/0/motion/matrix", "exactly 4 elements, got 3"},
      {"MotionMatrixEmptyEntry", moving(R"({"type":"polynomial","matrix":[[1,0,0,[]],[0,1,0,0],[0,0,1,0],[0,0,0,1]]})"),
       "/objects/0/motion/matrix/0/3", "must not be empty"},
      {"MotionMatrixEntryString", moving(R"({"type":"polynomial","matrix":[[1,0,0,0],[0,"1",0,0],[0,0,1,0],[0,0,0,1]]})"),
       "/objects/0/motion/matrix/1/1", "must be a number or an array"},
      {"MotionMatrixWVanishes", moving(R"({"type":"polynomial","matrix":[[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,[-0.5,1]]]})"),
       "/objects/0/motion/matrix", "w(t)"},
      {"MotionMatrixSingular", moving(R"({"type":"polynomial","matrix":[[[1,-2],0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]})"),
       "/objects/0/motion/matrix", "det of the linear part"},
      {"MotionMatrixLastRow", moving(R"({"type":"polynomial","matrix":[[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,[0,1],0,1]]})"),
       "/objects/0/motion/matrix", "last row"},
      {"CcdBadInterpolation", R"({"objects":[],"ccd":{"interpolation":"slerp"}})", "/ccd/interpolation", "\"rigid\" or \"affine\""},
      {"CcdUnknownField", R"({"objects":[],"ccd":{"first_only":true}})", "/ccd/first_only", "unknown field"},
      {"CcdAllIntervalsNotBool", R"({"objects":[],"ccd":{"all_intervals":1}})", "/ccd/all_intervals", "true or false"},
      // Pairs.
      {"PairsNotArray", paired(R"({"A":"B"})"), "/pairs", "must be an array"},
      {"PairNotArray", paired(R"(["A"])"), "/pairs/0", "must be an array of two object names, got string"},
      {"PairTooLong", paired(R"([["A","B","A"]])"), "/pairs/0", "exactly 2 elements, got 3"},
      {"PairElementNotString", paired(R"([["A","B"],["A",1]])"), "/pairs/1/1", "must be an object name"},
      {"PairUnknownObject", paired(R"([["A","B"],["Z","A"]])"), "/pairs/1/0", "unknown object \"Z\""},
      {"PairSameObjectTwice", paired(R"([["A","B"],["B","B"]])"), "/pairs/1", "names object \"B\" twice"},
  };
}

}  // namespace test
}  // namespace cli
}  // namespace fcl_quadric
