#pragma once
// Private: fcl_quadric::distance's own traversal of an fcl::OcTree against an fcl::Ellipsoid or an
// fcl::Sphere (docs/fcl_integration.md §3.2, "Distance").
#include <fcl/common/types.h>
#include <fcl/geometry/collision_geometry.h>
#include <fcl/narrowphase/distance_request.h>
#include <fcl/narrowphase/distance_result.h>

#include "fcl_quadric/fcl/quadric_solver.h"

namespace fcl_quadric {
namespace detail {

/// Distance between an OcTree and an Ellipsoid or a Sphere (either order) through `solver`, as FCL 0.7's
/// OcTreeSolver::OcTreeShapeDistanceRecurse computes it, with its leaf call and result:
///  - nothing is done when the result already holds a distance <= 0 (request.isSatisfied);
///  - an inner cell that is not occupied is skipped; an occupied leaf cell gets the leaf test
///    solver.shapeDistance(box, box_tf, ellipsoid, tf_e, &d, &p_tree, &p_e) on FCL's box of the
///    cell (constructBox: the same bits) and result.update(d, tree, ellipsoid, the cell's index,
///    NONE, p_tree, p_e), in either argument order as FCL writes it;
///  - the search ends when the result's distance is <= 0;
///  - with enable_signed_distance and a negative minimum, FCL's fix-up (mesh_distance.h), and the
///    value FCL returns, the minimum before it.
/// What differs: FCL goes depth first, children 0..7, entering a child when the distance between
/// its world AABB and the ellipsoid's AABB is below the minimum held, and the rest of the octree
/// ignores rel_err and abs_err, as FCL does. Here the search is best first, the cells in the
/// order of a lower bound of their distance to the ellipsoid (PlacedEllipsoid::boxBound in the
/// tree frame: the gaps along seven axes, padded), and a cell is entered when its bound is below
/// the minimum held. Each bound is a true lower bound, so the minimum is the leaf test's over every
/// occupied leaf cell bit for bit; which cell attains it on a tie follows the visiting order.
/// FCL's AABB distance is loose for a rotated ellipsoid and its order ignores distance: on a
/// terrain of ~10^5 leaves it runs the exact leaf test on many cells (docs/benchmarks.md,
/// session 28).
/// A sphere is searched the same way (as the ellipsoid of equal radii); its leaf test is the one
/// QuadricSolver makes, FCL's box-sphere closed form (-1 on overlap, as libccd), so the value is
/// FCL's too.
/// Bad input: the ellipsoid and the tree's pose are checked once, before the traversal, by the
/// leaf test's own checks (std::invalid_argument naming the value).
/// \return false, leaving `result` untouched, for other pairs; otherwise true with *value = the
/// distance FCL's distance() would return.
bool distanceOcTreeShape(const fcl::CollisionGeometry<double>* o1, const fcl::Transform3<double>& tf1,
                         const fcl::CollisionGeometry<double>* o2, const fcl::Transform3<double>& tf2,
                         const QuadricSolver<double>& solver, const fcl::DistanceRequest<double>& request,
                         fcl::DistanceResult<double>& result, double* value);

}  // namespace detail
}  // namespace fcl_quadric
