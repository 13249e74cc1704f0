#pragma once
/// \file plane_frame.h
/// The homogeneous frame of a plane, shared by the boundary elements' edge classification
/// (quadric_region.cpp) and the dimension reduction's section lines (dimension_reduction_ccd.cpp).
/// Eigen only.

#include <Eigen/Core>
#include <Eigen/Geometry>

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

}  // namespace detail
}  // namespace fcl_quadric
