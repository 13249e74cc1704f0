#pragma once
// Private: the front doors' dispatch for fcl_quadric's quadric shapes (quadric_shapes.h), which
// FCL's NODE_TYPE tables do not know (they report fcl::BV_UNKNOWN). docs/fcl_integration.md,
// section "Quadric shapes".
#include <cstddef>

#include <fcl/common/types.h>
#include <fcl/geometry/collision_geometry.h>
#include <fcl/narrowphase/collision_request.h>
#include <fcl/narrowphase/collision_result.h>

namespace fcl_quadric {
namespace detail {

/// True if g is an fcl_quadric::QuadricShape (EllipticCylinder, Quadric, QuadricCSG).
bool isQuadricShape(const fcl::CollisionGeometry<double>* g);

/// Static collision of o1 (posed tf1) and o2 (posed tf2), at least one a QuadricShape, the other
/// a QuadricShape, an fcl Sphere / Ellipsoid / Box / Cylinder / Cone / Capsule / Halfspace, a BVH
/// mesh (each non-degenerate triangle; zero-area triangles are skipped) or an OcTree (each
/// occupied leaf box): collideRegions' certified classification (Touching counts as contact;
/// a triangle has no interior, so a crossing triangle is found as an undecided box: contact).
/// Meshes and octrees are walked piece by piece with AABB culling, not through FCL's BVH
/// traversal nodes (cost linear in the pieces). On contact one
/// fcl::Contact is added (if request.num_max_contacts allows): pos = the witness point (world),
/// normal = unit outward normal of o1's nearest surface there, penetration_depth = 0 (not
/// computed for these shapes). \return the number of contacts in result.
/// \throws std::invalid_argument for any other geometry (planes, convex meshes, TriangleP: not
/// supported with quadric shapes; the message names the node type),
/// or an unbounded pair (two half-spaces / unbounded quadrics).
std::size_t collideQuadricShapes(const fcl::CollisionGeometry<double>* o1, const fcl::Transform3<double>& tf1,
                                 const fcl::CollisionGeometry<double>* o2, const fcl::Transform3<double>& tf2,
                                 const fcl::CollisionRequest<double>& request, fcl::CollisionResult<double>& result);

}  // namespace detail
}  // namespace fcl_quadric
