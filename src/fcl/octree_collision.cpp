// fcl_quadric::collide's traversal of an OcTree against an Ellipsoid or a Sphere: FCL 0.7's
// OcTreeShapeIntersectRecurse without cost sources, with a cheaper, tighter pruning test.
#include "fcl/octree_collision.h"
#include "fcl/input_checks.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

#include <fcl/config.h>

#if FCL_HAVE_OCTOMAP
#include <fcl/geometry/octree/octree.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/sphere.h>
#endif

#include "fcl/traversal_bound.h"
#include "fcl_quadric/tolerances.h"

namespace fcl_quadric {
namespace detail {

#if FCL_HAVE_OCTOMAP
namespace {

template <typename Shape>
class OcTreeShapeTraversal {
 public:
  OcTreeShapeTraversal(const fcl::OcTree<double>& tree, const fcl::Transform3<double>& tf_tree, const Shape& shape,
                       const fcl::Transform3<double>& tf_shape, const QuadricSolver<double>& solver,
                       const fcl::CollisionRequest<double>& request, fcl::CollisionResult<double>& result)
      : tree_(tree), tf_tree_(tf_tree), shape_(shape), tf_shape_(tf_shape), solver_(solver), request_(request),
        result_(result) {}

  void run() {
    const auto* root = tree_.getRoot();
    if (root == nullptr) return;
    // The checks the leaf test makes (QuadricSolver::shapeIntersect(box, box_tf, shape, tf_s)),
    // made once here: bad input throws whether or not the pruning lets a leaf be reached (an empty
    // tree has no leaf to test and throws nothing, as through FCL), and
    // the box computed below from the shape's radii and rotation is then meaningful.
    const fcl::AABB<double> root_bv = tree_.getRootBV();
    checkOcTreeQuery(root_bv, tf_tree_, shape_, tf_shape_);
    // The shape's exact bounding box in the tree frame: centre c = R_t^T (p_s - p_t), half widths
    // |row_i(R_t^T R_s S)| (S = diag(radii)), padded.
    const PlacedEllipsoid placed = placeInFrame(tf_tree_, tf_shape_, shapeRadii(shape_));
    const Eigen::Vector3d half = (placed.R * placed.radii.asDiagonal()).rowwise().norm();
    const Eigen::Vector3d pad = half + Eigen::Vector3d::Constant(tolerance::kTraversalPruningPadding * placed.scale);
    lo_ = placed.p - pad;
    hi_ = placed.p + pad;
    recurse(root, root_bv);
  }

 private:
  bool meets(const fcl::AABB<double>& bv) const {
    return bv.min_[0] <= hi_[0] && bv.min_[1] <= hi_[1] && bv.min_[2] <= hi_[2] && bv.max_[0] >= lo_[0] &&
           bv.max_[1] >= lo_[1] && bv.max_[2] >= lo_[2];
  }

  // The branches of FCL 0.7's OcTreeShapeIntersectRecurse (octree_solver-inl.h) for a non-null
  // node and enable_cost == false, in its order; only the pruning test differs.
  bool recurse(const fcl::OcTree<double>::OcTreeNode* node, const fcl::AABB<double>& bv) {
    if (!tree_.nodeHasChildren(node)) {
      if (!(tree_.isNodeOccupied(node) && shape_.isOccupied())) return false;  // free or uncertain leaf
      if (!meets(bv)) return false;
      return leaf(node, bv);
    }
    if (tree_.isNodeFree(node) || shape_.isFree()) return false;
    if (tree_.isNodeUncertain(node) || shape_.isUncertain()) return false;
    if (!meets(bv)) return false;
    for (unsigned i = 0; i < 8; ++i) {
      if (!tree_.nodeChildExists(node, i)) continue;
      fcl::AABB<double> child_bv;
      octreeChildBox(bv, i, &child_bv);
      if (recurse(tree_.getNodeChild(node, i), child_bv)) return true;
    }
    return false;
  }

