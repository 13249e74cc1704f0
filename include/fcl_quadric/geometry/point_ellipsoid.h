#pragma once
/// \file point_ellipsoid.h
/// Closest point of an ellipsoid's surface to a point, in 3D and (for projected shadows) in 2D.
///
/// Method (D. Eberly, "Distance from a point to an ellipse, an ellipsoid, or a hyperellipsoid",
/// 2013): with y the point in the principal frame and radii e_i, the closest surface point is
/// x_i = e_i^2 y_i / (e_i^2 + t) where t is the root on (-e_min^2, inf) of
///     g(t) = sum_i (e_i y_i / (e_i^2 + t))^2 - 1,
/// which is decreasing there; t > 0 outside, t < 0 inside. It is solved in double in the shifted
/// unknown s = t + e_min^2, so that next to the pole (interior points near a principal plane
/// through the longer axes) the coordinates x_i = e_i^2 y_i / (s + e_i^2 - e_min^2) lose nothing to
/// cancellation: until session 45 the solver worked on t in long double and was off by up to
/// 1e-5 of the scale there (a 50-digit oracle in the tests; now within 4e-16). Newton from a
/// bracket, bisection-safeguarded, capped at kMaxPointEllipsoidIterations (~4 steps on average);
/// points with no coordinate along the shortest axes, where the nearest point may leave the
/// principal plane, by Eberly's case analysis. Lengths are scaled by a power of two (exact).

#include <Eigen/Core>

#include "fcl_quadric/geometry/ellipsoid.h"

namespace fcl_quadric {

struct PointEllipsoidResult {
  Eigen::Vector3d closest = Eigen::Vector3d::Zero();  ///< on the surface (world frame)
  double signed_distance = 0.0;                       ///< < 0 inside
};

/// Closest surface point of e to q, and the signed distance (negative inside).
/// \throws std::invalid_argument if q is not finite.
PointEllipsoidResult closestPointOnEllipsoid(const Ellipsoid& e, const Eigen::Vector3d& q);

namespace detail {
/// Principal-frame solver for N = 2 or 3: radii e (any order, > 0), point y; writes the closest
/// point x and returns the signed distance. ~100 ns in 2D (the sphere against an elliptic
/// cylinder, sphere_solid.h, calls it on every query). \pre e > 0 and finite, y finite.
template <int N>
double closestPointPrincipal(const Eigen::Matrix<double, N, 1>& e, const Eigen::Matrix<double, N, 1>& y,
                             Eigen::Matrix<double, N, 1>* x);

/// Every critical point of the distance from y to the surface (up to 2N: the roots of g(t) on each
/// interval between its poles -e_i^2 - one on (-e_min^2, inf), one on (-inf, -e_max^2), zero or
/// two on each interval in between where g is convex - plus the points with t = -e_i^2 when
/// y_i = 0). Used for penetration depth, whose optimum need not be the global closest point.
template <int N>
int criticalPointsPrincipal(const Eigen::Matrix<double, N, 1>& e, const Eigen::Matrix<double, N, 1>& y,
                            Eigen::Matrix<double, N, 1>* out, int max_out);
}  // namespace detail

}  // namespace fcl_quadric
