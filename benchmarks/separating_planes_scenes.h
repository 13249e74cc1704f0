#pragma once
/// \file separating_planes_scenes.h
/// The two set-ups of Wang et al. 2004 §5 (separating planes for moving ellipsoids), shared by
/// bench_separating_planes.cpp and `fcl_quadric bench` (experiment separating_planes):
///  Table 1: two ellipsoids with half-axes (3, 3, 5), centres 8 apart, each rotating about its own
///    random axis by omega rad per frame (rotatingFrames()).
///  Table 2: a unit sphere orbiting the ellipsoid (4.5, 4, 2) in the plane of its two longest
///    axes, orbit radius 5.49, 0.01 rad per frame, 13,746 frames; the narrow phase runs only where
///    the axis-aligned boxes overlap (orbitCentre(), orbitBoxesOverlap()).
/// No FCL here: the peers convert the poses themselves.

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "fcl_quadric/geometry/ellipsoid.h"
#include "random_rotations.h"

namespace fcl_quadric {
namespace bench {

constexpr int kTable1Frames = 10000;
constexpr std::uint64_t kTable1FirstSeed = 2004;
constexpr double kTable1Omegas[] = {0.1, 0.5, 1.0};

constexpr int kTable2Frames = 13746;
constexpr double kOrbitRadius = 5.49;
constexpr double kOrbitStep = 0.01;  // rad per frame

/// The frames of one Table 1 sequence.
struct RotatingFrames {
  std::vector<Ellipsoid> a, b;
};

/// Seed -> initial orientations R_A0, R_B0 (uniform), then axes u_A, u_B (uniform); frame k has
/// R_A = AngleAxis(k omega, u_A) R_A0, R_B = AngleAxis(k omega, u_B) R_B0, p_A = 0, p_B = (8,0,0).
inline RotatingFrames rotatingFrames(double omega, std::uint64_t seed, int frames = kTable1Frames) {
  RotatingFrames s;
  std::mt19937_64 rng(seed);
  const Eigen::Matrix3d R_A0 = randomRotation(rng), R_B0 = randomRotation(rng);
  const Eigen::Vector3d axis_a = randomUnitVector(rng), axis_b = randomUnitVector(rng);
  const Eigen::Vector3d radii(3.0, 3.0, 5.0), p_WA(0.0, 0.0, 0.0), p_WB(8.0, 0.0, 0.0);
  s.a.reserve(static_cast<std::size_t>(frames));
  s.b.reserve(static_cast<std::size_t>(frames));
  for (int k = 0; k < frames; ++k) {
    const double angle = omega * k;
    s.a.emplace_back(radii, Eigen::AngleAxisd(angle, axis_a).toRotationMatrix() * R_A0, p_WA);
    s.b.emplace_back(radii, Eigen::AngleAxisd(angle, axis_b).toRotationMatrix() * R_B0, p_WB);
  }
  return s;
}

/// The orbited ellipsoid of Table 2 (axis-aligned at the origin).
inline Ellipsoid orbitEllipsoid() {
  return Ellipsoid(Eigen::Vector3d(4.5, 4.0, 2.0), Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
}

/// Centre of the unit sphere at frame k.
inline Eigen::Vector3d orbitCentre(int k) {
  const double t = kOrbitStep * k;
  return Eigen::Vector3d(kOrbitRadius * std::cos(t), kOrbitRadius * std::sin(t), 0.0);
}

/// The paper's box test: the unit sphere's box at p overlaps the orbited ellipsoid's box.
inline bool orbitBoxesOverlap(const Eigen::Vector3d& p) {
  const Eigen::Vector3d half_b = orbitEllipsoid().radii();
  return (p.cwiseAbs().array() <= half_b.array() + 1.0).all();
}

}  // namespace bench
}  // namespace fcl_quadric
