// fcl_quadric::collide's traversal of a triangle mesh against an Ellipsoid or a Sphere: FCL 0.7's
// collisionRecurse over a mesh-shape node without cost sources, with a cheaper node test, and for
// AABB and k-DOP meshes without FCL's per-query copy of the model.
#include "fcl/mesh_collision.h"
#include "fcl/input_checks.h"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/sphere.h>

#include "fcl/mesh_node_box.h"
#include "fcl/traversal_bound.h"
#include "fcl_quadric/geometry/ellipsoid.h"
#include "fcl_quadric/tolerances.h"

namespace fcl_quadric {
namespace detail {

namespace {

template <typename BV, typename Shape>
class MeshShapeTraversal {
 public:
  static constexpr bool kOriented = NodeBox<BV>::kOriented;

  MeshShapeTraversal(const fcl::BVHModel<BV>& mesh, const fcl::Transform3<double>& tf_mesh, const Shape& shape,
                     const fcl::Transform3<double>& tf_shape, const QuadricSolver<double>& solver,
                     const fcl::CollisionRequest<double>& request, fcl::CollisionResult<double>& result)
      : mesh_(mesh), tf_mesh_(tf_mesh), shape_(shape), tf_shape_(tf_shape), solver_(solver), request_(request),
        result_(result) {}

  void run() {
    // The check the leaf test makes of the shape (QuadricSolver::shapeTriangleIntersect), made
    // once here: a bad shape throws whether or not the pruning lets a leaf be reached, and the
    // node test below is computed from valid radii and rotation.
    (void)asExact(shape_, tf_shape_, "shape");
    radii_ = shapeRadii(shape_);
    if constexpr (kOriented) {
      // The leaf test would take any affine mesh pose (triangles are points), but the node test
      // places the shape in the mesh frame with R_m^T, as FCL's OBB test uses R_m: the pose must
      // be rigid. The shape in the mesh frame: axes R = R_m^T R_s (columns), centre
      // p = R_m^T (p_s - p_m).
      checkRotation(tf_mesh_.linear(), "fcl_quadric::collide: the rotation of the mesh's pose");
      const PlacedEllipsoid placed = placeInFrame(tf_mesh_, tf_shape_, radii_);
      R_ = placed.R;
      p_ = placed.p;
      scale_ = placed.scale;
      r2_ = radii_.cwiseProduct(radii_);
    } else {
      // FCL maps the vertices by the mesh's pose, any affine map, and tests the triangles in the
      // world frame: so does the leaf test below, and the node test compares world boxes. A
      // non-finite pose would make every box comparison false and prune nothing silently wrong
      // (FCL's rebuilt tree of NaN vertices): it throws instead.
      detail::checkTransform(tf_mesh_, "fcl_quadric::collide: the mesh's pose");
      // FCL's test, Eigen's isIdentity() (entries within 1e-12 of the identity's): FCL then leaves
      // the vertices as they are. The node test maps the boxes by the pose either way; the
      // padding covers the difference.
      identity_ = tf_mesh_.matrix().isIdentity();
      abs_linear_ = tf_mesh_.linear().cwiseAbs();
      linear_norm_ = abs_linear_.rowwise().sum().maxCoeff();
      // A rigid pose (the usual one) maps the shape into the mesh frame instead, where its exact
      // box is compared with each node's own box: six comparisons, and tighter than the world box
      // of a rotated node box.
      rigid_ = isRotation(tf_mesh_.linear());
      Eigen::Matrix3d axes = tf_shape_.linear();
      if (rigid_) {
        const PlacedEllipsoid placed = placeInFrame(tf_mesh_, tf_shape_, radii_);
        axes = placed.R;
        p_ = placed.p;
        scale_ = placed.scale;
      } else {
        scale_ = tf_mesh_.translation().cwiseAbs().maxCoeff() + tf_shape_.translation().cwiseAbs().maxCoeff() +
                 radii_.maxCoeff();
      }
      // The shape's exact box in that frame: half-extent j = |row j of R S|.
      shape_half_ = (axes * radii_.asDiagonal()).rowwise().norm();
    }
    recurse(0);
  }

