#pragma once
/// \file ellipsoid_region_distance.h
/// A certified lower bound of the distance between an ellipsoid and a composite quadric model
/// (quadric_region.h), for the queries that need only a bound: conservative advancement and
/// clearance in the OMPL layer. No exact distance for composite models exists in the library yet
/// (fcl_quadric::distance rejects them); this bound never exceeds the true distance.
///
/// Method. For delta >= 0 the ellipsoid scaled about its centre by s = 1 + delta / r_min contains
/// every point within delta of it: its support function s |S R^T n| = |S R^T n| + (delta / r_min)
/// |S R^T n| >= h(n) + delta, since |S R^T n| >= r_min for unit n. So if the certified region
/// engine (collideRegions) reports the scaled ellipsoid Separated from the region, the distance
/// is at least delta. The bound is the larger of the distance to the region's bounding box
/// (signedDistanceEllipsoidBox: the box contains the region) and the largest delta certified by
/// bisection on [that, cap]. Pure geometry (std + Eigen).

#include <Eigen/Core>

#include "fcl_quadric/geometry/ellipsoid.h"
#include "fcl_quadric/geometry/quadric_region.h"

namespace fcl_quadric {

namespace tolerance_region {
/// Bisection steps of ellipsoidRegionDistanceLowerBound: the bound is within 2^-10 of the range
/// [box bound, cap] below the largest certifiable delta (each step is one collideRegions call).
constexpr int kRegionDistanceBisections = 10;
}  // namespace tolerance_region

/// Certified lower bound of the distance between the ellipsoid e (world frame) and the region
/// (in its local frame, with its local bounding box `region_box`) posed in the world by
/// x -> R x + p; in [0, cap]. 0 when the two may touch or overlap (collideRegions is not
/// Separated); cap when nothing closer than cap is possible.
/// \throws std::invalid_argument if cap is negative or NaN, the box is empty or not finite, or
/// (R, p) is not a finite rigid transform.
double ellipsoidRegionDistanceLowerBound(const Ellipsoid& e, const QuadricRegion& region, const Box3& region_box,
                                         const Eigen::Matrix3d& R, const Eigen::Vector3d& p, double cap);

}  // namespace fcl_quadric
