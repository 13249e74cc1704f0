#pragma once
// Private: the geometries the planning layer accepts as robot bodies and obstacles, with their
// parameters checked once, when they are added (docs/ompl.md, "Bodies"; reliability.md finding 33).
#include <string>

#include <fcl/geometry/collision_geometry.h>

namespace fcl_quadric {
namespace planning {
namespace detail {

/// \throws std::invalid_argument naming `where` and the bad value for a geometry the layer cannot
/// check (fcl::TriangleP, for which FCL 0.7 has no collision or distance function against most
/// shapes, so it was silently never in contact; any other unknown node type) or one whose
/// parameters are not finite or not positive (radii, sizes, lengths; a plane's normal; mesh and
/// convex vertices; a mesh that is not finished with endModel()).
void checkSupportedGeometry(const fcl::CollisionGeometry<double>& g, const std::string& where);

}  // namespace detail
}  // namespace planning
}  // namespace fcl_quadric
