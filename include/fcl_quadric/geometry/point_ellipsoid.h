#pragma once
/// \file point_ellipsoid.h
/// Closest point of an ellipsoid's surface to a point, in 3D and (for projected shadows) in 2D.
///
/// Method (D. Eberly, "Distance from a point to an ellipse, an ellipsoid, or a hyperellipsoid",
/// 2013): with y the point in the principal frame and radii e_i, the closest surface point is
/// x_i = e_i^2 y_i / (e_i^2 + t) where t is the largest root of
///     g(t) = sum_i (e_i y_i / (e_i^2 + t))^2 - 1,
/// which is decreasing on (-e_min^2, inf); t > 0 outside, t < 0 inside. The root is found by
/// bisection-safeguarded Newton in long double, capped at kMaxPointEllipsoidIterations; components
/// with y_i = 0 along the smallest axis (where the maximiser may leave the ellipse's evolute) are
/// handled by Eberly's case analysis.

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
/// point x and returns the signed distance.
template <int N>
double closestPointPrincipal(const Eigen::Matrix<double, N, 1>& e, const Eigen::Matrix<double, N, 1>& y,
                             Eigen::Matrix<double, N, 1>* x);

/// The closest point x of the ellipse u^2 / e0^2 + v^2 / e1^2 = 1 to y, in double, and the signed
/// distance (< 0 inside): the 2D case of closestPointPrincipal() for the hot paths (the sphere
/// against an elliptic cylinder, sphere_solid.h), ~10 times faster. The same secular equation in
/// s = t + e_min^2 > 0, g(s) = (c_max / (s + e_max^2 - e_min^2))^2 + (c_min / s)^2 - 1 with
/// c_i = e_i |y_i|, convex and decreasing, bracketed by [c_min, hypot(c_max, c_min)] (g >= 0 at the
/// left end, <= 0 at the right). One Newton step from the right end lands left of the root
/// (convexity) and Newton steps from there climb to it; a step that leaves the bracket or halves
/// it too slowly is replaced by a bisection (geometric while the bracket spans more than a factor
/// 4), at most tolerance::kMaxPointEllipsoidIterations steps. y on the major axis (y_min = 0) and
/// circles are Eberly's closed-form cases. Lengths are scaled by a power of two (exact) so that no
/// square overflows or underflows. \pre e0, e1 > 0 and finite; y finite (not checked).
double closestPointOnEllipse(double e0, double e1, const Eigen::Vector2d& y, Eigen::Vector2d* x);

/// Every critical point of the distance from y to the surface (up to 2N: the roots of g(t) on each
/// interval between its poles -e_i^2 - one on (-e_min^2, inf), one on (-inf, -e_max^2), zero or
/// two on each interval in between where g is convex - plus the points with t = -e_i^2 when
/// y_i = 0). Used for penetration depth, whose optimum need not be the global closest point.
template <int N>
int criticalPointsPrincipal(const Eigen::Matrix<double, N, 1>& e, const Eigen::Matrix<double, N, 1>& y,
                            Eigen::Matrix<double, N, 1>* out, int max_out);
}  // namespace detail

}  // namespace fcl_quadric