 private:
  /// False when the node's box and the shape are certainly apart (separating axis among the
  /// box's axes, with the shape's exact support, and the shape's axes).
  bool meetsOriented(const fcl::OBB<double>& box) const {
    const Eigen::Vector3d d = box.To - p_;
    const double pad = tolerance::kTraversalPruningPadding * (scale_ + box.To.cwiseAbs().maxCoeff() + box.extent.maxCoeff());
    const Eigen::Matrix3d B = R_.transpose() * box.axis;  // B(j, k) = shape axis j . box axis k
    const Eigen::Vector3d d_box = box.axis.transpose() * d;
    for (int k = 0; k < 3; ++k) {
      const double support = std::sqrt(r2_.dot(B.col(k).cwiseProduct(B.col(k))));
      if (std::fabs(d_box[k]) > box.extent[k] + support + pad) return false;
    }
    const Eigen::Vector3d d_shape = R_.transpose() * d;
    const Eigen::Vector3d box_half = B.cwiseAbs() * box.extent;
    for (int j = 0; j < 3; ++j)
      if (std::fabs(d_shape[j]) > radii_[j] + box_half[j] + pad) return false;
    return true;
  }

  /// False when the node's box (corners lo, hi in the mesh frame) and the shape's exact box are
  /// certainly apart: in the mesh frame for a rigid pose, otherwise in the world frame, where
  /// the node's box mapped by the pose lies in the box of centre L c + t and half-extents |L| h.
  /// The padding covers the rounding of both boxes and of the leaf test's world vertices, which
  /// are within ~eps (|L| |v| + |t|) of the exact images.
  bool meetsAligned(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) const {
    const Eigen::Vector3d c = 0.5 * (lo + hi);
    const Eigen::Vector3d h = 0.5 * (hi - lo);
    const double pad = tolerance::kTraversalPruningPadding *
                       (scale_ + linear_norm_ * (c.cwiseAbs().maxCoeff() + h.maxCoeff()));
    if (rigid_) {
      for (int j = 0; j < 3; ++j)
        if (std::fabs(c[j] - p_[j]) > h[j] + shape_half_[j] + pad) return false;
      return true;
    }
    const Eigen::Vector3d d = tf_mesh_.linear() * c + tf_mesh_.translation() - tf_shape_.translation();
    const Eigen::Vector3d h_world = abs_linear_ * h;
    for (int j = 0; j < 3; ++j)
      if (std::fabs(d[j]) > h_world[j] + shape_half_[j] + pad) return false;
    return true;
  }

  bool meets(const BV& bv) const {
    if constexpr (kOriented) {
      return meetsOriented(NodeBox<BV>::box(bv));
    } else {
      Eigen::Vector3d lo, hi;
      NodeBox<BV>::corners(bv, &lo, &hi);
      return meetsAligned(lo, hi);
    }
  }

  // FCL's collisionRecurse (traversal_recurse-inl.h) for a mesh-shape node: the shape is a leaf,
  // the mesh's node is tested, then its leaf test or its children, left first, stopping when the
  // request is satisfied after the left child.
  void recurse(int b) {
    const fcl::BVNode<BV>& node = mesh_.getBV(b);
    if (!meets(node.bv)) return;
    if (node.isLeaf()) {
      leaf(node.primitiveId());
      return;
    }
    recurse(node.leftChild());
    if (request_.isSatisfied(result_)) return;
    recurse(node.rightChild());
  }

  /// The leaf test of FCL's node: oriented nodes pass the mesh-frame vertices and the mesh's pose
  /// (meshShapeCollisionOrientedNodeLeafTesting); MeshShapeCollisionTraversalNode::leafTesting
  /// passes the world vertices tf_mesh * v that FCL's initialize() computed (the raw vertices
  /// when the pose is the identity), bit for bit the same expression.
  bool intersects(const fcl::Vector3d& v1, const fcl::Vector3d& v2, const fcl::Vector3d& v3, fcl::Vector3d* point,
                  double* penetration, fcl::Vector3d* normal) const {
    if constexpr (kOriented) {
      return solver_.shapeTriangleIntersect(shape_, tf_shape_, v1, v2, v3, tf_mesh_, point, penetration, normal);
    } else {
      if (identity_) return solver_.shapeTriangleIntersect(shape_, tf_shape_, v1, v2, v3, point, penetration, normal);
      const fcl::Vector3d w1 = tf_mesh_ * v1, w2 = tf_mesh_ * v2, w3 = tf_mesh_ * v3;
      return solver_.shapeTriangleIntersect(shape_, tf_shape_, w1, w2, w3, point, penetration, normal);
    }
  }

