// Documented bad-input behaviour of the FCL layer that had no test of its own (issue 8 audit of
// include/fcl_quadric/**; docs/reliability.md lists them).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/halfspace.h>

#include "support/expect_invalid.h"
#include "fcl_quadric/fcl/collision.h"
#include "fcl_quadric/fcl/continuous_broadphase.h"
#include "fcl_quadric/fcl/distance.h"
#include "fcl_quadric/fcl/quadric_shapes.h"
#include "fcl_quadric/fcl/rational_motion.h"

namespace fcl_quadric {
namespace {

/// The two front doors as queries whose answer is not looked at (collide with a contact, distance
/// with nearest points): what the bad-input tests below call each input with.
using Query = std::function<void(const fcl::CollisionGeometryd*, const fcl::Transform3d&, const fcl::CollisionGeometryd*,
                                 const fcl::Transform3d&)>;
std::vector<Query> frontDoorQueries() {
  return {[](const fcl::CollisionGeometryd* a, const fcl::Transform3d& ta, const fcl::CollisionGeometryd* b,
             const fcl::Transform3d& tb) {
            fcl::CollisionResultd r;
            fcl_quadric::collide(a, ta, b, tb, fcl::CollisionRequestd(1, true), r);
          },
          [](const fcl::CollisionGeometryd* a, const fcl::Transform3d& ta, const fcl::CollisionGeometryd* b,
             const fcl::Transform3d& tb) {
            fcl::DistanceResultd r;
            fcl_quadric::distance(a, ta, b, tb, fcl::DistanceRequestd(true), r);
          }};
}

using test::expectInvalid;

TEST(DocumentedErrors, RationalMotionRejectsAnInvalidMatrixAndTimesOutsideTheInterval) {
  PolynomialMatrix4 M(Eigen::Matrix4d::Identity());
  M(3, 3) = Polynomial{1.0, -2.0};  // w(t) = 1 - 2t vanishes at t = 1/2
  expectInvalid([&] { RationalMotion<double> r(M); }, "w(t)");
  const RationalMotion<double> ok{PolynomialMatrix4(Eigen::Matrix4d::Identity())};
  expectInvalid([&] { (void)ok.directionalSpeedBound(Eigen::Vector3d::UnitX(), {Eigen::Vector3d::Zero()}, 1.0, 2.0); },
                "t0");
  expectInvalid([&] { (void)ok.speedBound(Eigen::Vector3d::Zero(), 1.0, -0.5); }, "t0");
  EXPECT_EQ(ok.speedBound(Eigen::Vector3d::Zero(), 1.0, 0.5), 0.0);  // a constant motion does not move
}

TEST(DocumentedErrors, SweptAABBOfABallRejectsBadRadiusAndCentre) {
  const PiecewiseMotion still;
  expectInvalid([&] { (void)sweptAABB(Eigen::Vector3d::Zero(), -1.0, still); }, "radius");
  expectInvalid([&] { (void)sweptAABB(Eigen::Vector3d::Zero(), std::numeric_limits<double>::infinity(), still); },
                "radius");
  expectInvalid([&] { (void)sweptAABB(Eigen::Vector3d(std::nan(""), 0, 0), 1.0, still); }, "centre");
  const fcl::AABB<double> box = sweptAABB(Eigen::Vector3d(1, 2, 3), 0.5, still);
  EXPECT_LE(box.min_[0], 0.5);
  EXPECT_GE(box.max_[2], 3.5);
}

// Session 35, an audit of the static front door: partners of an ellipsoid posed beyond kMaxLength
// were accepted (a box 1e300 away "collided" with an ellipsoid at the origin: its products
// overflowed), and a quadric shape's partner posed by a scaled transform was silently scaled.
// Both are now errors naming the argument, for collide and distance alike.
TEST(DocumentedErrors, PartnersPosedOutOfRangeOrByNonRigidTransformsAreRejected) {
  const auto ellipsoid = std::make_shared<fcl::Ellipsoidd>(1.0, 0.5, 0.3);
  const auto box = std::make_shared<fcl::Boxd>(1.0, 1.0, 1.0);
  const auto cylinder = std::make_shared<fcl::Cylinderd>(1.0, 1.0);
  const auto halfspace = std::make_shared<fcl::Halfspaced>(Eigen::Vector3d::UnitX(), -2.0);
  const auto elliptic = std::make_shared<EllipticCylinder<double>>(1.0, 0.5, 1.0);
  const fcl::Transform3d I = fcl::Transform3d::Identity();
  fcl::Transform3d far = I, scaled = I;
  far.translation() = Eigen::Vector3d(1e300, 0.0, 0.0);
  scaled.linear() = 2.0 * Eigen::Matrix3d::Identity();
  scaled.translation() = Eigen::Vector3d(2.5, 0.0, 0.0);
  const fcl::CollisionRequestd creq(1, true);
  fcl::DistanceRequestd dreq(true);
  for (const Query& query : frontDoorQueries()) {
    expectInvalid([&] { query(ellipsoid.get(), I, box.get(), far); }, "box centre coordinates must be within +-1e+100");
    expectInvalid([&] { query(cylinder.get(), far, ellipsoid.get(), I); }, "cylinder centre coordinates must be within");
    expectInvalid([&] { query(ellipsoid.get(), I, halfspace.get(), scaled); }, "plane rotation");
    expectInvalid([&] { query(elliptic.get(), I, ellipsoid.get(), scaled); }, "the rotation of tf2");
    expectInvalid([&] { query(elliptic.get(), far, ellipsoid.get(), I); }, "the translation of tf1");
  }
  // The same pairs posed in range and rigidly are answered.
  fcl::Transform3d near = I;
  near.translation() = Eigen::Vector3d(2.5, 0.0, 0.0);
  fcl::CollisionResultd r;
  EXPECT_EQ(fcl_quadric::collide(elliptic.get(), I, ellipsoid.get(), near, creq, r), 0u);
  fcl::DistanceResultd d;
  EXPECT_NEAR(fcl_quadric::distance(elliptic.get(), I, ellipsoid.get(), near, dreq, d), 0.5, 1e-12);
}

// Session 36's audit of the sphere pairs: FCL's own closed forms (sphere against a box, capsule,
// cylinder or sphere, collide and unsigned distance) took a NaN radius, a centre at 1e200 or a
// scaled pose and answered NaN or DBL_MAX with unwritten points; a sphere's scaled pose was
// ignored on the exact paths too. Now every sphere pair validates both operands.
TEST(DocumentedErrors, SpherePairsValidateBothOperandsOnEveryPath) {
  const auto nan_ball = std::make_shared<fcl::Sphered>(std::nan(""));
  const auto ball = std::make_shared<fcl::Sphered>(0.5);
  const auto box = std::make_shared<fcl::Boxd>(1.0, 1.0, 1.0);
  const auto capsule = std::make_shared<fcl::Capsuled>(0.3, 1.0);
  const auto cone = std::make_shared<fcl::Coned>(0.5, 1.0);
  const fcl::Transform3d I = fcl::Transform3d::Identity();
  fcl::Transform3d far = I, scaled = I, near = I;
  far.translation() = Eigen::Vector3d(1e200, 0.0, 0.0);
  scaled.linear() = 2.0 * Eigen::Matrix3d::Identity();
  near.translation() = Eigen::Vector3d(2.0, 0.0, 0.0);
  for (const Query& query : frontDoorQueries()) {
    expectInvalid([&] { query(nan_ball.get(), I, box.get(), near); }, "o1 (fcl::Sphere): sphere radius must be finite");
    expectInvalid([&] { query(capsule.get(), near, nan_ball.get(), I); }, "o2 (fcl::Sphere): sphere radius");
    expectInvalid([&] { query(ball.get(), far, ball.get(), I); }, "o1 (fcl::Sphere): sphere centre coordinates must be within");
    expectInvalid([&] { query(ball.get(), I, box.get(), scaled); }, "box rotation");
    expectInvalid([&] { query(ball.get(), scaled, cone.get(), near); }, "o1 (fcl::Sphere): sphere rotation");
    expectInvalid([&] { query(ball.get(), scaled, box.get(), near); }, "sphere rotation");
  }
  // Rigid poses in range are answered, and a touching pair's unsigned distance on the exact paths
  // is 0 (it was -1): a ball of radius 0.5 centred at z = 1 touches the cone's apex at z = 0.5.
  // (FCL's own closed forms, sphere-box for one, keep their -1 for touching.)
  fcl::DistanceResultd dc;
  fcl::Transform3d above_apex = I;
  above_apex.translation() = Eigen::Vector3d(0.0, 0.0, 1.0);  // the apex is at z = 0.5
  EXPECT_EQ(fcl_quadric::distance(ball.get(), above_apex, cone.get(), I, fcl::DistanceRequestd(true), dc), 0.0);
}

}  // namespace
}  // namespace fcl_quadric
