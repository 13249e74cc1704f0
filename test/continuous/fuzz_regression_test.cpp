// Regression tests of the findings of the fuzz targets (docs/reliability.md, section 5).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "fcl_quadric/continuous/ellipsoid_ccd.h"
#include "support/random_ellipsoids.h"

namespace fcl_quadric {
namespace {

// fuzz_motion, seed corpus "degree6_huge": a motion matrix with coefficients ~1e300 passed
// MotionMatrix::fromPolynomialMatrix (its determinant overflowed to inf unnoticed) and then
// continuousCollideEllipsoids threw std::invalid_argument ("non-finite coefficient") from deep
// inside. M and s M are the same motion: scaled by 1e300 or 1e-300 the answer must not change.
TEST(FuzzRegression, HugeAndTinyMotionMatricesAreTheSameMotion) {
  std::mt19937_64 rng(300);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  int collisions = 0;
  for (int k = 0; k < 8; ++k) {
    const MotionMatrix base =
        MotionMatrix::fromPoses(test::randomRotation(rng), Eigen::Vector3d(-2.5, U(rng), U(rng)), test::randomRotation(rng),
                                Eigen::Vector3d(2.5, U(rng), U(rng)));
    const MotionMatrix other =
        MotionMatrix::fromPoses(test::randomRotation(rng), Eigen::Vector3d(U(rng), -2.5, 3 * U(rng)), test::randomRotation(rng),
                                Eigen::Vector3d(U(rng), 2.5, 3 * U(rng)));  // some paths miss
    const Ellipsoid body_a(test::randomRadii(rng, 1.0, 4.0), Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
    const Ellipsoid body_b(test::randomRadii(rng, 1.0, 4.0), Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
    const MovingEllipsoid b{body_b, PiecewiseMotion(other)};
    const EllipsoidCcdResult ref = continuousCollideEllipsoids(MovingEllipsoid{body_a, PiecewiseMotion(base)}, b);
    collisions += ref.collide;
    for (double s : {1e300, 1e-300, 3.0}) {
      const MotionMatrix scaled = MotionMatrix::fromPolynomialMatrix(base.matrix() * s);
      EXPECT_TRUE(scaled.evaluate(0.5).isApprox(base.evaluate(0.5), 1e-12)) << "scale " << s;
      const EllipsoidCcdResult r = continuousCollideEllipsoids(MovingEllipsoid{body_a, PiecewiseMotion(scaled)}, b);
      ASSERT_EQ(r.collide, ref.collide) << "k " << k << " scale " << s;
      if (r.collide) {
        EXPECT_NEAR(*r.first_contact_time, *ref.first_contact_time, 1e-9) << "k " << k << " scale " << s;
      }
    }
  }
  EXPECT_GT(collisions, 1);
  EXPECT_LT(collisions, 8);
}

// fuzz_motion: a similarity L(t) = s(t) R(t) with s != w passed the rigidity test (L^T L = sigma I
// only), so the rigid shortcuts took L / w for a rotation and continuousCollideEllipsoids threw
// "ellipsoid rotation is not a rotation". A body scaled by 2 is not rigid and is solved as the
// affine motion it is.
TEST(FuzzRegression, AUniformScalingIsNotRigid) {
  PolynomialMatrix4 M(Eigen::Matrix4d::Identity());
  for (int i = 0; i < 3; ++i) M(i, i) = Polynomial{2.0, 1.0};  // scale 2 + t, w = 1
  M(0, 3) = Polynomial{-3.0, 6.0};                              // x from -3 to 3
  const MotionMatrix m = MotionMatrix::fromPolynomialMatrix(M);
  EXPECT_FALSE(m.isRigid());
  const MovingEllipsoid a{Ellipsoid({1, 1, 1}, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()), PiecewiseMotion(m)};
  // A unit sphere at (0, 3.5, 0): the moving body (radius 2 + t) reaches it only when scaled
  // enough, at t = 1/2 (radius 2.5, centre at the origin: distance 3.5 = 2.5 + 1).
  const MovingEllipsoid b{Ellipsoid({1, 1, 1}, Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 3.5, 0)), PiecewiseMotion()};
  const EllipsoidCcdResult r = continuousCollideEllipsoids(a, b);
  ASSERT_TRUE(r.collide);
  EXPECT_NEAR(*r.first_contact_time, 0.5, 1e-6);
  EXPECT_TRUE(ellipsoidAt(a, 0.5).radii().isApprox(Eigen::Vector3d::Constant(2.5)));
  // A rigid matrix (fromPoses) is still detected as rigid.
  EXPECT_TRUE(MotionMatrix::fromPolynomialMatrix(MotionMatrix::fromPoses(Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(),
                                                                         Eigen::Matrix3d::Identity(), Eigen::Vector3d(1, 0, 0))
                                                     .matrix())
                  .isRigid());
}

}  // namespace
}  // namespace fcl_quadric
