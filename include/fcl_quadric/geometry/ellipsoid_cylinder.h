#pragma once
/// \file ellipsoid_cylinder.h
/// Ellipsoid against a solid cylinder (fcl::Cylinder) and a solid cone (fcl::Cone).
///
/// FCL's conventions, in the solid's frame (rotation R, centre p, axis a = R e_z):
///  - Cylinder(radius r, lz L): { |(x, y)| <= r, |z| <= L/2 };
///  - Cone(radius r, lz L): base disk of radius r at z = -L/2, apex at z = +L/2.
/// Both are K = conv(D0 u D1) of two coaxial disks D_i (centre q_i = p -+ (L/2) a, radius r_i;
/// the cone's apex is the disk of radius 0), so h_K = max(h_D0, h_D1) with
/// h_Di(m) = m.q_i + r_i |m - (m.a) a|.
///
/// Method (docs/algorithms.md section 7). Signed distance d = max over unit n of
/// phi(n) = -h_E(n) - h_K(-n) = min(phi_0(n), phi_1(n)), phi_i(n) = n.(q_i - c) - |S R^T n| - r_i|Pi n|
/// (Pi = I - a a^T). The maximiser is one of: a pole n = +-a (a flat cap supports K); a direction
/// on the boundary where both disks support K (the ruled side: the point-ellipse problem of the
/// axis projected with the ellipsoid's shadow for a cylinder, a one-parameter search on the
/// circle of slant normals for a cone); an exact point-ellipsoid critical point of a disk of radius
/// 0 (the cone's apex, a degenerate radius); or a smooth critical point of one phi_i, found by
/// capped Riemannian Newton (as signed_distance.cpp) from ranked seeds (centre direction, radial
/// direction, cap normals, ellipsoid axes, a spherical grid). phi is evaluated at every candidate
/// and the best is kept. For separated pairs each sub-problem is concave, so one start per disk
/// suffices; penetration depth takes several starts (kPenetrationStarts).
///
/// Status is certified, never read off an iterate:
///  - Separated only if the best direction n has phi(n) > 2^-40 * scale (scale = |p - c| + L +
///    r + largest ellipsoid radius; phi is computed from p - c, so this bounds its rounding);
///  - Overlapping only if a point y of K (parameters exactly in K's domain) has
///    |S^-1 R^T (y - c)|^2 < 1 - 2^-40 (1 + s_u)^2 (s_u the unit-frame magnitude): y minimises the
///    ellipsoid's function over K (convex: golden section on the axial coordinate of a
///    trust-region problem on each disk section);
///  - otherwise Touching (distance 0): near tangency, and whenever an iteration cap leaves both
///    certificates unproven, the answer errs toward contact.
/// Witness points: point_a = the ellipsoid's support point at n, point_b = point_a + phi(n) n (on
/// K's supporting plane; at the optimum the point of K's supporting face nearest to point_a).
/// Degenerate solids are accepted: radius 0 (a segment / the axis), length 0 (a disk), both (a
/// point); such a K has no interior, and Overlapping then means it meets the ellipsoid's interior.

#include <Eigen/Core>

#include "fcl_quadric/geometry/ellipsoid.h"
#include "fcl_quadric/geometry/signed_distance.h"

namespace fcl_quadric {

namespace round_solid {
/// Riemannian Newton steps per start on a smooth phi_i (fallback at the cap: best iterate, which
/// only lowers phi, i.e. Separated may become Touching; never a false answer).
constexpr int kMaxNewtonIterations = 100;
/// Starts per disk for penetration depth (overlapping or uncertain pairs); separated pairs use 1.
constexpr int kPenetrationStarts = 3;
/// Golden-section steps on the axial coordinate of the witness search (interval 0.618^80 ~ 1e-17
/// of the length); fallback at the cap: the best point so far (only weakens the certificate).
constexpr int kMaxWitnessAxialIterations = 80;
/// Newton steps of the secular equation of the disk-section trust-region problem.
constexpr int kMaxWitnessRadialIterations = 60;
/// Samples of the cone's slant-normal circle and safeguarded Newton/bisection steps per bracket.
constexpr int kConeSideSamples = 64;
constexpr int kMaxConeSideIterations = 100;
}  // namespace round_solid

/// Ellipsoid e against fcl::Cylinder(radius, length) posed at (R_WC, p_WC). normal points from the
/// ellipsoid to the cylinder; point_a on the ellipsoid, point_b on the cylinder.
/// \throws std::invalid_argument for a negative or non-finite radius or length, a non-rotation
/// R_WC or a non-finite centre (the message names the value).
SignedDistanceResult signedDistanceEllipsoidCylinder(const Ellipsoid& e, double radius, double length,
                                                     const Eigen::Matrix3d& R_WC, const Eigen::Vector3d& p_WC);

/// Ellipsoid e against fcl::Cone(radius, length) posed at (R_WC, p_WC) (base at local z = -L/2,
/// apex at +L/2). Same conventions and exceptions.
SignedDistanceResult signedDistanceEllipsoidCone(const Ellipsoid& e, double radius, double length,
                                                 const Eigen::Matrix3d& R_WC, const Eigen::Vector3d& p_WC);

}  // namespace fcl_quadric
