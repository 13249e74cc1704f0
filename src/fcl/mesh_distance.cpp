// fcl_quadric::distance's traversal of a triangle mesh against an Ellipsoid or a Sphere: FCL 0.7's
// mesh-shape distance node (leaf call, result, canStop) searched best first with lower bounds that
// need no fitted BV, for every BV type (FCL's distance has only RSS, kIOS and OBBRSS meshes).
#include "fcl/mesh_distance.h"
#include "fcl/input_checks.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>
#include <vector>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/sphere.h>

#include "fcl/mesh_node_box.h"
#include "fcl/shape_pieces.h"
#include "fcl/distance_fix_up.h"
#include "fcl/traversal_bound.h"
#include "fcl_quadric/geometry/ellipsoid.h"
#include "fcl_quadric/tolerances.h"

namespace fcl_quadric {
namespace detail {

namespace {

template <typename BV, typename Shape>
class MeshShapeDistance {
 public:
  static constexpr bool kOriented = NodeBox<BV>::kOriented;

  MeshShapeDistance(const fcl::BVHModel<BV>& mesh, const fcl::Transform3<double>& tf_mesh, const Shape& shape,
                    const fcl::Transform3<double>& tf_shape, const QuadricSolver<double>& solver,
                    const fcl::DistanceRequest<double>& request, fcl::DistanceResult<double>& result)
      : mesh_(mesh), tf_mesh_(tf_mesh), shape_(shape), tf_shape_(tf_shape), solver_(solver), request_(request),
        result_(result) {}

  void run() {
    // The leaf test's check of the shape, once, before the descent (mesh_collision.cpp).
    (void)asExact(shape_, tf_shape_, "shape");
    radii_ = shapeRadii(shape_);
    if constexpr (kOriented) {
      checkRotation(tf_mesh_.linear(), "fcl_quadric::distance: the rotation of the mesh's pose");
      rigid_ = true;
    } else {
      detail::checkTransform(tf_mesh_, "fcl_quadric::distance: the mesh's pose");
      identity_ = tf_mesh_.matrix().isIdentity();  // FCL's test (mesh_collision.cpp)
      rigid_ = isRotation(tf_mesh_.linear());
    }
    abs_linear_ = tf_mesh_.linear().cwiseAbs();
    linear_norm_ = abs_linear_.rowwise().sum().maxCoeff();
    // The frame of the lower bounds: the mesh frame under a rigid pose (the shape placed there
    // with R_m^T), else the world frame (axis-aligned types only: node boxes mapped by the pose).
    if (rigid_) {
      placed_ = placeInFrame(tf_mesh_, tf_shape_, radii_);
    } else {
      placed_.R = tf_shape_.linear();
      placed_.p = tf_shape_.translation();
      placed_.radii = radii_;
      placed_.scale = tf_mesh_.translation().cwiseAbs().maxCoeff() + 2.0 * tf_shape_.translation().cwiseAbs().maxCoeff() +
                      radii_.maxCoeff();
    }
    search();
  }

 private:
  double boxBound(const Eigen::Matrix3d& A, const Eigen::Vector3d& c, const Eigen::Vector3d& e) const {
    return placed_.boxBound(A, c, e, linear_norm_ * (c.cwiseAbs().maxCoeff() + e.maxCoeff()));
  }

  double bound(const BV& bv) const {
    if constexpr (kOriented) {
      const auto& box = NodeBox<BV>::box(bv);
      return boxBound(box.axis, box.To, box.extent);
    } else {
      Eigen::Vector3d lo, hi;
      NodeBox<BV>::corners(bv, &lo, &hi);
      const Eigen::Vector3d c = 0.5 * (lo + hi), h = 0.5 * (hi - lo);
      if (rigid_) return boxBound(Eigen::Matrix3d::Identity(), c, h);
      return boxBound(Eigen::Matrix3d::Identity(), tf_mesh_.linear() * c + tf_mesh_.translation(), abs_linear_ * h);
    }
  }

  /// MeshShapeDistanceTraversalNode*::canStop.
  bool canStop(double c) const {
    return c >= result_.min_distance - request_.abs_err && c * (1 + request_.rel_err) >= result_.min_distance;
  }

  // Best first: the nodes in the order of their lower bounds (a binary heap), until the smallest
  // bound left lets the search stop (canStop), or none is left.
  void search() {
    struct Entry {
      double bound;
      int node;
      bool operator<(const Entry& o) const { return bound > o.bound || (bound == o.bound && node > o.node); }
    };
    std::vector<Entry> heap;
    heap.push_back({0.0, 0});
    while (!heap.empty()) {
      std::pop_heap(heap.begin(), heap.end());
      const Entry e = heap.back();
      heap.pop_back();
      if (canStop(e.bound)) break;
      const fcl::BVNode<BV>& node = mesh_.getBV(e.node);
      if (node.isLeaf()) {
        const int primitive = node.primitiveId();
        leaf(mesh_.tri_indices[primitive], primitive);
        continue;
      }
      for (int child : {node.leftChild(), node.rightChild()}) {
        const double b = bound(mesh_.getBV(child).bv);
        if (canStop(b)) continue;
        heap.push_back({b, child});
        std::push_heap(heap.begin(), heap.end());
      }
    }
  }

