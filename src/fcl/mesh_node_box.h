#pragma once
// Private: what fcl_quadric's own mesh traversals (mesh_collision.cpp, mesh_distance.cpp) read of
// a BVHModel node's bounding volume, for each of FCL 0.7's BV types.
#include <cstddef>

#include <Eigen/Core>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/AABB.h>
#include <fcl/math/bv/OBB.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/math/bv/RSS.h>
#include <fcl/math/bv/kDOP.h>
#include <fcl/math/bv/kIOS.h>

namespace fcl_quadric {
namespace detail {

/// What the node test reads of a node's bounding volume. Oriented types (FCL's oriented mesh-shape
/// nodes, which test the mesh in its own frame): a box with its own axes in the mesh frame that
/// contains the volume. Axis-aligned types (AABB, k-DOPs: FCL's MeshShapeCollisionTraversalNode):
/// the corners lo, hi of an axis-aligned box in the mesh frame that contains it.
template <typename BV>
struct NodeBox;

template <>
struct NodeBox<fcl::OBB<double>> {
  static constexpr bool kOriented = true;
  static const fcl::OBB<double>& box(const fcl::OBB<double>& bv) { return bv; }
};

template <>
struct NodeBox<fcl::OBBRSS<double>> {
  static constexpr bool kOriented = true;
  static const fcl::OBB<double>& box(const fcl::OBBRSS<double>& bv) { return bv.obb; }
};

template <>
struct NodeBox<fcl::kIOS<double>> {
  static constexpr bool kOriented = true;
  static const fcl::OBB<double>& box(const fcl::kIOS<double>& bv) { return bv.obb; }  // bounds every sphere's part
};

/// The points within r of the rectangle To + [0, l0] axis0 + [0, l1] axis1 (RSS.h): inside the box
/// of centre RSS::center(), the same axes and half-extents (l0 / 2 + r, l1 / 2 + r, r).
template <>
struct NodeBox<fcl::RSS<double>> {
  static constexpr bool kOriented = true;
  static fcl::OBB<double> box(const fcl::RSS<double>& bv) {
    fcl::OBB<double> b;
    b.axis = bv.axis;
    b.To = bv.center();
    b.extent = Eigen::Vector3d(0.5 * bv.l[0] + bv.r, 0.5 * bv.l[1] + bv.r, bv.r);
    return b;
  }
};

template <>
struct NodeBox<fcl::AABB<double>> {
  static constexpr bool kOriented = false;
  static void corners(const fcl::AABB<double>& bv, Eigen::Vector3d* lo, Eigen::Vector3d* hi) {
    *lo = bv.min_;
    *hi = bv.max_;
  }
};

/// A k-DOP's first three directions are the coordinate axes (kDOP.h): dist(i) its minimum and
/// dist(N / 2 + i) its maximum along axis i, for i < 3. Their slabs bound it.
template <std::size_t N>
struct NodeBox<fcl::KDOP<double, N>> {
  static constexpr bool kOriented = false;
  static void corners(const fcl::KDOP<double, N>& bv, Eigen::Vector3d* lo, Eigen::Vector3d* hi) {
    *lo = Eigen::Vector3d(bv.dist(0), bv.dist(1), bv.dist(2));
    *hi = Eigen::Vector3d(bv.dist(N / 2), bv.dist(N / 2 + 1), bv.dist(N / 2 + 2));
  }
};

/// The BV type of a BVHModel type: BVOf<fcl::BVHModel<BV>>::type is BV.
template <typename Model>
struct BVOf;
template <typename BV>
struct BVOf<fcl::BVHModel<BV>> {
  using type = BV;
};

/// Calls f(model) with `mesh` as the BVHModel of its BV type (any of FCL 0.7's: OBBRSS, OBB, RSS,
/// kIOS, AABB, KDOP16/18/24) when it is a triangle model with a tree, and returns what f returns;
/// false for anything else (other node types, point clouds, an empty model: FCL's traversals
/// handle or refuse those).
template <typename F>
bool withTriangleModel(const fcl::CollisionGeometry<double>* mesh, F&& f) {
  auto call = [&](const auto* model) {
    if (model->getModelType() != fcl::BVH_MODEL_TRIANGLES || model->getNumBVs() <= 0 || model->num_tris <= 0)
      return false;
    return static_cast<bool>(f(*model));
  };
  switch (mesh->getNodeType()) {
    case fcl::BV_OBBRSS: return call(static_cast<const fcl::BVHModel<fcl::OBBRSS<double>>*>(mesh));
    case fcl::BV_OBB: return call(static_cast<const fcl::BVHModel<fcl::OBB<double>>*>(mesh));
    case fcl::BV_RSS: return call(static_cast<const fcl::BVHModel<fcl::RSS<double>>*>(mesh));
    case fcl::BV_kIOS: return call(static_cast<const fcl::BVHModel<fcl::kIOS<double>>*>(mesh));
    case fcl::BV_AABB: return call(static_cast<const fcl::BVHModel<fcl::AABB<double>>*>(mesh));
    case fcl::BV_KDOP16: return call(static_cast<const fcl::BVHModel<fcl::KDOP<double, 16>>*>(mesh));
    case fcl::BV_KDOP18: return call(static_cast<const fcl::BVHModel<fcl::KDOP<double, 18>>*>(mesh));
    case fcl::BV_KDOP24: return call(static_cast<const fcl::BVHModel<fcl::KDOP<double, 24>>*>(mesh));
    default: return false;
  }
}

}  // namespace detail
}  // namespace fcl_quadric
