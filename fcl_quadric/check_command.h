#pragma once
/// \file check_command.h
/// `fcl_quadric check SCENE.json`: classify and measure every requested pair of a scene.

#include <ostream>
#include <string>

#include <nlohmann/json.hpp>

#include "fcl_quadric/pair_report.h"
#include "fcl_quadric/scene.h"

namespace fcl_quadric {
namespace cli {

/// Exact report for two ellipsoids: status from classifyEllipsoids(), distance, witness points
/// and normal from signedDistance(). `method` is PairMethod::Exact.
PairReport exactPairReport(const Ellipsoid& a, const Ellipsoid& b);

/// The report for two scene objects: exact for ellipsoid/sphere pairs, FCL for pairs with a box.
PairReport evaluatePair(const SceneObject& a, const SceneObject& b);

/// The JSON document printed by `check`:
/// {"pairs":[{"a","b","status","collide","signed_distance","points":[p_a,p_b],"normal","method"}]}
/// with the pairs in scene order and the keys in that order.
nlohmann::ordered_json checkScene(const Scene& scene);

/// Runs `check`: reads the scene file, evaluates it and writes the JSON (2-space indent, newline)
/// to `out`. Nothing is written if the scene is bad.
/// \throws SceneError for an unreadable or invalid scene.
void runCheck(const std::string& scene_path, std::ostream& out);

}  // namespace cli
}  // namespace fcl_quadric
