#pragma once
// Private: fcl_quadric::collide's own traversal of a triangle BVHModel<OBBRSS> or BVHModel<OBB>
// against an fcl::Ellipsoid or fcl::Sphere (docs/fcl_integration.md §3.3, "fcl_quadric's own
// traversal").
#include <cstddef>

#include <fcl/common/types.h>
#include <fcl/geometry/collision_geometry.h>
#include <fcl/narrowphase/collision_request.h>
#include <fcl/narrowphase/collision_result.h>

#include "fcl_quadric/fcl/quadric_solver.h"

namespace fcl_quadric {
namespace detail {

/// Boolean and contact collision of a triangle mesh (BVHModel<OBBRSS> or BVHModel<OBB>, model
/// type BVH_MODEL_TRIANGLES) with an Ellipsoid or a Sphere (either order) through `solver`, with
/// FCL 0.7's result: the nodes visited depth first as FCL's collisionRecurse visits them (left
/// child, stop if the request is satisfied, right child), the same leaf call
/// solver.shapeTriangleIntersect(shape, tf_shape, P1, P2, P3, tf_mesh, ...), the same contacts (o1
/// the mesh, b1 the triangle, b2 NONE, the normal negated as FCL's oriented nodes do, in either
/// order of the arguments). What differs is the node test: FCL fits an OBBRSS to the shape on
/// every query (an eigen-decomposition) and runs a 15-axis separating test of each node's OBB
/// against it. Here each node's OBB, in the mesh frame, is tested along its own three axes
/// against the shape's exact support and along the shape's three axes against the node's, with
/// a padding of tolerance::kTraversalPruningPadding (1e-7) of the pose's scale, as the OcTree
/// traversal (octree_collision.h): every node it prunes holds only triangles that the exact leaf
/// test finds separate.
/// Bad input: the shape is checked once, before the traversal, by the leaf test's own checks
/// (std::invalid_argument naming the value), so an invalid shape throws even where no triangle
/// would be reached; so does a mesh pose that is not rigid (the node test, like FCL's, assumes a
/// rotation; through FCL's traversal such a pose gave unreliable pruning without an error).
/// \return false, leaving `result` untouched, for other pairs, other BV types or model types,
/// an empty model, or a request with cost sources (FCL's traversal handles those); otherwise
/// true with *count = result.numContacts().
bool collideMeshShape(const fcl::CollisionGeometry<double>* o1, const fcl::Transform3<double>& tf1,
                      const fcl::CollisionGeometry<double>* o2, const fcl::Transform3<double>& tf2,
                      const QuadricSolver<double>& solver, const fcl::CollisionRequest<double>& request,
                      fcl::CollisionResult<double>& result, std::size_t* count);

}  // namespace detail
}  // namespace fcl_quadric
