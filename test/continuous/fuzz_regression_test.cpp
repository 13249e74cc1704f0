// Regression tests of the findings of the fuzz targets (docs/reliability.md, section 5).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>

#include "fcl_quadric/continuous/ellipsoid_ccd.h"
#include "support/exact_oracle.h"
#include "support/oracle_margin.h"
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

// fuzz_motion finding 8 (fuzz/findings/fuzz_motion-oracle-overlap-outside-intervals): a constant
// shear of condition number ~6e7 turns a small ellipsoid into a needle ~3,840 long through the
// origin; ellipsoid b moves onto the origin. From t = 0.375 on, the origin (a's centre) is inside
// b, yet the solver certified separation on [0.34, 1]: F(u, t) was built from entries ~1e12
// whose rounding exceeded F itself, and the margins ignored it. The coefficient error bounds
// (MotionMatrix::inverseMagnitudes, ccdFunctionWithMagnitude) now cover the rounding. Oracle: the
// point test of a's centre against b, independent of the CCD.
TEST(FuzzRegression, AnIllConditionedShearIsNotCertifiedSeparateWhileOverlapping) {
  Eigen::Matrix4d M0 = Eigen::Matrix4d::Identity();
  M0(0, 2) = 32.0;
  M0(2, 1) = -7680.0;
  const MotionMatrix shear = MotionMatrix::fromPolynomialMatrix(PolynomialMatrix4(M0));
  ASSERT_FALSE(shear.isRigid());
  const MovingEllipsoid a{Ellipsoid({0.251, 0.501, 1.001}, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()),
                          PiecewiseMotion(shear)};
  Eigen::Isometry3d X0 = Eigen::Isometry3d::Identity();
  X0.linear() = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  X0.translation() = Eigen::Vector3d(0, -3, 0);
  const MovingEllipsoid b{Ellipsoid({2, 3, 2}, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()),
                          PiecewiseMotion(MotionMatrix::fromPoses(X0, Eigen::Isometry3d::Identity()))};
  // Both safeguards, each on its own: the default conditioning limit (this pair's estimate is
  // ~6e19, so it is reported colliding throughout, unresolved), and with the limit lifted the
  // extended-precision check plus Theorem 5.1's sign condition on det A, det B.
  for (double max_condition : {tolerance::kCcdMaxCondition, std::numeric_limits<double>::infinity()})
  for (bool culling : {true, false}) {
    CcdOptions options;
    options.culling = culling;
    options.max_condition = max_condition;
    for (bool swapped : {false, true}) {
      const EllipsoidCcdResult r = swapped ? continuousCollideEllipsoids(b, a, options) : continuousCollideEllipsoids(a, b, options);
      int inside = 0;
      for (int i = 0; i <= 64; ++i) {
        const double t = i / 64.0;
        if (ellipsoidAt(b, t).implicit(Eigen::Vector3d::Zero()) >= -1e-9) continue;  // a's centre not clearly inside b
        ++inside;
        bool covered = false;
        for (const CcdInterval& c : r.collision_intervals) covered = covered || (t >= c.begin && t <= c.end);
        EXPECT_TRUE(covered) << "t = " << t << " culling " << culling << " swapped " << swapped << " limit " << max_condition;
      }
      EXPECT_GT(inside, 30);  // the oracle has something to say
    }
  }
}

