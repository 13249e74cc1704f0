#pragma once
// Private: the front doors' dispatch for fcl_quadric's quadric shapes (quadric_shapes.h), which
// FCL's NODE_TYPE tables do not know (they report fcl::BV_UNKNOWN). docs/fcl_integration.md,
// section "Quadric shapes".
#include <cstddef>
#include <string>
#include <vector>

#include <fcl/common/types.h>
#include <fcl/geometry/collision_geometry.h>
#include <fcl/narrowphase/collision_request.h>
#include <fcl/narrowphase/collision_result.h>
#include <fcl/narrowphase/distance_request.h>
#include <fcl/narrowphase/distance_result.h>

#include "fcl_quadric/continuous/region_ccd.h"

namespace fcl_quadric {
namespace detail {

/// True if g is an fcl_quadric::QuadricShape (EllipticCylinder, Quadric, QuadricCSG).
bool isQuadricShape(const fcl::CollisionGeometry<double>* g);

/// Static collision of o1 (posed tf1) and o2 (posed tf2), at least one a QuadricShape, the other
/// a QuadricShape, an fcl Sphere / Ellipsoid / Box / Cylinder / Cone / Capsule / Halfspace, a BVH
/// mesh (each non-degenerate triangle; zero-area triangles are skipped) or an OcTree (each
/// occupied leaf box): collideRegions' certified classification (Touching counts as contact;
/// a triangle has no interior, so a crossing triangle is found as an undecided box: contact).
/// Meshes and octrees are visited through their own hierarchies (the mesh's BVH, the octree's
/// cells), only where their boxes meet the shape's box; FCL's traversal node templates are not used. On contact one
/// fcl::Contact is added (if request.num_max_contacts allows): pos = the witness point (world),
/// normal = unit outward normal of o1's nearest surface there, penetration_depth = 0 (not
/// computed for these shapes). \return the number of contacts in result.
/// \throws std::invalid_argument for any other geometry (planes, convex meshes, TriangleP: not
/// supported with quadric shapes; the message names the node type),
/// or an unbounded pair (two half-spaces / unbounded quadrics).
std::size_t collideQuadricShapes(const fcl::CollisionGeometry<double>* o1, const fcl::Transform3<double>& tf1,
                                 const fcl::CollisionGeometry<double>* o2, const fcl::Transform3<double>& tf2,
                                 const fcl::CollisionRequest<double>& request, fcl::CollisionResult<double>& result);

/// Distance of o1 (posed tf1) and o2 (posed tf2), at least one a QuadricShape, by GJK / EPA on
/// support mappings (convex_distance.h): a quadric shape must be convex (ConvexSupport::
/// fromRegion, or an EllipticCylinder) or a union of convex solids (its exact convex cover,
/// convex_cover.h: the smallest distance to a piece, the deepest piece's penetration depth); the
/// partner such a quadric shape, an fcl Sphere /
/// Ellipsoid / Box / Cylinder / Cone / Capsule (one piece), a Halfspace (closed form), a BVH mesh
/// (best first over its BVH) or an OcTree (occupied leaves pruned by their box gap). FCL's
/// semantics: result.update with the distance, -1 for an overlapping pair unless
/// request.enable_signed_distance (then minus the penetration depth of the deepest piece), nearest
/// points in the world frame, b1 / b2 = the triangle index of a mesh partner (NONE for leaves). Within 1e-8 of the
/// pair's scale of contact, the sign is the one fcl_quadric::collide gives the same pair (touching
/// = 0). \return result.min_distance. \throws std::invalid_argument for another non-convex
/// quadric shape, an unbounded one, or any other partner (the message names it).
double distanceQuadricShapes(const fcl::CollisionGeometry<double>* o1, const fcl::Transform3<double>& tf1,
                             const fcl::CollisionGeometry<double>* o2, const fcl::Transform3<double>& tf2,
                             const fcl::DistanceRequest<double>& request, fcl::DistanceResult<double>& result);

/// First contact over t in [0, 1] of o1 moving by m1 and o2 moving by m2 (body -> world), at
/// least one a QuadricShape, the other a QuadricShape or one of the FCL primitives above
/// (continuousCollideRegions, region_ccd.h). When both are non-null, `elements1` / `elements2`
/// receive the labels of the boundary elements in contact (boundaryElementLabel over
/// boundaryElements: extra certified searches; empty when there is no contact).
/// `dimension_reduction`: try continuousCollideRegionsByReduction first (thesis §6.2.2; both
/// operands bounded) and fall back to the space-time engine when it is Undecided; a decided
/// answer has `boxes` = candidates verified and no atom lists (the labels come from the pair).
/// `decided_by_reduction` (if non-null) tells whether the reduction answered.
/// A BVH mesh or OcTree operand is taken piece by piece (continuousCollideShapePieces: the
/// engine only, with the pieces' labels "T<triangle>" / "leaf").
/// \throws std::invalid_argument (message starting with `where`) for an unsupported geometry,
/// two meshes / octrees, or two unbounded operands.
RegionCcdResult continuousCollideQuadricShapes(const fcl::CollisionGeometry<double>* o1, const PiecewiseMotion& m1,
                                               const fcl::CollisionGeometry<double>* o2, const PiecewiseMotion& m2,
                                               const char* where, std::string* elements1, std::string* elements2,
                                               bool dimension_reduction = false, bool* decided_by_reduction = nullptr);

}  // namespace detail
}  // namespace fcl_quadric
