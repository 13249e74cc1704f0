#pragma once
/// \file region_distance_bound.h
/// Certified lower bounds of the distance between a composite quadric model (quadric_region.h) and
/// an ellipsoid or any convex solid given as a region, for the queries that need only a bound:
/// conservative advancement and clearance in the OMPL layer. No exact distance for composite models exists in the library yet
/// (fcl_quadric::distance rejects them); this bound never exceeds the true distance.
///
/// Method. For delta >= 0 the ellipsoid scaled about its centre by s = 1 + delta / r_min contains
/// every point within delta of it: its support function s |S R^T n| = |S R^T n| + (delta / r_min)
/// |S R^T n| >= h(n) + delta, since |S R^T n| >= r_min for unit n. So if the certified region
/// engine (collideRegions) reports the scaled ellipsoid Separated from the region, the distance
/// is at least delta. The bound is the larger of the distance to the region's bounding box
/// (signedDistanceEllipsoidBox: the box contains the region) and the largest delta certified by
/// bisection on [that, cap]. The same holds for any convex solid K that contains the ball of radius
/// rho about a point c: K scaled about c by 1 + delta / rho has support h_K(n) + (delta / rho)
/// (h_K(n) - n.c) >= h_K(n) + delta (regionConvexDistanceLowerBound). Pure geometry (std + Eigen).

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

/// Certified lower bound of the distance between region a (its local frame; bounding box a_box)
/// and a convex solid b given as a region in its own frame that contains the ball of radius
/// `b_inradius` about its origin (bounding box b_box), b posed in a's frame by x -> R_AB x + p_AB;
/// in [0, cap]: 0 when they may touch or overlap, else the largest delta (to 2^-10 of the search
/// range) for which b scaled by 1 + delta / b_inradius about its origin is certified separate.
/// \pre b is convex (not checked: for a non-convex b the scaled copy need not contain b's
/// neighbourhood). \throws std::invalid_argument if cap is negative or NaN, b_inradius is not
/// finite and > 0, a box is empty or not finite, b's box does not contain that ball, or (R_AB,
/// p_AB) is not a finite rigid transform.
double regionConvexDistanceLowerBound(const QuadricRegion& a, const Box3& a_box, const QuadricRegion& b,
                                      const Box3& b_box, double b_inradius, const Eigen::Matrix3d& R_AB,
                                      const Eigen::Vector3d& p_AB, double cap);

}  // namespace fcl_quadric
