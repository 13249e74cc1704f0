// In-process tests of the FCL fallback used for pairs with a box, against closed forms.
#include <gtest/gtest.h>

#include "fcl_quadric/fcl_fallback.h"

namespace fcl_quadric {
namespace cli {
namespace {

SceneObject object(ShapeType type, const Eigen::Vector3d& dimensions, const Eigen::Vector3d& p,
                   const Eigen::Matrix3d& R = Eigen::Matrix3d::Identity()) {
  SceneObject o;
  o.name = "o";
  o.shape.type = type;
  o.shape.dimensions = dimensions;
  o.pose.linear() = R;
  o.pose.translation() = p;
  return o;
}

TEST(FclFallback, SphereIntoBoxPenetrationDepthAndNormal) {
  // Unit sphere at the origin; box [0.5, 2.5] x [-1, 1] x [-1, 1]: depth 0.5 along +x.
  const SceneObject sphere = object(ShapeType::Sphere, Eigen::Vector3d::Constant(1.0), Eigen::Vector3d::Zero());
  const SceneObject box = object(ShapeType::Box, Eigen::Vector3d(2, 2, 2), Eigen::Vector3d(1.5, 0, 0));
  const PairReport r = fclPairReport(sphere, box);
  EXPECT_EQ(r.method, PairMethod::Fcl);
  EXPECT_TRUE(r.collide);
  EXPECT_EQ(r.status, Separation::Overlapping);
  EXPECT_NEAR(r.signed_distance, -0.5, 1e-6);
  EXPECT_LT((r.normal - Eigen::Vector3d::UnitX()).norm(), 1e-6);
  EXPECT_LT((r.point_a - Eigen::Vector3d(1, 0, 0)).norm(), 1e-4);
  EXPECT_LT((r.point_b - Eigen::Vector3d(0.5, 0, 0)).norm(), 1e-4);
  // The reversed pair reports the reversed normal and swapped points.
  const PairReport s = fclPairReport(box, sphere);
  EXPECT_NEAR(s.signed_distance, -0.5, 1e-6);
  EXPECT_LT((s.normal + Eigen::Vector3d::UnitX()).norm(), 1e-6);
}

TEST(FclFallback, RotatedBoxAndEllipsoidSeparatedDistance) {
  // A box rotated 45 degrees about z, centred at x = 4: its nearest edge is at x = 4 - sqrt(2).
  // An ellipsoid with semi-axis 1.5 along x at the origin: distance 4 - sqrt(2) - 1.5.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(EIGEN_PI / 4, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const SceneObject box = object(ShapeType::Box, Eigen::Vector3d(2, 2, 2), Eigen::Vector3d(4, 0, 0), R);
  const SceneObject ellipsoid = object(ShapeType::Ellipsoid, Eigen::Vector3d(1.5, 0.5, 0.5), Eigen::Vector3d::Zero());
  const PairReport r = fclPairReport(ellipsoid, box);
  const double expected = 4.0 - std::sqrt(2.0) - 1.5;
  EXPECT_FALSE(r.collide);
  EXPECT_EQ(r.status, Separation::Separated);
  EXPECT_NEAR(r.signed_distance, expected, 1e-6);
  EXPECT_LT((r.point_a - Eigen::Vector3d(1.5, 0, 0)).norm(), 1e-3);
  EXPECT_NEAR(r.point_b.x(), 4.0 - std::sqrt(2.0), 1e-6);
  EXPECT_LT((r.normal - Eigen::Vector3d::UnitX()).norm(), 1e-3);
}

TEST(FclFallback, BoxBoxSeparatedAlongY) {
  const SceneObject a = object(ShapeType::Box, Eigen::Vector3d(1, 1, 1), Eigen::Vector3d::Zero());
  const SceneObject b = object(ShapeType::Box, Eigen::Vector3d(1, 3, 1), Eigen::Vector3d(0.2, 3, 0));
  const PairReport r = fclPairReport(a, b);
  EXPECT_FALSE(r.collide);
  EXPECT_NEAR(r.signed_distance, 1.0, 1e-6);  // 3 - 0.5 - 1.5
  EXPECT_LT((r.normal - Eigen::Vector3d::UnitY()).norm(), 1e-6);
}

}  // namespace
}  // namespace cli
}  // namespace fcl_quadric
