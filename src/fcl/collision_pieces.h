#pragma once
// Private: the pieces of FCL's CollisionFunctionMatrix<QuadricSolver<double>> compiled in their own
// translation units (instantiating the whole matrix in one file takes ~40-50 s here, 3/4 of it in
// the optimiser). collision.cpp sees them as `extern template`; collision_bvh.cpp and
// collision_octree.cpp define FCL_QUADRIC_INSTANTIATE_BVH / FCL_QUADRIC_INSTANTIATE_OCTREE before
// including this header and so hold the explicit instantiation definitions. The lists mirror the
// constructor of CollisionFunctionMatrix in fcl/narrowphase/detail/collision_func_matrix-inl.h.
#include <cstddef>

#include <fcl/config.h>
#include <fcl/narrowphase/collision.h>

#include "fcl_quadric/fcl/quadric_solver.h"

#ifdef FCL_QUADRIC_INSTANTIATE_BVH
#define FCL_QUADRIC_BVH_EXTERN
#else
#define FCL_QUADRIC_BVH_EXTERN extern
#endif
#ifdef FCL_QUADRIC_INSTANTIATE_OCTREE
#define FCL_QUADRIC_OCTREE_EXTERN
#else
#define FCL_QUADRIC_OCTREE_EXTERN extern
#endif

/// The parameters of CollisionFunctionMatrix<QuadricSolver<double>>::CollisionFunc.
#define FCL_QUADRIC_COLLISION_FUNC_PARAMS                                                          \
  const CollisionGeometry<double>*, const Transform3<double>&, const CollisionGeometry<double>*, \
      const Transform3<double>&, const fcl_quadric::QuadricSolver<double>*,                      \
      const CollisionRequest<double>&, CollisionResult<double>&

