// The one translation unit that instantiates FCL's collision templates for QuadricSolver<double>:
// CollisionFunctionMatrix (every shape/BVH/OcTree pair's traversal), its lookup table and the two
// fcl::collide overloads taking a solver; plus fcl_quadric::collide and defaultCollisionFunction.
#include "fcl_quadric/fcl/collision.h"

#include <sstream>
#include <stdexcept>
#include <type_traits>

#include <fcl/broadphase/default_broadphase_callbacks.h>
#include <fcl/narrowphase/collision.h>

#include "fcl_quadric/fcl/quadric_solver.h"
#include "fcl/collision_pieces.h"
#include "fcl/input_checks.h"
#include "fcl/mesh_collision.h"
#include "fcl/octree_collision.h"
#include "fcl/quadric_shape_dispatch.h"

// --- FCL templates for QuadricSolver<double> (declared extern in quadric_solver.h) ------------
namespace fcl {
namespace detail {
template struct CollisionFunctionMatrix<fcl_quadric::QuadricSolver<double>>;
}  // namespace detail

template detail::CollisionFunctionMatrix<fcl_quadric::QuadricSolver<double>>&
getCollisionFunctionLookTable<fcl_quadric::QuadricSolver<double>>();

template std::size_t collide(const CollisionObject<double>* o1, const CollisionObject<double>* o2,
                             const fcl_quadric::QuadricSolver<double>* nsolver, const CollisionRequest<double>& request,
                             CollisionResult<double>& result);
template std::size_t collide(const CollisionGeometry<double>* o1, const Transform3<double>& tf1,
                             const CollisionGeometry<double>* o2, const Transform3<double>& tf2,
                             const fcl_quadric::QuadricSolver<double>* nsolver, const CollisionRequest<double>& request,
                             CollisionResult<double>& result);
}  // namespace fcl

namespace fcl_quadric {

template <typename S>
std::size_t collide(const fcl::CollisionGeometry<S>* o1, const fcl::Transform3<S>& tf1,
                    const fcl::CollisionGeometry<S>* o2, const fcl::Transform3<S>& tf2,
                    const fcl::CollisionRequest<S>& request, fcl::CollisionResult<S>& result) {
  detail::checkPosedPair(o1, tf1, o2, tf2, "fcl_quadric::collide");
  QuadricSolver<S> solver;
  solver.libccd().collision_tolerance = request.gjk_tolerance;
  // fcl_quadric's quadric shapes report fcl::BV_UNKNOWN (FCL's NODE_TYPE is closed): they are
  // recognised here, before FCL's lookup table is consulted (docs/fcl_integration.md).
  if constexpr (std::is_same_v<S, double>) {
    if (detail::isQuadricShape(o1) || detail::isQuadricShape(o2))
      return detail::collideQuadricShapes(o1, tf1, o2, tf2, request, result);
    // An OcTree against an ellipsoid or a sphere: FCL's answer through a cheaper traversal
    // (octree_collision.h).
    std::size_t count = 0;
    if (detail::collideOcTreeShape(o1, tf1, o2, tf2, solver, request, result, &count)) return count;
    // A triangle mesh (any BV type) against an ellipsoid or a sphere: likewise.
    if (detail::collideMeshShape(o1, tf1, o2, tf2, solver, request, result, &count)) return count;
  }
  return fcl::collide(o1, tf1, o2, tf2, &solver, request, result);
}

template <typename S>
std::size_t collide(const fcl::CollisionObject<S>* o1, const fcl::CollisionObject<S>* o2,
                    const fcl::CollisionRequest<S>& request, fcl::CollisionResult<S>& result) {
  detail::checkObject(o1, "fcl_quadric::collide", "o1");
  detail::checkObject(o2, "fcl_quadric::collide", "o2");
  return fcl_quadric::collide(o1->collisionGeometry().get(), o1->getTransform(), o2->collisionGeometry().get(),
                              o2->getTransform(), request, result);
}

template <typename S>
bool defaultCollisionFunction(fcl::CollisionObject<S>* o1, fcl::CollisionObject<S>* o2, void* data) {
  if (data == nullptr)
    throw std::invalid_argument("fcl_quadric::defaultCollisionFunction: data is null (expected a "
                                "fcl::DefaultCollisionData)");
  auto* collision_data = static_cast<fcl::DefaultCollisionData<S>*>(data);
  const fcl::CollisionRequest<S>& request = collision_data->request;
  fcl::CollisionResult<S>& result = collision_data->result;

  if (collision_data->done) return true;

  fcl_quadric::collide(o1, o2, request, result);

  if (!request.enable_cost && result.isCollision() && result.numContacts() >= request.num_max_contacts)
    collision_data->done = true;
  return collision_data->done;
}

template std::size_t collide(const fcl::CollisionObject<double>*, const fcl::CollisionObject<double>*,
                             const fcl::CollisionRequest<double>&, fcl::CollisionResult<double>&);
template std::size_t collide(const fcl::CollisionGeometry<double>*, const fcl::Transform3<double>&,
                             const fcl::CollisionGeometry<double>*, const fcl::Transform3<double>&,
                             const fcl::CollisionRequest<double>&, fcl::CollisionResult<double>&);
template bool defaultCollisionFunction(fcl::CollisionObject<double>*, fcl::CollisionObject<double>*, void*);

}  // namespace fcl_quadric
