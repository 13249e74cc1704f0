// Regressions of the OMPL layer's audit (docs/reliability.md finding 33), each against an
// independent oracle: pairwise fcl_quadric::collide / distance with no broad phase, closed-form
// overlaps, dense samples of the motion the planner executes, and OMPL's own interpolate().
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/triangle_p.h>
#include <fcl/math/bv/OBBRSS.h>
#include <octomap/OcTree.h>
#include <ompl/util/Console.h>

#include "ompl_support.h"
#include "support/expect_invalid.h"

namespace fcl_quadric {
namespace planning {
namespace test {
namespace {

using fcl_quadric::test::expectInvalid;

struct QuietAuditTests {
  QuietAuditTests() { ompl::msg::setLogLevel(ompl::msg::LOG_WARN); }
} quiet_audit_tests;

/// Pairwise signed distance of one posed body to every obstacle, each in a fresh result: the
/// oracle of clearance() (no broad phase).
double pairwiseClearance(const Body& body, const Eigen::Isometry3d& X, const Environment& env) {
  double d = std::numeric_limits<double>::infinity();
  for (const auto& obj : env.objects()) {
    fcl::DistanceRequest<double> request;
    request.enable_signed_distance = true;
    fcl::DistanceResult<double> result;
    d = std::min(d, fcl_quadric::distance(body.geometry.get(), toFcl(X * body.offset), obj->collisionGeometry().get(),
                                          obj->getTransform(), request, result));
  }
  return d;
}

// (1) The broad phase stopped at the first overlap it met: -0.1 or -0.5 by insertion order.
TEST(StateValidityChecker, ClearanceInSeveralObstaclesIsTheDeepestOverlapWhateverTheInsertionOrder) {
  // A unit sphere at the origin in box A (face x = 0.9: depth 0.1) and box B (face y = 0.5: 0.5).
  for (bool a_first : {true, false}) {
    auto robot = std::make_shared<RobotModel>(RobotModel::Base::Free);
    robot->addBody(0, std::make_shared<fcl::Sphere<double>>(1.0));
    auto env = std::make_shared<Environment>();
    const Eigen::Isometry3d A = translation(1.9, 0, 0), B = translation(0, 1.5, 0);
    env->add(std::make_shared<fcl::Box<double>>(2, 2, 2), a_first ? A : B);
    env->add(std::make_shared<fcl::Box<double>>(2, 2, 2), a_first ? B : A);
    RobotCollisionChecker checker(robot, env);
    EXPECT_NEAR(checker.clearance(Configuration{}), -0.5, 1e-12) << "a_first " << a_first;
  }
  // Random scenes: an ellipsoid body among boxes and ellipsoids, several of them overlapping it.
  std::mt19937_64 rng(33);
  std::uniform_real_distribution<double> u(-1.0, 1.0), r(0.2, 0.8);
  int overlapping_scenes = 0;
  for (int scene = 0; scene < 60; ++scene) {
    auto robot = std::make_shared<RobotModel>(RobotModel::Base::Free);
    robot->addBody(0, std::make_shared<fcl::Ellipsoid<double>>(r(rng), r(rng), r(rng)));
    auto env = std::make_shared<Environment>();
    for (int k = 0; k < 6; ++k) {
      Eigen::Isometry3d X = translation(1.2 * u(rng), 1.2 * u(rng), 1.2 * u(rng));
      X.linear() = randomQuaternion(rng).toRotationMatrix();
      if (k % 2 == 0)
        env->add(std::make_shared<fcl::Box<double>>(r(rng), r(rng), r(rng)), X);
      else
        env->add(std::make_shared<fcl::Ellipsoid<double>>(r(rng), r(rng), r(rng)), X);
    }
    RobotCollisionChecker checker(robot, env);
    Configuration q;
    q.base.linear() = randomQuaternion(rng).toRotationMatrix();
    const double truth = pairwiseClearance(robot->bodies(0)[0], q.base, *env);
    overlapping_scenes += truth < 0.0;
    EXPECT_NEAR(checker.clearance(q), truth, 1e-9 * (1.0 + std::abs(truth))) << "scene " << scene;
  }
  EXPECT_GT(overlapping_scenes, 30);  // the property is exercised
}

// (2) OMPL's SE3 slerp keeps the start rotation when |q1 . q2| > 1 - 1e-9 (arcLength 0), so the
// rotation to s2 was never checked.
struct NeedleScene {
  std::shared_ptr<RobotModel> robot = std::make_shared<RobotModel>(RobotModel::Base::Free);
  std::shared_ptr<Environment> env = std::make_shared<Environment>();
  std::shared_ptr<ob::SE3StateSpace> space = std::make_shared<ob::SE3StateSpace>();
  std::shared_ptr<ob::SpaceInformation> si;
  ob::State* s1 = nullptr;
  ob::State* s2 = nullptr;
  NeedleScene(const Eigen::Vector3d& radii, double angle, const std::shared_ptr<fcl::CollisionGeometry<double>>& obstacle,
              const Eigen::Isometry3d& at) {
    robot->addBody(0, std::make_shared<fcl::Ellipsoid<double>>(radii));
    env->add(obstacle, at);
    ob::RealVectorBounds b(3);
    b.setLow(-20);
    b.setHigh(20);
    space->setBounds(b);
    si = std::make_shared<ob::SpaceInformation>(space);
    installCollisionChecking(si, std::make_shared<RobotCollisionChecker>(robot, env));
    s1 = si->allocState();
    s2 = si->allocState();
    setSE3(s1, Eigen::Vector3d::Zero(), Eigen::Quaterniond::Identity());
    setSE3(s2, Eigen::Vector3d::Zero(), Eigen::Quaterniond(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ())));
  }
  ~NeedleScene() {
    si->freeState(s1);
    si->freeState(s2);
  }
  Configuration rotated(double angle) const {
    Configuration q;
    q.base.linear() = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    return q;
  }
  /// The premise: OMPL's interpolate(s1, s2, 1) is not s2 (it kept the start rotation).
  bool omplSkipsTheRotation() const {
    ob::State* m = si->allocState();
    space->interpolate(s1, s2, 1.0, m);
    // (Not equalStates: SO3StateSpace compares by arcLength, which is 0 here too.)
    const bool skipped = m->as<ob::SE3StateSpace::StateType>()->rotation().z !=
                         s2->as<ob::SE3StateSpace::StateType>()->rotation().z;
    si->freeState(m);
    return skipped;
  }
};

TEST(ContinuousMotionValidator, RejectsATinySE3RotationThatOmplsSlerpSkipsIntoAnObstacle) {
  const double angle = 8e-5;  // |q1 . q2| = cos(4e-5) > 1 - 1e-9
  const Eigen::Vector3d radii(10, 0.01, 0.01);
  auto box = std::make_shared<fcl::Box<double>>(2, 1, 1);
  // The box's lower face y = f: the needle rotated by `angle` touches it at f = f*, found by
  // bisection of the pairwise oracle; the box then sits 2e-4 below f*, clear of the start.
  auto goalCollides = [&](double f) {
    NeedleScene s(radii, angle, box, translation(10, f + 0.5, 0));
    return oracleCollides(*s.robot, *s.env, s.rotated(angle));
  };
  double lo = 0.0, hi = 0.02;
  for (int i = 0; i < 60; ++i) (goalCollides(0.5 * (lo + hi)) ? lo : hi) = 0.5 * (lo + hi);
  for (double offset : {-2e-4, +2e-4}) {
    NeedleScene s(radii, angle, box, translation(10, lo + offset + 0.5, 0));
    ASSERT_TRUE(s.omplSkipsTheRotation());
    ASSERT_FALSE(oracleCollides(*s.robot, *s.env, s.rotated(0.0)));
    const bool goal_collides = oracleCollides(*s.robot, *s.env, s.rotated(angle));
    ASSERT_EQ(goal_collides, offset < 0.0);
    EXPECT_EQ(s.si->checkMotion(s.s1, s.s2), !goal_collides) << offset;
    ob::State* last = s.si->allocState();
    std::pair<ob::State*, double> lv(last, -1.0);
    EXPECT_EQ(s.si->getMotionValidator()->checkMotion(s.s1, s.s2, lv), !goal_collides) << offset;
    if (goal_collides) {
      EXPECT_LT(lv.second, 1.0);
      EXPECT_FALSE(oracleCollides(*s.robot, *s.env, toConfiguration(*s.space, lv.first)));
    }
    s.si->freeState(last);
  }
}

TEST(ContinuousMotionValidator, CertifiesTheRotationOmplsSlerpSkipsBetweenTwoFreeEndStates) {
  // A needle of thickness 2e-4 turned by 8e-5 rad: at x = 9.5 it moves 7.6e-4 in y, more than its
  // thickness there (6.2e-5), so a thin plate between the two positions is missed by both end
  // states and hit by the rotation between them.
  const double angle = 8e-5;
  auto plate = std::make_shared<fcl::Box<double>>(2e-5, 2e-5, 1.0);
  NeedleScene s(Eigen::Vector3d(10, 1e-4, 1e-4), angle, plate, translation(9.5, 9.5 * std::sin(0.5 * angle), 0));
  ASSERT_TRUE(s.omplSkipsTheRotation());
  ASSERT_TRUE(s.si->isValid(s.s1));
  ASSERT_TRUE(s.si->isValid(s.s2));
  bool swept_collides = false;  // the rotation at constant speed, sampled
  for (int k = 0; k <= 1000 && !swept_collides; ++k)
    swept_collides = oracleCollides(*s.robot, *s.env, s.rotated(angle * k / 1000.0));
  ASSERT_TRUE(swept_collides);
  EXPECT_FALSE(s.si->checkMotion(s.s1, s.s2));
}

// (3) libccd's MPR (fcl_quadric::collide for these pairs) missed overlaps of 1e-12 to 3e-7.
TEST(StateValidityChecker, CapsuleCylinderAndBoxBodiesTouchingAFloorByAsLittleAs1e12AreInCollision) {
  // Bodies whose lowest point in the base frame is known in closed form; the floor is z <= 0 as a
  // box, a two-triangle mesh and an OcTree of 0.1 voxels (registered whole, and as merged boxes).
  struct Case {
    const char* name;
    std::shared_ptr<fcl::CollisionGeometry<double>> g;
    Eigen::Isometry3d offset;
    double lowest;
  };
  const double a = 0.3;
  auto rotY = [](double angle) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.linear() = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitY()).toRotationMatrix();
    return X;
  };
  const std::vector<Case> cases = {
      {"capsule, point contact", std::make_shared<fcl::Capsule<double>>(0.05, 0.4), rotY(M_PI / 2 - a),
       -(0.2 * std::cos(M_PI / 2 - a) + 0.05)},
      {"capsule, line contact", std::make_shared<fcl::Capsule<double>>(0.05, 0.4), rotY(M_PI / 2), -0.05},
      {"cylinder, cap on the face", std::make_shared<fcl::Cylinder<double>>(0.05, 0.4), rotY(0.0), -0.2},
      {"cylinder, line contact", std::make_shared<fcl::Cylinder<double>>(0.05, 0.4), rotY(M_PI / 2), -0.05},
      {"box, edge contact", std::make_shared<fcl::Box<double>>(0.4, 0.1, 0.06), rotY(a),
       -(0.2 * std::sin(a) + 0.03 * std::cos(a))},
  };
  auto floorBox = [] {
    auto env = std::make_shared<Environment>();
    env->add(std::make_shared<fcl::Box<double>>(2, 2, 1), translation(0, 0, -0.5));
    return env;
  };
  auto floorMesh = [] {
    auto m = std::make_shared<fcl::BVHModel<fcl::OBBRSS<double>>>();
    std::vector<fcl::Vector3<double>> p = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    std::vector<fcl::Triangle> t = {{0, 1, 2}, {0, 2, 3}};
    m->beginModel();
    m->addSubModel(p, t);
    m->endModel();
    auto env = std::make_shared<Environment>();
    env->add(m);
    return env;
  };
  auto tree = std::make_shared<octomap::OcTree>(0.1);
  for (double x = -0.95; x < 1.0; x += 0.1)
    for (double y = -0.95; y < 1.0; y += 0.1) tree->updateNode(octomap::point3d(x, y, -0.05), true);
  auto floorTree = [&](Environment::OcTreeMode mode) {
    auto env = std::make_shared<Environment>();
    env->addOcTree(tree, Eigen::Isometry3d::Identity(), mode);
    return env;
  };
  const std::vector<std::pair<const char*, std::shared_ptr<Environment>>> floors = {
      {"box", floorBox()},
      {"mesh", floorMesh()},
      {"whole OcTree", floorTree(Environment::OcTreeMode::WholeTree)},
      {"merged OcTree boxes", floorTree(Environment::OcTreeMode::MergedBoxes)}};
  for (const auto& [floor_name, env] : floors)
    for (const Case& c : cases) {
      auto robot = std::make_shared<RobotModel>(RobotModel::Base::Free);
      robot->addBody(0, c.g, c.offset);
      RobotCollisionChecker checker(robot, env);
      for (double height : {-1e-5, -1e-7, -1e-9, -1e-12, 0.0, 1e-7, 1e-5}) {
        Configuration q;
        q.base.translation() = Eigen::Vector3d(0.1, 0.05, height - c.lowest);  // lowest point at z = height
        EXPECT_EQ(checker.isValid(q), height > 0.0) << c.name << " on the " << floor_name << " floor at " << height;
      }
    }
}

TEST(StateValidityChecker, SelfPairsOfCapsuleAndBoxLinksTouchingByAsLittleAs1e12AreInCollision) {
  // Base link: a box of side 0.4 at the origin (top face z = 0.2). Two prismatic joints (x, then
  // z) carry link 2: a capsule (r = 0.05) lying along x, so its lowest point is at z = q_z - 0.05.
  // Links 0 and 2 are not adjacent: a self-collision pair. Link 1 has no body.
  for (bool cylinder : {false, true}) {
    auto arm = std::make_shared<RobotModel>(RobotModel::Base::Fixed);
    arm->addBody(0, std::make_shared<fcl::Box<double>>(0.4, 0.4, 0.4));
    const std::size_t l1 =
        arm->addJoint("x", JointType::Prismatic, Eigen::Isometry3d::Identity(), Eigen::Vector3d::UnitX(), -1, 1);
    const std::size_t l2 =
        arm->addJoint("z", JointType::Prismatic, Eigen::Isometry3d::Identity(), Eigen::Vector3d::UnitZ(), -1, 1);
    (void)l1;
    Eigen::Isometry3d along_x = Eigen::Isometry3d::Identity();
    along_x.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
    if (cylinder)
      arm->addBody(l2, std::make_shared<fcl::Cylinder<double>>(0.05, 0.3), along_x);
    else
      arm->addBody(l2, std::make_shared<fcl::Capsule<double>>(0.05, 0.3), along_x);
    ASSERT_EQ(arm->selfCollisionPairs().size(), 1u);
    RobotCollisionChecker checker(arm, std::make_shared<Environment>());
    for (double height : {-1e-5, -1e-9, -1e-12, 0.0, 1e-7, 1e-5}) {
      Configuration q;
      q.joints = {0.03, 0.2 + 0.05 + height};
      EXPECT_EQ(checker.isValid(q), height > 0.0) << (cylinder ? "cylinder" : "capsule") << " at " << height;
    }
  }
}

// (4) The start state was never checked: out of bounds it breaks the speed bound.
TEST(ContinuousMotionValidator, RejectsMotionsFromAStartOutsideTheBoundsAndNamesItInCheck) {
  // SE(2): from a yaw of 10 (not in [-pi, pi]) OMPL turns 6.2 rad to reach -2.5, through a box
  // the arm meets at a yaw of pi / 2; the speed bound assumed the 0.07 rad of the shorter arc.
  auto robot = std::make_shared<RobotModel>(RobotModel::Base::Planar);
  robot->addBody(0, std::make_shared<fcl::Ellipsoid<double>>(1.0, 0.1, 0.1), translation(1, 0, 0));
  auto env = std::make_shared<Environment>();
  env->add(std::make_shared<fcl::Box<double>>(0.4, 0.4, 0.4), translation(0, 1.5, 0));
  auto space = makeStateSpace(*robot, Eigen::Vector3d::Constant(-5), Eigen::Vector3d::Constant(5));
  auto si = std::make_shared<ob::SpaceInformation>(space);
  installCollisionChecking(si, std::make_shared<RobotCollisionChecker>(robot, env));
  ob::State* s1 = si->allocState();
  ob::State* s2 = si->allocState();
  setSE2(s1, 0, 0, 10.0);
  setSE2(s2, 0, 0, -2.5);
  ASSERT_GT(oracleFirstCollidingSample(*si, *robot, *env, s1, s2, 2000), 0.0);  // OMPL's own path collides
  EXPECT_FALSE(si->checkMotion(s1, s2));
  std::pair<ob::State*, double> lv(nullptr, -1.0);
  EXPECT_FALSE(si->getMotionValidator()->checkMotion(s1, s2, lv));
  EXPECT_EQ(lv.second, 0.0);
  const auto& validator = dynamic_cast<const ContinuousMotionValidator&>(*si->getMotionValidator());
  expectInvalid([&] { validator.check(s1, s2, false); }, "yaw of s1 is 10");
  si->freeState(s1);
  si->freeState(s2);

  // Joints: a prismatic joint of s1 beyond its limit, directly and through the validator.
  auto arm = std::make_shared<RobotModel>(RobotModel::Base::Fixed);
  const std::size_t l1 =
      arm->addJoint("turn", JointType::Revolute, Eigen::Isometry3d::Identity(), Eigen::Vector3d::UnitZ(), -3, 3);
  const std::size_t l2 = arm->addJoint("slide", JointType::Prismatic, translation(0.5, 0, 0), Eigen::Vector3d::UnitX(), 0, 0.1);
  (void)l1;
  arm->addBody(l2, std::make_shared<fcl::Sphere<double>>(0.1));
  auto arm_env = std::make_shared<Environment>();
  arm_env->add(std::make_shared<fcl::Box<double>>(0.4, 0.4, 0.4), translation(0, 3.5, 0));
  RobotCollisionChecker checker(arm, arm_env);
  Configuration from, to, short_q;
  from.joints = {0.0, 3.0};
  to.joints = {3.0, 3.0};
  short_q.joints = {0.0};
  auto lerp = [&](double t, Configuration& q) { q.joints = {3.0 * t, 3.0}; };
  expectInvalid([&] { checker.checkMotion(from, to, Interpolation::Joints, lerp); },
                "joint 1 (\"slide\") of the start is 3, outside its limits [0, 0.1");
  expectInvalid([&] { checker.checkMotion(short_q, to, Interpolation::Joints, lerp); },
                "the start has 1 joint values, the robot has 2 joints");
  auto arm_space = makeStateSpace(*arm, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  auto arm_si = std::make_shared<ob::SpaceInformation>(arm_space);
  installCollisionChecking(arm_si, std::make_shared<RobotCollisionChecker>(arm, arm_env));
  ob::State* j1 = arm_si->allocState();
  ob::State* j2 = arm_si->allocState();
  auto* v1 = j1->as<ob::RealVectorStateSpace::StateType>();
  auto* v2 = j2->as<ob::RealVectorStateSpace::StateType>();
  v1->values[0] = 0.0, v1->values[1] = 3.0;
  v2->values[0] = 3.0, v2->values[1] = 0.1;
  ASSERT_TRUE(oracleCollides(*arm, *arm_env, [] {
    Configuration q;
    q.joints = {M_PI / 2, 3.0};  // on the way, with the slide where s1 has it
    return q;
  }()));
  EXPECT_FALSE(arm_si->checkMotion(j1, j2));
  arm_si->freeState(j1);
  arm_si->freeState(j2);
}

// Bad input: geometries the layer silently never saw in contact, overflowing JSON numbers, a
// zero quaternion (OMPL's interpolation asserts on it).
TEST(Environment, UnsupportedOrMalformedGeometriesAreRejectedWithTheirValue) {
  auto tri = std::make_shared<fcl::TriangleP<double>>(fcl::Vector3<double>(-0.2, -0.2, 0), fcl::Vector3<double>(0.2, -0.2, 0),
                                                      fcl::Vector3<double>(0, 0.2, 0));
  Environment env;
  expectInvalid([&] { env.add(tri); }, "fcl::TriangleP is not supported");
  RobotModel robot(RobotModel::Base::Free);
  expectInvalid([&] { robot.addBody(0, tri); }, "fcl::TriangleP is not supported");
  expectInvalid([&] { robot.addBody(0, std::make_shared<fcl::Ellipsoid<double>>(-0.1, 0.1, 0.1)); },
                "ellipsoid radius 0 must be finite and > 0, got -0.1");
  expectInvalid([&] { env.add(std::make_shared<fcl::Box<double>>(1.0, std::nan(""), 1.0)); },
                "box side 1 must be finite and > 0, got nan");
  expectInvalid([&] { env.add(std::make_shared<fcl::Capsule<double>>(0.0, 1.0)); }, "capsule radius");
  auto unfinished = std::make_shared<fcl::BVHModel<fcl::OBBRSS<double>>>();
  unfinished->beginModel();
  expectInvalid([&] { env.add(unfinished); }, "endModel");
  EXPECT_EQ(env.size(), 0u);
  EXPECT_EQ(robot.bodies(0).size(), 0u);
  expectInvalid([] { robotModelFromJson(R"({"bodies": [{"shape": "sphere", "radius": 1e999}]})"); }, "robot JSON");

  auto body = std::make_shared<RobotModel>(RobotModel::Base::Free);
  body->addBody(0, std::make_shared<fcl::Sphere<double>>(0.1));
  auto boxes = std::make_shared<Environment>();
  boxes->add(std::make_shared<fcl::Box<double>>(1, 1, 1), translation(3, 0, 0));
  for (bool rational : {false, true}) {
    auto space = makeStateSpace(*body, Eigen::Vector3d::Constant(-5), Eigen::Vector3d::Constant(5), rational);
    auto si = std::make_shared<ob::SpaceInformation>(space);
    installCollisionChecking(si, std::make_shared<RobotCollisionChecker>(body, boxes));
    ob::State* s1 = si->allocState();
    ob::State* s2 = si->allocState();
    setSE3(s1, Eigen::Vector3d::Zero(), Eigen::Quaterniond::Identity());
    setSE3(s2, Eigen::Vector3d(1, 0, 0), Eigen::Quaterniond::Identity());
    auto* r = &s1->as<ob::SE3StateSpace::StateType>()->rotation();
    r->w = r->x = r->y = r->z = 0.0;
    EXPECT_FALSE(si->checkMotion(s1, s2)) << rational;  // rejected, no assertion inside OMPL
    expectInvalid([&] { si->getStateValidityChecker()->clearance(s1); }, "is zero or not finite");
    si->freeState(s1);
    si->freeState(s2);
  }
}

// RationalSE3: the exact CCD ran on every ellipsoid obstacle (10.5 ms per motion among 1,000 far
// ones); a swept ball through the broad phase now picks the candidates.
TEST(ContinuousMotionValidator, ExactEllipsoidPairsOnlyRunAgainstObstaclesNearTheSweep) {
  auto robot = rigidRobot(RobotModel::Base::Free);
  auto env = std::make_shared<Environment>();
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j)
      env->add(std::make_shared<fcl::Ellipsoid<double>>(0.3, 0.2, 0.1), translation(-40.0 + 4.0 * i, -40.0 + 4.0 * j, 30.0));
  env->add(std::make_shared<fcl::Ellipsoid<double>>(0.2, 0.2, 0.2), translation(0, 0, 0));  // on the path
  auto space = makeStateSpace(*robot, Eigen::Vector3d::Constant(-50), Eigen::Vector3d::Constant(50), true);
  auto si = std::make_shared<ob::SpaceInformation>(space);
  installCollisionChecking(si, std::make_shared<RobotCollisionChecker>(robot, env));
  const auto& validator = dynamic_cast<const ContinuousMotionValidator&>(*si->getMotionValidator());
  ob::State* s1 = si->allocState();
  ob::State* s2 = si->allocState();
  for (double y : {0.0, 2.0}) {  // through the ellipsoid at the origin, and beside it
    setSE3(s1, Eigen::Vector3d(-3, y, 0), Eigen::Quaterniond::Identity());
    setSE3(s2, Eigen::Vector3d(3, y, 0), Eigen::Quaterniond(Eigen::AngleAxisd(1.0, Eigen::Vector3d::UnitY())));
    const MotionCheckResult r = validator.check(s1, s2, false);
    EXPECT_EQ(r.valid, oracleFirstCollidingSample(*si, *robot, *env, s1, s2, 2000) < 0.0) << y;
    EXPECT_EQ(r.valid, y != 0.0);
    EXPECT_LE(r.exact_solves, 2u) << y;  // two ellipsoidal bodies, one obstacle near the sweep at most
  }
  si->freeState(s1);
  si->freeState(s2);
}

}  // namespace
}  // namespace test
}  // namespace planning
}  // namespace fcl_quadric