namespace fcl {
namespace detail {

// BVH model vs shape (BVHShapeCollider; shape vs BVH is dispatched to it with swapped operands)
// and BVH model vs BVH model of the same BV type (BVHCollide, solver unused).
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<AABB<double>, Box<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<AABB<double>, Sphere<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<AABB<double>, Ellipsoid<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<AABB<double>, Capsule<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<AABB<double>, Cone<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<AABB<double>, Cylinder<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<AABB<double>, Convex<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<AABB<double>, Plane<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<AABB<double>, Halfspace<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<OBB<double>, Box<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<OBB<double>, Sphere<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<OBB<double>, Ellipsoid<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<OBB<double>, Capsule<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<OBB<double>, Cone<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<OBB<double>, Cylinder<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<OBB<double>, Convex<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<OBB<double>, Plane<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<OBB<double>, Halfspace<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<RSS<double>, Box<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<RSS<double>, Sphere<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<RSS<double>, Ellipsoid<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<RSS<double>, Capsule<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<RSS<double>, Cone<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<RSS<double>, Cylinder<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<RSS<double>, Convex<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<RSS<double>, Plane<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<RSS<double>, Halfspace<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<KDOP<double, 16>, Box<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<KDOP<double, 16>, Sphere<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<KDOP<double, 16>, Ellipsoid<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<KDOP<double, 16>, Capsule<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<KDOP<double, 16>, Cone<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<KDOP<double, 16>, Cylinder<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<KDOP<double, 16>, Convex<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<KDOP<double, 16>, Plane<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<KDOP<double, 16>, Halfspace<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<KDOP<double, 18>, Box<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<KDOP<double, 18>, Sphere<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<KDOP<double, 18>, Ellipsoid<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<KDOP<double, 18>, Capsule<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<KDOP<double, 18>, Cone<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<KDOP<double, 18>, Cylinder<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<KDOP<double, 18>, Convex<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<KDOP<double, 18>, Plane<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<KDOP<double, 18>, Halfspace<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<KDOP<double, 24>, Box<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<KDOP<double, 24>, Sphere<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<KDOP<double, 24>, Ellipsoid<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<KDOP<double, 24>, Capsule<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<KDOP<double, 24>, Cone<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<KDOP<double, 24>, Cylinder<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<KDOP<double, 24>, Convex<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<KDOP<double, 24>, Plane<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<KDOP<double, 24>, Halfspace<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<kIOS<double>, Box<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<kIOS<double>, Sphere<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<kIOS<double>, Ellipsoid<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<kIOS<double>, Capsule<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<kIOS<double>, Cone<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<kIOS<double>, Cylinder<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<kIOS<double>, Convex<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<kIOS<double>, Plane<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<kIOS<double>, Halfspace<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<OBBRSS<double>, Box<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<OBBRSS<double>, Sphere<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<OBBRSS<double>, Ellipsoid<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<OBBRSS<double>, Capsule<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<OBBRSS<double>, Cone<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<OBBRSS<double>, Cylinder<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<OBBRSS<double>, Convex<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<OBBRSS<double>, Plane<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template struct BVHShapeCollider<OBBRSS<double>, Halfspace<double>, fcl_quadric::QuadricSolver<double>>;
FCL_QUADRIC_BVH_EXTERN template std::size_t BVHCollide<AABB<double>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_BVH_EXTERN template std::size_t BVHCollide<OBB<double>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_BVH_EXTERN template std::size_t BVHCollide<RSS<double>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_BVH_EXTERN template std::size_t BVHCollide<KDOP<double, 16>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_BVH_EXTERN template std::size_t BVHCollide<KDOP<double, 18>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_BVH_EXTERN template std::size_t BVHCollide<KDOP<double, 24>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_BVH_EXTERN template std::size_t BVHCollide<kIOS<double>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_BVH_EXTERN template std::size_t BVHCollide<OBBRSS<double>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);

#if FCL_HAVE_OCTOMAP
// OcTree vs shape, shape vs OcTree, OcTree vs OcTree, OcTree vs BVH model, BVH model vs OcTree.
FCL_QUADRIC_OCTREE_EXTERN template std::size_t OcTreeShapeCollide<Box<double>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_OCTREE_EXTERN template std::size_t ShapeOcTreeCollide<Box<double>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_OCTREE_EXTERN template std::size_t OcTreeShapeCollide<Sphere<double>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_OCTREE_EXTERN template std::size_t ShapeOcTreeCollide<Sphere<double>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_OCTREE_EXTERN template std::size_t OcTreeShapeCollide<Ellipsoid<double>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_OCTREE_EXTERN template std::size_t ShapeOcTreeCollide<Ellipsoid<double>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_OCTREE_EXTERN template std::size_t OcTreeShapeCollide<Capsule<double>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_OCTREE_EXTERN template std::size_t ShapeOcTreeCollide<Capsule<double>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_OCTREE_EXTERN template std::size_t OcTreeShapeCollide<Cone<double>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_OCTREE_EXTERN template std::size_t ShapeOcTreeCollide<Cone<double>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_OCTREE_EXTERN template std::size_t OcTreeShapeCollide<Cylinder<double>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_OCTREE_EXTERN template std::size_t ShapeOcTreeCollide<Cylinder<double>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_OCTREE_EXTERN template std::size_t OcTreeShapeCollide<Convex<double>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_OCTREE_EXTERN template std::size_t ShapeOcTreeCollide<Convex<double>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_OCTREE_EXTERN template std::size_t OcTreeShapeCollide<Plane<double>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_OCTREE_EXTERN template std::size_t ShapeOcTreeCollide<Plane<double>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_OCTREE_EXTERN template std::size_t OcTreeShapeCollide<Halfspace<double>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_OCTREE_EXTERN template std::size_t ShapeOcTreeCollide<Halfspace<double>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_OCTREE_EXTERN template std::size_t OcTreeCollide<fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_OCTREE_EXTERN template std::size_t OcTreeBVHCollide<AABB<double>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_OCTREE_EXTERN template std::size_t BVHOcTreeCollide<AABB<double>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_OCTREE_EXTERN template std::size_t OcTreeBVHCollide<OBB<double>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_OCTREE_EXTERN template std::size_t BVHOcTreeCollide<OBB<double>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_OCTREE_EXTERN template std::size_t OcTreeBVHCollide<RSS<double>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_OCTREE_EXTERN template std::size_t BVHOcTreeCollide<RSS<double>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_OCTREE_EXTERN template std::size_t OcTreeBVHCollide<KDOP<double, 16>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_OCTREE_EXTERN template std::size_t BVHOcTreeCollide<KDOP<double, 16>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_OCTREE_EXTERN template std::size_t OcTreeBVHCollide<KDOP<double, 18>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_OCTREE_EXTERN template std::size_t BVHOcTreeCollide<KDOP<double, 18>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_OCTREE_EXTERN template std::size_t OcTreeBVHCollide<KDOP<double, 24>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_OCTREE_EXTERN template std::size_t BVHOcTreeCollide<KDOP<double, 24>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_OCTREE_EXTERN template std::size_t OcTreeBVHCollide<kIOS<double>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_OCTREE_EXTERN template std::size_t BVHOcTreeCollide<kIOS<double>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_OCTREE_EXTERN template std::size_t OcTreeBVHCollide<OBBRSS<double>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
FCL_QUADRIC_OCTREE_EXTERN template std::size_t BVHOcTreeCollide<OBBRSS<double>, fcl_quadric::QuadricSolver<double>>(FCL_QUADRIC_COLLISION_FUNC_PARAMS);
#endif  // FCL_HAVE_OCTOMAP

}  // namespace detail
}  // namespace fcl

#undef FCL_QUADRIC_COLLISION_FUNC_PARAMS
#undef FCL_QUADRIC_BVH_EXTERN
#undef FCL_QUADRIC_OCTREE_EXTERN
