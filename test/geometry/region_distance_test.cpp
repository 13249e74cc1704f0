// region_distance.h: the distance of non-convex composite quadric models (a ring, a clipped
// one-sheet hyperboloid, a wedge) to convex solids and to each other, against closed forms and
// against an independent oracle: the minimum over a dense parametric sampling of the model's
// boundary (every sample is a point of the model, so that minimum is never below the true
// distance, and is within the sampling step of it). Properties: the certified lower bound never
// exceeds the oracle, the distance never exceeds it by more than the tolerance, the witnesses lie
// on the solids and realise the distance, symmetry and rigid invariance; bad input rejected.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include <Eigen/Geometry>

#include "fcl_quadric/algebra/quadric_matrix.h"
#include "fcl_quadric/geometry/convex_support.h"
#include "fcl_quadric/geometry/region_distance.h"
#include "fcl_quadric/geometry/region_distance_bound.h"
#include "support/expect_invalid.h"
#include "support/random_ellipsoids.h"

namespace fcl_quadric {
namespace {

using Op = QuadricRegion::Op;
const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
const Eigen::Vector3d O = Eigen::Vector3d::Zero();

/// The ring: the ellipsoid (a, a, c) minus the cylinder of radius rho about z.
struct Ring {
  double a = 2.0, c = 1.0, rho = 1.0;
  QuadricRegion region() const {
    return QuadricRegion::combine(Op::Difference, {QuadricRegion::atom(quadric::ellipsoid({a, a, c})),
                                                   QuadricRegion::atom(quadric::ellipticCylinder(rho, rho))});
  }
  Box3 box() const { return Box3{Eigen::Vector3d(-a, -a, -c), Eigen::Vector3d(a, a, c)}; }
  /// Points of the ring's boundary (local frame): the outer ellipsoid outside the bore and the
  /// bore wall inside the ellipsoid, n x n/2 samples each, the rim circles included.
  std::vector<Eigen::Vector3d> boundary(int n) const {
    std::vector<Eigen::Vector3d> out;
    const double phi_rim = std::asin(rho / a), z_rim = c * std::sqrt(1.0 - rho * rho / (a * a));
    for (int i = 0; i < n; ++i) {
      const double th = 2.0 * M_PI * i / n;
      for (int j = 0; j <= n / 2; ++j) {
        const double phi = phi_rim + (M_PI - 2.0 * phi_rim) * j / (n / 2);
        out.emplace_back(a * std::sin(phi) * std::cos(th), a * std::sin(phi) * std::sin(th), c * std::cos(phi));
        out.emplace_back(rho * std::cos(th), rho * std::sin(th), -z_rim + 2.0 * z_rim * j / (n / 2));
      }
    }
    return out;
  }
};

RegionDistanceResult ringToBall(const Ring& ring, const QuadricRegion& region, const Eigen::Matrix3d& R,
                                const Eigen::Vector3d& p, const ConvexSupport& ball, const Eigen::Vector3d& q,
                                double tol = 0.0) {
  return regionDistance(DistanceOperand::ofRegion(region, ring.box(), R, p), DistanceOperand::ofConvex(ball, I, q), tol);
}

TEST(RegionDistance, RingAgainstABallMatchesTheClosedFormsOnTheOuterFaceTheRimAndTheBore) {
  const Ring ring;
  const QuadricRegion region = ring.region();
  const double s = 0.3;
  const ConvexSupport ball = ConvexSupport::ellipsoid(Eigen::Vector3d::Constant(s));
  const double z_rim = std::sqrt(0.75);
  struct Case {
    Eigen::Vector3d q;
    double expected;
  };
  const std::vector<Case> cases = {
      {{3.0, 0.0, 0.0}, 1.0 - s},                                        // outer face, isolated
      {{0.3, 0.0, 0.0}, 1.0 - 0.3 - s},                                  // in the bore, off axis
      {{1.0, 0.0, 1.5}, 1.5 - z_rim - s},                                // straight above the rim
      {{0.0, 0.0, 2.0}, std::hypot(1.0, 2.0 - z_rim) - s},               // on the axis: the rim circle
      {{0.0, 0.0, 0.0}, 1.0 - s},                                        // centred: the bore's circle
  };
  for (const Case& cs : cases) {
    const RegionDistanceResult r = ringToBall(ring, region, I, O, ball, cs.q);
    SCOPED_TRACE(testing::Message() << "ball at " << cs.q.transpose());
    EXPECT_EQ(r.status, RegionDistanceResult::Status::Separated);
    const double tol = tolerance_region_distance::kRegionDistanceRelative * (ring.box().halfWidth().norm() + s + cs.q.norm());
    EXPECT_LE(r.lower_bound, cs.expected + 1e-12);
    EXPECT_GE(r.distance, cs.expected - 1e-12);
    EXPECT_LE(r.distance, cs.expected + (r.converged ? tol : r.distance - r.lower_bound) + 1e-12);
    // Witnesses: on the ball and on the ring's boundary, realising the distance.
    EXPECT_NEAR((r.point_a - r.point_b).norm(), r.distance, 1e-12);
    EXPECT_NEAR((r.point_b - cs.q).norm(), s, 1e-9);
    EXPECT_EQ(region.classifyPoint(r.point_a), 0);
  }
}

TEST(RegionDistance, ClippedOneSheetHyperboloidAgainstABallIsNearestAtTheRim) {
  // {x^2 + y^2 - z^2 <= 1, |z| <= 1}: its waist makes it non-convex. From (3, 0, 0) the profile
  // distance (sqrt(1 + z^2) - 3)^2 + z^2 decreases towards |z| = 1 (its interior minimum would be
  // at |z| = sqrt(1.25)), so the nearest points are the rim points (sqrt 2, 0, +-1).
  const QuadricRegion hyper = QuadricRegion::combine(
      Op::Intersection, {QuadricRegion::atom(quadric::hyperboloidOneSheet(1.0, 1.0, 1.0)),
                         QuadricRegion::halfspace({0, 0, 1}, 1.0), QuadricRegion::halfspace({0, 0, -1}, 1.0)});
  const Box3 box{Eigen::Vector3d(-std::sqrt(2.0), -std::sqrt(2.0), -1.0), Eigen::Vector3d(std::sqrt(2.0), std::sqrt(2.0), 1.0)};
  const double s = 0.25;
  const ConvexSupport ball = ConvexSupport::ellipsoid(Eigen::Vector3d::Constant(s));
  const double expected = std::hypot(3.0 - std::sqrt(2.0), 1.0) - s;
  std::mt19937_64 rng(5);
  for (int k = 0; k < 4; ++k) {
    // The same pair under a common rigid motion.
    const Eigen::Matrix3d R = k == 0 ? I : test::randomRotation(rng);
    const Eigen::Vector3d p = k == 0 ? O : Eigen::Vector3d(k * 10.0, -3.0, 7.0 * k);
    const RegionDistanceResult r = regionDistance(DistanceOperand::ofRegion(hyper, box, R, p),
                                                  DistanceOperand::ofConvex(ball, R, R * Eigen::Vector3d(3, 0, 0) + p));
    EXPECT_TRUE(r.converged) << k;
    EXPECT_NEAR(r.distance, expected, 1e-9) << k;
    EXPECT_LE(r.lower_bound, expected + 1e-12) << k;
    const Eigen::Vector3d local = R.transpose() * (r.point_a - p);
    EXPECT_NEAR(std::fabs(local.z()), 1.0, 1e-6) << k;
    EXPECT_NEAR(local.x(), std::sqrt(2.0), 1e-6) << k;
  }
}

TEST(RegionDistance, RandomRingAndBallPairsNeverExceedTheSampledBoundaryMinimum) {
  const Ring ring;
  const QuadricRegion region = ring.region();
  const std::vector<Eigen::Vector3d> samples = ring.boundary(1200);
  // The sampling step: neighbouring samples are at most this far apart on the boundary, so the
  // sampled minimum is within it of the true distance.
  const double step = 2.0 * M_PI * ring.a / 1200 + M_PI * ring.a / 600;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int separated = 0;
  for (int k = 0; k < 40; ++k) {
    const Eigen::Matrix3d R = test::randomRotation(rng);
    const Eigen::Vector3d p(u(rng) * 50.0, u(rng) * 50.0, u(rng) * 50.0);
    const double s = 0.1 + 0.4 * (0.5 + 0.5 * u(rng));
    // Ball centres around the ring, in its bore and above it.
    const Eigen::Vector3d q_local(u(rng) * 3.0, u(rng) * 3.0, u(rng) * 2.0);
    double oracle = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& x : samples) oracle = std::min(oracle, (x - q_local).norm() - s);
    if (oracle < 0.02 || region.classifyPoint(q_local) >= 0) continue;  // contact cases: static collide's job
    ++separated;
    const ConvexSupport ball = ConvexSupport::ellipsoid(Eigen::Vector3d::Constant(s));
    const RegionDistanceResult r = ringToBall(ring, region, R, p, ball, R * q_local + p);
    SCOPED_TRACE(testing::Message() << "case " << k << " ball at " << q_local.transpose() << " radius " << s);
    const double scale = ring.box().halfWidth().norm() + s + q_local.norm();
    const double tol = tolerance_region_distance::kRegionDistanceRelative * scale;
    EXPECT_EQ(r.status, RegionDistanceResult::Status::Separated);
    EXPECT_LE(r.lower_bound, oracle + 1e-12);                     // certified: never above the truth
    EXPECT_LE(r.distance, oracle + (r.converged ? tol : r.distance - r.lower_bound) + 1e-12);
    EXPECT_GE(r.distance, oracle - step);                          // the oracle is within its step
    EXPECT_NEAR((r.point_a - r.point_b).norm(), r.distance, 1e-12);
    const Eigen::Vector3d a_local = R.transpose() * (r.point_a - p);
    EXPECT_GE(region.classifyPoint(a_local), 0);                   // a point of the ring
    EXPECT_NEAR((r.point_b - (R * q_local + p)).norm(), s, 1e-9);  // on the ball
  }
  EXPECT_GE(separated, 20);
}

TEST(RegionDistance, TwoRingsAgreeBothWaysStayBelowSampledPairsAndAboveTheCertifiedBound) {
  const Ring ring;
  const QuadricRegion region = ring.region();
  const std::vector<Eigen::Vector3d> samples = ring.boundary(60);
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int separated = 0;
  for (int k = 0; k < 12; ++k) {
    const Eigen::Matrix3d R = test::randomRotation(rng);
    const Eigen::Vector3d p = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized() * (3.0 + 2.5 * (0.5 + 0.5 * u(rng)));
    double sampled = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& x : samples)
      for (const Eigen::Vector3d& y : samples) sampled = std::min(sampled, (x - (R * y + p)).norm());
    const Box3 box = ring.box();
    const double bound = regionPairDistanceLowerBound(region, box, region, box, R, p, 10.0);
    if (bound <= 0.0) continue;  // may touch: the static collide decides those
    ++separated;
    const RegionDistanceResult ab =
        regionDistance(DistanceOperand::ofRegion(region, box, I, O), DistanceOperand::ofRegion(region, box, R, p));
    const RegionDistanceResult ba =
        regionDistance(DistanceOperand::ofRegion(region, box, R, p), DistanceOperand::ofRegion(region, box, I, O));
    SCOPED_TRACE(testing::Message() << "case " << k << " offset " << p.transpose());
    const double tol = tolerance_region_distance::kRegionDistanceRelative * (2.0 * box.halfWidth().norm() + p.norm());
    for (const RegionDistanceResult* r : {&ab, &ba}) {
      EXPECT_EQ(r->status, RegionDistanceResult::Status::Separated);
      EXPECT_LE(r->distance, sampled + 1e-12);
      EXPECT_GE(r->distance, bound - 1e-12);  // the grown-region engine's independent bound
      EXPECT_LE(r->lower_bound, r->distance);
      EXPECT_NEAR((r->point_a - r->point_b).norm(), r->distance, 1e-12);
    }
    EXPECT_GE(region.classifyPoint(ab.point_a), 0);
    EXPECT_GE(region.classifyPoint(R.transpose() * (ab.point_b - p)), 0);
    // Both orders bracket the same distance.
    EXPECT_LE(ab.lower_bound, ba.distance + 1e-12);
    EXPECT_LE(ba.lower_bound, ab.distance + 1e-12);
    EXPECT_NEAR(ab.distance, ba.distance, std::max(ab.distance - ab.lower_bound, ba.distance - ba.lower_bound) + tol);
  }
  EXPECT_GE(separated, 4);
}

