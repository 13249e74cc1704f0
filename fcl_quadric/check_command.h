#pragma once
/// \file check_command.h
/// `fcl_quadric check SCENE.json`: classify and measure every requested pair of a scene.

#include <optional>
#include <ostream>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "fcl_quadric/pair_report.h"
#include "fcl_quadric/scene.h"

namespace fcl_quadric {
namespace cli {

/// A 3-vector as a JSON array [x, y, z] (the commands' points and normals).
inline nlohmann::ordered_json toJson(const Eigen::Vector3d& v) { return nlohmann::ordered_json::array({v[0], v[1], v[2]}); }

/// Exact report for two ellipsoids: status from classifyEllipsoids(), distance, witness points
/// and normal from signedDistance(). `method` is PairMethod::Exact.
PairReport exactPairReport(const Ellipsoid& a, const Ellipsoid& b);

/// Exact report for an ellipsoid (or sphere) and a box object: status from classifyEllipsoidBox(),
/// distance, witness points and normal from signedDistanceEllipsoidBox(), turned around when the
/// box is the first object of the pair (`box_first`). `method` is PairMethod::Exact.
PairReport exactBoxReport(const Ellipsoid& e, const SceneObject& box, bool box_first);

/// Any 3D scene shape (not an ellipse) as a region in its body frame with its local AABB (none:
/// unbounded): quadric shapes as parsed, a box as six half-spaces, an ellipsoid or sphere as one
/// atom.
std::pair<QuadricRegion, std::optional<Box3>> asRegion(const Shape& shape);

/// Report for a pair with at least one quadric shape (elliptic_cylinder, cylinder, halfspace,
/// quadric, csg; the other may be any 3D shape): the certified classification of the composite-
/// quadric engine (findPoint on the intersection, quadric_region.h): Separated / Overlapping
/// certified, Touching within the tolerance band. No signed distance (NaN); point_a = point_b =
/// the witness (world), normal = outward normal of a's nearest surface there.
/// \throws std::invalid_argument if both objects are unbounded (half-spaces).
PairReport quadricRegionReport(const SceneObject& a, const SceneObject& b);

/// The report for two scene objects: exact for every pair with an ellipsoid or sphere, FCL
/// (libccd) for box-box pairs.
PairReport evaluatePair(const SceneObject& a, const SceneObject& b);

/// The JSON document printed by `check`:
/// {"pairs":[{"a","b","status","collide","signed_distance","points":[p_a,p_b],"normal","method"}]}
/// with the pairs in scene order and the keys in that order.
nlohmann::ordered_json checkScene(const Scene& scene);

/// Runs `check`: reads the scene file, evaluates it at t = 0 (sceneAtTime: objects with a motion
/// where the motion puts them at t = 0) and writes the JSON (2-space indent, newline) to `out`. Nothing is written if the scene is bad.
/// \throws SceneError for an unreadable or invalid scene.
void runCheck(const std::string& scene_path, std::ostream& out);

}  // namespace cli
}  // namespace fcl_quadric