  // FCL's leaf test without cost sources; the contact's normal is negated, as both FCL nodes do.
  void leaf(int primitive) {
    if (!(mesh_.isOccupied() && shape_.isOccupied())) return;
    const fcl::Triangle& t = mesh_.tri_indices[primitive];
    const fcl::Vector3d& p1 = mesh_.vertices[t[0]];
    const fcl::Vector3d& p2 = mesh_.vertices[t[1]];
    const fcl::Vector3d& p3 = mesh_.vertices[t[2]];
    if (!request_.enable_contact) {
      if (intersects(p1, p2, p3, nullptr, nullptr, nullptr) && request_.num_max_contacts > result_.numContacts())
        result_.addContact(fcl::Contact<double>(&mesh_, &shape_, primitive, fcl::Contact<double>::NONE));
    } else {
      double penetration;
      fcl::Vector3d normal, point;
      if (intersects(p1, p2, p3, &point, &penetration, &normal) && request_.num_max_contacts > result_.numContacts())
        result_.addContact(
            fcl::Contact<double>(&mesh_, &shape_, primitive, fcl::Contact<double>::NONE, point, -normal, penetration));
    }
  }

  const fcl::BVHModel<BV>& mesh_;
  const fcl::Transform3<double>& tf_mesh_;
  const Shape& shape_;
  const fcl::Transform3<double>& tf_shape_;
  const QuadricSolver<double>& solver_;
  const fcl::CollisionRequest<double>& request_;
  fcl::CollisionResult<double>& result_;
  Eigen::Vector3d radii_;
  double scale_ = 0.0;
  // Oriented nodes, and axis-aligned ones under a rigid pose: the shape's centre in the mesh frame.
  Eigen::Vector3d p_;
  // Oriented nodes: the shape's axes in the mesh frame and its squared radii.
  Eigen::Matrix3d R_;
  Eigen::Vector3d r2_;
  // Axis-aligned nodes: the mesh's pose, and the shape's box in the mesh frame (rigid pose) or
  // in the world frame.
  bool identity_ = false, rigid_ = false;
  Eigen::Matrix3d abs_linear_;
  double linear_norm_ = 0.0;
  Eigen::Vector3d shape_half_;
};

}  // namespace

bool collideMeshShape(const fcl::CollisionGeometry<double>* o1, const fcl::Transform3<double>& tf1,
                      const fcl::CollisionGeometry<double>* o2, const fcl::Transform3<double>& tf2,
                      const QuadricSolver<double>& solver, const fcl::CollisionRequest<double>& request,
                      fcl::CollisionResult<double>& result, std::size_t* count) {
  if (request.enable_cost || request.num_max_contacts == 0) return false;  // FCL's own paths
  const bool mesh_first = o1->getObjectType() == fcl::OT_BVH;
  const fcl::CollisionGeometry<double>* mesh = mesh_first ? o1 : o2;
  const fcl::CollisionGeometry<double>* shape = mesh_first ? o2 : o1;
  if (mesh->getObjectType() != fcl::OT_BVH) return false;
  const fcl::NODE_TYPE kind = shape->getNodeType();
  if (kind != fcl::GEOM_ELLIPSOID && kind != fcl::GEOM_SPHERE) return false;
  checkTranslations(tf1, tf2, "fcl_quadric::collide");  // (input_checks.h)
  const fcl::Transform3<double>& tf_mesh = mesh_first ? tf1 : tf2;
  const fcl::Transform3<double>& tf_shape = mesh_first ? tf2 : tf1;
  const bool handled = withTriangleModel(mesh, [&](const auto& model) {
    using BV = typename BVOf<std::decay_t<decltype(model)>>::type;
    if (request.isSatisfied(result)) return true;  // FCL's colliders return at once
    if (shape->getNodeType() == fcl::GEOM_ELLIPSOID)
      MeshShapeTraversal<BV, fcl::Ellipsoid<double>>(model, tf_mesh, *static_cast<const fcl::Ellipsoid<double>*>(shape),
                                                     tf_shape, solver, request, result)
          .run();
    else
      MeshShapeTraversal<BV, fcl::Sphere<double>>(model, tf_mesh, *static_cast<const fcl::Sphere<double>*>(shape),
                                                  tf_shape, solver, request, result)
          .run();
    return true;
  });
  if (handled) *count = result.numContacts();
  return handled;
}

}  // namespace detail
}  // namespace fcl_quadric
