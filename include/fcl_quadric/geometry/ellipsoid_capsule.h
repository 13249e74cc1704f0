#pragma once
/// \file ellipsoid_capsule.h
/// Ellipsoid against a capsule (FCL's fcl::Capsule: the segment { p + R (0,0,s) : |s| <= L/2 }
/// swept by a ball of radius r).
///
/// A capsule is a segment plus a ball, so its signed distance to the ellipsoid is the segment's
/// minus r (Minkowski sum with a ball shifts signed distance by the radius). The segment is a
/// degenerate triangle: its intersection test is the exact classifyEllipsoidTriangle, and its
/// signed distance the feature-candidate method of signedDistanceEllipsoidTriangle (vertices by
/// the point-ellipsoid root, the edge by the point-ellipse root of its projected line; both solved
/// in long double). Status: Overlapping when the segment meets the ellipsoid (r > 0); otherwise
/// Separated when the certified lower bound of the segment's distance exceeds r (band: 2^-40 times
/// the bound's absolute evaluation), Overlapping when a point certified inside the ellipsoid lies
/// within r of the segment (an upper bound), and Touching (contact) in between.

#include <Eigen/Core>

#include "fcl_quadric/geometry/ellipsoid.h"
#include "fcl_quadric/geometry/signed_distance.h"

namespace fcl_quadric {

/// \throws std::invalid_argument for a negative or non-finite radius or length, a non-rotation R
/// or a non-finite centre.
SignedDistanceResult signedDistanceEllipsoidCapsule(const Ellipsoid& e, double radius, double length,
                                                    const Eigen::Matrix3d& R_WC, const Eigen::Vector3d& p_WC);

}  // namespace fcl_quadric
