#pragma once
/// \file collision.h
/// fcl_quadric::collide: FCL's collide() with the exact narrow phase (QuadricSolver) and checked
/// input, plus the broad-phase callback defaultCollisionFunction.
///
/// Same overloads and meaning as fcl::collide in <fcl/narrowphase/collision.h>; the call is routed
/// through FCL's CollisionFunctionMatrix instantiated for QuadricSolver<double> (src/fcl/collision.cpp),
/// so shapes, BVH meshes and OcTrees work as with FCL. Differences from fcl::collide:
///  - the narrow phase is QuadricSolver<S> (exact pairs with an ellipsoid or a sphere, libccd for
///    the rest; quadric_solver.h's table)
///    whatever request.gjk_solver_type says; its libccd fallback gets
///    collision_tolerance = request.gjk_tolerance, as fcl::collide does for GST_LIBCCD;
///  - bad input throws std::invalid_argument instead of crashing: a null object or geometry
///    pointer, a non-finite transform (and, from QuadricSolver, an ellipsoid whose pose is not
///    rigid or whose radii are invalid).
///  - fcl_quadric's quadric shapes (EllipticCylinder, Quadric, QuadricCSG; quadric_shapes.h),
///    which FCL's tables do not know (BV_UNKNOWN), are answered here against each other, FCL's
///    Sphere / Ellipsoid / Box / Cylinder / Cone / Capsule / Halfspace, BVH meshes and OcTrees
///    (certified region engine, docs/fcl_integration.md section 9): one contact, depth 0; other
///    partners throw std::invalid_argument.
/// Kept from FCL: request.num_max_contacts == 0 and pairs of node types FCL has no function for
/// (e.g. fcl::TriangleP) print FCL's warning on std::cerr and return 0 contacts.
///
/// Call it qualified (fcl_quadric::collide): the arguments are FCL types, so an unqualified call
/// would also find fcl::collide by argument-dependent lookup.
///
/// Only S = double is instantiated.

#include <cstddef>

#include <fcl/common/types.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/collision_request.h>
#include <fcl/narrowphase/collision_result.h>

namespace fcl_quadric {

/// Collision of two collision objects (geometry and pose taken from each object).
/// \return the number of contacts in `result` (as fcl::collide).
/// \throws std::invalid_argument if o1 or o2, or its collision geometry, is null, or a transform
///         is not finite; see also QuadricSolver.
template <typename S>
std::size_t collide(const fcl::CollisionObject<S>* o1, const fcl::CollisionObject<S>* o2,
                    const fcl::CollisionRequest<S>& request, fcl::CollisionResult<S>& result);

/// Collision of geometry o1 posed at tf1 (X_WO1) and o2 posed at tf2 (X_WO2).
/// \throws std::invalid_argument if o1 or o2 is null or tf1 / tf2 is not finite.
template <typename S>
std::size_t collide(const fcl::CollisionGeometry<S>* o1, const fcl::Transform3<S>& tf1,
                    const fcl::CollisionGeometry<S>* o2, const fcl::Transform3<S>& tf2,
                    const fcl::CollisionRequest<S>& request, fcl::CollisionResult<S>& result);

/// Broad-phase callback (fcl::CollisionCallBack<S>), FCL's DefaultCollisionFunction with
/// fcl_quadric::collide. `data` must point to an fcl::DefaultCollisionData<S>
/// (<fcl/broadphase/default_broadphase_callbacks.h>): its request is used and its result
/// accumulates the contacts; evaluation stops (returns true, sets data->done) when cost is
/// disabled and the result holds request.num_max_contacts contacts, as in FCL. Usage:
///   fcl::DefaultCollisionData<double> data;
///   manager.collide(&data, fcl_quadric::defaultCollisionFunction<double>);
/// \throws std::invalid_argument if data is null (FCL's version asserts), or from collide().
template <typename S>
bool defaultCollisionFunction(fcl::CollisionObject<S>* o1, fcl::CollisionObject<S>* o2, void* data);

extern template std::size_t collide(const fcl::CollisionObject<double>*, const fcl::CollisionObject<double>*,
                                    const fcl::CollisionRequest<double>&, fcl::CollisionResult<double>&);
extern template std::size_t collide(const fcl::CollisionGeometry<double>*, const fcl::Transform3<double>&,
                                    const fcl::CollisionGeometry<double>*, const fcl::Transform3<double>&,
                                    const fcl::CollisionRequest<double>&, fcl::CollisionResult<double>&);
extern template bool defaultCollisionFunction(fcl::CollisionObject<double>*, fcl::CollisionObject<double>*, void*);

}  // namespace fcl_quadric