  /// A lower bound of the distance from the shape to the triangle v1 v2 v3 (mesh frame under a
  /// rigid pose, else mapped to the world frame): the larger of the gaps between them along the
  /// triangle's normal and along the line from the shape's centre to the triangle's point nearest
  /// to it, lowered by the padding; 0 when neither is positive.
  double triangleBound(fcl::Vector3d v1, fcl::Vector3d v2, fcl::Vector3d v3) const {
    if (!rigid_) {
      v1 = tf_mesh_ * v1;
      v2 = tf_mesh_ * v2;
      v3 = tf_mesh_ * v3;
    }
    double gap = 0.0;
    auto along = [&](const Eigen::Vector3d& a) {  // a of any length > 0
      const double n = a.norm();
      if (!(n > 0.0)) return;
      const double s1 = a.dot(v1), s2 = a.dot(v2), s3 = a.dot(v3), sp = a.dot(placed_.p);
      const double h = (placed_.R.transpose() * a).cwiseProduct(radii_).norm();
      const double lo = std::min({s1, s2, s3}), hi = std::max({s1, s2, s3});
      gap = std::max(gap, std::max(lo - (sp + h), (sp - h) - hi) / n);
    };
    along((v2 - v1).cross(v3 - v1));
    along(closestPointOnTriangle(placed_.p, v1, v2, v3) - placed_.p);
    const double size = std::max({v1.cwiseAbs().maxCoeff(), v2.cwiseAbs().maxCoeff(), v3.cwiseAbs().maxCoeff()});
    return std::max(0.0, gap - tolerance::kTraversalPruningPadding * (placed_.scale + size));
  }

  /// meshShapeDistanceOrientedNodeLeafTesting, and for AABB / k-DOP meshes the same on the world
  /// vertices (MeshShapeDistanceTraversalNode::leafTesting). A triangle whose own lower bound
  /// already lets the traversal stop (canStop) is skipped: it cannot lower the minimum.
  void leaf(const fcl::Triangle& t, int primitive) {
    if (canStop(triangleBound(mesh_.vertices[t[0]], mesh_.vertices[t[1]], mesh_.vertices[t[2]]))) return;
    const fcl::Vector3d& v1 = mesh_.vertices[t[0]];
    const fcl::Vector3d& v2 = mesh_.vertices[t[1]];
    const fcl::Vector3d& v3 = mesh_.vertices[t[2]];
    double d = 0.0;  // always written by the exact ellipsoid-triangle distance (spheres included)
    fcl::Vector3d p_mesh, p_shape;
    if constexpr (kOriented) {
      solver_.shapeTriangleDistance(shape_, tf_shape_, v1, v2, v3, tf_mesh_, &d, &p_shape, &p_mesh);
    } else if (identity_) {
      solver_.shapeTriangleDistance(shape_, tf_shape_, v1, v2, v3, &d, &p_shape, &p_mesh);
    } else {
      const fcl::Vector3d w1 = tf_mesh_ * v1, w2 = tf_mesh_ * v2, w3 = tf_mesh_ * v3;
      solver_.shapeTriangleDistance(shape_, tf_shape_, w1, w2, w3, &d, &p_shape, &p_mesh);
    }
    result_.update(d, &mesh_, &shape_, primitive, fcl::DistanceResult<double>::NONE, p_mesh, p_shape);
  }

  const fcl::BVHModel<BV>& mesh_;
  const fcl::Transform3<double>& tf_mesh_;
  const Shape& shape_;
  const fcl::Transform3<double>& tf_shape_;
  const QuadricSolver<double>& solver_;
  const fcl::DistanceRequest<double>& request_;
  fcl::DistanceResult<double>& result_;
  bool identity_ = false, rigid_ = false;
  Eigen::Matrix3d abs_linear_;
  Eigen::Vector3d radii_;
  double linear_norm_ = 0.0;
  PlacedEllipsoid placed_;  ///< the shape in the frame of the bounds
};

}  // namespace

bool distanceMeshShape(const fcl::CollisionGeometry<double>* o1, const fcl::Transform3<double>& tf1,
                       const fcl::CollisionGeometry<double>* o2, const fcl::Transform3<double>& tf2,
                       const QuadricSolver<double>& solver, const fcl::DistanceRequest<double>& request,
                       fcl::DistanceResult<double>& result, double* value) {
  const bool mesh_first = o1->getObjectType() == fcl::OT_BVH;
  const fcl::CollisionGeometry<double>* mesh = mesh_first ? o1 : o2;
  const fcl::CollisionGeometry<double>* shape = mesh_first ? o2 : o1;
  if (mesh->getObjectType() != fcl::OT_BVH) return false;
  const fcl::NODE_TYPE kind = shape->getNodeType();
  if (kind != fcl::GEOM_ELLIPSOID && kind != fcl::GEOM_SPHERE) return false;
  checkTranslations(tf1, tf2, "fcl_quadric::distance");  // (input_checks.h)
  const fcl::Transform3<double>& tf_mesh = mesh_first ? tf1 : tf2;
  const fcl::Transform3<double>& tf_shape = mesh_first ? tf2 : tf1;
  const bool handled = withTriangleModel(mesh, [&](const auto& model) {
    using BV = typename BVOf<std::decay_t<decltype(model)>>::type;
    if (kind == fcl::GEOM_ELLIPSOID)
      MeshShapeDistance<BV, fcl::Ellipsoid<double>>(model, tf_mesh, *static_cast<const fcl::Ellipsoid<double>*>(shape),
                                                    tf_shape, solver, request, result)
          .run();
    else
      MeshShapeDistance<BV, fcl::Sphere<double>>(model, tf_mesh, *static_cast<const fcl::Sphere<double>*>(shape),
                                                 tf_shape, solver, request, result)
          .run();
    return true;
  });
  if (!handled) return false;
  const double res = result.min_distance;
  signedDistanceFixUp(o1, tf1, o2, tf2, request, result);
  *value = res;
  return true;
}

}  // namespace detail
}  // namespace fcl_quadric
