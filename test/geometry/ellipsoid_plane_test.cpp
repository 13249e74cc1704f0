// Ellipsoid vs plane and half-space (Theorem 13, Corollary 14 of the ellipsoid-vs-quadrics seed).
#include <gtest/gtest.h>

#include <random>

#include <Eigen/Eigenvalues>

#include "fcl_quadric/algebra/polynomial_matrix.h"
#include "fcl_quadric/geometry/ellipsoid_plane.h"
#include "support/random_ellipsoids.h"

namespace fcl_quadric {
namespace {

TEST(EllipsoidPlane, CharacteristicPolynomialHasTheRebuiltForm) {
  // det(lambda A - P) computed numerically from the 4x4 matrices has a double root 0 and a
  // quadratic factor proportional to lambda^2 - e lambda + |m|^2/4 (Theorem 13).
  std::mt19937_64 rng(91);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  for (int i = 0; i < 500; ++i) {
    const Ellipsoid e = test::anchorEllipsoid(rng);
    const Eigen::Vector3d n = test::randomUnitVector(rng);
    const double d = u(rng);
    Eigen::Matrix4d P = Eigen::Matrix4d::Zero();
    P.topRightCorner<3, 1>() = 0.5 * n;
    P.bottomLeftCorner<1, 3>() = 0.5 * n.transpose();
    P(3, 3) = -d;
    const Polynomial f = pencilDeterminant(e.quadricMatrix(), P);  // det(lambda A - P)
    const auto q = ellipsoidPlaneQuadratic(e, n, d);
    const double scale = f.maxAbsCoefficient();
    EXPECT_NEAR(f.coefficient(0), 0.0, 1e-10 * scale);
    EXPECT_NEAR(f.coefficient(1), 0.0, 1e-10 * scale);
    // f = -k lambda^2 (q2 lambda^2 + q1 lambda + q0), k > 0.
    const double k = -f.coefficient(4) / q[2];
    ASSERT_GT(k, 0.0);
    EXPECT_NEAR(f.coefficient(3), -k * q[1], 1e-9 * scale);
    EXPECT_NEAR(f.coefficient(2), -k * q[0], 1e-9 * scale);
  }
}

TEST(EllipsoidPlane, RelationAgreesWithSampledSurface) {
  std::mt19937_64 rng(93);
  std::uniform_real_distribution<double> u(-4.0, 4.0);
  const auto dirs = test::fibonacciSphere(4000);
  int counts[4] = {0, 0, 0, 0};
  for (int i = 0; i < 2000; ++i) {
    const Ellipsoid e = test::anchorEllipsoid(rng);
    const Eigen::Vector3d n = test::randomUnitVector(rng);
    const double d = u(rng);
    const EllipsoidPlaneResult r = classifyEllipsoidPlane(e, n, d);
    ++counts[static_cast<int>(r.relation)];
    double lo = 1e300, hi = -1e300;
    for (const auto& v : dirs) {
      const double s = n.dot(e.center() + e.rotation() * v.cwiseProduct(e.radii())) - d;
      lo = std::min(lo, s);
      hi = std::max(hi, s);
    }
    // Sampled extremes lie inside the true ones; the support points are the true ones.
    EXPECT_NEAR(n.dot(r.farthest_negative) - d, r.centre_offset - r.half_width, 1e-12);
    EXPECT_LE(n.dot(r.farthest_negative) - d, lo + 1e-12);
    EXPECT_GE(n.dot(r.farthest_positive) - d, hi - 1e-12);
    switch (r.relation) {
      case PlaneRelation::PositiveSide: EXPECT_GT(lo, 0.0); break;
      case PlaneRelation::NegativeSide: EXPECT_LT(hi, 0.0); break;
      case PlaneRelation::Transversal: EXPECT_TRUE(n.dot(r.farthest_negative) < d && n.dot(r.farthest_positive) > d); break;
      case PlaneRelation::Touching: break;
    }
  }
  EXPECT_GT(counts[0], 200);
  EXPECT_GT(counts[1], 200);
  EXPECT_GT(counts[3], 200);
}

TEST(EllipsoidPlane, ExactTangencyIsTouchingAndNearTangencyIsDecided) {
  const Ellipsoid e({1, 2, 3}, Eigen::Matrix3d::Identity(), {0, 0, 0});
  EXPECT_EQ(classifyEllipsoidPlane(e, {0, 0, 1}, 3.0).relation, PlaneRelation::Touching);
  EXPECT_EQ(classifyEllipsoidPlane(e, {0, 0, 1}, 3.0 * (1 + 1e-9)).relation, PlaneRelation::NegativeSide);
  EXPECT_EQ(classifyEllipsoidPlane(e, {0, 0, 1}, 3.0 * (1 - 1e-9)).relation, PlaneRelation::Transversal);
  EXPECT_EQ(classifyEllipsoidPlane(e, {0, 0, -1}, -3.0 * (1 + 1e-9)).relation, PlaneRelation::PositiveSide);
}

TEST(EllipsoidHalfspace, DepthAndDeepestPoint) {
  const Ellipsoid e({1, 2, 3}, Eigen::Matrix3d::Identity(), {0, 0, 5});
  // Half-space z <= 2.5: lowest point z = 2 -> depth 0.5.
  EllipsoidHalfspaceResult h = ellipsoidHalfspace(e, {0, 0, 1}, 2.5);
  EXPECT_TRUE(h.collide);
  EXPECT_NEAR(h.penetration_depth, 0.5, 1e-15);
  EXPECT_NEAR((h.deepest_point - Eigen::Vector3d(0, 0, 2)).norm(), 0.0, 1e-15);
  h = ellipsoidHalfspace(e, {0, 0, 1}, 1.5);
  EXPECT_FALSE(h.collide);
  EXPECT_NEAR(h.penetration_depth, -0.5, 1e-15);
  EXPECT_TRUE(ellipsoidHalfspace(e, {0, 0, 1}, 2.0).collide);  // exact touching counts
}

TEST(EllipsoidPlane, RejectsBadPlanes) {
  const Ellipsoid e = Ellipsoid::sphere(1.0, {0, 0, 0});
  EXPECT_THROW(classifyEllipsoidPlane(e, {0, 0, 0}, 1.0), std::invalid_argument);
  EXPECT_THROW(classifyEllipsoidPlane(e, {0, std::nan(""), 1}, 1.0), std::invalid_argument);
  EXPECT_THROW(ellipsoidHalfspace(e, {0, 0, 1}, std::numeric_limits<double>::infinity()), std::invalid_argument);
}

}  // namespace
}  // namespace fcl_quadric
