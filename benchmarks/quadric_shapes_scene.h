#pragma once
/// \file quadric_shapes_scene.h
/// Pairs of composite quadric models (issue 5; geometry/quadric_region.h), shared by
/// bench_quadric_shapes.cpp and `fcl_quadric bench` (experiment quadric_shapes):
///  - capped circular cylinders (radius U(0.3, 1), length U(0.6, 2)), the second posed by a
///    random rotation and a translation in [-2, 2]^3 in the first one's frame (std::mt19937_64(7));
///  - CSG: a ring (ellipsoid (1.2, 1.2, 0.6) minus a bore of radius 0.6) against a wedge (capped
///    elliptic cylinder (1.0, 0.7, length 0.8) minus the half-space y > 0 minus a bore of radius
///    0.3), the wedge posed randomly as above (std::mt19937_64(11)).
///  - capped elliptic cylinders (semi-axes U(0.3, 1) each, length U(0.6, 2)), posed as the
///    circular ones (std::mt19937_64(13)), with their polygonal tessellation for mesh peers.
/// No FCL here.

#include <cmath>
#include <cstddef>
#include <random>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "fcl_quadric/algebra/quadric_matrix.h"
#include "sqrt3_tessellation.h"
#include "fcl_quadric/geometry/quadric_region.h"

namespace fcl_quadric {
namespace bench {

/// The capped elliptic cylinder |(x/a, y/b)| <= 1, |z| <= L/2.
inline QuadricRegion cappedCylinderRegion(double a, double b, double L) {
  using Op = QuadricRegion::Op;
  return QuadricRegion::combine(Op::Intersection, {QuadricRegion::atom(quadric::ellipticCylinder(a, b)),
                                                   QuadricRegion::halfspace({0, 0, 1}, 0.5 * L),
                                                   QuadricRegion::halfspace({0, 0, -1}, 0.5 * L)});
}

inline Eigen::Matrix3d quadricSceneRotation(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
  q.normalize();
  return q.toRotationMatrix();
}

struct CylinderPair {
  double r1, L1, r2, L2;
  Eigen::Matrix3d R;  ///< cylinder 2 in cylinder 1's frame (= world; cylinder 1 at the identity)
  Eigen::Vector3d p;
};

inline std::vector<CylinderPair> makeCylinderPairs(std::size_t n) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> r(0.3, 1.0), L(0.6, 2.0), u(-2.0, 2.0);
  std::vector<CylinderPair> pairs;
  for (std::size_t i = 0; i < n; ++i) {
    // Named draws: the order of evaluation of function arguments is unspecified.
    const double r1 = r(rng), L1 = L(rng), r2 = r(rng), L2 = L(rng);
    const Eigen::Matrix3d R = quadricSceneRotation(rng);
    const double x = u(rng), y = u(rng), z = u(rng);
    pairs.push_back({r1, L1, r2, L2, R, Eigen::Vector3d(x, y, z)});
  }
  return pairs;
}

/// The certified relation (the region engine) of capped elliptic cylinders (a1, b1, L1) at the
/// identity and (a2, b2, L2) posed by (R, p).
inline RegionRelation cappedCylindersRelation(double a1, double b1, double L1, double a2, double b2, double L2,
                                              const Eigen::Matrix3d& R, const Eigen::Vector3d& p) {
  const Box3 box1{Eigen::Vector3d(-a1, -b1, -0.5 * L1), Eigen::Vector3d(a1, b1, 0.5 * L1)};
  const Box3 box2{Eigen::Vector3d(-a2, -b2, -0.5 * L2), Eigen::Vector3d(a2, b2, 0.5 * L2)};
  return collideRegions(cappedCylinderRegion(a1, b1, L1), box1, cappedCylinderRegion(a2, b2, L2), box2, R, p).relation;
}

inline RegionRelation cylinderPairRelation(const CylinderPair& c) {
  return cappedCylindersRelation(c.r1, c.r1, c.L1, c.r2, c.r2, c.L2, c.R, c.p);
}

struct EllipticCylinderPair {
  double a1, b1, L1, a2, b2, L2;
  Eigen::Matrix3d R;  ///< cylinder 2 in cylinder 1's frame
  Eigen::Vector3d p;
};

inline std::vector<EllipticCylinderPair> makeEllipticCylinderPairs(std::size_t n) {
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> r(0.3, 1.0), L(0.6, 2.0), u(-2.0, 2.0);
  std::vector<EllipticCylinderPair> pairs;
  for (std::size_t i = 0; i < n; ++i) {
    const double a1 = r(rng), b1 = r(rng), L1 = L(rng), a2 = r(rng), b2 = r(rng), L2 = L(rng);
    const Eigen::Matrix3d R = quadricSceneRotation(rng);
    const double x = u(rng), y = u(rng), z = u(rng);
    pairs.push_back({a1, b1, L1, a2, b2, L2, R, Eigen::Vector3d(x, y, z)});
  }
  return pairs;
}

inline RegionRelation ellipticCylinderPairRelation(const EllipticCylinderPair& c) {
  return cappedCylindersRelation(c.a1, c.b1, c.L1, c.a2, c.b2, c.L2, c.R, c.p);
}

/// The capped elliptic cylinder as the prism over a polygon of k vertices inscribed in its
/// ellipse (what a mesh user would build): 2k vertices, side quads and cap fans as triangles.
inline TriangleMesh ellipticCylinderMesh(double a, double b, double L, int k) {
  TriangleMesh m;
  for (const double z : {-0.5 * L, 0.5 * L}) {
    for (int i = 0; i < k; ++i) {
      const double s = 2.0 * M_PI * i / k;
      m.vertices.emplace_back(a * std::cos(s), b * std::sin(s), z);
    }
  }
  for (int i = 0; i < k; ++i) {
    const int j = (i + 1) % k;
    m.faces.push_back({i, j, k + j});
    m.faces.push_back({i, k + j, k + i});
  }
  for (int i = 1; i + 1 < k; ++i) {
    m.faces.push_back({0, i + 1, i});          // bottom cap, facing -z
    m.faces.push_back({k, k + i, k + i + 1});  // top cap, facing +z
  }
  return m;
}

inline QuadricRegion ringRegion() {
  using Op = QuadricRegion::Op;
  return QuadricRegion::combine(Op::Difference, {QuadricRegion::atom(quadric::ellipsoid({1.2, 1.2, 0.6})),
                                                 QuadricRegion::atom(quadric::ellipticCylinder(0.6, 0.6))});
}

inline QuadricRegion wedgeRegion() {
  using Op = QuadricRegion::Op;
  return QuadricRegion::combine(Op::Difference, {cappedCylinderRegion(1.0, 0.7, 0.8), QuadricRegion::halfspace({0, 1, 0}, 0.0),
                                                 QuadricRegion::atom(quadric::ellipticCylinder(0.3, 0.3))});
}

/// Poses of the wedge in the ring's frame.
inline std::vector<std::pair<Eigen::Matrix3d, Eigen::Vector3d>> makeRingWedgePoses(std::size_t n) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  std::vector<std::pair<Eigen::Matrix3d, Eigen::Vector3d>> poses;
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Matrix3d R = quadricSceneRotation(rng);
    const double x = u(rng), y = u(rng), z = u(rng);
    poses.emplace_back(R, Eigen::Vector3d(x, y, z));
  }
  return poses;
}

}  // namespace bench
}  // namespace fcl_quadric