// The same failure mode on random data: constant shears of growing condition (up to ~1e9) carry a
// small ellipsoid; a rigid ellipsoid passes through. Wherever the exact oracle (GMP, on the world
// ellipsoids at t, with its margin) clearly sees an overlap, the instant lies in a reported
// collision interval. Before the fix, shears from ~2e3 on were certified separate at overlapping
// instants. Run with the default conditioning limit and with the limit lifted (the extended-
// precision check alone must then decide the pairs the limit would have refused).
void illConditionedShears(double max_condition, int* judged, int* checked, int* fallback) {
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  CcdOptions options;
  options.max_condition = max_condition;
  for (int k = 0; k < 24; ++k) {
    const double shear = std::pow(10.0, 1.0 + 8.0 * (k % 8) / 7.0);
    Eigen::Matrix4d M0 = Eigen::Matrix4d::Identity();
    M0(static_cast<int>(rng() % 3), 0) += 0.001 * U(rng) * shear;
    M0(2, 1) = shear * U(rng);
    M0(0, 2) = 1.0 / std::max(std::abs(U(rng)), 0.1) * 4;
    const MovingEllipsoid a{Ellipsoid(test::randomRadii(rng, 0.1, 1.0), test::randomRotation(rng), Eigen::Vector3d::Zero()),
                            PiecewiseMotion(MotionMatrix::fromPolynomialMatrix(PolynomialMatrix4(M0)))};
    Eigen::Isometry3d X0 = Eigen::Isometry3d::Identity(), X1 = Eigen::Isometry3d::Identity();
    X0.linear() = test::randomRotation(rng);
    X1.linear() = test::randomRotation(rng);
    X0.translation() = Eigen::Vector3d(3 * U(rng), -4, U(rng));
    X1.translation() = Eigen::Vector3d(U(rng), 4 * U(rng), U(rng));
    const MovingEllipsoid b{Ellipsoid(test::randomRadii(rng, 1.0, 3.0), Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()),
                            PiecewiseMotion(MotionMatrix::fromPoses(X0, X1))};
    const EllipsoidCcdResult r = continuousCollideEllipsoids(a, b, options);
    *checked += r.precision_checked && !r.unresolved;
    *fallback += r.unresolved;
    for (int i = 0; i <= 32; ++i) {
      const double t = i / 32.0;
      std::optional<Ellipsoid> ea;
      try {
        ea = ellipsoidAt(a, t);
      } catch (const std::invalid_argument&) {
        continue;  // too ill-conditioned to be an Ellipsoid (documented)
      }
      const Ellipsoid eb = ellipsoidAt(b, t);
      const std::optional<bool> exact = test::clearExactCollision(*ea, eb, std::max(1e-6, 1e3 * test::rigidMargin(*ea, eb)));
      if (!exact || !*exact) continue;
      ++*judged;
      bool covered = false;
      for (const CcdInterval& c : r.collision_intervals) covered = covered || (t >= c.begin && t <= c.end);
      EXPECT_TRUE(covered) << "k " << k << " shear " << shear << " t " << t << " limit " << max_condition;
    }
  }
}

TEST(FuzzRegression, IllConditionedShearsNeverDropAnOverlap) {
  int judged = 0, checked = 0, fallback = 0;
  illConditionedShears(tolerance::kCcdMaxCondition, &judged, &checked, &fallback);
  EXPECT_GT(judged, 40);
  EXPECT_GT(checked, 4);   // decided through the extended-precision check
  EXPECT_GT(fallback, 2);  // beyond the limit: colliding throughout, unresolved
  std::printf("ill-conditioned shears, default limit: %d judged instants, %d precision-checked, %d refused\n", judged,
              checked, fallback);
  int judged_open = 0, checked_open = 0, fallback_open = 0;
  illConditionedShears(std::numeric_limits<double>::infinity(), &judged_open, &checked_open, &fallback_open);
  EXPECT_GT(checked_open, checked);  // the check decides some pairs the limit refused
  std::printf("ill-conditioned shears, no limit: %d judged instants, %d precision-checked, %d unresolved\n", judged_open,
              checked_open, fallback_open);
}
// fuzz_motion (session 4, 500-run check; corpus entry finding11-subnormal-w): w(t) = 5.6e-309, a
// subnormal with no root, passes MotionMatrix validation, but the affine map M / w overflows to
// inf, the centre at t = 0 became inf * 0 = NaN and building the moving quadric threw
// "Polynomial: non-finite coefficient" from inside continuousCollideEllipsoids. Now the pair gets
// the documented conservative answer (colliding throughout, unresolved) with a finite contact
// point, in both argument orders.
TEST(FuzzRegression, AnOverflowingAffineMapGetsTheConservativeAnswer) {
  const double sub = 5.5626846462680035e-309;
  Eigen::Matrix4d M0;
  M0 << 1, 8, 0, 0, 224, sub, sub, sub, sub, sub, sub, sub, 0, 0, 0, sub;
  const MotionMatrix m = MotionMatrix::fromPolynomialMatrix(PolynomialMatrix4(M0));
  const MovingEllipsoid a{Ellipsoid({1e-3, 1e-3, 1e-3}, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()),
                          PiecewiseMotion(m)};
  const MovingEllipsoid b{Ellipsoid({1, 1, 1}, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()), PiecewiseMotion()};
  for (bool swapped : {false, true}) {
    const EllipsoidCcdResult r = swapped ? continuousCollideEllipsoids(b, a) : continuousCollideEllipsoids(a, b);
    EXPECT_TRUE(r.collide);
    EXPECT_TRUE(r.unresolved);
    EXPECT_TRUE(r.contact_point.allFinite());
    ASSERT_EQ(r.collision_intervals.size(), 1u);
    EXPECT_EQ(r.collision_intervals[0].begin, 0.0);
    EXPECT_EQ(r.collision_intervals[0].end, 1.0);
  }
}

