#pragma once
// Private: FCL's signed-distance fix-up, for fcl_quadric::distance's own traversals
// (mesh_distance.cpp, octree_distance.cpp); defined in distance.cpp.
#include <fcl/common/types.h>
#include <fcl/geometry/collision_geometry.h>
#include <fcl/narrowphase/distance_request.h>
#include <fcl/narrowphase/distance_result.h>

namespace fcl_quadric {
namespace detail {

/// FCL's signed-distance fix-up in distance() (distance-inl.h), for the own traversals: with
/// enable_signed_distance and result.min_distance < 0, a one-contact collide of the pair
/// (fcl_quadric::collide), min_distance = -(the deepest penetration above DBL_MIN, else DBL_MIN),
/// and with enable_nearest_points both points at that contact (the first contact when none is
/// deeper: FCL reads contact number -1 there).
void signedDistanceFixUp(const fcl::CollisionGeometry<double>* o1, const fcl::Transform3<double>& tf1,
                         const fcl::CollisionGeometry<double>* o2, const fcl::Transform3<double>& tf2,
                         const fcl::DistanceRequest<double>& request, fcl::DistanceResult<double>& result);

}  // namespace detail
}  // namespace fcl_quadric
