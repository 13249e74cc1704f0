#pragma once
// Private: fcl_quadric::collide's own traversal of a triangle BVHModel (OBBRSS, OBB, RSS, kIOS,
// AABB, KDOP16/18/24) against an fcl::Ellipsoid or fcl::Sphere (docs/fcl_integration.md §3.3,
// "fcl_quadric's own traversal").
#include <cstddef>

#include <fcl/common/types.h>
#include <fcl/geometry/collision_geometry.h>
#include <fcl/narrowphase/collision_request.h>
#include <fcl/narrowphase/collision_result.h>

#include "fcl_quadric/fcl/quadric_solver.h"

namespace fcl_quadric {
namespace detail {

/// Boolean and contact collision of a triangle mesh (BVHModel of any of FCL 0.7's BV types, model
/// type BVH_MODEL_TRIANGLES) with an Ellipsoid or a Sphere (either order) through `solver`: the
/// nodes visited depth first as FCL's collisionRecurse visits them (left child, stop if the
/// request is satisfied, right child), FCL's leaf call and FCL's contacts (o1 the mesh, b1 the
/// triangle, b2 NONE, the normal negated as FCL's mesh-shape nodes do, in either order of the
/// arguments).
///  - Oriented BV types (OBBRSS, OBB, RSS, kIOS): the same leaf call
///    solver.shapeTriangleIntersect(shape, tf_shape, P1, P2, P3, tf_mesh, ...) on the same tree:
///    FCL's result exactly. What differs is the node test: FCL fits a BV of the node's type to
///    the shape on every query (an eigen-decomposition for OBBRSS) and runs its overlap test.
///    Here a box with the node's axes that contains its volume (the OBB of OBBRSS and kIOS; for
///    RSS the box of its rectangle grown by its radius) is tested along its own three axes
///    against the shape's exact support and along the shape's three axes against the box's.
///  - Axis-aligned types (AABB, k-DOPs): FCL copies the whole model on every query, maps its
///    vertices by the mesh's pose and rebuilds its tree in the world frame (BVHShapeCollider,
///    MeshShapeCollisionTraversalNode's initialize(): milliseconds for a few thousand triangles),
///    then calls solver.shapeTriangleIntersect(shape, tf_shape, W1, W2, W3, ...) on the world
///    vertices W = tf_mesh * V. Here the model's own tree is traversed; each node's box (a k-DOP's
///    three axis slabs) is mapped by the pose to a world box and compared with the shape's exact
///    world box; the leaf call is FCL's, on the same world vertices bit for bit. Hence the same
///    collision flag and, when the contact limit does not cut the list, the same contacts with the
///    same geometry. The order of the contacts, and so which ones a limit keeps, follows the
///    model's tree rather than FCL's rebuilt one; the two trees are the same when the pose is the
///    identity. o1 is the caller's model: FCL's is its temporary copy, deleted before it returns.
/// Both node tests are padded by tolerance::kTraversalPruningPadding (1e-7) of the poses' scale,
/// as the OcTree traversal (octree_collision.h): every node pruned holds only triangles that the
/// exact leaf test finds separate.
/// Bad input: the shape is checked once, before the traversal, by the leaf test's own checks
/// (std::invalid_argument naming the value), so an invalid shape throws even where no triangle
/// would be reached. For oriented types the mesh pose must be rigid (the node test, like FCL's,
/// assumes a rotation; through FCL's traversal such a pose gave unreliable pruning without an
/// error); for axis-aligned types any finite affine pose is accepted, as FCL does, and a
/// non-finite one throws.
/// \return false, leaving `result` untouched, for other pairs or model types, an empty model, or
/// a request with cost sources (FCL's traversal handles those); otherwise true with
/// *count = result.numContacts().
bool collideMeshShape(const fcl::CollisionGeometry<double>* o1, const fcl::Transform3<double>& tf1,
                      const fcl::CollisionGeometry<double>* o2, const fcl::Transform3<double>& tf2,
                      const QuadricSolver<double>& solver, const fcl::CollisionRequest<double>& request,
                      fcl::CollisionResult<double>& result, std::size_t* count);

}  // namespace detail
}  // namespace fcl_quadric
