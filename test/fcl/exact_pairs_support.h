#pragma once
// Generators of the FCL-layer tests for ellipsoid-plane, ellipsoid-half-space, ellipsoid-box and
// ellipsoid-triangle pairs: random configurations and near-tangent ones, built by placing the
// other solid against a support plane of the ellipsoid and moving it by a relative gap.
#include <cmath>
#include <random>

#include <Eigen/Geometry>
#include <fcl/common/types.h>

#include "fcl_quadric/geometry/ellipsoid.h"
#include "support/random_ellipsoids.h"

namespace fcl_quadric {
namespace test {

inline fcl::Transform3d makePose(const Eigen::Matrix3d& R, const Eigen::Vector3d& p) {
  fcl::Transform3d tf = fcl::Transform3d::Identity();
  tf.linear() = R;
  tf.translation() = p;
  return tf;
}

inline fcl::Transform3d poseOf(const Ellipsoid& e) { return makePose(e.rotation(), e.center()); }

/// A rotation whose column k is the unit vector u (the other two columns random).
inline Eigen::Matrix3d rotationWithColumn(std::mt19937_64& rng, int k, const Eigen::Vector3d& u) {
  Eigen::Vector3d a = randomUnitVector(rng);
  a = (a - a.dot(u) * u).normalized();
  const Eigen::Vector3d b = u.cross(a);
  Eigen::Matrix3d R;
  R.col(k) = u;
  R.col((k + 1) % 3) = a;
  R.col((k + 2) % 3) = b;
  return R;
}

/// An ellipsoid with radii log-uniform in [scale/10, scale], scale in [0.3, 3], centre in a cube.
inline Ellipsoid randomEllipsoid(std::mt19937_64& rng, double centre_spread) {
  std::uniform_real_distribution<double> u(0.0, 1.0), c(-centre_spread, centre_spread);
  const double scale = 0.3 * std::pow(10.0, u(rng));
  return Ellipsoid(randomRadii(rng, scale, 10.0), randomRotation(rng), Eigen::Vector3d(c(rng), c(rng), c(rng)));
}

/// The near-tangent step: the support distance h of e in direction u (from its centre) times the
/// relative gap.
inline double gapStep(const Ellipsoid& e, const Eigen::Vector3d& u, double gap) {
  return gap * (e.support(u) - u.dot(e.center()));
}

struct BoxConfig {
  Eigen::Vector3d side;  ///< full side lengths, as fcl::Box stores them
  Eigen::Matrix3d R;
  Eigen::Vector3d p;
  const char* kind = "random";
  int expected = -1;  ///< near-tangent: 1 overlapping (moved inward), 0 separate, -1 unknown
};

inline BoxConfig randomBox(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> s(0.3, 3.0), c(-3.0, 3.0);
  return BoxConfig{Eigen::Vector3d(s(rng), s(rng), s(rng)), randomRotation(rng), Eigen::Vector3d(c(rng), c(rng), c(rng))};
}

/// A box outside e touching it at x0 = supportPoint(u) with a face (kind 0), an edge (1) or a
/// vertex (2), then moved along u by `signed_gap` (relative to the support distance): < 0 makes
/// them overlap, > 0 separates them.
inline BoxConfig tangentBox(std::mt19937_64& rng, const Ellipsoid& e, int kind, double signed_gap) {
  std::uniform_real_distribution<double> s(0.3, 3.0), f(-0.8, 0.8), ang(0.2, M_PI / 2 - 0.2);
  const Eigen::Vector3d u = randomUnitVector(rng);
  const Eigen::Vector3d x0 = e.supportPoint(u) + gapStep(e, u, std::fabs(signed_gap)) * (signed_gap < 0 ? -u : u);
  BoxConfig b;
  b.side = Eigen::Vector3d(s(rng), s(rng), s(rng));
  const Eigen::Vector3d h = 0.5 * b.side;
  if (kind == 0) {
    // Face with outward normal -u through x0, x0 inside the face.
    const int k = static_cast<int>(rng() % 3);
    b.R = rotationWithColumn(rng, k, u);
    Eigen::Vector3d s_local = Eigen::Vector3d(f(rng) * h[0], f(rng) * h[1], f(rng) * h[2]);
    s_local[k] = -h[k];  // on the face facing -u
    b.p = x0 - b.R * s_local;
    b.kind = "near-tangent face";
  } else if (kind == 1) {
    // Edge along axis k, orthogonal to u; the other two axes at an angle to u.
    const int k = static_cast<int>(rng() % 3);
    Eigen::Vector3d a = randomUnitVector(rng);
    a = (a - a.dot(u) * u).normalized();  // edge direction
    const Eigen::Vector3d w = u.cross(a);  // (a, w, u) orthonormal
    const double t = ang(rng);
    const Eigen::Vector3d b1 = std::cos(t) * u + std::sin(t) * w, b2 = a.cross(b1);
    b.R.col(k) = a;
    b.R.col((k + 1) % 3) = b1;
    b.R.col((k + 2) % 3) = b2;
    Eigen::Vector3d s_local;
    for (int j = 0; j < 3; ++j) s_local[j] = -(u.dot(b.R.col(j)) > 0 ? 1.0 : -1.0) * h[j];
    s_local[k] = f(rng) * h[k];
    b.p = x0 - b.R * s_local;
    b.kind = "near-tangent edge";
  } else {
    // The vertex of the box lowest along u at x0.
    b.R = randomRotation(rng);
    Eigen::Vector3d s_local;
    for (int j = 0; j < 3; ++j) s_local[j] = -(u.dot(b.R.col(j)) > 0 ? 1.0 : -1.0) * h[j];
    b.p = x0 - b.R * s_local;
    b.kind = "near-tangent vertex";
  }
  b.expected = signed_gap < 0 ? 1 : 0;
  return b;
}

struct TriangleConfig {
  Eigen::Vector3d a, b, c;
  const char* kind = "random";
  int expected = -1;
};

inline TriangleConfig randomTriangle(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> c(-3.0, 3.0), r(0.3, 2.5);
  const Eigen::Vector3d centre(c(rng), c(rng), c(rng));
  TriangleConfig t;
  t.a = centre + r(rng) * randomUnitVector(rng);
  t.b = centre + r(rng) * randomUnitVector(rng);
  t.c = centre + r(rng) * randomUnitVector(rng);
  return t;
}

/// A triangle outside e touching it at x0 = supportPoint(u) with its face (kind 0), an edge (1)
/// or a vertex (2), moved along u by `signed_gap` as tangentBox.
inline TriangleConfig tangentTriangle(std::mt19937_64& rng, const Ellipsoid& e, int kind, double signed_gap) {
  std::uniform_real_distribution<double> r(0.3, 2.5), up(0.1, 2.0), ang(0.0, 2 * M_PI), bary(0.15, 1.0);
  const Eigen::Vector3d u = randomUnitVector(rng);
  const Eigen::Vector3d x0 = e.supportPoint(u) + gapStep(e, u, std::fabs(signed_gap)) * (signed_gap < 0 ? -u : u);
  Eigen::Vector3d a = randomUnitVector(rng);
  a = (a - a.dot(u) * u).normalized();
  const Eigen::Vector3d w = u.cross(a);
  auto inPlane = [&](double angle, double radius) { return radius * (std::cos(angle) * a + std::sin(angle) * w); };
  TriangleConfig t;
  if (kind == 0) {
    // x0 strictly inside: vertices at random barycentric weights around it.
    const double l0 = bary(rng), l1 = bary(rng), l2 = bary(rng), sum = l0 + l1 + l2;
    const Eigen::Vector3d d1 = inPlane(ang(rng), r(rng)), d2 = inPlane(ang(rng), r(rng));
    // x0 = (l0 A + l1 B + l2 C) / sum with B = A + d1, C = A + d2.
    t.a = x0 - (l1 * d1 + l2 * d2) / sum;
    t.b = t.a + d1;
    t.c = t.a + d2;
    // A degenerate pair (d1 parallel to d2) would put x0 on a segment; still tangent, fine.
    t.kind = "near-tangent face";
  } else if (kind == 1) {
    const Eigen::Vector3d d = inPlane(ang(rng), 1.0);
    const double s = std::uniform_real_distribution<double>(0.15, 0.85)(rng), len = r(rng);
    t.a = x0 - s * len * d;
    t.b = x0 + (1 - s) * len * d;
    t.c = x0 + inPlane(ang(rng), r(rng)) + up(rng) * u;
    t.kind = "near-tangent edge";
  } else {
    t.a = x0;
    t.b = x0 + inPlane(ang(rng), r(rng)) + up(rng) * u;
    t.c = x0 + inPlane(ang(rng), r(rng)) + up(rng) * u;
    t.kind = "near-tangent vertex";
  }
  t.expected = signed_gap < 0 ? 1 : 0;
  return t;
}

}  // namespace test
}  // namespace fcl_quadric
