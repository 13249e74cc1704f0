// region_distance_bound.h: ellipsoidRegionDistanceLowerBound and regionConvexDistanceLowerBound
// never above the true distance (spheres and cubes against a capped cylinder, where the distance
// is known in closed form; random ellipsoids against a CSG ring, bounded above by the distance to
// certified interior points), close to it where the scaled solid is exactly the
// delta-neighbourhood (a sphere; a cube seen face-on), 0 on contact, cap far away, bad input
// rejected.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "fcl_quadric/algebra/quadric_matrix.h"
#include "fcl_quadric/geometry/region_distance_bound.h"
#include "fcl_quadric/geometry/point_ellipsoid.h"
#include "support/random_ellipsoids.h"

namespace fcl_quadric {
namespace {

using Op = QuadricRegion::Op;

QuadricRegion cappedCylinder(double r, double L) {
  return QuadricRegion::combine(Op::Intersection, {QuadricRegion::atom(quadric::ellipticCylinder(r, r)),
                                                   QuadricRegion::halfspace({0, 0, 1}, 0.5 * L),
                                                   QuadricRegion::halfspace({0, 0, -1}, 0.5 * L)});
}

/// Distance from a point (in the cylinder's frame) to the capped cylinder |xy| <= r, |z| <= L/2.
double pointCylinderDistance(const Eigen::Vector3d& x, double r, double L) {
  const double dr = std::max(std::hypot(x[0], x[1]) - r, 0.0), dz = std::max(std::fabs(x[2]) - 0.5 * L, 0.0);
  return std::hypot(dr, dz);
}

TEST(EllipsoidRegionDistance, SphereAgainstCappedCylinderIsBelowAndNearTheClosedForm) {
  const double r = 0.5, L = 2.0;
  const QuadricRegion cyl = cappedCylinder(r, L);
  const Box3 box{Eigen::Vector3d(-r, -r, -0.5 * L), Eigen::Vector3d(r, r, 0.5 * L)};
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-2.5, 2.5), rad(0.1, 0.6);
  int separated = 0;
  for (int k = 0; k < 60; ++k) {
    const double x = u(rng), y = u(rng), z = u(rng), rho = rad(rng);
    const Eigen::Matrix3d R = test::randomRotation(rng);
    const Eigen::Vector3d p(0.3, -0.2, 0.1);
    const Eigen::Vector3d c(x, y, z);
    const double truth = pointCylinderDistance(R.transpose() * (c - p), r, L) - rho;
    const double cap = 3.0;
    const double lb = ellipsoidRegionDistanceLowerBound(Ellipsoid::sphere(rho, c), cyl, box, R, p, cap);
    SCOPED_TRACE(testing::Message() << "k = " << k << " truth " << truth << " bound " << lb);
    EXPECT_GE(lb, 0.0);
    EXPECT_LE(lb, std::max(truth, 0.0) + 1e-9);
    if (truth > 1e-6) {
      ++separated;
      // Bisection to 2^-10 of [box bound, cap] below the certified value; the region engine's
      // own band is ~1e-9 of the extent.
      EXPECT_GE(lb, truth - cap / 1000.0 - 1e-6);
    } else if (truth < -1e-6) {
      EXPECT_EQ(lb, 0.0);
    }
  }
  EXPECT_GT(separated, 20);
}

TEST(EllipsoidRegionDistance, RandomEllipsoidsAgainstARingNeverExceedTheDistanceToInteriorPoints) {
  // Ring: ellipsoid (1.2, 1.2, 0.6) minus a bore of radius 0.6 along z.
  const QuadricRegion ring = QuadricRegion::combine(
      Op::Difference, {QuadricRegion::atom(quadric::ellipsoid({1.2, 1.2, 0.6})),
                       QuadricRegion::atom(quadric::ellipticCylinder(0.6, 0.6))});
  const Box3 box{Eigen::Vector3d(-1.2, -1.2, -0.6), Eigen::Vector3d(1.2, 1.2, 0.6)};
  // Certified interior points of the ring (a grid, kept where classifyPoint is +1).
  std::vector<Eigen::Vector3d> inside;
  for (double x = -1.2; x <= 1.2; x += 0.05)
    for (double y = -1.2; y <= 1.2; y += 0.05)
      for (double z = -0.6; z <= 0.6; z += 0.05)
        if (ring.classifyPoint({x, y, z}) > 0) inside.emplace_back(x, y, z);
  ASSERT_GT(inside.size(), 1000u);
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-2.5, 2.5);
  int positive = 0, zero = 0;
  for (int k = 0; k < 40; ++k) {
    const Eigen::Vector3d radii = test::randomRadii(rng, 0.5, 5.0);
    const Eigen::Matrix3d Re = test::randomRotation(rng);
    const double x = u(rng), y = u(rng), z = u(rng);
    const Ellipsoid e(radii, Re, Eigen::Vector3d(x, y, z));
    const double lb = ellipsoidRegionDistanceLowerBound(e, ring, box, Eigen::Matrix3d::Identity(),
                                                        Eigen::Vector3d::Zero(), 4.0);
    double upper = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& q : inside) upper = std::min(upper, std::max(0.0, closestPointOnEllipsoid(e, q).signed_distance));
    SCOPED_TRACE(testing::Message() << "k = " << k << " bound " << lb << " upper " << upper);
    EXPECT_GE(lb, 0.0);
    EXPECT_LE(lb, upper + 1e-9);
    positive += lb > 0.0;
    zero += lb == 0.0;
  }
  EXPECT_GT(positive, 5);  // the bound is not trivially 0
  EXPECT_GT(zero, 0);      // and some pairs touch or overlap
}

