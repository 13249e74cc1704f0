#pragma once
/// \file pair_report.h
/// The result of checking one pair of scene objects, as printed by `fcl_quadric check`.

#include <Eigen/Core>

#include "fcl_quadric/geometry/ellipsoid_separation.h"

namespace fcl_quadric {
namespace cli {

/// How a pair was computed: by the exact ellipsoid library or by FCL's own GJK/EPA (pairs with a
/// box, until exact ellipsoid-box lands).
/// QuadricRegion: pairs with a quadric shape (elliptic_cylinder, cylinder, halfspace, quadric,
/// csg), classified by the certified composite-quadric engine (quadric_region.h); no signed
/// distance (the report has NaN, printed as null), witness point only on contact.
enum class PairMethod { Exact, Fcl, QuadricRegion };

/// "exact", "fcl" or "quadric_region" (the JSON spelling).
const char* toString(PairMethod method);

struct PairReport {
  Separation status = Separation::Touching;
  /// True unless separate (touching counts as contact).
  bool collide = true;
  /// > 0: distance; < 0: minus the penetration depth.
  double signed_distance = 0.0;
  Eigen::Vector3d point_a = Eigen::Vector3d::Zero();  ///< witness on the first object (world)
  Eigen::Vector3d point_b = Eigen::Vector3d::Zero();  ///< witness on the second object (world)
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();  ///< unit, from the first object to the second
  PairMethod method = PairMethod::Exact;
};

}  // namespace cli
}  // namespace fcl_quadric
