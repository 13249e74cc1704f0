#pragma once
/// \file random_rotations.h
/// Uniform random rotations and directions from a std::mt19937_64, as every benchmark scene draws
/// them (normalised Gaussian quaternion / vector; a distribution per call, so the stream does not
/// depend on a cached normal).

#include <random>

#include <Eigen/Geometry>

namespace fcl_quadric {
namespace bench {

inline Eigen::Matrix3d randomRotation(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  const double w = n(rng), x = n(rng), y = n(rng), z = n(rng);
  return Eigen::Quaterniond(w, x, y, z).normalized().toRotationMatrix();
}

inline Eigen::Vector3d randomUnitVector(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  const double x = n(rng), y = n(rng), z = n(rng);
  return Eigen::Vector3d(x, y, z).normalized();
}

}  // namespace bench
}  // namespace fcl_quadric
