#pragma once
// Private: the formula form of dualLinearBound (quadric_region.h), a certified upper bound of a
// linear function over a composite quadric model by weak (Lagrangian) duality over pairs of its
// atoms, the S-procedure. docs/algorithms.md section 9, "Faces by duality". maxLinear
// (quadric_region.cpp) starts its bisection from it, so that a face whose maximum lies on a curve
// where two atoms meet (a ring's rim) needs no search to exclude the levels above it.

#include <Eigen/Core>

#include "fcl_quadric/geometry/quadric_region.h"
#include "geometry/region_formula.h"

namespace fcl_quadric {
namespace detail {

/// An upper bound of e.y over the points y of the formula's region inside `outer`, or +infinity
/// when no pair of atoms gives one. Certified: every rounding of its evaluation is bounded and
/// added (region_dual_bound.cpp). Tight where the duality gap of the best pair is zero: always
/// for two convex atoms (a lens), and for an ellipsoid minus a coaxial cylinder (a ring).
double dualLinearBound(const Formula& f, const Eigen::Vector3d& e, const Box3& outer);

}  // namespace detail
}  // namespace fcl_quadric
