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

#include <vector>

#include <Eigen/Core>

#include "fcl_quadric/geometry/ellipsoid.h"
#include "fcl_quadric/geometry/ellipsoid_separation.h"
#include "fcl_quadric/geometry/signed_distance.h"

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

/// The status of classifyEllipsoidBox only, with two cheap certificates tried first (the box
/// centre inside the ellipsoid; all vertices beyond the tangent plane orthogonal to the centre
/// line in the unit frame): the fast path for OcTree leaves. Same answer, same exceptions.
Separation ellipsoidBoxStatus(const Ellipsoid& e, const Eigen::Vector3d& half_extents, const Eigen::Matrix3d& R_WB,
                              const Eigen::Vector3d& p_WB);

/// Ellipsoid e against the (closed, solid 2D) triangle abc. Degenerate triangles (collinear or
/// coincident vertices) are handled as segments / points. \throws std::invalid_argument for
/// non-finite vertices.
EllipsoidPolytopeResult classifyEllipsoidTriangle(const Ellipsoid& e, const Eigen::Vector3d& a,
                                                  const Eigen::Vector3d& b, const Eigen::Vector3d& c);

/// Signed distance between ellipsoid e (a) and the box or triangle (b): Euclidean distance when
/// separate, minus the penetration depth when overlapping, 0 in the touching band; `normal` points
/// from the ellipsoid to the polytope, point_a is on the ellipsoid, point_b on the polytope.
///
/// Method: d = max over unit n of phi(n) = min_j n.v_j - h_e(n) (v_j the vertices). The maximiser
/// lies in the normal cone of one feature of the polytope, where phi reduces to a smooth problem
/// solved in closed form or by a one-dimensional root: a face gives n = -(outward face normal); a
/// vertex gives the point-ellipsoid problem (point_ellipsoid.h); an edge gives the point-ellipse
/// problem of the edge's line projected, with the ellipsoid's shadow, onto the plane orthogonal to
/// it. phi is evaluated exactly at every candidate direction and the best is kept, so no validity
/// test of the cones is needed. For separate pairs every sub-problem is convex and the result is
/// the exact distance (to rounding); penetration depth takes the best of the same candidates
/// (tested against dense direction sampling). The sign is the certified one of
/// classifyEllipsoidBox / classifyEllipsoidTriangle.
/// \throws std::invalid_argument as classifyEllipsoidBox / classifyEllipsoidTriangle (which
/// validate the input first).
SignedDistanceResult signedDistanceEllipsoidBox(const Ellipsoid& e, const Eigen::Vector3d& half_extents,
                                                const Eigen::Matrix3d& R_WB, const Eigen::Vector3d& p_WB);
SignedDistanceResult signedDistanceEllipsoidTriangle(const Ellipsoid& e, const Eigen::Vector3d& a,
                                                     const Eigen::Vector3d& b, const Eigen::Vector3d& c);

/// A convex polytope in the world frame (fcl::Convex): its vertices and its faces, each the
/// indices of one planar convex polygon's vertices in order around it (either orientation).
struct ConvexPolytope {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::vector<int>> faces;
};

/// Ellipsoid e against the convex polytope P. They intersect iff e's centre is in P or e meets
/// P's boundary (P and e convex: a segment from the centre to a common point crosses the
/// boundary inside e). The centre counts as in P when it is inside every face plane by more than
/// the plane test's rounding; the boundary is the faces' fan triangles, each classified by
/// classifyEllipsoidTriangle (certified). Overlapping if the centre is in P or a triangle
/// overlaps; Touching if a triangle touches; otherwise Separated, with the nearest triangle's
/// unit distance and point. \pre P is convex and its faces are its boundary (as fcl::Convex
/// assumes; not checked). \throws std::invalid_argument for no vertices, a vertex not finite or
/// beyond kMaxLength, a face with fewer than three vertices or an index out of range.
EllipsoidPolytopeResult classifyEllipsoidConvex(const Ellipsoid& e, const ConvexPolytope& P);

/// Signed distance between e and P, as signedDistanceEllipsoidBox (the same feature candidates:
/// P's faces, vertices and edges), with the status of classifyEllipsoidConvex.
/// \throws std::invalid_argument as classifyEllipsoidConvex.
SignedDistanceResult signedDistanceEllipsoidConvex(const Ellipsoid& e, const ConvexPolytope& P);

}  // namespace fcl_quadric
