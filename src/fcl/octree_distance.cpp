// fcl_quadric::distance's traversal of an OcTree against an Ellipsoid or a Sphere: FCL 0.7's
// OcTreeShapeDistanceRecurse with its leaf test, best first with padded lower bounds.
#include "fcl/octree_distance.h"
#include "fcl/input_checks.h"

#include <algorithm>
#include <cstdint>
#include <vector>

#include <fcl/config.h>

#if FCL_HAVE_OCTOMAP
#include <fcl/geometry/octree/octree.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/sphere.h>
#endif

#include "fcl/distance_fix_up.h"
#include "fcl/octree_collision.h"
#include "fcl/traversal_bound.h"

namespace fcl_quadric {
namespace detail {

#if FCL_HAVE_OCTOMAP
namespace {

/// Shape: fcl::Ellipsoid or fcl::Sphere (the leaf call is then FCL's box-sphere closed form, which
/// QuadricSolver hands to FCL).
template <typename Shape>
class OcTreeShapeDistance {
 public:
  using Node = fcl::OcTree<double>::OcTreeNode;

  OcTreeShapeDistance(const fcl::OcTree<double>& tree, const fcl::Transform3<double>& tf_tree, const Shape& shape,
                      const fcl::Transform3<double>& tf_shape, const QuadricSolver<double>& solver,
                      fcl::DistanceResult<double>& result)
      : tree_(tree), tf_tree_(tf_tree), shape_(shape), tf_shape_(tf_shape), solver_(solver), result_(result) {}

  void run() {
    const Node* root = tree_.getRoot();
    if (root == nullptr) return;
    // The leaf test's checks (QuadricSolver::shapeDistance(box, box_tf, shape, tf_shape)), once:
    // bad input throws whether or not a leaf is reached, and the placement below is meaningful.
    const fcl::AABB<double> root_bv = tree_.getRootBV();
    checkOcTreeQuery(root_bv, tf_tree_, shape_, tf_shape_);
    // The shape in the tree frame (the tree's pose is a rotation, checked just above).
    placed_ = placeInFrame(tf_tree_, tf_shape_, shapeRadii(shape_));
    search(root, root_bv);
  }

 private:
  struct Entry {
    double bound;
    const Node* node;
    fcl::AABB<double> bv;
    bool operator<(const Entry& o) const { return bound > o.bound; }  // a min-heap on the bound
  };

  double bound(const fcl::AABB<double>& bv) const {
    const Eigen::Vector3d c = 0.5 * (bv.min_ + bv.max_), e = 0.5 * (bv.max_ - bv.min_);
    return placed_.boxBound(Eigen::Matrix3d::Identity(), c, e, c.cwiseAbs().maxCoeff() + e.maxCoeff());
  }

  // The branches of OcTreeShapeDistanceRecurse (octree_solver-inl.h): a leaf is tested when
  // occupied; an inner cell that is not occupied is skipped; the root is entered without a
  // bound; the search stops when the distance held is <= 0 (DistanceRequest::isSatisfied).
  void search(const Node* root, const fcl::AABB<double>& root_bv) {
    std::vector<Entry> heap;
    heap.push_back({0.0, root, root_bv});
    while (!heap.empty() && !(result_.min_distance <= 0.0)) {
      std::pop_heap(heap.begin(), heap.end());
      const Entry e = heap.back();
      heap.pop_back();
      if (!(e.bound < result_.min_distance)) break;  // every cell left is at least as far
      if (!tree_.nodeHasChildren(e.node)) {
        if (tree_.isNodeOccupied(e.node)) leaf(e.node, e.bv);
        continue;
      }
      if (!tree_.isNodeOccupied(e.node)) continue;
      for (unsigned i = 0; i < 8; ++i) {
        if (!tree_.nodeChildExists(e.node, i)) continue;
        Entry child{0.0, tree_.getNodeChild(e.node, i), fcl::AABB<double>()};
        octreeChildBox(e.bv, i, &child.bv);
        child.bound = bound(child.bv);
        if (!(child.bound < result_.min_distance)) continue;
        heap.push_back(child);
        std::push_heap(heap.begin(), heap.end());
      }
    }
  }

