// Numerical stress of the static narrow phase (docs/reliability.md): aspect ratios to 1e-4,
// coordinates to 1e6, near-parallel flat ellipsoids, near-coincident pairs. For every case: no
// NaN, iterations within their caps, one query within the time guard, and the classification
// (direct and through fcl_quadric::collide / distance) agrees with the exact oracle whenever the
// oracle is clear outside the tolerance band (support/oracle_margin.h). Counts are printed as
// "stress: NAME cases=... judged=... disagreements=...".
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <fcl/geometry/shape/ellipsoid.h>

#include "fcl_quadric/fcl/collision.h"
#include "fcl_quadric/fcl/distance.h"
#include "fcl_quadric/geometry/signed_distance.h"
#include "fcl_quadric/tolerances.h"
#include "stress/stress_support.h"
#include "support/oracle_margin.h"
#include "support/random_ellipsoids.h"

namespace fcl_quadric {
namespace {

using test::StressCounts;

/// One pair through every static entry point; updates the counts.
void checkPair(const Ellipsoid& a, const Ellipsoid& b, StressCounts& c, bool through_fcl) {
  ++c.cases;
  const SeparationCertificate ab = c.timed([&] { return classifyEllipsoids(a, b); });
  const SeparationCertificate ba = classifyEllipsoids(b, a);
  EXPECT_EQ(ab.status, ba.status) << c.name << " case " << c.cases;
  // The cap is per Newton search; classifyEllipsoids runs up to three (two in double, one in
  // double-double) and reports their sum.
  EXPECT_LE(ab.iterations, 3 * tolerance::kMaxPencilNewtonIterations);
  EXPECT_FALSE(std::isnan(ab.psi) || ab.witness.hasNaN() || ab.normal.hasNaN()) << c.name << " case " << c.cases;
  const SignedDistanceResult d = c.timed([&] { return signedDistance(a, b); });
  // The cap is per ascent; overlapping pairs ascend from up to 8 seeds (signed_distance.cpp).
  EXPECT_LE(d.iterations, 8 * tolerance::kMaxDistanceNewtonIterations);
  EXPECT_FALSE(std::isnan(d.distance) || d.point_a.hasNaN() || d.point_b.hasNaN() || d.normal.hasNaN())
      << c.name << " case " << c.cases;
  EXPECT_EQ(d.status, ab.status);
  const bool collide = ab.status != Separation::Separated;
  if (through_fcl) {
    fcl::Ellipsoidd ga(a.radii()), gb(b.radii());
    fcl::Transform3d Xa = fcl::Transform3d::Identity(), Xb = fcl::Transform3d::Identity();
    Xa.linear() = a.rotation();
    Xa.translation() = a.center();
    Xb.linear() = b.rotation();
    Xb.translation() = b.center();
    fcl::CollisionRequestd req;
    fcl::CollisionResultd res;
    fcl_quadric::collide(&ga, Xa, &gb, Xb, req, res);
    EXPECT_EQ(res.isCollision(), collide) << c.name << " case " << c.cases;
    fcl::DistanceRequestd dreq(true);
    dreq.enable_signed_distance = true;
    fcl::DistanceResultd dres;
    const double dist = fcl_quadric::distance(&ga, Xa, &gb, Xb, dreq, dres);
    EXPECT_FALSE(std::isnan(dist));
    EXPECT_EQ(dist <= 0, collide) << c.name << " case " << c.cases << ": distance " << dist;
  }
  if (const auto exact = test::clearExactCollision(a, b, test::rigidMargin(a, b))) {
    ++c.judged;
    if (ab.status == Separation::Touching && !*exact) {
      ++c.conservative;  // cannot certify: reported as contact (docs/tolerances.md item 2)
    } else if (*exact != collide) {
      ++c.disagreements;
      ADD_FAILURE() << c.name << " case " << c.cases << ": " << toString(ab.status) << ", oracle clearly "
                    << (*exact ? "collides" : "separate");
    }
  }
}

/// Random pairs with radii log-uniform down to 1e-4 of the largest, centres up to `coord` away
/// from the origin (both ellipsoids near a common far point), gaps around tangency.
void aspectAndCoordinates(int n, std::uint64_t seed, double coord, StressCounts& c) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d base = coord * test::randomUnitVector(rng);
    const Ellipsoid a(test::randomRadii(rng, 1.0, 1e4), test::randomRotation(rng), base);
    const Eigen::Vector3d rb = test::randomRadii(rng, 1.0, 1e4);
    const Eigen::Matrix3d Rb = test::randomRotation(rng);
    const Eigen::Vector3d dir = test::randomUnitVector(rng);
    // Bisect the centre offset along dir to the library's tangency, then step by a relative gap
    // of 10^-k (k in 2..8) to either side: the cases straddle the tolerance band.
    double lo = 0.0, hi = 2.0 * (a.maxRadius() + rb.maxCoeff());
    for (int it = 0; it < 80; ++it) {
      const double mid = 0.5 * (lo + hi);
      if (classifyEllipsoids(a, Ellipsoid(rb, Rb, base + mid * dir)).status == Separation::Separated) hi = mid;
      else lo = mid;
    }
    const double gap = std::pow(10.0, -2.0 - 6.0 * u(rng));
    checkPair(a, Ellipsoid(rb, Rb, base + lo * (1 - gap) * dir), c, i % 4 == 0);
    checkPair(a, Ellipsoid(rb, Rb, base + hi * (1 + gap) * dir), c, i % 4 == 0);
  }
}

