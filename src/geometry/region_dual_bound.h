#pragma once
// Private: the formula form of dualLinearBound (quadric_region.h), a certified upper bound of a
// linear function over a composite quadric model by weak (Lagrangian) duality over its atoms.
// docs/algorithms.md section 9, "Faces by duality". maxLinear (quadric_region.cpp) starts its
// bisection from it, so that a face whose maximum lies on a curve where two atoms meet (a ring's
// rim) needs no search to exclude the levels above it.

#include <Eigen/Core>

#include "fcl_quadric/geometry/quadric_region.h"
#include "geometry/region_formula.h"

namespace fcl_quadric {
namespace detail {

/// An upper bound of e.y over the points y of the formula's region inside `outer`, or +infinity
/// when no pair of inequalities, plane subset or convex part gives one. Certified: every rounding
/// of its evaluation is bounded and added (region_dual_bound.cpp). Where it is tight: the public
/// dualLinearBound's comment (quadric_region.h).
double dualLinearBound(const Formula& f, const Eigen::Vector3d& e, const Box3& outer);

}  // namespace detail
}  // namespace fcl_quadric
