#pragma once
/// \file distance.h
/// fcl_quadric::distance: FCL's distance() with the exact narrow phase (QuadricSolver) and checked
/// input, plus the broad-phase callback defaultDistanceFunction.
///
/// Same overloads and meaning as fcl::distance in <fcl/narrowphase/distance.h>; routed through
/// FCL's DistanceFunctionMatrix instantiated for QuadricSolver<double> (src/fcl/distance.cpp).
///  - result.min_distance: the distance; for colliding pairs, with
///    request.enable_signed_distance, minus the penetration depth, otherwise -1 (FCL's
///    "implementation defined" value, as GJKSolver_libccd).
///  - result.nearest_points (request.enable_nearest_points): world frame, p[0] on o1, p[1] on o2.
///    For primitive pairs they lie on the surfaces (also when penetrating, with signed distance);
///    for BVH / OcTree operands FCL's workaround applies (both points = a contact position).
///    Exception, as FCL 0.7 does it: an ellipsoid or sphere against a BVH mesh reports the mesh as
///    result.o1 / b1 and p[0] on the mesh in either argument order (src/fcl/mesh_distance.h).
///  - the libccd fallback gets distance_tolerance = request.distance_tolerance, as fcl::distance
///    does for GST_LIBCCD; request.gjk_solver_type is ignored.
///  - bad input (null object / geometry, non-finite transform) throws std::invalid_argument;
///  - quadric shapes (EllipticCylinder, Quadric, QuadricCSG): convex ones are answered by GJK / EPA
///    on support mappings, their witnesses refined near contact (docs/algorithms.md section 12,
///    12c; relative accuracy 1e-10 plus 1e-14 of the pair's scale; a mesh triangle is refined
///    feature by feature, docs/reliability.md finding 34); against another convex quadric shape, FCL's convex primitives, half-spaces, meshes and octrees, whose
///    triangle / leaf index goes to b1 / b2); near contact the sign is fcl_quadric::collide's. A
///    union of convex solids (an exact convex cover, convex_cover.h) is answered piece by piece
///    (nearest piece; deepest piece's penetration depth). Any other (non-convex) quadric shape by
///    the branch and bound of geometry/region_distance.h (docs/algorithms.md section 12b) against
///    the same partners and each other: witnesses on both solids, the distance at most
///    max(request.abs_err, 1e-6 of the pair's scale) above the true one; an overlap reports -1
///    (with enable_signed_distance: 0, its depth is not computed). An unsupported partner throws
///    std::invalid_argument naming it (distanceLowerBound below bounds every quadric shape).
/// Kept from FCL: pairs FCL has no function for print FCL's warning and return
/// std::numeric_limits<S>::max() with `result` untouched.
///
/// Call it qualified (fcl_quadric::distance), see collision.h. Only S = double is instantiated.

#include <optional>

#include <fcl/common/types.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/distance_request.h>
#include <fcl/narrowphase/distance_result.h>

namespace fcl_quadric {

/// Distance between two collision objects. \return result.min_distance as computed (as fcl::distance).
/// \throws std::invalid_argument if o1 or o2, or its geometry, is null, or a transform is not finite.
template <typename S>
S distance(const fcl::CollisionObject<S>* o1, const fcl::CollisionObject<S>* o2,
           const fcl::DistanceRequest<S>& request, fcl::DistanceResult<S>& result);

/// Distance between geometry o1 posed at tf1 and o2 posed at tf2.
/// \throws std::invalid_argument if o1 or o2 is null or tf1 / tf2 is not finite.
template <typename S>
S distance(const fcl::CollisionGeometry<S>* o1, const fcl::Transform3<S>& tf1, const fcl::CollisionGeometry<S>* o2,
           const fcl::Transform3<S>& tf2, const fcl::DistanceRequest<S>& request, fcl::DistanceResult<S>& result);

/// Broad-phase callback (fcl::DistanceCallBack<S>), FCL's DefaultDistanceFunction with
/// fcl_quadric::distance. `data` must point to an fcl::DefaultDistanceData<S>
/// (<fcl/broadphase/default_broadphase_callbacks.h>); `dist` receives result.min_distance;
/// evaluation stops (returns true) once dist <= 0, as in FCL.
/// \throws std::invalid_argument if data is null (FCL's version asserts), or from distance().
template <typename S>
bool defaultDistanceFunction(fcl::CollisionObject<S>* o1, fcl::CollisionObject<S>* o2, void* data, S& dist);

/// Certified lower bound, in [0, cap], of the distance between o1 posed at tf1 and o2 posed at
/// tf2, for the pairs whose distance() is not exact or not available: at least one operand a
/// bounded quadric shape (quadric_shapes.h; convex or not), or an fcl Box / Cylinder / Cone /
/// Capsule against one of those, a BVH mesh, an OcTree or a Halfspace (whose distance() is FCL's
/// libccd GJK, not certified). 0 when they may touch or overlap; cap when nothing closer than cap
/// is possible. Method (docs/algorithms.md section 12): each operand is covered by convex pieces
/// (convex_cover.h; one piece for a convex one), a mesh or octree is searched best first over its
/// triangles / occupied leaves, and each pair of pieces gets GJK's distance less its certified
/// error. Where a cover touches but is larger than its solid (rings, wedges), the region engine
/// certifies a grown copy of the convex partner or piece separate (region_distance_bound.h): the
/// partner scaled about an inner ball, a triangle's delta-prism, a box or half-space pushed out by
/// delta, or either operand with its atoms grown (grownRegion: two non-convex models; 0 when
/// neither operand's atoms can be grown). \return std::nullopt for every other
/// pair (no quadric shape and no such FCL primitive, or one against a sphere / ellipsoid, whose
/// distance is exact). \throws std::invalid_argument for a null geometry, a cap < 0 or NaN, a
/// transform that is not finite and rigid, an unbounded quadric shape, or a partner that
/// fcl_quadric::collide does not support with quadric shapes (the message names it).
std::optional<double> distanceLowerBound(const fcl::CollisionGeometry<double>* o1, const fcl::Transform3<double>& tf1,
                                         const fcl::CollisionGeometry<double>* o2, const fcl::Transform3<double>& tf2,
                                         double cap);

extern template double distance(const fcl::CollisionObject<double>*, const fcl::CollisionObject<double>*,
                                const fcl::DistanceRequest<double>&, fcl::DistanceResult<double>&);
extern template double distance(const fcl::CollisionGeometry<double>*, const fcl::Transform3<double>&,
                                const fcl::CollisionGeometry<double>*, const fcl::Transform3<double>&,
                                const fcl::DistanceRequest<double>&, fcl::DistanceResult<double>&);
extern template bool defaultDistanceFunction(fcl::CollisionObject<double>*, fcl::CollisionObject<double>*, void*,
                                             double&);

}  // namespace fcl_quadric
