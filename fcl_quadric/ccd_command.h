#pragma once
/// \file ccd_command.h
/// `fcl_quadric ccd SCENE.json`: continuous collision of the scene's moving objects over
/// t in [0, 1]: ellipsoid pairs by thesis ch.5 (continuousCollideEllipsoids), pairs with quadric
/// shapes or boxes by the region CCD (continuous/region_ccd.h).

#include <ostream>
#include <string>

#include <nlohmann/json.hpp>

#include "fcl_quadric/continuous/ellipse_ccd.h"
#include "fcl_quadric/continuous/ellipsoid_ccd.h"
#include "fcl_quadric/scene.h"

namespace fcl_quadric {
namespace cli {

/// The moving ellipsoid of a 3D scene object (its motion, or its pose held fixed).
/// \throws SceneError ("/objects/<index>/shape") if the object is not an ellipsoid or sphere.
MovingEllipsoid movingEllipsoid(const SceneObject& object, std::size_t index);

/// The bad-scene error for a pair whose motions exceed a continuous solver's degree limit
/// (CcdDegreeError): it names the motion of the pair's object of higher motion degree
/// ("/objects/<index>/motion/matrix" for a polynomial motion, ".../motion" otherwise).
SceneError degreeLimitError(const Scene& scene, std::size_t i, std::size_t j, const CcdDegreeError& e);

/// The moving ellipse of a planar scene object (its motion2). No failure mode for parsed scenes.
MovingEllipse2 movingEllipse2(const SceneObject& object);

/// The JSON document printed by `ccd`:
/// {"pairs":[{"a","b","collide","first_contact_time","contact_point","overlap_intervals",
///            "near_tangent","unresolved"}]}
/// with times in [0, 1]; first_contact_time and contact_point are null for a collision-free pair;
/// overlap_intervals lists the maximal collision intervals [t0, t1] (a grazing contact is a short
/// interval about the touching instant, as wide as the touching band allows; with
/// "all_intervals": false only the first contact, as [t, t]). Objects without a
/// motion stay at their pose.
/// Pairs with a quadric shape or a box (anything but two ellipsoids / spheres) are solved by the
/// region CCD (continuous/region_ccd.h): first contact only, so overlap_intervals is null, and
/// the entry adds "elements": the labels of the contacting boundary elements of a and b
/// ("F<i>" face, "E<i>" edge, "V<i>" vertex, indices into the shape's boundaryElements; [] when
/// there is no contact). near_tangent: some reported interval has no instant certified
/// overlapping (a contact within the tolerance band, or an uncertified conservative answer: the
/// work cap; reported early, never late). unresolved: the answer is that conservative one (the
/// work cap, or an ellipsoid pair's motion beyond the condition the solver decides).
///
/// `solver` (`ccd --solver`) chooses the method for those region pairs:
///  - RegionCcdSolver::SpaceTime (default): the certified space-time search;
///  - RegionCcdSolver::DimensionReduction: thesis §6.2's dimension reduction first
///    (continuous/dimension_reduction_ccd.h) for two bounded objects, falling back to the
///    space-time search for a pair it leaves undecided (a ring's quartic edge, a cone apex,
///    coincident planes, ...). Each region entry then adds "method": "dimension_reduction" or
///    "space_time", and "undecided_reason" (the reduction's reason) when it fell back.
/// \throws SceneError for two unbounded objects (half-spaces) in a pair, and for a pair whose
/// motions exceed the solver's degree limit (degreeLimitError()).
enum class RegionCcdSolver { SpaceTime, DimensionReduction };
nlohmann::ordered_json ccdScene(const Scene& scene, RegionCcdSolver solver = RegionCcdSolver::SpaceTime);

/// Runs `ccd`: reads the scene, solves every pair and writes the JSON (2-space indent, newline).
/// \throws SceneError for an unreadable or invalid scene; nothing is written then.
void runCcd(const std::string& scene_path, std::ostream& out, RegionCcdSolver solver = RegionCcdSolver::SpaceTime);

}  // namespace cli
}  // namespace fcl_quadric