TEST(RegionDistance, WedgeAgainstABoxAndOverlapsAreContact) {
  // A wedge: the elliptic cylinder (1.5, 1, |z| <= 0.5) minus the half-space y >= 0 minus a
  // circular cylinder of radius 0.5 about z. A unit cube below it, face towards -y.
  const QuadricRegion capped = QuadricRegion::combine(
      Op::Intersection, {QuadricRegion::atom(quadric::ellipticCylinder(1.5, 1.0)), QuadricRegion::halfspace({0, 0, 1}, 0.5),
                         QuadricRegion::halfspace({0, 0, -1}, 0.5)});
  const QuadricRegion wedge = QuadricRegion::combine(
      Op::Difference, {capped, QuadricRegion::halfspace({0, -1, 0}, 0.0), QuadricRegion::atom(quadric::ellipticCylinder(0.5, 0.5))});
  const Box3 box{Eigen::Vector3d(-1.5, -1.0, -0.5), Eigen::Vector3d(1.5, 0.0, 0.5)};
  const ConvexSupport cube = ConvexSupport::box(Eigen::Vector3d::Constant(0.5));
  // Cube centred at (0, -2, 0): its top face y = -1.5 faces the wedge's lowest point (0, -1, z).
  RegionDistanceResult r =
      regionDistance(DistanceOperand::ofRegion(wedge, box, I, O), DistanceOperand::ofConvex(cube, I, {0, -2, 0}));
  EXPECT_NEAR(r.distance, 0.5, 1e-9);
  EXPECT_NEAR(r.point_a.y(), -1.0, 1e-9);
  // A small cube in the hollow the bore leaves (centre (0, -0.2, 0), half side 0.1): its lower
  // corners (+-0.1, -0.3, z) are the farthest from the axis, 0.5 - hypot(0.1, 0.3) from the wall.
  const ConvexSupport small = ConvexSupport::box(Eigen::Vector3d::Constant(0.1));
  r = regionDistance(DistanceOperand::ofRegion(wedge, box, I, O), DistanceOperand::ofConvex(small, I, {0, -0.2, 0}));
  EXPECT_EQ(r.status, RegionDistanceResult::Status::Separated);
  EXPECT_NEAR(r.distance, 0.5 - std::hypot(0.1, 0.3), 1e-9);
  EXPECT_NEAR(std::hypot(r.point_a.x(), r.point_a.y()), 0.5, 1e-9);
  // Overlapping the wedge's material: contact, with witnesses within the tolerance.
  r = regionDistance(DistanceOperand::ofRegion(wedge, box, I, O), DistanceOperand::ofConvex(small, I, {0, -0.7, 0}));
  EXPECT_EQ(r.status, RegionDistanceResult::Status::Contact);
  EXPECT_LE(r.lower_bound, r.distance);
}