// fuzz_motion (session 52, seed 52; corpus entry regression_affine_interpolant_overflow): a
// constant motion whose linear part, M / w, has entries of 2.4e106 and of 1 passes MotionMatrix
// validation. MotionMatrix::linearCondition() formed inf - inf in the cofactors, and std::max
// dropped the NaN: the condition (~1e160) came out small, the motion was not refused, and
// through the affine interpolant (thesis section 5.2) b's end states in a's frame overflowed:
// building a's scaled quadric threw "Polynomial: non-finite coefficient c[0] = -nan" from inside
// continuousCollideEllipsoids. Now the condition (~1.5e159, from scaled cofactors) is far above
// kCcdMaxCondition and the pair gets the documented conservative answer (colliding throughout,
// unresolved), in both argument orders and without a floating-point exception
// (docs/reliability.md finding 42).
TEST(FuzzRegression, AnOverflowingAffineInterpolantGetsTheConservativeAnswer) {
  const double big = -2.9444959457990247e+47, tiny = -1.2260560296460538e-59;
  Eigen::Matrix4d M0;
  M0 << 1, 0, big, big,  //
      big, big, -2.9444574660818194e+47, tiny,  //
      tiny, tiny, tiny, tiny,  //
      0, 0, 0, -1.2260560296460587e-59;
  const MotionMatrix m = MotionMatrix::fromPolynomialMatrix(PolynomialMatrix4(M0));
  const MovingEllipsoid a{Ellipsoid(Eigen::Vector3d::Constant(2.001), Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()),
                          PiecewiseMotion(m)};
  Eigen::Matrix3d R1;
  R1 << 0, 0, 1, 1, 0, 0, 0, 1, 0;
  const MovingEllipsoid b{Ellipsoid(Eigen::Vector3d::Constant(2.0), Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()),
                          PiecewiseMotion(MotionMatrix::fromPoses(Eigen::Matrix3d::Identity(), {0, 0, -1}, R1, {-1, -1, -1}))};
  EXPECT_GT(m.linearCondition(), 1e100);  // ~1.5e159, from the scaled cofactors
  for (int mode = 0; mode < 2; ++mode) {
    CcdOptions options;
    options.interpolation = CcdInterpolation::Affine;
    options.all_intervals = mode == 1;
    options.culling = false;
    for (bool swapped : {false, true}) {
      const EllipsoidCcdResult r =
          swapped ? continuousCollideEllipsoids(b, a, options) : continuousCollideEllipsoids(a, b, options);
      EXPECT_TRUE(r.collide) << mode << swapped;
      EXPECT_TRUE(r.unresolved) << mode << swapped;
      EXPECT_TRUE(r.contact_point.allFinite()) << mode << swapped;
      ASSERT_EQ(r.collision_intervals.size(), 1u) << mode << swapped;
      EXPECT_EQ(r.collision_intervals[0].begin, 0.0);
    }
  }
}

// fuzz_motion (session 52, seed 52; corpus entry regression_last_row_flushed_by_rescaling): a
// motion with coefficients of 1e300 and a subnormal (3, 0) entry was accepted. The last row was
// checked after the rescaling by a power of two (finding 2), which flushed 5e-324 to zero; it
// is checked as given now (docs/reliability.md finding 43), whatever the scale of the rest.
TEST(FuzzRegression, ALastRowEntryIsRejectedWhateverTheScaleOfTheRest) {
  for (const double scale : {1.0, 1e-300, 1e300}) {
    for (const double entry : {5e-324, 1e-310, 1e-20, 1.0}) {
      Eigen::Matrix4d M0 = scale * Eigen::Matrix4d::Identity();
      M0(3, 0) = entry;
      try {
        (void)MotionMatrix::fromPolynomialMatrix(PolynomialMatrix4(M0));
        ADD_FAILURE() << "accepted (3, 0) = " << entry << " beside " << scale;
      } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("(3,0)"), std::string::npos) << e.what();
      }
    }
    // The same matrix with a zero last row is a valid motion (a uniform scaling).
    EXPECT_NO_THROW((void)MotionMatrix::fromPolynomialMatrix(PolynomialMatrix4(Eigen::Matrix4d(scale * Eigen::Matrix4d::Identity()))));
  }
}

}  // namespace
}  // namespace fcl_quadric