TEST(StaticStress, AspectRatio1e4AtTheOrigin) {
  StressCounts c("static-aspect-1e4");
  aspectAndCoordinates(150, 81, 0.0, c);
  EXPECT_GT(c.judged, c.cases / 2);
  EXPECT_EQ(c.disagreements, 0);
}

TEST(StaticStress, AspectRatio1e4AtCoordinates1e6) {
  StressCounts c("static-aspect-1e4-coord-1e6");
  aspectAndCoordinates(150, 82, 1e6, c);
  // At 1e6 with radii down to 1e-4 the rounding band (1e-13 L / r_min) reaches 1e-3: the oracle
  // judges only the wider gaps (about a fifth of the cases).
  EXPECT_GT(c.judged, c.cases / 10);
  EXPECT_EQ(c.disagreements, 0);
}

TEST(StaticStress, LongAspectAndCoordinates) {
  StressCounts c("static-aspect-coord-long");
  for (double coord : {0.0, 1e3, 1e6}) aspectAndCoordinates(3000, 83, coord, c);
  EXPECT_EQ(c.disagreements, 0);
}

/// Two flat ellipsoids (thickness 1e-4 of their width) with nearly parallel planes, stacked at
/// relative gaps around contact and tilted by tiny angles; and sliding edge to edge.
void nearParallel(int n, std::uint64_t seed, StressCounts& c) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < n; ++i) {
    const double t = 1e-4 * (0.5 + u(rng));
    const Eigen::Matrix3d R = test::randomRotation(rng);
    const Eigen::Vector3d p = 100.0 * test::randomUnitVector(rng);
    const Ellipsoid a(Eigen::Vector3d(1.0, 1.0 + u(rng), t), R, p);
    const double tilt = std::pow(10.0, -12.0 + 10.0 * u(rng));
    const Eigen::Matrix3d Rb = R * Eigen::AngleAxisd(tilt, test::randomUnitVector(rng)).toRotationMatrix();
    const double tb = 1e-4 * (0.5 + u(rng));
    const double gap = (u(rng) - 0.5) * std::pow(10.0, -1.0 - 7.0 * u(rng)) * (t + tb);
    const Eigen::Vector3d lateral = R * Eigen::Vector3d(u(rng) - 0.5, u(rng) - 0.5, 0.0);
    const Eigen::Vector3d normal = R.col(2);
    checkPair(a, Ellipsoid(Eigen::Vector3d(1.0 + u(rng), 1.0, tb), Rb, p + lateral + (t + tb + gap) * normal), c,
              i % 4 == 0);
  }
}

TEST(StaticStress, NearParallelFlatEllipsoids) {
  StressCounts c("static-near-parallel");
  nearParallel(200, 84, c);
  EXPECT_GT(c.judged, c.cases / 4);
  EXPECT_EQ(c.disagreements, 0);
}

TEST(StaticStress, LongNearParallelFlatEllipsoids) {
  StressCounts c("static-near-parallel-long");
  nearParallel(5000, 85, c);
  EXPECT_EQ(c.disagreements, 0);
}

/// Coincident and nearly coincident pairs (the same solid, moved by 1e-15 .. 1e-3 of its size,
/// rotated by as little), which always collide; and a copy scaled by (1 + eps) around the same
/// centre (nested solids).
void nearCoincident(int n, std::uint64_t seed, StressCounts& c) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d r = test::randomRadii(rng, 1.0, i % 2 ? 1e4 : 10.0);
    const Eigen::Matrix3d R = test::randomRotation(rng);
    const Eigen::Vector3d p = (i % 3 == 0 ? 1e6 : 1.0) * test::randomUnitVector(rng);
    const Ellipsoid a(r, R, p);
    const double eps = std::pow(10.0, -15.0 + 12.0 * u(rng));
    const Eigen::Matrix3d Rb = R * Eigen::AngleAxisd(eps, test::randomUnitVector(rng)).toRotationMatrix();
    checkPair(a, a, c, i % 4 == 0);
    checkPair(a, Ellipsoid(r, Rb, p + eps * r.minCoeff() * test::randomUnitVector(rng)), c, false);
    checkPair(a, Ellipsoid(r * (1 + eps), R, p), c, false);
    // Identical solids always collide, whatever the margin.
    EXPECT_NE(classifyEllipsoids(a, a).status, Separation::Separated);
  }
}

TEST(StaticStress, NearCoincidentPairs) {
  StressCounts c("static-near-coincident");
  nearCoincident(150, 86, c);
  EXPECT_EQ(c.judged, c.cases);  // coincident solids overlap by their whole volume
  EXPECT_EQ(c.disagreements, 0);
}

TEST(StaticStress, LongNearCoincidentPairs) {
  StressCounts c("static-near-coincident-long");
  nearCoincident(3000, 87, c);
  EXPECT_EQ(c.disagreements, 0);
}

}  // namespace
}  // namespace fcl_quadric
