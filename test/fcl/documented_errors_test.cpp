// Documented bad-input behaviour of the FCL layer that had no test of its own (issue 8 audit of
// include/fcl_quadric/**; docs/reliability.md lists them).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "support/expect_invalid.h"
#include "fcl_quadric/fcl/continuous_broadphase.h"
#include "fcl_quadric/fcl/rational_motion.h"

namespace fcl_quadric {
namespace {

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

}  // namespace
}  // namespace fcl_quadric
