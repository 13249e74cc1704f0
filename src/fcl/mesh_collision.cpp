// fcl_quadric::collide's traversal of a triangle mesh against an Ellipsoid or a Sphere: FCL 0.7's
// collisionRecurse over an oriented mesh-shape node without cost sources, with a cheaper node test.
#include "fcl/mesh_collision.h"

#include <algorithm>
#include <cmath>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/bv/OBB.h>
#include <fcl/math/bv/OBBRSS.h>

#include "fcl_quadric/geometry/ellipsoid.h"
#include "fcl_quadric/tolerances.h"

namespace fcl_quadric {
namespace detail {

namespace {

inline const fcl::OBB<double>& orientedBox(const fcl::OBB<double>& bv) { return bv; }
inline const fcl::OBB<double>& orientedBox(const fcl::OBBRSS<double>& bv) { return bv.obb; }

inline Eigen::Vector3d shapeRadii(const fcl::Ellipsoid<double>& e) { return e.radii; }
inline Eigen::Vector3d shapeRadii(const fcl::Sphere<double>& s) { return Eigen::Vector3d::Constant(s.radius); }

template <typename BV, typename Shape>
class MeshShapeTraversal {
 public:
  MeshShapeTraversal(const fcl::BVHModel<BV>& mesh, const fcl::Transform3<double>& tf_mesh, const Shape& shape,
                     const fcl::Transform3<double>& tf_shape, const QuadricSolver<double>& solver,
                     const fcl::CollisionRequest<double>& request, fcl::CollisionResult<double>& result)
      : mesh_(mesh), tf_mesh_(tf_mesh), shape_(shape), tf_shape_(tf_shape), solver_(solver), request_(request),
        result_(result) {}

  void run() {
    // The check the leaf test makes of the shape (QuadricSolver::shapeTriangleIntersect), made
    // once here: a bad shape throws whether or not the pruning lets a leaf be reached, and the
    // node test below is computed from valid radii and rotation. The leaf test would take any
    // affine mesh pose (triangles are points), but the node test places the shape in the mesh
    // frame with R_m^T, as FCL's OBB test uses R_m: the pose must be rigid.
    (void)asExact(shape_, tf_shape_, "shape");
    checkRotation(tf_mesh_.linear(), "fcl_quadric::collide: the rotation of the mesh's pose");
    // The shape in the mesh frame: axes R = R_m^T R_s (columns), centre p = R_m^T (p_s - p_m).
    R_ = tf_mesh_.linear().transpose() * tf_shape_.linear();
    p_ = tf_mesh_.linear().transpose() * (tf_shape_.translation() - tf_mesh_.translation());
    radii_ = shapeRadii(shape_);
    r2_ = radii_.cwiseProduct(radii_);
    scale_ = tf_mesh_.translation().cwiseAbs().maxCoeff() + tf_shape_.translation().cwiseAbs().maxCoeff() +
             p_.cwiseAbs().maxCoeff() + radii_.maxCoeff();
    recurse(0);
  }

 private:
  /// False when the node's box and the shape are certainly apart (separating axis among the
  /// box's axes, with the shape's exact support, and the shape's axes).
  bool meets(const BV& bv) const {
    const fcl::OBB<double>& box = orientedBox(bv);
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

  // FCL's meshShapeCollisionOrientedNodeLeafTesting without cost sources.
  void leaf(int primitive) {
    if (!(mesh_.isOccupied() && shape_.isOccupied())) return;
    const fcl::Triangle& t = mesh_.tri_indices[primitive];
    const fcl::Vector3d& p1 = mesh_.vertices[t[0]];
    const fcl::Vector3d& p2 = mesh_.vertices[t[1]];
    const fcl::Vector3d& p3 = mesh_.vertices[t[2]];
    if (!request_.enable_contact) {
      if (solver_.shapeTriangleIntersect(shape_, tf_shape_, p1, p2, p3, tf_mesh_, nullptr, nullptr, nullptr) &&
          request_.num_max_contacts > result_.numContacts())
        result_.addContact(fcl::Contact<double>(&mesh_, &shape_, primitive, fcl::Contact<double>::NONE));
    } else {
      double penetration;
      fcl::Vector3d normal, point;
      if (solver_.shapeTriangleIntersect(shape_, tf_shape_, p1, p2, p3, tf_mesh_, &point, &penetration, &normal) &&
          request_.num_max_contacts > result_.numContacts())
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
  Eigen::Matrix3d R_;
  Eigen::Vector3d p_, radii_, r2_;
  double scale_ = 0.0;
};

template <typename BV>
bool traverseMesh(const fcl::CollisionGeometry<double>* mesh, const fcl::Transform3<double>& tf_mesh,
              const fcl::CollisionGeometry<double>* shape, const fcl::Transform3<double>& tf_shape,
              const QuadricSolver<double>& solver, const fcl::CollisionRequest<double>& request,
              fcl::CollisionResult<double>& result) {
  const auto& model = *static_cast<const fcl::BVHModel<BV>*>(mesh);
  // FCL's setup refuses other model types; an empty model has no root node.
  if (model.getModelType() != fcl::BVH_MODEL_TRIANGLES || model.getNumBVs() <= 0) return false;
  if (request.isSatisfied(result)) return true;  // orientedBVHShapeCollide returns at once
  if (shape->getNodeType() == fcl::GEOM_ELLIPSOID)
    MeshShapeTraversal<BV, fcl::Ellipsoid<double>>(model, tf_mesh, *static_cast<const fcl::Ellipsoid<double>*>(shape),
                                                   tf_shape, solver, request, result)
        .run();
  else
    MeshShapeTraversal<BV, fcl::Sphere<double>>(model, tf_mesh, *static_cast<const fcl::Sphere<double>*>(shape),
                                                tf_shape, solver, request, result)
        .run();
  return true;
}

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
  const fcl::Transform3<double>& tf_mesh = mesh_first ? tf1 : tf2;
  const fcl::Transform3<double>& tf_shape = mesh_first ? tf2 : tf1;
  bool handled = false;
  switch (mesh->getNodeType()) {
    case fcl::BV_OBBRSS:
      handled = traverseMesh<fcl::OBBRSS<double>>(mesh, tf_mesh, shape, tf_shape, solver, request, result);
      break;
    case fcl::BV_OBB:
      handled = traverseMesh<fcl::OBB<double>>(mesh, tf_mesh, shape, tf_shape, solver, request, result);
      break;
    default:
      break;
  }
  if (handled) *count = result.numContacts();
  return handled;
}

}  // namespace detail
}  // namespace fcl_quadric