  // FCL's leaf test: the box of constructBox(bv, tf_tree), the solver, the contacts as FCL adds them.
  bool leaf(const fcl::OcTree<double>::OcTreeNode* node, const fcl::AABB<double>& bv) {
    const fcl::Box<double> box(bv.max_ - bv.min_);
    const fcl::Transform3<double> box_tf = tf_tree_ * fcl::Translation3<double>(bv.center());
    const std::intptr_t index = node - tree_.getRoot();
    if (!request_.enable_contact) {
      if (solver_.shapeIntersect(box, box_tf, shape_, tf_shape_, nullptr) &&
          result_.numContacts() < request_.num_max_contacts)
        result_.addContact(fcl::Contact<double>(&tree_, &shape_, static_cast<int>(index), fcl::Contact<double>::NONE));
    } else {
      std::vector<fcl::ContactPoint<double>> contacts;
      if (solver_.shapeIntersect(box, box_tf, shape_, tf_shape_, &contacts) &&
          request_.num_max_contacts > result_.numContacts()) {
        const std::size_t free_space = request_.num_max_contacts - result_.numContacts();
        std::size_t adding = contacts.size();
        if (free_space < contacts.size()) {  // the deepest first, as FCL
          std::partial_sort(contacts.begin(), contacts.begin() + free_space, contacts.end(),
                            [](const fcl::ContactPoint<double>& x, const fcl::ContactPoint<double>& y) {
                              return x.penetration_depth > y.penetration_depth;
                            });
          adding = free_space;
        }
        for (std::size_t k = 0; k < adding; ++k)
          result_.addContact(fcl::Contact<double>(&tree_, &shape_, static_cast<int>(index), fcl::Contact<double>::NONE,
                                                  contacts[k].pos, contacts[k].normal,
                                                  contacts[k].penetration_depth));
      }
    }
    return request_.isSatisfied(result_);
  }

  const fcl::OcTree<double>& tree_;
  const fcl::Transform3<double>& tf_tree_;
  const Shape& shape_;
  const fcl::Transform3<double>& tf_shape_;
  const QuadricSolver<double>& solver_;
  const fcl::CollisionRequest<double>& request_;
  fcl::CollisionResult<double>& result_;
  Eigen::Vector3d lo_, hi_;
};

template <typename Shape>
void traverseOcTree(const fcl::CollisionGeometry<double>* tree, const fcl::Transform3<double>& tf_tree,
              const fcl::CollisionGeometry<double>* shape, const fcl::Transform3<double>& tf_shape,
              const QuadricSolver<double>& solver, const fcl::CollisionRequest<double>& request,
              fcl::CollisionResult<double>& result) {
  OcTreeShapeTraversal<Shape>(*static_cast<const fcl::OcTree<double>*>(tree), tf_tree,
                              *static_cast<const Shape*>(shape), tf_shape, solver, request, result)
      .run();
}

}  // namespace
#endif  // FCL_HAVE_OCTOMAP

bool collideOcTreeShape(const fcl::CollisionGeometry<double>* o1, const fcl::Transform3<double>& tf1,
                        const fcl::CollisionGeometry<double>* o2, const fcl::Transform3<double>& tf2,
                        const QuadricSolver<double>& solver, const fcl::CollisionRequest<double>& request,
                        fcl::CollisionResult<double>& result, std::size_t* count) {
#if FCL_HAVE_OCTOMAP
  if (request.enable_cost || request.num_max_contacts == 0) return false;  // FCL's own paths
  const bool tree_first = o1->getNodeType() == fcl::GEOM_OCTREE;
  const fcl::CollisionGeometry<double>* tree = tree_first ? o1 : o2;
  const fcl::CollisionGeometry<double>* shape = tree_first ? o2 : o1;
  if (tree->getNodeType() != fcl::GEOM_OCTREE) return false;
  const fcl::NODE_TYPE kind = shape->getNodeType();
  if (kind != fcl::GEOM_ELLIPSOID && kind != fcl::GEOM_SPHERE) return false;
  checkTranslations(tf1, tf2, "fcl_quadric::collide");  // (input_checks.h)
  // FCL's OcTreeShapeCollide / ShapeOcTreeCollide return at once when the result is already full.
  if (!request.isSatisfied(result)) {
    const fcl::Transform3<double>& tf_tree = tree_first ? tf1 : tf2;
    const fcl::Transform3<double>& tf_shape = tree_first ? tf2 : tf1;
    if (kind == fcl::GEOM_ELLIPSOID)
      traverseOcTree<fcl::Ellipsoid<double>>(tree, tf_tree, shape, tf_shape, solver, request, result);
    else
      traverseOcTree<fcl::Sphere<double>>(tree, tf_tree, shape, tf_shape, solver, request, result);
  }
  *count = result.numContacts();
  return true;
#else
  (void)o1, (void)tf1, (void)o2, (void)tf2, (void)solver, (void)request, (void)result, (void)count;
  return false;
#endif
}

}  // namespace detail
}  // namespace fcl_quadric
