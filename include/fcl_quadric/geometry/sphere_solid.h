#pragma once
/// \file sphere_solid.h
/// A sphere against FCL's convex primitives (box, capsule, cylinder, cone), a triangle and
/// fcl_quadric's EllipticCylinder, in closed form.
///
/// A solid ball of radius r and centre c is the Minkowski sum of its centre with the ball, so its
/// signed distance to a convex solid K is the signed distance of the point c to K minus r (for
/// separated and overlapping pairs alike; docs/algorithms.md section 12d). The point's signed
/// distance is elementary geometry in K's frame:
///  - box: the clamped point outside; inside, the nearest face (largest |x_i| - h_i);
///  - capsule: the distance to the axis segment minus the capsule's radius;
///  - cylinder and cone: solids of revolution, so the problem is the point (rho, z) against the
///    rectangle [-R, R] x [-L/2, L/2] or the triangle with apex (0, L/2) and base corners
///    (+-R, -L/2) in the meridian half-plane through the point (the nearest point of a convex set
///    symmetric about the axis lies in the point's own half-plane);
///  - triangle: the nearest point of the triangle (Voronoi regions of its vertices and edges), a
///    solid without interior: a centre on it is at depth r along either normal.
/// The problem is computed in the solid's frame x = R^T (c - p) (p its centre; a triangle's first
/// vertex), with every length multiplied by the power of two that brings the largest into [1, 2)
/// (exact; no square overflows or underflows at any size within the accepted ranges), and a
/// triangle's normal and orientation tests from cross products accurate to one rounding (Kahan's
/// difference of products), so that nearly degenerate triangles stay exact. Each computed
/// distance is then within a few eps of the scale |x| + |d| + r of the exact one (d the centre's
/// distance; for the cone plus the two terms of its slant-line distance). The status is read with
/// the touching band of the other exact kernels, tolerance::kCertificateRelativeBoundDouble
/// (2^-40) times that scale: Separated above it, Overlapping below its negative, Touching
/// (distance 0, counts as contact) within it.
///
/// Outputs follow SignedDistanceResult: normal unit, from the sphere (a) to the solid (b);
/// point_a = c + r normal on the sphere (its deepest point in the solid when they overlap);
/// point_b the solid's boundary point nearest to c (when c is inside: on the nearest face);
/// point_b - point_a = distance * normal. Where the direction is not unique (c on a capsule's or
/// cylinder's axis, on a cone's axis, on a triangle) the first of the solid's frame axes that
/// fits is taken. converged = true, iterations = 0.
///
/// ellipsoid_polytope.h, ellipsoid_capsule.h and ellipsoid_cylinder.h call these when their
/// ellipsoid has three equal radii: the general kernels take 8-55 us for what this does in
/// 0.1-0.4 us. signedDistanceEllipsoidConvex does the same for a convex polytope: the nearest
/// face plane when the centre is inside every one, otherwise the nearest of its fan triangles.

#include <optional>

#include <Eigen/Core>

#include "fcl_quadric/geometry/signed_distance.h"

