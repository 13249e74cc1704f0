// Signed distance between ellipsoids: optimality conditions, closed forms, independent oracles.
#include <gtest/gtest.h>

#include <random>

#include "fcl_quadric/geometry/signed_distance.h"
#include "support/exact_oracle.h"
#include "support/random_ellipsoids.h"

namespace fcl_quadric {
namespace {

/// Independent oracle: signed distance from a point to an ellipsoid surface (negative inside),
/// by bisection in long double on the Lagrange multiplier t of the closest point
/// x_i = y_i e_i^2 / (e_i^2 + t) (Eberly's formulation), body frame.
long double pointEllipsoidSignedDistance(const Ellipsoid& e, const Eigen::Vector3d& p) {
  const Eigen::Vector3d yd = e.rotation().transpose() * (p - e.center());
  long double y[3], r[3];
  for (int i = 0; i < 3; ++i) {
    y[i] = yd[i];
    r[i] = e.radii()[i];
  }
  auto g = [&](long double t) {
    long double s = 0;
    for (int i = 0; i < 3; ++i) {
      const long double q = r[i] * y[i] / (r[i] * r[i] + t);
      s += q * q;
    }
    return s - 1;
  };
  long double rmin2 = std::min({r[0] * r[0], r[1] * r[1], r[2] * r[2]});
  long double lo = -rmin2, hi = 1;
  while (g(hi) > 0) hi *= 2;
  for (int it = 0; it < 200; ++it) {
    const long double mid = 0.5L * (lo + hi);
    (g(mid) > 0 ? lo : hi) = mid;
  }
  long double d2 = 0;
  for (int i = 0; i < 3; ++i) {
    const long double x = y[i] * r[i] * r[i] / (r[i] * r[i] + hi);
    d2 += (x - y[i]) * (x - y[i]);
  }
  const long double d = std::sqrt(d2);
  return e.implicit(p) < 0 ? -d : d;
}

TEST(SignedDistance, SphereSphereMatchesClosedForm) {
  std::mt19937_64 rng(61);
  std::uniform_real_distribution<double> u(0.2, 3.0);
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector3d c1 = 3 * test::randomUnitVector(rng) * u(rng), c2 = 3 * test::randomUnitVector(rng) * u(rng);
    const double r1 = u(rng), r2 = u(rng);
    const SignedDistanceResult d = signedDistance(Ellipsoid::sphere(r1, c1), Ellipsoid::sphere(r2, c2));
    const double expected = (c2 - c1).norm() - r1 - r2;
    ASSERT_NEAR(d.distance, expected, 1e-12 * (1 + std::fabs(expected))) << i;
    ASSERT_NEAR(d.normal.dot((c2 - c1).normalized()), 1.0, 1e-10);
  }
}

TEST(SignedDistance, SphereEllipsoidMatchesPointDistanceOracle) {
  std::mt19937_64 rng(63);
  std::uniform_real_distribution<double> u(-4.0, 4.0), ur(0.5, 3.0);
  int overlapping = 0;
  for (int i = 0; i < 3000; ++i) {
    const Ellipsoid e(test::randomRadii(rng, 3.0, 20.0), test::randomRotation(rng), {u(rng), u(rng), u(rng)});
    const Eigen::Vector3d c(u(rng), u(rng), u(rng));
    const double r = ur(rng);
    const double expected = static_cast<double>(pointEllipsoidSignedDistance(e, c) - r);
    const SignedDistanceResult d = signedDistance(e, Ellipsoid::sphere(r, c));
    overlapping += expected < 0;
    ASSERT_NEAR(d.distance, expected, 1e-10 * (1 + std::fabs(expected))) << "case " << i;
  }
  EXPECT_GT(overlapping, 300);
}

TEST(SignedDistance, SeparatedPairsSatisfyTheOptimalityConditions) {
  // For convex bodies these KKT conditions certify the global minimum distance.
  std::mt19937_64 rng(65);
  int separated = 0;
  for (int i = 0; i < 20000 && separated < 5000; ++i) {
    const Ellipsoid a = test::anchorEllipsoid(rng), b = test::anchorEllipsoid(rng);
    const SignedDistanceResult d = signedDistance(a, b);
    if (d.status != Separation::Separated) continue;
    ++separated;
    ASSERT_GT(d.distance, 0.0);
    EXPECT_TRUE(d.converged);
    ASSERT_NEAR(a.implicit(d.point_a), 0.0, 1e-12);
    ASSERT_NEAR(b.implicit(d.point_b), 0.0, 1e-12);
    ASSERT_NEAR((d.point_b - d.point_a).norm(), d.distance, 1e-12 * (1 + d.distance));
    ASSERT_NEAR((d.point_b - d.point_a - d.distance * d.normal).norm(), 0.0, 1e-9);
    ASSERT_NEAR(a.normalAt(d.point_a).dot(d.normal), 1.0, 1e-12);
    ASSERT_NEAR(b.normalAt(d.point_b).dot(-d.normal), 1.0, 1e-12);
  }
  EXPECT_EQ(separated, 5000);
}

/// -distance = min over unit n of h_a(n) + h_b(-n) (support function of the Minkowski difference).
/// Dense sampling of 20,000 directions gives an upper bound of the true minimum: the library's
/// value must not exceed it (else it stopped in a worse local optimum), and must be attained at its
/// own normal. `aspect` = largest axis ratio of the random ellipsoids.
void checkPenetrationDepth(int wanted, std::uint64_t seed, double aspect) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uc(-2.0, 2.0);
  const std::vector<Eigen::Vector3d> dirs = test::fibonacciSphere(20000);
  int overlapping = 0, worse = 0;
  for (int i = 0; i < 50 * wanted && overlapping < wanted; ++i) {
    auto make = [&] {
      return aspect <= 6.0 ? test::anchorEllipsoid(rng)
                           : Ellipsoid(test::randomRadii(rng, 2.0, aspect), test::randomRotation(rng),
                                       Eigen::Vector3d(uc(rng), uc(rng), uc(rng)));
    };
    const Ellipsoid a = make(), b = make();
    const SignedDistanceResult d = signedDistance(a, b);
    if (d.status != Separation::Overlapping) continue;
    ++overlapping;
    auto hK = [&](const Eigen::Vector3d& n) { return a.support(n) + b.support(-n); };
    double sampled = std::numeric_limits<double>::infinity();
    for (const auto& n : dirs) sampled = std::min(sampled, hK(n));
    ASSERT_LT(d.distance, 0.0);
    if (-d.distance > sampled + 1e-12) {
      ++worse;
      ADD_FAILURE() << "case " << i << ": depth " << -d.distance << " but direction sampling finds " << sampled;
    }
    ASSERT_NEAR(hK(d.normal), -d.distance, 1e-12 * (1 - d.distance));
    // Translating b by -distance * normal makes the pair touch.
    const Ellipsoid moved(b.radii(), b.rotation(), b.center() - d.distance * d.normal);
    EXPECT_LT(std::fabs(classifyEllipsoids(a, moved).psi), 1e-8);
  }
  EXPECT_EQ(overlapping, wanted);
  EXPECT_EQ(worse, 0);
}