  // FCL's leaf test: the box of constructBox(bv, tf_tree), shapeDistance, result.update.
  void leaf(const Node* node, const fcl::AABB<double>& bv) {
    const fcl::Box<double> box(bv.max_ - bv.min_);
    const fcl::Transform3<double> box_tf = tf_tree_ * fcl::Translation3<double>(bv.center());
    double d = 0.0;  // written by the exact ellipsoid-box distance; FCL's sphere-box one writes it too
    fcl::Vector3d p_tree = fcl::Vector3d::Zero(), p_shape = fcl::Vector3d::Zero();
    solver_.shapeDistance(box, box_tf, shape_, tf_shape_, &d, &p_tree, &p_shape);
    const std::intptr_t index = node - tree_.getRoot();
    result_.update(d, &tree_, &shape_, static_cast<int>(index), fcl::DistanceResult<double>::NONE, p_tree, p_shape);
  }

  const fcl::OcTree<double>& tree_;
  const fcl::Transform3<double>& tf_tree_;
  const Shape& shape_;
  const fcl::Transform3<double>& tf_shape_;
  const QuadricSolver<double>& solver_;
  fcl::DistanceResult<double>& result_;
  PlacedEllipsoid placed_;
};

}  // namespace
#endif  // FCL_HAVE_OCTOMAP

bool distanceOcTreeShape(const fcl::CollisionGeometry<double>* o1, const fcl::Transform3<double>& tf1,
                         const fcl::CollisionGeometry<double>* o2, const fcl::Transform3<double>& tf2,
                         const QuadricSolver<double>& solver, const fcl::DistanceRequest<double>& request,
                         fcl::DistanceResult<double>& result, double* value) {
#if FCL_HAVE_OCTOMAP
  const bool tree_first = o1->getNodeType() == fcl::GEOM_OCTREE;
  const fcl::CollisionGeometry<double>* tree = tree_first ? o1 : o2;
  const fcl::CollisionGeometry<double>* shape = tree_first ? o2 : o1;
  if (tree->getNodeType() != fcl::GEOM_OCTREE) return false;
  const bool ellipsoid = shape->getNodeType() == fcl::GEOM_ELLIPSOID;
  if (!ellipsoid && shape->getNodeType() != fcl::GEOM_SPHERE) return false;
  checkTranslations(tf1, tf2, "fcl_quadric::distance");  // (input_checks.h)
  // FCL's OcTreeShapeDistance / ShapeOcTreeDistance return at once when the result is satisfied.
  if (!request.isSatisfied(result)) {
    const auto& t = *static_cast<const fcl::OcTree<double>*>(tree);
    const fcl::Transform3<double>& tf_tree = tree_first ? tf1 : tf2;
    const fcl::Transform3<double>& tf_shape = tree_first ? tf2 : tf1;
    if (ellipsoid) {
      OcTreeShapeDistance<fcl::Ellipsoid<double>>(t, tf_tree, *static_cast<const fcl::Ellipsoid<double>*>(shape),
                                                  tf_shape, solver, result)
          .run();
    } else {
      OcTreeShapeDistance<fcl::Sphere<double>>(t, tf_tree, *static_cast<const fcl::Sphere<double>*>(shape), tf_shape,
                                               solver, result)
          .run();
    }
  }
  *value = result.min_distance;
  signedDistanceFixUp(o1, tf1, o2, tf2, request, result);
  return true;
#else
  (void)o1, (void)tf1, (void)o2, (void)tf2, (void)solver, (void)request, (void)result, (void)value;
  return false;
#endif
}

}  // namespace detail
}  // namespace fcl_quadric
