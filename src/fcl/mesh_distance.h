#pragma once
// Private: fcl_quadric::distance's own traversal of a triangle BVHModel (any of FCL 0.7's BV types)
// against an fcl::Ellipsoid or fcl::Sphere (docs/fcl_integration.md §3.3, "Distance").
#include <fcl/common/types.h>
#include <fcl/geometry/collision_geometry.h>
#include <fcl/narrowphase/distance_request.h>
#include <fcl/narrowphase/distance_result.h>

#include "fcl_quadric/fcl/quadric_solver.h"

namespace fcl_quadric {
namespace detail {

/// Distance between a triangle mesh (BVHModel of any BV type, model type BVH_MODEL_TRIANGLES) and
/// an Ellipsoid or a Sphere (either order) through `solver`, as FCL 0.7's mesh-shape distance
/// nodes compute it (MeshShapeDistanceTraversalNodeOBBRSS and its RSS / kIOS siblings), with these
/// differences:
///  - the search is best first: the nodes in the order of their lower bounds (a binary heap),
///    where FCL's distanceRecurse goes depth first, the nearer child first, after the leaf test of
///    triangle 0; it stops when canStop(the smallest bound left) holds, FCL's test:
///    bound >= min_distance - abs_err and bound (1 + rel_err) >= min_distance;
///  - a leaf whose own lower bound (the gaps along the triangle's normal and along the line from
///    the shape's centre to the triangle's nearest point) satisfies canStop is skipped;
///  - the leaf call solver.shapeTriangleDistance(shape, tf_shape, P1, P2, P3, tf_mesh, &d, &p_shape,
///    &p_mesh) for oriented BV types, and on the world vertices tf_mesh * V for AABB and k-DOPs
///    (mesh_collision.h), then result.update(d, mesh, shape, triangle, NONE, p_mesh, p_shape):
///    o1 the mesh, b1 the triangle, nearest_points[0] on the mesh, in either argument order;
///  - with enable_signed_distance and a negative minimum, FCL's fix-up: a contact collide of the
///    pair (fcl_quadric::collide, FCL's own result for these pairs), min_distance = -(its deepest
///    penetration), both nearest points at that contact; the return value is the minimum before
///    the fix-up, as FCL's distance() returns it.
/// The lower bound of a node: FCL fits a BV of the node's type to the shape on every query (for
/// OBBRSS an eigen-decomposition) and computes the RSS-RSS distance. Here it is
/// the largest gap between the shape and a box that contains the node's volume (NodeBox; under a
/// non-rigid pose of an AABB or k-DOP mesh, that box mapped to the world frame) along seven unit
/// axes: the box's three, the shape's three, and the line of their centres. The projection onto a
/// unit axis does not increase distances, so each gap bounds the distance from the shape to every
/// triangle in the node; the gap is lowered by tolerance::kTraversalPruningPadding of the scale,
/// which covers its rounding and that of the leaf's world vertices. A node is therefore skipped
/// only when none of its triangles can give a smaller distance than the one held, and the minimum
/// is that of the leaf test over every triangle, bit for bit (with rel_err = abs_err = 0, the
/// default; otherwise within FCL's canStop tolerance, as FCL's is). Which triangle attains it on a tie
/// (two triangles sharing the nearest edge) follows the visiting order, which differs from FCL's.
/// FCL 0.7 has no distance for OBB, AABB or k-DOP meshes against shapes (it prints "not
/// supported" and leaves the result untouched); this traversal gives them.
/// Bad input: as the collision traversal (mesh_collision.h): the shape is checked once before the
/// descent; oriented BV types need a rigid mesh pose.
/// \return false, leaving `result` untouched, for other pairs or model types and empty models;
/// otherwise true with *value = the distance FCL's distance() would return.
bool distanceMeshShape(const fcl::CollisionGeometry<double>* o1, const fcl::Transform3<double>& tf1,
                       const fcl::CollisionGeometry<double>* o2, const fcl::Transform3<double>& tf2,
                       const QuadricSolver<double>& solver, const fcl::DistanceRequest<double>& request,
                       fcl::DistanceResult<double>& result, double* value);

}  // namespace detail
}  // namespace fcl_quadric
