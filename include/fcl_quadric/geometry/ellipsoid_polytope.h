#pragma once
/// \file ellipsoid_polytope.h
/// Exact intersection tests of an ellipsoid with a box (FCL boxes, OcTree leaves) and with a
/// triangle (BVH meshes).
///
/// In the ellipsoid's unit frame u = S^-1 R^T (x - p) the ellipsoid is the unit ball and the
/// polytope the affine image { g + G s : s in D } of its parameter domain D (the cube [-1,1]^3 for
/// a box, the standard triangle for a triangle). They intersect iff min over D of |g + G s|^2 <= 1:
/// a convex quadratic program in <= 3 variables, solved exactly by enumerating the faces of D (the
/// minimiser is the least-squares solution on the affine hull of the face whose relative interior
/// contains it). The answer is certified: overlap by a polytope point strictly inside the unit
/// ball, separation by the plane orthogonal to the minimiser that leaves every vertex strictly
/// outside; otherwise Touching (within a relative band of 2^-40; counts as contact).

#include <Eigen/Core>

#include "fcl_quadric/geometry/ellipsoid.h"
#include "fcl_quadric/geometry/ellipsoid_separation.h"

namespace fcl_quadric {

struct EllipsoidPolytopeResult {
  Separation status = Separation::Touching;
  /// min over the polytope of |S^-1 R^T (y - p)|^2 (<= 1 iff they intersect).
  double unit_distance2 = 0.0;
  /// The polytope point attaining it (world frame): inside the ellipsoid when Overlapping.
  Eigen::Vector3d closest = Eigen::Vector3d::Zero();
};

/// Ellipsoid e against the box { p_WB + R_WB s : |s_i| <= h_i } (FCL's fcl::Box of side 2h).
/// \throws std::invalid_argument for non-finite or negative half extents, a non-rotation R_WB or
/// a non-finite centre.
EllipsoidPolytopeResult classifyEllipsoidBox(const Ellipsoid& e, const Eigen::Vector3d& half_extents,
                                             const Eigen::Matrix3d& R_WB, const Eigen::Vector3d& p_WB);

/// Ellipsoid e against the (closed, solid 2D) triangle abc. Degenerate triangles (collinear or
/// coincident vertices) are handled as segments / points. \throws std::invalid_argument for
/// non-finite vertices.
EllipsoidPolytopeResult classifyEllipsoidTriangle(const Ellipsoid& e, const Eigen::Vector3d& a,
                                                  const Eigen::Vector3d& b, const Eigen::Vector3d& c);

}  // namespace fcl_quadric
