// The one translation unit that instantiates FCL's distance templates for QuadricSolver<double>:
// DistanceFunctionMatrix (every shape/BVH/OcTree pair's traversal), its lookup table, the
// specialization of fcl::distance declared in quadric_solver.h; plus fcl_quadric::distance and
// defaultDistanceFunction.
#include "fcl_quadric/fcl/distance.h"

#include <cassert>
#include <iostream>
#include <limits>
#include <stdexcept>
#include <type_traits>

#include <fcl/broadphase/default_broadphase_callbacks.h>
#include <fcl/narrowphase/distance.h>

#include "fcl/distance_fix_up.h"
#include "fcl/input_checks.h"
#include "fcl/mesh_distance.h"
#include "fcl/octree_distance.h"
#include "fcl/quadric_shape_dispatch.h"
#include "fcl_quadric/fcl/collision.h"
#include "fcl_quadric/fcl/quadric_solver.h"

// --- FCL templates for QuadricSolver<double> (declared in quadric_solver.h) -------------------
namespace fcl {
namespace detail {
template struct DistanceFunctionMatrix<fcl_quadric::QuadricSolver<double>>;
}  // namespace detail

template detail::DistanceFunctionMatrix<fcl_quadric::QuadricSolver<double>>&
getDistanceFunctionLookTable<fcl_quadric::QuadricSolver<double>>();

// FCL 0.7's distance() (fcl/narrowphase/distance-inl.h, the CollisionGeometry overload) verbatim
// except for the marked condition, where FCL tests std::is_same<NarrowPhaseSolver,
// GJKSolver_libccd<S>>: QuadricSolver, like libccd, returns a true signed distance with surface
// points for primitive pairs, so FCL's collide()-based workaround is applied only to BVH / OcTree
// operands.
template <>
double distance<fcl_quadric::QuadricSolver<double>>(const CollisionGeometry<double>* o1, const Transform3<double>& tf1,
                                                    const CollisionGeometry<double>* o2, const Transform3<double>& tf2,
                                                    const fcl_quadric::QuadricSolver<double>* nsolver_,
                                                    const DistanceRequest<double>& request,
                                                    DistanceResult<double>& result) {
  using S = double;
  using NarrowPhaseSolver = fcl_quadric::QuadricSolver<double>;

  const NarrowPhaseSolver* nsolver = nsolver_;
  if (!nsolver_) nsolver = new NarrowPhaseSolver();

  // fcl_quadric: FCL 0.7's table has no (Halfspace, Ellipsoid) entry (distance_func_matrix-inl.h
  // lists every other half-space pair); QuadricSolver answers that order exactly, so the entry is
  // added once, thread-safely (a function-local static), before the first lookup. Every lookup
  // in this table goes through this function.
  static const bool halfspace_ellipsoid_added = [] {
    auto& table = getDistanceFunctionLookTable<NarrowPhaseSolver>();
    if (!table.distance_matrix[GEOM_HALFSPACE][GEOM_ELLIPSOID]) {
      table.distance_matrix[GEOM_HALFSPACE][GEOM_ELLIPSOID] =
          &detail::ShapeShapeDistance<Halfspace<S>, Ellipsoid<S>, NarrowPhaseSolver>;
    }
    return true;
  }();
  (void)halfspace_ellipsoid_added;

  const auto& looktable = getDistanceFunctionLookTable<NarrowPhaseSolver>();

  OBJECT_TYPE object_type1 = o1->getObjectType();
  NODE_TYPE node_type1 = o1->getNodeType();
  OBJECT_TYPE object_type2 = o2->getObjectType();
  NODE_TYPE node_type2 = o2->getNodeType();

  S res = std::numeric_limits<S>::max();

  if (object_type1 == OT_GEOM && object_type2 == OT_BVH) {
    if (!looktable.distance_matrix[node_type2][node_type1]) {
      std::cerr << "Warning: distance function between node type " << node_type1 << " and node type " << node_type2
                << " is not supported\n";
    } else {
      res = looktable.distance_matrix[node_type2][node_type1](o2, tf2, o1, tf1, nsolver, request, result);
    }
  } else {
    if (!looktable.distance_matrix[node_type1][node_type2]) {
      std::cerr << "Warning: distance function between node type " << node_type1 << " and node type " << node_type2
                << " is not supported\n";
    } else {
      res = looktable.distance_matrix[node_type1][node_type2](o1, tf1, o2, tf2, nsolver, request, result);
    }
  }

  if (res && result.min_distance < static_cast<S>(0) && request.enable_signed_distance) {
    // fcl_quadric: FCL has std::is_same<NarrowPhaseSolver, detail::GJKSolver_libccd<S>>::value here.
    if (object_type1 == OT_GEOM && object_type2 == OT_GEOM) {
      if (!nsolver_) delete nsolver;
      return res;
    }

    CollisionRequest<S> collision_request;
    collision_request.enable_contact = true;

    CollisionResult<S> collision_result;

    collide(o1, tf1, o2, tf2, nsolver, collision_request, collision_result);
    assert(collision_result.isCollision());

    std::size_t index = static_cast<std::size_t>(-1);
    S max_pen_depth = std::numeric_limits<S>::min();
    for (auto i = 0u; i < collision_result.numContacts(); ++i) {
      const auto& contact = collision_result.getContact(i);
      if (max_pen_depth < contact.penetration_depth) {
        max_pen_depth = contact.penetration_depth;
        index = i;
      }
    }
    result.min_distance = -max_pen_depth;
    assert(index != static_cast<std::size_t>(-1));

    if (request.enable_nearest_points) {
      const Vector3<S>& pos = collision_result.getContact(index).pos;
      result.nearest_points[0] = pos;
      result.nearest_points[1] = pos;
    }
  }

  if (!nsolver_) delete nsolver;

  return res;
}

template double distance<fcl_quadric::QuadricSolver<double>>(const CollisionObject<double>* o1,
                                                             const CollisionObject<double>* o2,
                                                             const fcl_quadric::QuadricSolver<double>* nsolver,
                                                             const DistanceRequest<double>& request,
                                                             DistanceResult<double>& result);
}  // namespace fcl

