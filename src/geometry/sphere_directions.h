#pragma once
/// \file sphere_directions.h
/// Unit-sphere helpers of the Riemannian Newton ascents over directions (signed distance,
/// ellipsoid-cylinder): a tangent frame at a direction, and a Fibonacci lattice of seed
/// directions. Internal (src/); Eigen's core only.

#include <array>
#include <cmath>

#include <Eigen/Core>

namespace fcl_quadric::detail {

/// e1, e2 with (e1, e2, n) a right-handed orthonormal frame, for a unit vector n. The helper axis
/// is x unless n is within about 53 degrees of it, so e1 never comes from a near-parallel pair.
inline void tangentBasis(const Eigen::Vector3d& n, Eigen::Vector3d* e1, Eigen::Vector3d* e2) {
  const Eigen::Vector3d helper = std::fabs(n.x()) < 0.6 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  *e1 = (helper - helper.dot(n) * n).normalized();
  *e2 = n.cross(*e1);
}

/// N nearly uniform unit directions: the Fibonacci (golden-angle) lattice, z_i = 1 - (2i + 1)/N.
template <int N>
std::array<Eigen::Vector3d, N> fibonacciLattice() {
  std::array<Eigen::Vector3d, N> g;
  const double golden = 3.14159265358979323846 * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < N; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / N, r = std::sqrt(1.0 - z * z);
    g[i] = Eigen::Vector3d(r * std::cos(golden * i), r * std::sin(golden * i), z);
  }
  return g;
}

}  // namespace fcl_quadric::detail
