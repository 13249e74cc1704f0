#pragma once
/// \file plane_frame.h
/// Planes of plane atoms, shared by the boundary elements (quadric_region.cpp: edge
/// classification, witnesses on plane-plane lines) and the dimension reduction
/// (dimension_reduction_ccd.cpp: section lines, line edges). Eigen only.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "algebra/dense_decompositions.h"

namespace fcl_quadric {
namespace detail {

/// For the plane n.x + d = 0 given as the covector (n, d), n finite and non-zero: E (4x3) with
/// X = E (s, t, 1) the homogeneous point o + s u + t v, where o is the plane's point nearest the
/// origin and (u, v) an orthonormal basis of its directions (u = n.unitOrthogonal(), v = n x u,
/// n normalised). E^T Q E is a quadric Q restricted to the plane, in (s, t).
inline Eigen::Matrix<double, 4, 3> planeFrame(const Eigen::Vector4d& plane) {
  const Eigen::Vector3d n = plane.head<3>();
  const Eigen::Vector3d nu = n.normalized();
  const Eigen::Vector3d u = nu.unitOrthogonal(), v = nu.cross(u);
  Eigen::Matrix<double, 4, 3> E = Eigen::Matrix<double, 4, 3>::Zero();
  E.block<3, 1>(0, 0) = u;
  E.block<3, 1>(0, 1) = v;
  E.block<3, 1>(0, 2) = -plane[3] / n.squaredNorm() * n;
  E(3, 2) = 1.0;
  return E;
}

/// The covector pi = (n, d) with X^T Q X = (pi.X) w for a plane atom Q (zero quadratic block;
/// its interior pi.X <= 0 for w = 1).
inline Eigen::Vector4d planeOf(const Eigen::Matrix4d& Q) {
  return Eigen::Vector4d(2 * Q(0, 3), 2 * Q(1, 3), 2 * Q(2, 3), Q(3, 3));
}

/// The line x + s d where the planes p1, p2 (covectors) meet: d = n1 x n2, x their point nearest
/// the origin. False when they are parallel to 1e-12 (|d| <= 1e-12 |n1| |n2|).
inline bool lineOfPlanes(const Eigen::Vector4d& p1, const Eigen::Vector4d& p2, Eigen::Vector3d* x, Eigen::Vector3d* d) {
  const Eigen::Vector3d n1 = p1.head<3>(), n2 = p2.head<3>();
  *d = n1.cross(n2);
  if (d->norm() <= 1e-12 * n1.norm() * n2.norm()) return false;
  Eigen::Matrix<double, 2, 3> N;
  N.row(0) = n1.transpose();
  N.row(1) = n2.transpose();
  const Eigen::Vector2d rhs(-p1[3], -p2[3]);
  *x = N.transpose() * ldltSolve(Eigen::Matrix2d(N * N.transpose()), rhs);
  return true;
}

}  // namespace detail
}  // namespace fcl_quadric
