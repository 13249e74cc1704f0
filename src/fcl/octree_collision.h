#pragma once
// Private: fcl_quadric::collide's own traversal of an fcl::OcTree against an fcl::Ellipsoid or
// fcl::Sphere (docs/fcl_integration.md §3.2, "fcl_quadric's own traversal").
#include <cstddef>

#include <fcl/common/types.h>
#include <fcl/geometry/collision_geometry.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/math/bv/AABB.h>
#include <fcl/narrowphase/collision_request.h>
#include <fcl/narrowphase/collision_result.h>

#include "fcl_quadric/fcl/quadric_solver.h"

namespace fcl_quadric {
namespace detail {

/// The checks the leaf test makes (QuadricSolver's box of a cell posed tf_tree, against the shape
/// posed tf_shape), made once before a traversal of the tree whose root box is `root_bv`: bad
/// input (a tree pose that is not a rotation, a shape's bad radius or rotation) throws
/// std::invalid_argument naming "o1" or "o2", whether or not a leaf is reached; the placement the
/// traversal computes from the poses is then meaningful.
template <typename Shape>
void checkOcTreeQuery(const fcl::AABB<double>& root_bv, const fcl::Transform3<double>& tf_tree, const Shape& shape,
                      const fcl::Transform3<double>& tf_shape) {
  (void)asExact(fcl::Box<double>(root_bv.max_ - root_bv.min_), tf_tree * fcl::Translation3<double>(root_bv.center()),
                "o1");
  (void)asExact(shape, tf_shape, "o2");
}

/// FCL's computeChildBV (octree-inl.h), written out so that it inlines: the same arithmetic, so
/// the leaf boxes handed to the solver are FCL's bit for bit (both own OcTree traversals).
inline void octreeChildBox(const fcl::AABB<double>& bv, unsigned i, fcl::AABB<double>* child) {
  for (int k = 0; k < 3; ++k) {
    const double mid = (bv.min_[k] + bv.max_[k]) * 0.5;
    if (i >> k & 1u) {
      child->min_[k] = mid;
      child->max_[k] = bv.max_[k];
    } else {
      child->min_[k] = bv.min_[k];
      child->max_[k] = mid;
    }
  }
}

/// Boolean and contact collision of an OcTree with an Ellipsoid or a Sphere (either order) through
/// `solver`, with FCL 0.7's result: the same leaves tested in the same depth-first order as
/// FCL's OcTreeSolver::OcTreeShapeIntersectRecurse (children 0..7, occupancy and free thresholds,
/// the shape's own thresholds), the same contacts (o1 the tree, b1 the leaf's index, b2 NONE, in
/// either order of the arguments, as FCL writes them), the same early stop
/// (request.isSatisfied). What differs is the pruning: each cell's box is compared, in the tree's
/// frame, with the shape's exact bounding box there, padded by tolerance::kTraversalPruningPadding (1e-7) of the pose's scale
/// (|p_tree| + |p_shape| + |c| + r_max, c the shape's centre in the tree frame): six comparisons
/// per cell instead of FCL's box-to-OBB conversion and 15-axis separating test. The padding is
/// ~25 times what the rotation defect that poses may carry (tolerance::kRotationOrthogonality,
/// 1e-9) can move a point (4e-9 of that scale) and ~10^5 times the exact tests' touching band, so every cell it prunes is certified separate by
/// the leaf test as well: the answer is FCL's with this solver (tested against it,
/// ExactOcTree.OwnTraversalGivesFclsTraversalResultExactly).
/// Bad input: the shape and the tree's pose are checked once, before the traversal, by the
/// leaf test's own checks (std::invalid_argument naming the value), so an invalid shape throws even
/// where no leaf would be reached (a non-empty tree).
/// \return false, leaving `result` untouched, when the pair is not OcTree/Ellipsoid or
/// OcTree/Sphere, or the request asks for cost sources (FCL's traversal handles those);
/// otherwise true with *count = result.numContacts().
bool collideOcTreeShape(const fcl::CollisionGeometry<double>* o1, const fcl::Transform3<double>& tf1,
                        const fcl::CollisionGeometry<double>* o2, const fcl::Transform3<double>& tf2,
                        const QuadricSolver<double>& solver, const fcl::CollisionRequest<double>& request,
                        fcl::CollisionResult<double>& result, std::size_t* count);

}  // namespace detail
}  // namespace fcl_quadric
