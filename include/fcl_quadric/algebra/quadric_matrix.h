#pragma once
/// \file quadric_matrix.h
/// 4x4 symmetric matrices of quadric surfaces in homogeneous coordinates X = (x, y, z, 1).
///
/// Convention (Choi 2008 §4.1, used throughout fcl_quadric): the solid bounded by the quadric is
/// { X : X^T Q X <= 0 }, the interior is X^T Q X < 0. Under the affine map x = M u + p (body to
/// world, homogeneous T = [M p; 0 1]) a body-frame matrix Q_B becomes Q_W = T^-T Q_B T^-1.
/// Only std and Eigen are used here.

#include <Eigen/Core>

namespace fcl_quadric {
namespace quadric {

/// Bad input: every shape parameter (radius, semi-axis, half-width) must be finite and > 0,
/// planePair's normal finite and unit (within 1e-12) and its offset finite; otherwise
/// std::invalid_argument naming the function and the parameter. posedEllipsoid validates the
/// radii the same way; affineEllipsoid throws as transform(); affineTransform and evaluate take
/// their inputs as given (no validation: a non-finite input gives a non-finite result).

/// Ellipsoid x^2/a^2 + y^2/b^2 + z^2/c^2 <= 1: diag(1/a^2, 1/b^2, 1/c^2, -1) (thesis (4.1)).
Eigen::Matrix4d ellipsoid(const Eigen::Vector3d& radii);
/// Elliptic cylinder along z: x^2/a^2 + y^2/b^2 <= 1.
Eigen::Matrix4d ellipticCylinder(double a, double b);
/// Elliptic cone with apex at the origin, axis z: x^2/a^2 + y^2/b^2 <= z^2/c^2 (both nappes).
Eigen::Matrix4d ellipticCone(double a, double b, double c);
/// Elliptic paraboloid opening towards +z: x^2/a^2 + y^2/b^2 <= z.
Eigen::Matrix4d ellipticParaboloid(double a, double b);
/// Hyperbolic paraboloid: x^2/a^2 - y^2/b^2 <= z.
Eigen::Matrix4d hyperbolicParaboloid(double a, double b);
/// Hyperboloid of one sheet: x^2/a^2 + y^2/b^2 - z^2/c^2 <= 1 (the solid around the z axis).
Eigen::Matrix4d hyperboloidOneSheet(double a, double b, double c);
/// Hyperboloid of two sheets: x^2/a^2 + y^2/b^2 - z^2/c^2 <= -1 (the two solid caps).
Eigen::Matrix4d hyperboloidTwoSheets(double a, double b, double c);
/// Half-space n.x <= d as a degenerate quadric is not representable with X^T Q X <= 0 alone;
/// the slab |n.x - d| <= w (a pair of parallel planes) is: (n.x - d)^2 <= w^2, n unit.
Eigen::Matrix4d planePair(const Eigen::Vector3d& n, double d, double w);

/// Homogeneous 4x4 of the affine map x = M u + p.
Eigen::Matrix4d affineTransform(const Eigen::Matrix3d& M, const Eigen::Vector3d& p);
/// Q_W = T^-T Q_B T^-1 for an invertible affine T (last row [0 0 0 1]).
/// \throws std::invalid_argument if T is not finite, not affine, or singular.
Eigen::Matrix4d transform(const Eigen::Matrix4d& Q_body, const Eigen::Matrix4d& T);
/// Ellipsoid of the given radii posed by a rigid (R, p): T^-1 = [R^T, -R^T p] without inversion.
Eigen::Matrix4d posedEllipsoid(const Eigen::Vector3d& radii, const Eigen::Matrix3d& R, const Eigen::Vector3d& p);
/// posedEllipsoid() (the matrix A of thesis §4.1) formed in long double from the same double
/// inputs (1/r^2, R^T p and every product in the 64-bit significand): the continuous solver's
/// precision check (thesis ch.5; docs/algorithms.md §8) expands its extended function from it,
/// so that the estimate of that function's error also covers the rounding of the quadric itself. \throws std::invalid_argument as
/// posedEllipsoid (a radius not finite or not > 0).
Eigen::Matrix<long double, 4, 4> posedEllipsoidExtended(const Eigen::Vector3d& radii, const Eigen::Matrix3d& R,
                                                        const Eigen::Vector3d& p);
/// The image of the unit ball under x = M u + p: T^-T diag(1,1,1,-1) T^-1.
Eigen::Matrix4d affineEllipsoid(const Eigen::Matrix3d& M, const Eigen::Vector3d& p);

/// X^T Q X at the point x (w = 1).
double evaluate(const Eigen::Matrix4d& Q, const Eigen::Vector3d& x);

}  // namespace quadric
}  // namespace fcl_quadric
