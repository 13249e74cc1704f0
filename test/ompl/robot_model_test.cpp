// RobotModel: forward kinematics against hand computation, self-collision pairs, the speed bound
// against finite differences, JSON, and bad input.
#include <cmath>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "ompl_support.h"

namespace fcl_quadric {
namespace planning {
namespace test {
namespace {

// A planar 3-link arm (z axes), links of length 1 along x, each bounded by an ellipsoid.
std::shared_ptr<RobotModel> planarArm() {
  auto arm = std::make_shared<RobotModel>(RobotModel::Base::Fixed);
  arm->addBody(0, std::make_shared<fcl::Sphere<double>>(0.1));
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
  for (int i = 0; i < 3; ++i) {
    const std::size_t l = arm->addJoint("j" + std::to_string(i), JointType::Revolute, origin, Eigen::Vector3d(0, 0, 2),
                                        -3.0, 3.0);
    arm->addBody(l, std::make_shared<fcl::Ellipsoid<double>>(0.45, 0.06, 0.06), translation(0.5, 0, 0));
    origin = translation(1.0, 0, 0);
  }
  return arm;
}

TEST(RobotModel, ForwardKinematicsOfAPlanarArmMatchesTheClosedForm) {
  auto arm = planarArm();
  Configuration q;
  q.joints = {0.3, -1.1, 0.7};
  std::vector<Eigen::Isometry3d> X;
  arm->linkPoses(q, X);
  ASSERT_EQ(X.size(), 4u);
  double a = 0.0, x = 0.0, y = 0.0;
  for (int i = 0; i < 3; ++i) {
    a += q.joints[i];
    EXPECT_NEAR(X[i + 1].translation().x(), x, 1e-12);
    EXPECT_NEAR(X[i + 1].translation().y(), y, 1e-12);
    EXPECT_NEAR(std::atan2(X[i + 1].linear()(1, 0), X[i + 1].linear()(0, 0)), std::remainder(a, 2 * M_PI), 1e-12);
    x += std::cos(a);
    y += std::sin(a);
  }
}

TEST(RobotModel, SelfCollisionPairsAreNonAdjacentMinusAllowed) {
  auto arm = planarArm();
  // Links 0..3: non-adjacent pairs (0,2), (0,3), (1,3).
  ASSERT_EQ(arm->selfCollisionPairs().size(), 3u);
  arm->allowCollision(3, 1);
  const auto& p = arm->selfCollisionPairs();
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[0], std::make_pair(std::size_t{0}, std::size_t{2}));
  EXPECT_EQ(p[1], std::make_pair(std::size_t{0}, std::size_t{3}));
}

TEST(RobotModel, JointSpeedBoundDominatesFiniteDifferenceSpeedsOfBodyPoints) {
  auto arm = planarArm();
  // A prismatic joint in the middle makes chainLength include its extent.
  auto env = std::make_shared<Environment>();
  RobotCollisionChecker checker(arm, env);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  for (int trial = 0; trial < 50; ++trial) {
    Configuration a, b;
    a.joints = {u(rng), u(rng), u(rng)};
    b.joints = {u(rng), u(rng), u(rng)};
    const std::vector<double> V = checker.speedBounds(a, b, Interpolation::Joints);
    ASSERT_EQ(V.size(), 4u);  // base sphere + 3 links
    EXPECT_EQ(V[0], 0.0);
    // Points on the surface of each link ellipsoid: the tip at (0.95, 0, 0) in the link frame.
    const int n = 400;
    std::vector<Eigen::Isometry3d> X0, X1;
    for (int i = 0; i < n; ++i) {
      Configuration q0, q1;
      for (int j = 0; j < 3; ++j) {
        q0.joints.push_back(a.joints[j] + (b.joints[j] - a.joints[j]) * i / n);
        q1.joints.push_back(a.joints[j] + (b.joints[j] - a.joints[j]) * (i + 1) / n);
      }
      arm->linkPoses(q0, X0);
      arm->linkPoses(q1, X1);
      for (int l = 1; l <= 3; ++l) {
        const Eigen::Vector3d tip(0.95, 0.0, 0.0);
        const double speed = (X1[l] * tip - X0[l] * tip).norm() * n;
        EXPECT_LE(speed, V[l]) << "link " << l;
      }
    }
  }
}

TEST(RobotModel, JsonReadsTheDocumentedFormat) {
  const RobotModel m = robotModelFromJson(R"({
    "base": "fixed",
    "bodies": [{"link": 0, "shape": "sphere", "radius": 0.1},
               {"link": 1, "shape": "ellipsoid", "radii": [0.5, 0.1, 0.1], "translation": [0.5, 0, 0]},
               {"link": 2, "shape": "box", "size": [0.2, 0.2, 0.2]}],
    "joints": [{"name": "a", "type": "revolute", "axis": [0, 0, 1], "limits": [-1, 1]},
               {"name": "b", "type": "prismatic", "translation": [1, 0, 0], "axis": [1, 0, 0], "limits": [0, 0.5]}],
    "allowed_collisions": [[0, 2]]})");
  EXPECT_EQ(m.linkCount(), 3u);
  EXPECT_EQ(m.jointCount(), 2u);
  EXPECT_EQ(m.joint(1).type, JointType::Prismatic);
  EXPECT_TRUE(m.selfCollisionPairs().empty());
  EXPECT_DOUBLE_EQ(m.bodies(1)[0].ball_radius, 0.5);
  EXPECT_DOUBLE_EQ(m.chainLength(0, 2), 1.5);  // |origin of joint b| + its prismatic extent
}

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(RobotModel, ExampleJsonRobotsLoad) {
  const RobotModel drone = robotModelFromJson(readFile(FCL_QUADRIC_SOURCE_DIR "/examples/ompl_drone.json"));
  EXPECT_EQ(drone.base(), RobotModel::Base::Free);
  EXPECT_EQ(drone.bodies(0).size(), 2u);
  const RobotModel arm = robotModelFromJson(readFile(FCL_QUADRIC_SOURCE_DIR "/examples/ompl_arm.json"));
  EXPECT_EQ(arm.jointCount(), 4u);
  EXPECT_EQ(arm.joint(2).type, JointType::Prismatic);
  // Links 0..4; non-adjacent pairs (0,2) (0,3) (0,4) (1,3) (1,4) (2,4) minus the allowed (2,4).
  EXPECT_EQ(arm.selfCollisionPairs().size(), 5u);
  EXPECT_DOUBLE_EQ(arm.fixedBasePose().translation().z(), 0.1);
  // The sphere body is stored as an ellipsoid with equal radii (exact pairs everywhere).
  EXPECT_EQ(arm.bodies(3)[0].geometry->getNodeType(), fcl::GEOM_ELLIPSOID);
}

template <typename F>
std::string thrownMessage(F&& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "<no std::invalid_argument>";
}

TEST(RobotModel, BadInputThrowsInvalidArgumentNamingTheValue) {
  RobotModel free_body(RobotModel::Base::Free);
  EXPECT_NE(thrownMessage([&] {
              free_body.addJoint("j", JointType::Revolute, Eigen::Isometry3d::Identity(), Eigen::Vector3d::UnitZ(), 0, 1);
            }).find("Fixed base"),
            std::string::npos);
  RobotModel arm(RobotModel::Base::Fixed);
  EXPECT_NE(thrownMessage([&] {
              arm.addJoint("j", JointType::Revolute, Eigen::Isometry3d::Identity(), Eigen::Vector3d::UnitZ(), 2.0, 1.0);
            }).find("[2, 1]"),
            std::string::npos);
  EXPECT_NE(thrownMessage([&] {
              arm.addJoint("k", JointType::Revolute, Eigen::Isometry3d::Identity(), Eigen::Vector3d::Zero(), 0, 1);
            }).find("axis"),
            std::string::npos);
  EXPECT_NE(thrownMessage([&] { arm.addBody(5, std::make_shared<fcl::Sphere<double>>(1.0)); }).find("link 5"),
            std::string::npos);
  EXPECT_NE(thrownMessage([&] { arm.addBody(0, nullptr); }).find("null geometry"), std::string::npos);
  Eigen::Isometry3d skew = Eigen::Isometry3d::Identity();
  skew.linear()(0, 1) = 0.5;
  EXPECT_NE(thrownMessage([&] { arm.addBody(0, std::make_shared<fcl::Sphere<double>>(1.0), skew); }).find("rigid"),
            std::string::npos);
  EXPECT_NE(thrownMessage([&] { arm.allowCollision(0, 0); }).find("(0, 0)"), std::string::npos);
  EXPECT_NE(thrownMessage([&] { arm.validate(); }).find("no collision body"), std::string::npos);

  EXPECT_NE(thrownMessage([] { robotModelFromJson(R"({"base": "flying", "bodies": []})"); }).find("/base"),
            std::string::npos);
  EXPECT_NE(thrownMessage([] {
              robotModelFromJson(R"({"base": "free", "bodies": [{"shape": "ellipsoid", "radii": [1, -1, 1]}]})");
            }).find("/bodies/0/radii"),
            std::string::npos);
  EXPECT_NE(thrownMessage([] {
              robotModelFromJson(R"({"base": "free", "bodies": [{"link": 3, "shape": "sphere", "radius": 1}]})");
            }).find("/bodies/0/link"),
            std::string::npos);
  EXPECT_NE(thrownMessage([] { robotModelFromJson("{"); }).find("parse error"), std::string::npos);

  auto env = std::make_shared<Environment>();
  EXPECT_NE(thrownMessage([&] { env->add(nullptr); }).find("null geometry"), std::string::npos);
  EXPECT_NE(thrownMessage([&] { RobotCollisionChecker(nullptr, env); }).find("null robot"), std::string::npos);
  auto robot = rigidRobot(RobotModel::Base::Free);
  RobotCollisionChecker checker(robot, env);
  Configuration a, b;
  MotionCheckOptions bad;
  bad.contact_distance = -1.0;
  EXPECT_NE(thrownMessage([&] {
              checker.checkMotion(a, b, Interpolation::Slerp, [&](double, Configuration& q) { q = a; }, bad);
            }).find("contact_distance must be finite and >= 0, got -1"),
            std::string::npos);
  b.base.translation().x() = std::numeric_limits<double>::infinity();
  EXPECT_NE(thrownMessage([&] {
              checker.checkMotion(a, b, Interpolation::Slerp, [&](double, Configuration& q) { q = a; });
            }).find("goal is not finite"),
            std::string::npos);
  EXPECT_NE(thrownMessage([&] { checker.speedBounds(a, a, Interpolation::Joints); }).find("Fixed-base"),
            std::string::npos);

  // An unsupported state space is named.
  auto so3 = std::make_shared<ob::SO3StateSpace>();
  auto si = std::make_shared<ob::SpaceInformation>(so3);
  auto shared_checker = std::make_shared<RobotCollisionChecker>(robot, env);
  EXPECT_NE(thrownMessage([&] { ContinuousMotionValidator(si, shared_checker); }).find(so3->getName()),
            std::string::npos);
}

}  // namespace
}  // namespace test
}  // namespace planning
}  // namespace fcl_quadric
