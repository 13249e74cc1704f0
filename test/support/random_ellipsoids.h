#pragma once
// Seeded generators of ellipsoid pairs shared by the tests (std::mt19937_64, fixed seeds).
#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "fcl_quadric/geometry/ellipsoid.h"

namespace fcl_quadric {
namespace test {

inline Eigen::Matrix3d randomRotation(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  // Named draws in the order gcc evaluates the arguments (right to left): the order is
  // unspecified, and the clang sanitizer build must draw the same cases as the Release build.
  const double z = n(rng), y = n(rng), x = n(rng), w = n(rng);
  Eigen::Quaterniond q(w, x, y, z);
  q.normalize();
  return q.toRotationMatrix();
}

/// Radii with aspect ratio down to 1:max_aspect: log-uniform in [scale/max_aspect, scale].
inline Eigen::Vector3d randomRadii(std::mt19937_64& rng, double scale, double max_aspect) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Eigen::Vector3d r;
  for (int i = 0; i < 3; ++i) r[i] = scale * std::pow(max_aspect, -u(rng));
  return r;
}

inline Eigen::Vector3d randomUnitVector(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  const double z = n(rng), y = n(rng), x = n(rng);  // gcc's order, as in randomRotation
  Eigen::Vector3d v(x, y, z);
  return v.normalized();
}

/// n directions of a Fibonacci lattice on the unit sphere (near-uniform, deterministic).
inline std::vector<Eigen::Vector3d> fibonacciSphere(int n) {
  std::vector<Eigen::Vector3d> dirs;
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / n, r = std::sqrt(1.0 - z * z);
    dirs.emplace_back(r * std::cos(golden * i), r * std::sin(golden * i), z);
  }
  return dirs;
}

/// The ANCHORS.md generator: radii 3x U(0.5,3), centre 3x U(-3,3), quaternion from 4x N(0,1).
inline Ellipsoid anchorEllipsoid(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> ur(0.5, 3.0), uc(-3.0, 3.0);
  Eigen::Vector3d r;
  for (int i = 0; i < 3; ++i) r[i] = ur(rng);
  Eigen::Vector3d c;
  for (int i = 0; i < 3; ++i) c[i] = uc(rng);
  return Ellipsoid(r, randomRotation(rng), c);
}

}  // namespace test
}  // namespace fcl_quadric
