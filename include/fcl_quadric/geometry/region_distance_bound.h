#pragma once
/// \file region_distance_bound.h
/// Certified lower bounds of the distance between a composite quadric model (quadric_region.h) and
/// an ellipsoid or any convex solid given as a region, for the queries that need only a bound:
/// conservative advancement and clearance in the OMPL layer, where a model's convex cover
/// (convex_cover.h) touches its partner but the model need not; cheaper than the distance of a
/// non-convex model (region_distance.h). These bounds never exceed the true distance.
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

#include <functional>
#include <optional>
#include <utility>

#include <Eigen/Core>

#include "fcl_quadric/geometry/ellipsoid.h"
#include "fcl_quadric/geometry/quadric_region.h"

namespace fcl_quadric {

namespace tolerance_region {
/// Bisection steps of the bounds below (each step is one collideRegions call): the bound is within
/// 2^-10 of its bracket below the largest certifiable delta. The bracket is [box bound, cap] when
/// the box bound is positive, else [delta, 2 delta] found by halving the range.
constexpr int kRegionDistanceBisections = 10;
/// Halvings of the search range tried from 0 (down to 2^-40 of it, ~1e-12): below, the bound is 0.
constexpr int kRegionDistanceDescents = 40;
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
/// in [0, cap]: 0 when they may touch or overlap, else the largest delta (to 2^-10 of itself, see
/// kRegionDistanceBisections) for which b scaled by 1 + delta / b_inradius about its origin is
/// certified separate.
/// \pre b is convex (not checked: for a non-convex b the scaled copy need not contain b's
/// neighbourhood). \throws std::invalid_argument if cap is negative or NaN, b_inradius is not
/// finite and > 0, a box is empty or not finite, b's box does not contain that ball, or (R_AB,
/// p_AB) is not a finite rigid transform.
double regionConvexDistanceLowerBound(const QuadricRegion& a, const Box3& a_box, const QuadricRegion& b,
                                      const Box3& b_box, double b_inradius, const Eigen::Matrix3d& R_AB,
                                      const Eigen::Vector3d& p_AB, double cap);

/// A superset of the delta-neighbourhood of a convex piece, for delta >= 0: the region (in the
/// piece's frame) and a bounding box of it. Growing by delta must contain every point within
/// delta of the piece; it need not be the exact neighbourhood (a lower bound then stays valid).
using OffsetSuperset = std::function<std::pair<QuadricRegion, Box3>(double delta)>;

/// The box c +- h grown to c +- (h + delta): contains the box's delta-neighbourhood.
/// \throws std::invalid_argument if c or h is not finite or h has a negative component.
OffsetSuperset boxOffsetSuperset(const Eigen::Vector3d& c, const Eigen::Vector3d& h);

/// The triangle's delta-prism: the slab |n.(x - p0)| <= delta cut by its three edge half-spaces
/// pushed out by delta (in-plane) and by two chamfers per edge (normals (m +- n) / sqrt 2, pushed
/// out by delta): contains every point within delta of the triangle, and along an edge reaches at
/// most delta / cos 22.5 deg ~ 1.082 delta from it (a bound found with it is within that factor of
/// the distance, when an edge is nearest). None for a
/// triangle of zero area (relative 1e-14) or with a non-finite vertex.
std::optional<OffsetSuperset> triangleOffsetSuperset(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                                     const Eigen::Vector3d& p2);

/// Certified lower bound of the distance between region a (local frame, bounding box a_box) and
/// a piece given by its offset supersets `grown` (OffsetSuperset above; piece frame), posed in
/// a's frame by x -> R_AB x + p_AB; in [0, cap]. The largest delta in [0, min(cap, 2 (a's half
/// diagonal + reach))] (to 2^-kRegionDistanceBisections of itself) for which collideRegions
/// certifies a Separated from grown(delta); 0 when grown(0) is not certified separate. `reach`
/// bounds |x| over the piece (piece frame): it sets the search range.
/// \throws std::invalid_argument if cap is negative or NaN, reach is not finite and >= 0, a_box
/// is empty or not finite, or (R_AB, p_AB) is not a finite rigid transform.
double regionOffsetDistanceLowerBound(const QuadricRegion& a, const Box3& a_box, const OffsetSuperset& grown,
                                      double reach, const Eigen::Matrix3d& R_AB, const Eigen::Vector3d& p_AB,
                                      double cap);

/// A region containing every point within delta >= 0 of `region` (its delta-neighbourhood), built
/// on the and/or formula over signed atoms (thesis §6.1's CSG tree, differences pushed to the atoms): each atom is replaced by a grown one and the formula
/// kept, which is a superset because growing distributes over unions and only shrinks an
/// intersection's neighbourhood. A plane is shifted by delta; a curved atom whose quadratic part
/// is positive semidefinite with its linear part in its range (ellipsoid, elliptic cylinder) is
/// scaled about its centre (axis) by 1 + delta / r_min, r_min its smallest semi-axis; the
/// complement of such an atom (a subtracted ellipsoid or cylinder, a ring's bore) is the
/// complement of the atom scaled by 1 - delta / r_min (the whole space once delta >= r_min): the
/// inner scaling lies in the atom's erosion by delta. None when an atom is of another kind
/// (paraboloids, hyperboloids, cones, their complements) or delta is negative or not finite.
std::optional<QuadricRegion> grownRegion(const QuadricRegion& region, double delta);

/// Certified lower bound of the distance between two regions of any shape (a in its frame with
/// bounding box a_box; b posed in a's frame by x -> R_AB x + p_AB, bounding box b_box): the largest
/// delta (to 2^-kRegionDistanceBisections of itself) for which collideRegions certifies a
/// separate from grownRegion(b, delta) searched in b_box grown by delta (which holds b's
/// delta-neighbourhood); in [0, cap]. 0 when they may touch, or when b's atoms cannot be grown
/// (then a's are tried: the bound is symmetric).
/// \throws std::invalid_argument if cap is negative or NaN, a box is empty or not finite, or
/// (R_AB, p_AB) is not a finite rigid transform.
double regionPairDistanceLowerBound(const QuadricRegion& a, const Box3& a_box, const QuadricRegion& b,
                                    const Box3& b_box, const Eigen::Matrix3d& R_AB, const Eigen::Vector3d& p_AB,
                                    double cap);

}  // namespace fcl_quadric