QuadricRegion cube(double h) {
  std::vector<QuadricRegion> faces;
  for (int i = 0; i < 3; ++i) {
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    n[i] = 1.0;
    faces.push_back(QuadricRegion::halfspace(n, h));
    faces.push_back(QuadricRegion::halfspace(-n, h));
  }
  return QuadricRegion::combine(Op::Intersection, faces);
}

TEST(RegionConvexDistance, SpheresAndCubesAgainstACappedCylinderAreBelowAndNearTheClosedForm) {
  const double r = 0.5, L = 2.0;
  const QuadricRegion cyl = cappedCylinder(r, L);
  const Box3 cyl_box{Eigen::Vector3d(-r, -r, -0.5 * L), Eigen::Vector3d(r, r, 0.5 * L)};
  const double cap = 3.0;
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> u(-2.5, 2.5), rad(0.1, 0.6);
  for (int k = 0; k < 30; ++k) {
    // A sphere anywhere (the scaled sphere is its delta-neighbourhood: the bound is tight).
    const double x = u(rng), y = u(rng), z = u(rng), rho = rad(rng);
    const QuadricRegion ball = QuadricRegion::atom(quadric::ellipsoid(Eigen::Vector3d::Constant(rho)));
    const Box3 ball_box{Eigen::Vector3d::Constant(-rho), Eigen::Vector3d::Constant(rho)};
    const Eigen::Vector3d c(x, y, z);
    const double truth = pointCylinderDistance(c, r, L) - rho;
    const double lb = regionConvexDistanceLowerBound(cyl, cyl_box, ball, ball_box, rho, test::randomRotation(rng), c, cap);
    SCOPED_TRACE(testing::Message() << "sphere k = " << k << " truth " << truth << " bound " << lb);
    EXPECT_GE(lb, 0.0);
    EXPECT_LE(lb, std::max(truth, 0.0) + 1e-9);
    if (truth > 1e-6) {
      EXPECT_GE(lb, truth - cap / 1000.0 - 1e-6);
    } else if (truth < -1e-6) {
      EXPECT_EQ(lb, 0.0);
    }
  }
  for (int k = 0; k < 20; ++k) {
    // An axis-aligned cube beside the cylinder along x, overlapping it in z: distance X - r - h,
    // and the cube scaled about its centre moves its facing face out by exactly delta.
    const double h = rad(rng), X = r + h + 0.05 * k;
    const Box3 cube_box{Eigen::Vector3d::Constant(-h), Eigen::Vector3d::Constant(h)};
    const double lb = regionConvexDistanceLowerBound(cyl, cyl_box, cube(h), cube_box, h, Eigen::Matrix3d::Identity(),
                                                     Eigen::Vector3d(X, 0, 0), cap);
    const double truth = X - r - h;
    SCOPED_TRACE(testing::Message() << "cube k = " << k << " truth " << truth << " bound " << lb);
    EXPECT_LE(lb, truth + 1e-9);
    if (truth > 1e-6) {
      EXPECT_GT(lb, 0.0);
      EXPECT_GE(lb, truth - cap / 1000.0 - 1e-6);
    }
  }
  // Bad input.
  const QuadricRegion ball = QuadricRegion::atom(quadric::ellipsoid(Eigen::Vector3d::Constant(0.2)));
  const Box3 ball_box{Eigen::Vector3d::Constant(-0.2), Eigen::Vector3d::Constant(0.2)};
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  const Eigen::Vector3d far(3, 0, 0);
  EXPECT_THROW(regionConvexDistanceLowerBound(cyl, cyl_box, ball, ball_box, 0.0, I, far, 1.0), std::invalid_argument);
  EXPECT_THROW(regionConvexDistanceLowerBound(cyl, cyl_box, ball, ball_box, std::nan(""), I, far, 1.0), std::invalid_argument);
  EXPECT_THROW(regionConvexDistanceLowerBound(cyl, cyl_box, ball, ball_box, 0.2, I, far, -1.0), std::invalid_argument);
  EXPECT_THROW(regionConvexDistanceLowerBound(cyl, cyl_box, ball, ball_box, 0.3, I, far, 1.0), std::invalid_argument);
  EXPECT_THROW(regionConvexDistanceLowerBound(cyl, cyl_box, ball, Box3{}, 0.2, I, far, 1.0), std::invalid_argument);
  EXPECT_THROW(regionConvexDistanceLowerBound(cyl, cyl_box, ball, ball_box, 0.2, 2.0 * I, far, 1.0), std::invalid_argument);
  EXPECT_THROW(regionConvexDistanceLowerBound(cyl, Box3{Eigen::Vector3d::Ones(), Eigen::Vector3d::Zero()}, ball, ball_box,
                                              0.2, I, far, 1.0),
               std::invalid_argument);
}