TEST(RegionDistance, BadInputIsRejectedNamingTheValue) {
  using test::expectInvalid;
  const Ring ring;
  const QuadricRegion region = ring.region();
  const ConvexSupport ball = ConvexSupport::ellipsoid(Eigen::Vector3d::Constant(0.3));
  const DistanceOperand a = DistanceOperand::ofRegion(region, ring.box(), I, O);
  const DistanceOperand b = DistanceOperand::ofConvex(ball, I, {5, 0, 0});
  expectInvalid([&] { regionDistance(a, b, -1.0); }, "tolerance must be >= 0");
  expectInvalid([&] { regionDistance(a, b, std::nan("")); }, "tolerance must be >= 0");
  DistanceOperand both = a;
  both.convex = &ball;
  expectInvalid([&] { regionDistance(both, b); }, "operand a must be exactly one");
  expectInvalid([&] { regionDistance(a, DistanceOperand{}); }, "operand b must be exactly one");
  DistanceOperand empty = a;
  empty.box = Box3{Eigen::Vector3d::Ones(), Eigen::Vector3d::Zero()};
  expectInvalid([&] { regionDistance(empty, b); }, "a's bounding box is empty");
  DistanceOperand sheared = b;
  sheared.R(0, 1) = 0.5;
  expectInvalid([&] { regionDistance(a, sheared); }, "b rotation");
  DistanceOperand far = b;
  far.p.x() = std::numeric_limits<double>::infinity();
  expectInvalid([&] { regionDistance(a, far); }, "b translation");
}

}  // namespace
}  // namespace fcl_quadric