namespace fcl_quadric {

namespace detail {

void signedDistanceFixUp(const fcl::CollisionGeometry<double>* o1, const fcl::Transform3<double>& tf1,
                         const fcl::CollisionGeometry<double>* o2, const fcl::Transform3<double>& tf2,
                         const fcl::DistanceRequest<double>& request, fcl::DistanceResult<double>& result) {
  // FCL's code above (the QuadricSolver copy of distance()), with fcl_quadric::collide, and no
  // read of contact number -1 when no contact is deeper than DBL_MIN (FCL asserts, then reads it).
  if (!(result.min_distance < 0.0 && request.enable_signed_distance)) return;
  fcl::CollisionRequest<double> collision_request;
  collision_request.enable_contact = true;
  fcl::CollisionResult<double> collision_result;
  fcl_quadric::collide(o1, tf1, o2, tf2, collision_request, collision_result);
  std::size_t index = 0;
  double max_depth = std::numeric_limits<double>::min();
  for (std::size_t i = 0; i < collision_result.numContacts(); ++i) {
    const double depth = collision_result.getContact(i).penetration_depth;
    if (max_depth < depth) {
      max_depth = depth;
      index = i;
    }
  }
  result.min_distance = -max_depth;
  if (request.enable_nearest_points && collision_result.numContacts() > 0) {
    const fcl::Vector3d& pos = collision_result.getContact(index).pos;
    result.nearest_points[0] = pos;
    result.nearest_points[1] = pos;
  }
}

}  // namespace detail

template <typename S>
S distance(const fcl::CollisionGeometry<S>* o1, const fcl::Transform3<S>& tf1, const fcl::CollisionGeometry<S>* o2,
           const fcl::Transform3<S>& tf2, const fcl::DistanceRequest<S>& request, fcl::DistanceResult<S>& result) {
  detail::checkPosedPair(o1, tf1, o2, tf2, "fcl_quadric::distance");
  QuadricSolver<S> solver;
  solver.libccd().distance_tolerance = request.distance_tolerance;
  // fcl_quadric's quadric shapes (BV_UNKNOWN for FCL): their own dispatch (convex ones by GJK / EPA
  // on support mappings; quadric_shape_dispatch.h).
  if constexpr (std::is_same_v<S, double>) {
    if (detail::isQuadricShape(o1) || detail::isQuadricShape(o2))
      return detail::distanceQuadricShapes(o1, tf1, o2, tf2, request, result);
    // A triangle mesh (any BV type) against an ellipsoid or a sphere: FCL's distance traversal
    // with a lower bound that needs no fitted BV (mesh_distance.h).
    double value = 0.0;
    if (detail::distanceMeshShape(o1, tf1, o2, tf2, solver, request, result, &value)) return value;
    // An OcTree against an ellipsoid: likewise, best first (octree_distance.h).
    if (detail::distanceOcTreeShape(o1, tf1, o2, tf2, solver, request, result, &value)) return value;
  }
  return fcl::distance(o1, tf1, o2, tf2, &solver, request, result);
}

template <typename S>
S distance(const fcl::CollisionObject<S>* o1, const fcl::CollisionObject<S>* o2,
           const fcl::DistanceRequest<S>& request, fcl::DistanceResult<S>& result) {
  detail::checkObject(o1, "fcl_quadric::distance", "o1");
  detail::checkObject(o2, "fcl_quadric::distance", "o2");
  return fcl_quadric::distance(o1->collisionGeometry().get(), o1->getTransform(), o2->collisionGeometry().get(),
                               o2->getTransform(), request, result);
}

template <typename S>
bool defaultDistanceFunction(fcl::CollisionObject<S>* o1, fcl::CollisionObject<S>* o2, void* data, S& dist) {
  if (data == nullptr)
    throw std::invalid_argument("fcl_quadric::defaultDistanceFunction: data is null (expected a "
                                "fcl::DefaultDistanceData)");
  auto* cdata = static_cast<fcl::DefaultDistanceData<S>*>(data);
  const fcl::DistanceRequest<S>& request = cdata->request;
  fcl::DistanceResult<S>& result = cdata->result;

  if (cdata->done) {
    dist = result.min_distance;
    return true;
  }

  fcl_quadric::distance(o1, o2, request, result);

  dist = result.min_distance;
  if (dist <= 0) return true;  // in collision or in touch
  return cdata->done;
}

template double distance(const fcl::CollisionObject<double>*, const fcl::CollisionObject<double>*,
                         const fcl::DistanceRequest<double>&, fcl::DistanceResult<double>&);
template double distance(const fcl::CollisionGeometry<double>*, const fcl::Transform3<double>&,
                         const fcl::CollisionGeometry<double>*, const fcl::Transform3<double>&,
                         const fcl::DistanceRequest<double>&, fcl::DistanceResult<double>&);
template bool defaultDistanceFunction(fcl::CollisionObject<double>*, fcl::CollisionObject<double>*, void*, double&);

}  // namespace fcl_quadric