namespace fcl_quadric {

/// Sphere (centre c, radius r) against the box { p_WB + R_WB s : |s_i| <= h_i }.
/// \throws std::invalid_argument for a radius or half extent not finite or outside
/// [0, tolerance::kMaxLength], a non-rotation R_WB, or a centre not finite or beyond kMaxLength
/// (the message names the value).
SignedDistanceResult signedDistanceSphereBox(const Eigen::Vector3d& c, double r, const Eigen::Vector3d& half_extents,
                                             const Eigen::Matrix3d& R_WB, const Eigen::Vector3d& p_WB);

/// Sphere against fcl::Capsule(radius, length) posed at (R_WC, p_WC): the segment
/// { p + R (0, 0, s) : |s| <= L/2 } swept by a ball of that radius. Same exceptions.
SignedDistanceResult signedDistanceSphereCapsule(const Eigen::Vector3d& c, double r, double radius, double length,
                                                 const Eigen::Matrix3d& R_WC, const Eigen::Vector3d& p_WC);

/// Sphere against fcl::Cylinder(radius, length): { |(x, y)| <= radius, |z| <= L/2 } in its frame.
SignedDistanceResult signedDistanceSphereCylinder(const Eigen::Vector3d& c, double r, double radius, double length,
                                                  const Eigen::Matrix3d& R_WC, const Eigen::Vector3d& p_WC);

/// Sphere against the capped elliptic cylinder { x^2/a^2 + y^2/b^2 <= 1, |z| <= L/2 } of
/// fcl_quadric::EllipticCylinder(a, b, length), posed at (R_WC, p_WC). The 2D problem of the
/// ellipse separates from the caps; its nearest point comes from detail::closestPointPrincipal<2>
/// (point_ellipsoid.h, to rounding), and outside the solid the status is read from a certified
/// bracket of the distance (the support function along the nearest direction below, the nearest
/// point above), not from the root's accuracy. converged = false (status Touching, distance 0)
/// only if that bracket is wider than the band (not met in the tests). Not from the seed papers:
/// Eberly's point-ellipse distance and the support function's weak duality (docs/algorithms.md
/// sections 6 and 12d). \throws std::invalid_argument as the cylinder's (a radius, semi-axis or
/// length not finite or outside [0, kMaxLength], a non-rotation, a centre not finite or beyond
/// kMaxLength; the message names the value), and also for a semi-axis of 0.
SignedDistanceResult signedDistanceSphereEllipticCylinder(const Eigen::Vector3d& c, double r, double a, double b,
                                                          double length, const Eigen::Matrix3d& R_WC,
                                                          const Eigen::Vector3d& p_WC);

namespace detail {
/// signedDistanceSphereEllipticCylinder without its checks, for the FCL front doors, which have
/// checked the poses (rigid within tolerance::kRotationOrthogonality, R used as given, as their
/// GJK does) and the cylinder at its construction. \pre r in [0, kMaxLength]; a, b > 0 and
/// length within kMaxLength; c and p finite within kMaxLength.
SignedDistanceResult sphereEllipticCylinder(const Eigen::Vector3d& c, double r, double a, double b, double length,
                                            const Eigen::Matrix3d& R, const Eigen::Vector3d& p);
/// Collision only, for the front doors' collide (same preconditions): false when apart, true with
/// *common a point of both solids, nullopt where sphereEllipticCylinder leaves the pair undecided.
/// Two certified tests come first and decide most pairs without the ellipse's root: apart along
/// the centre's own direction (the support function), and the centre inside the cylinder.
std::optional<bool> sphereEllipticCylinderContact(const Eigen::Vector3d& c, double r, double a, double b,
                                                  double length, const Eigen::Matrix3d& R, const Eigen::Vector3d& p,
                                                  Eigen::Vector3d* common);
}  // namespace detail

/// Sphere against fcl::Cone(radius, length): base disk of that radius at z = -L/2, apex at +L/2.
SignedDistanceResult signedDistanceSphereCone(const Eigen::Vector3d& c, double r, double radius, double length,
                                              const Eigen::Matrix3d& R_WC, const Eigen::Vector3d& p_WC);

/// Sphere against the closed solid triangle abc (degenerate triangles are segments or points).
/// \throws std::invalid_argument for a bad radius or a vertex not finite or beyond kMaxLength.
SignedDistanceResult signedDistanceSphereTriangle(const Eigen::Vector3d& c, double r, const Eigen::Vector3d& a,
                                                  const Eigen::Vector3d& b, const Eigen::Vector3d& t);

/// Two spheres: |c_b - c_a| - r_a - r_b, symmetric bit for bit (the arguments exchanged give the
/// same distance and the mirrored witnesses and normal; coincident centres: normal +x either way).
/// \throws std::invalid_argument for a bad radius or centre.
SignedDistanceResult signedDistanceSphereSphere(const Eigen::Vector3d& c_a, double r_a, const Eigen::Vector3d& c_b,
                                                double r_b);

/// True if e is a sphere (three equal radii), whose pairs the closed forms above answer.
inline bool isSphere(const Ellipsoid& e) {
  const auto r = e.radii();
  return r[0] == r[1] && r[1] == r[2];
}

}  // namespace fcl_quadric