TEST(SignedDistance, PenetrationDepthIsAtLeastAsGoodAsDenseSampling) { checkPenetrationDepth(2000, 67, 6.0); }
TEST(SignedDistance, PenetrationDepthOfElongatedPairsIsAtLeastAsGoodAsDenseSampling) {
  checkPenetrationDepth(500, 68, 20.0);
}
TEST(SignedDistance, LongPenetrationDepthSweep) {
  checkPenetrationDepth(20000, 69, 6.0);
  checkPenetrationDepth(5000, 70, 20.0);
}

TEST(SignedDistance, SignAgreesWithTheExactClassificationAndIsSymmetric) {
  std::mt19937_64 rng(69);
  for (int i = 0; i < 5000; ++i) {
    const Ellipsoid a = test::anchorEllipsoid(rng), b = test::anchorEllipsoid(rng);
    const SignedDistanceResult ab = signedDistance(a, b), ba = signedDistance(b, a);
    const Separation truth = test::exactClassify(a, b);
    ASSERT_EQ(ab.status, truth);
    ASSERT_EQ(ab.distance > 0, truth == Separation::Separated);
    ASSERT_NEAR(ab.distance, ba.distance, 1e-10 * (1 + std::fabs(ab.distance)));
    ASSERT_NEAR(ab.normal.dot(ba.normal), -1.0, 1e-6);
  }
}

TEST(SignedDistance, IsInvariantUnderRigidMotion) {
  std::mt19937_64 rng(71);
  std::uniform_real_distribution<double> u(-100.0, 100.0);
  for (int i = 0; i < 2000; ++i) {
    const Ellipsoid a = test::anchorEllipsoid(rng), b = test::anchorEllipsoid(rng);
    const Eigen::Matrix3d R = test::randomRotation(rng);
    const Eigen::Vector3d t(u(rng), u(rng), u(rng));
    auto move = [&](const Ellipsoid& e) { return Ellipsoid(e.radii(), R * e.rotation(), R * e.center() + t); };
    const SignedDistanceResult d1 = signedDistance(a, b), d2 = signedDistance(move(a), move(b));
    ASSERT_NEAR(d1.distance, d2.distance, 1e-9 * (1 + std::fabs(d1.distance))) << i;
  }
}

TEST(SignedDistance, NearTangentDistanceIsTinyWithTheRightSign) {
  std::mt19937_64 rng(73);
  for (int k = 0; k < 200; ++k) {
    const Ellipsoid a(test::randomRadii(rng, 1.0, 10.0), test::randomRotation(rng), Eigen::Vector3d::Zero());
    const Eigen::Vector3d rb = test::randomRadii(rng, 1.0, 10.0);
    const Eigen::Matrix3d Rb = test::randomRotation(rng);
    const Eigen::Vector3d dir = test::randomUnitVector(rng);
    double lo = 0, hi = 40;
    for (int it = 0; it < 100; ++it) {
      const double mid = 0.5 * (lo + hi);
      (test::exactClassify(a, Ellipsoid(rb, Rb, mid * dir)) == Separation::Separated ? hi : lo) = mid;
    }
    for (double gap : {1e-6, 1e-9}) {
      const SignedDistanceResult out = signedDistance(a, Ellipsoid(rb, Rb, hi * (1 + gap) * dir));
      const SignedDistanceResult in = signedDistance(a, Ellipsoid(rb, Rb, lo * (1 - gap) * dir));
      ASSERT_GT(out.distance, 0.0);
      ASSERT_LT(in.distance, 0.0);
      // The distance along dir is at most the offset moved.
      ASSERT_LE(out.distance, hi * gap * 1.0000001 + 1e-15);
      ASSERT_LE(-in.distance, lo * gap * 1.0000001 + 1e-15);
    }
  }
}

}  // namespace
}  // namespace fcl_quadric