TEST(EllipsoidRegionDistance, ContactFarAndBadInput) {
  const QuadricRegion cyl = cappedCylinder(0.5, 2.0);
  const Box3 box{Eigen::Vector3d(-0.5, -0.5, -1.0), Eigen::Vector3d(0.5, 0.5, 1.0)};
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  // Overlapping: 0; far: the cap.
  EXPECT_EQ(ellipsoidRegionDistanceLowerBound(Ellipsoid::sphere(0.3, {0.6, 0, 0}), cyl, box, I, Eigen::Vector3d::Zero(), 1.0), 0.0);
  EXPECT_EQ(ellipsoidRegionDistanceLowerBound(Ellipsoid::sphere(0.3, {9, 0, 0}), cyl, box, I, Eigen::Vector3d::Zero(), 1.0), 1.0);
  const Ellipsoid e = Ellipsoid::sphere(0.3, {2, 0, 0});
  EXPECT_THROW(ellipsoidRegionDistanceLowerBound(e, cyl, box, I, Eigen::Vector3d::Zero(), -1.0), std::invalid_argument);
  EXPECT_THROW(ellipsoidRegionDistanceLowerBound(e, cyl, box, I, Eigen::Vector3d::Zero(), std::nan("")), std::invalid_argument);
  EXPECT_THROW(ellipsoidRegionDistanceLowerBound(e, cyl, box, 2.0 * I, Eigen::Vector3d::Zero(), 1.0), std::invalid_argument);
  EXPECT_THROW(ellipsoidRegionDistanceLowerBound(e, cyl, box, I, Eigen::Vector3d(std::nan(""), 0, 0), 1.0),
               std::invalid_argument);
  const Box3 empty{Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(0, 0, 0)};
  EXPECT_THROW(ellipsoidRegionDistanceLowerBound(e, cyl, empty, I, Eigen::Vector3d::Zero(), 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace fcl_quadric
