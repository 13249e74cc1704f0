// Ellipsoid vs capsule: segment-plus-ball identities, dense sampling and tangency constructions.
#include <gtest/gtest.h>

#include <random>

#include "fcl_quadric/geometry/ellipsoid_capsule.h"
#include "fcl_quadric/geometry/point_ellipsoid.h"
#include "support/random_ellipsoids.h"

namespace fcl_quadric {
namespace {

TEST(EllipsoidCapsule, DistanceIsTheSegmentDistanceMinusTheRadiusAndBeatsSampling) {
  std::mt19937_64 rng(131);
  std::uniform_real_distribution<double> u(-3.0, 3.0), ur(0.05, 1.0), ul(0.0, 3.0);
  int counts[3] = {0, 0, 0};
  for (int i = 0; i < 1000; ++i) {
    const Ellipsoid e = test::anchorEllipsoid(rng);
    const double r = ur(rng), L = ul(rng);
    const Eigen::Matrix3d R = test::randomRotation(rng);
    const Eigen::Vector3d p(u(rng), u(rng), u(rng));
    const SignedDistanceResult d = signedDistanceEllipsoidCapsule(e, r, L, R, p);
    ++counts[static_cast<int>(d.status)];
    // Primal upper bound: distance from sampled axis points to the ellipsoid, minus r.
    double sampled = 1e300;
    for (int k = 0; k <= 400; ++k) {
      const Eigen::Vector3d q = p + R.col(2) * (L * (k / 400.0 - 0.5));
      sampled = std::min(sampled, closestPointOnEllipsoid(e, q).signed_distance - r);
    }
    if (d.status == Separation::Touching) continue;
    ASSERT_EQ(d.distance > 0, d.status == Separation::Separated);
    if (d.status == Separation::Separated) {
      ASSERT_LE(d.distance, sampled + 1e-12) << "case " << i;
      ASSERT_GE(d.distance, sampled - 1e-3) << "case " << i;  // sampling resolution
      ASSERT_NEAR((d.point_b - d.point_a).norm(), d.distance, 1e-10 * (1 + d.distance));
    } else {
      ASSERT_LT(sampled, 1e-12) << "case " << i;  // some axis point is within r of the ellipsoid
    }
    ASSERT_NEAR(e.implicit(d.point_a), 0.0, 1e-12);
  }
  EXPECT_GT(counts[0], 100);
  EXPECT_GT(counts[2], 100);
}

TEST(EllipsoidCapsule, TangencyConstructionsAndBadInput) {
  const Ellipsoid e({1, 2, 3}, Eigen::Matrix3d::Identity(), {0, 0, 0});
  // Capsule axis along y (rotate z to y), at x = 1 + r: touching the ellipsoid's x extreme.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const double r = 0.5;
  EXPECT_EQ(signedDistanceEllipsoidCapsule(e, r, 1.0, R, {1.5, 0, 0}).status, Separation::Touching);
  EXPECT_EQ(signedDistanceEllipsoidCapsule(e, r, 1.0, R, {1.5 * (1 + 1e-9), 0, 0}).status, Separation::Separated);
  EXPECT_EQ(signedDistanceEllipsoidCapsule(e, r, 1.0, R, {1.5 * (1 - 1e-9), 0, 0}).status, Separation::Overlapping);
  EXPECT_NEAR(signedDistanceEllipsoidCapsule(e, r, 1.0, R, {3.0, 0, 0}).distance, 1.5, 1e-14);
  EXPECT_THROW(signedDistanceEllipsoidCapsule(e, -1.0, 1.0, R, {3, 0, 0}), std::invalid_argument);
  EXPECT_THROW(signedDistanceEllipsoidCapsule(e, 1.0, std::nan(""), R, {3, 0, 0}), std::invalid_argument);
}

}  // namespace
}  // namespace fcl_quadric
