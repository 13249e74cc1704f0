// StateValidityChecker and ContinuousMotionValidator against independent oracles: pairwise exact
// collide (no broad phase), dense sampling of the space's own interpolate(), bisection of the first
// contact, closed-form contact times, and OMPL's DiscreteMotionValidator on thin walls.
#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>
#include <octomap/OcTree.h>
#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include "fcl_quadric/fcl/quadric_shapes.h"

#include "ompl_support.h"
#include "support/fcl_fixtures.h"

namespace fcl_quadric {
namespace planning {
namespace test {
namespace {

namespace og = ompl::geometric;

// Quiet, and seeded: OMPL's RNG instances draw their seeds from a global seed that otherwise
// changes between runs (the planners of Planning.* use it), which makes failures unreproducible.
struct Quiet {
  Quiet() {
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
    ompl::RNG::setSeed(20261122);
  }
} quiet;

std::shared_ptr<ob::SpaceInformation> makeSi(const ob::StateSpacePtr& space, const std::shared_ptr<RobotModel>& robot,
                                             const std::shared_ptr<Environment>& env,
                                             std::shared_ptr<RobotCollisionChecker>* checker_out = nullptr) {
  auto si = std::make_shared<ob::SpaceInformation>(space);
  auto checker = std::make_shared<RobotCollisionChecker>(robot, env);
  installCollisionChecking(si, checker);
  if (checker_out) *checker_out = checker;
  return si;
}

/// The first contact on [0, 1] by dense sampling then bisection of the bracket (1e-11), or -1.
double oracleFirstContact(const ob::SpaceInformation& si, const RobotModel& robot, const Environment& env,
                          const ob::State* s1, const ob::State* s2, int n = 2000) {
  const double hit = oracleFirstCollidingSample(si, robot, env, s1, s2, n);
  if (hit <= 0.0) return hit;
  double lo = hit - 1.0 / n, hi = hit;
  ob::State* s = si.allocState();
  while (hi - lo > 1e-11) {
    const double mid = 0.5 * (lo + hi);
    si.getStateSpace()->interpolate(s1, s2, mid, s);
    (oracleCollides(robot, env, toConfiguration(*si.getStateSpace(), s)) ? hi : lo) = mid;
  }
  si.freeState(s);
  return hi;
}

const ContinuousMotionValidator& validatorOf(const ob::SpaceInformation& si) {
  return dynamic_cast<const ContinuousMotionValidator&>(*si.getMotionValidator());
}

// ---------------------------------------------------------------------------------------------
// Thin walls: OMPL's DiscreteMotionValidator steps over them, ours does not.
// ---------------------------------------------------------------------------------------------

struct ThinWall {
  std::shared_ptr<RobotModel> robot;
  std::shared_ptr<Environment> env;
  ob::StateSpacePtr space;
  double wall_x = 0.0;
};

/// A sphere robot (r = 0.05) crossing x from -1 to 1; the wall (0.01 thick) sits halfway between
/// two consecutive samples of the discrete validator.
ThinWall thinWall(bool rational) {
  ThinWall w;
  w.robot = std::make_shared<RobotModel>(RobotModel::Base::Free);
  w.robot->addBody(0, std::make_shared<fcl::Sphere<double>>(0.05));
  w.space = makeStateSpace(*w.robot, Eigen::Vector3d::Constant(-5), Eigen::Vector3d::Constant(5), rational);
  ob::State* a = w.space->allocState();
  ob::State* b = w.space->allocState();
  setSE3(a, {-1, 0, 0}, Eigen::Quaterniond::Identity());
  setSE3(b, {1, 0, 0}, Eigen::Quaterniond::Identity());
  auto si = std::make_shared<ob::SpaceInformation>(w.space);
  si->setStateValidityChecker(std::make_shared<ob::AllValidStateValidityChecker>(si));
  si->setup();
  const unsigned n = w.space->validSegmentCount(a, b);
  // Samples at x_k = -1 + 2k/n: the wall goes between the two samples around 0.
  const double k = std::floor(n / 2.0);
  w.wall_x = -1.0 + (2.0 * k + 1.0) / n;
  w.space->freeState(a);
  w.space->freeState(b);
  EXPECT_GT(2.0 / n, 0.1 + 0.01) << "the sample spacing must exceed the sphere diameter plus the wall";
  w.env = std::make_shared<Environment>();
  w.env->add(std::make_shared<fcl::Box<double>>(0.01, 4.0, 4.0), translation(w.wall_x, 0, 0));
  return w;
}

TEST(ContinuousMotionValidator, RejectsATunnelThroughAThinWallThatTheDiscreteValidatorAccepts) {
  for (bool rational : {false, true}) {
    ThinWall w = thinWall(rational);
    auto si = makeSi(w.space, w.robot, w.env);
    auto discrete = std::make_shared<ob::SpaceInformation>(w.space);
    discrete->setStateValidityChecker(si->getStateValidityChecker());
    discrete->setup();  // DiscreteMotionValidator at the default resolution
    ob::ScopedState<> a(w.space), b(w.space);
    setSE3(a.get(), {-1, 0, 0}, Eigen::Quaterniond::Identity());
    setSE3(b.get(), {1, 0, 0}, Eigen::Quaterniond::Identity());
    ASSERT_TRUE(si->isValid(a.get()));
    ASSERT_TRUE(si->isValid(b.get()));
    EXPECT_TRUE(discrete->checkMotion(a.get(), b.get())) << "the scene must defeat the discrete validator";
    EXPECT_FALSE(si->checkMotion(a.get(), b.get()));
    // The true first contact: the sphere's front reaches the wall's face.
    const double t_star = ((w.wall_x - 0.005 - 0.05) + 1.0) / 2.0;
    std::pair<ob::State*, double> last(si->allocState(), -1.0);
    EXPECT_FALSE(si->getMotionValidator()->checkMotion(a.get(), b.get(), last));
    EXPECT_LE(last.second, t_star);
    EXPECT_GT(last.second, t_star - 1e-6);
    EXPECT_FALSE(oracleCollides(*w.robot, *w.env, toConfiguration(*w.space, last.first)));
    EXPECT_TRUE(si->isValid(last.first));
    // Planners may add s1 -> lastValid as an edge: that direct motion must be valid too.
    EXPECT_TRUE(si->checkMotion(a.get(), last.first));
    si->freeState(last.first);
  }
}

TEST(ContinuousMotionValidator, RejectsAJointSweepThroughAThinPostThatTheDiscreteValidatorAccepts) {
  // A one-link arm (ellipsoid of length 1, 4 cm thick) swinging about z; a 4 mm post at radius
  // 0.9 placed halfway between two of the discrete validator's samples.
  auto arm = std::make_shared<RobotModel>(RobotModel::Base::Fixed);
  const std::size_t l =
      arm->addJoint("swing", JointType::Revolute, Eigen::Isometry3d::Identity(), Eigen::Vector3d::UnitZ(), -3, 3);
  arm->addBody(l, std::make_shared<fcl::Ellipsoid<double>>(0.5, 0.02, 0.02), translation(0.5, 0, 0));
  auto space = makeStateSpace(*arm, {}, {});
  ob::ScopedState<> a(space), b(space);
  a[0] = -1.0;
  b[0] = 1.0;
  auto probe = std::make_shared<ob::SpaceInformation>(space);
  probe->setStateValidityChecker(std::make_shared<ob::AllValidStateValidityChecker>(probe));
  probe->setup();
  const unsigned n = space->validSegmentCount(a.get(), b.get());
  const double phi = -1.0 + (2.0 * std::floor(n / 2.0) + 1.0) / n;  // between two samples
  ASSERT_GT(0.9 * std::sin(1.0 / n), 0.02 + 0.002 * std::sqrt(2.0)) << "samples must straddle the post";
  auto env = std::make_shared<Environment>();
  env->add(std::make_shared<fcl::Box<double>>(0.004, 0.004, 1.0), translation(0.9 * std::cos(phi), 0.9 * std::sin(phi), 0));
  auto si = makeSi(space, arm, env);
  auto discrete = std::make_shared<ob::SpaceInformation>(space);
  discrete->setStateValidityChecker(si->getStateValidityChecker());
  discrete->setup();
  EXPECT_TRUE(discrete->checkMotion(a.get(), b.get())) << "the scene must defeat the discrete validator";
  EXPECT_FALSE(si->checkMotion(a.get(), b.get()));
  const double hit = oracleFirstContact(*si, *arm, *env, a.get(), b.get());
  ASSERT_GT(hit, 0.0) << "the oracle must see the sweep hit the post";
  std::pair<ob::State*, double> last(si->allocState(), -1.0);
  EXPECT_FALSE(si->getMotionValidator()->checkMotion(a.get(), b.get(), last));
  EXPECT_LE(last.second, hit);
  EXPECT_GT(last.second, hit - 1e-6);
  EXPECT_FALSE(oracleCollides(*arm, *env, toConfiguration(*space, last.first)));
  si->freeState(last.first);
}

TEST(ContinuousMotionValidator, AcceptsAMotionPassingAMillimetreFromTheWall) {
  ThinWall w = thinWall(true);
  auto si = makeSi(w.space, w.robot, w.env);
  ob::ScopedState<> a(w.space), b(w.space);
  const double x = w.wall_x - 0.005 - 0.05 - 1e-3;
  setSE3(a.get(), {x, -1.5, -1}, Eigen::Quaterniond::Identity());
  setSE3(b.get(), {x, 1.5, 1}, Eigen::Quaterniond(Eigen::AngleAxisd(2.0, Eigen::Vector3d(1, 2, 3).normalized())));
  EXPECT_TRUE(si->checkMotion(a.get(), b.get()));
  EXPECT_LT(oracleFirstCollidingSample(*si, *w.robot, *w.env, a.get(), b.get(), 2000), 0.0);
  // 2e-3 closer it touches.
  setSE3(a.get(), {x + 2e-3, -1.5, -1}, Eigen::Quaterniond::Identity());
  setSE3(b.get(), {x + 2e-3, 1.5, 1}, Eigen::Quaterniond::Identity());
  EXPECT_FALSE(si->checkMotion(a.get(), b.get()));
}

// ---------------------------------------------------------------------------------------------
// lastValid against the true first contact.
// ---------------------------------------------------------------------------------------------

TEST(ContinuousMotionValidator, LastValidOfTheExactEllipsoidPathIsWithin1e6OfTheFirstContact) {
  // Rotating ellipsoid robot (RationalSE3StateSpace) against an ellipsoid obstacle: exact CCD.
  auto robot = rigidRobot(RobotModel::Base::Free);
  auto env = std::make_shared<Environment>();
  env->add(std::make_shared<fcl::Ellipsoid<double>>(0.2, 0.5, 0.3),
           Eigen::Isometry3d(Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitY())));
  auto space = makeStateSpace(*robot, Eigen::Vector3d::Constant(-3), Eigen::Vector3d::Constant(3), true);
  auto si = makeSi(space, robot, env);
  ob::ScopedState<> a(space), b(space);
  setSE3(a.get(), {-1.2, 0.1, 0.05}, Eigen::Quaterniond::Identity());
  setSE3(b.get(), {1.2, -0.1, 0.0}, Eigen::Quaterniond(Eigen::AngleAxisd(2.5, Eigen::Vector3d(0, 0.3, 1).normalized())));
  const double t_star = oracleFirstContact(*si, *robot, *env, a.get(), b.get());
  ASSERT_GT(t_star, 0.05);
  const MotionCheckResult r = validatorOf(*si).check(a.get(), b.get(), false);
  EXPECT_GT(r.exact_solves, 0u);
  EXPECT_FALSE(r.valid);
  EXPECT_LE(r.contact_time, t_star + 1e-10);
  EXPECT_LE(r.last_valid_time, t_star);
  EXPECT_GT(r.last_valid_time, t_star - 1e-6);
  // Through the OMPL interface: lastValid is free, and so is the direct motion a -> lastValid
  // (the quaternion lerp is not sub-path consistent, so that is checked separately).
  std::pair<ob::State*, double> last(si->allocState(), -1.0);
  EXPECT_FALSE(si->getMotionValidator()->checkMotion(a.get(), b.get(), last));
  EXPECT_LE(last.second, t_star);
  EXPECT_FALSE(oracleCollides(*robot, *env, toConfiguration(*space, last.first)));
  EXPECT_TRUE(si->checkMotion(a.get(), last.first));
  EXPECT_LT(oracleFirstCollidingSample(*si, *robot, *env, a.get(), last.first, 2000), 0.0);
  si->freeState(last.first);
}

TEST(ContinuousMotionValidator, LastValidOfSE2AndJointMotionsIsCollisionFreeAndBeforeTheFirstContact) {
  // SE(2): an ellipsoid robot turning into a box corner.
  {
    auto robot = rigidRobot(RobotModel::Base::Planar);
    auto env = std::make_shared<Environment>();
    env->add(std::make_shared<fcl::Box<double>>(0.4, 0.4, 1.0), translation(0.6, 0.3, 0));
    auto space = makeStateSpace(*robot, Eigen::Vector3d::Constant(-3), Eigen::Vector3d::Constant(3));
    auto si = makeSi(space, robot, env);
    ob::ScopedState<> a(space), b(space);
    setSE2(a.get(), -0.5, 0.0, 0.0);
    setSE2(b.get(), 0.9, -0.2, 2.5);
    const double t_star = oracleFirstContact(*si, *robot, *env, a.get(), b.get());
    ASSERT_GT(t_star, 0.05);
    std::pair<ob::State*, double> last(si->allocState(), -1.0);
    EXPECT_FALSE(si->getMotionValidator()->checkMotion(a.get(), b.get(), last));
    EXPECT_LE(last.second, t_star);
    EXPECT_GT(last.second, t_star - 1e-6);
    EXPECT_FALSE(oracleCollides(*robot, *env, toConfiguration(*space, last.first)));
    si->freeState(last.first);
  }
  // Joint space: a 2-link arm sweeping its second link into a post.
  {
    auto arm = std::make_shared<RobotModel>(RobotModel::Base::Fixed);
    arm->addBody(0, std::make_shared<fcl::Sphere<double>>(0.1));
    const std::size_t l1 =
        arm->addJoint("shoulder", JointType::Revolute, Eigen::Isometry3d::Identity(), Eigen::Vector3d::UnitZ(), -3, 3);
    arm->addBody(l1, std::make_shared<fcl::Ellipsoid<double>>(0.45, 0.06, 0.06), translation(0.5, 0, 0));
    const std::size_t l2 = arm->addJoint("elbow", JointType::Revolute, translation(1, 0, 0), Eigen::Vector3d::UnitZ(), -3, 3);
    arm->addBody(l2, std::make_shared<fcl::Ellipsoid<double>>(0.45, 0.06, 0.06), translation(0.5, 0, 0));
    auto env = std::make_shared<Environment>();
    env->add(std::make_shared<fcl::Box<double>>(0.1, 0.1, 1.0), translation(1.2, 0.9, 0));
    auto space = makeStateSpace(*arm, {}, {});
    auto si = makeSi(space, arm, env);
    ob::ScopedState<> a(space), b(space);
    a[0] = -0.3, a[1] = -0.5;
    b[0] = 0.6, b[1] = 1.4;
    const double t_star = oracleFirstContact(*si, *arm, *env, a.get(), b.get());
    ASSERT_GT(t_star, 0.05);
    std::pair<ob::State*, double> last(si->allocState(), -1.0);
    EXPECT_FALSE(si->getMotionValidator()->checkMotion(a.get(), b.get(), last));
    EXPECT_LE(last.second, t_star);
    EXPECT_GT(last.second, t_star - 1e-6);
    EXPECT_FALSE(oracleCollides(*arm, *env, toConfiguration(*space, last.first)));
    si->freeState(last.first);
  }
}

// ---------------------------------------------------------------------------------------------
// Random motions in clutter: never accept what the dense oracle finds colliding.
// ---------------------------------------------------------------------------------------------

std::shared_ptr<Environment> clutter(std::mt19937_64& rng, bool planar) {
  auto env = std::make_shared<Environment>();
  std::uniform_real_distribution<double> pos(-1.5, 1.5), size(0.05, 0.4);
  for (int i = 0; i < 12; ++i) {
    Eigen::Isometry3d X(Eigen::AngleAxisd(pos(rng), Eigen::Vector3d(pos(rng), pos(rng), 1.0).normalized()));
    X.translation() = Eigen::Vector3d(pos(rng), pos(rng), planar ? 0.0 : pos(rng));
    if (i % 3 == 0)
      env->add(std::make_shared<fcl::Box<double>>(size(rng), size(rng), size(rng)), X);
    else if (i % 3 == 1)
      env->add(std::make_shared<fcl::Ellipsoid<double>>(size(rng), size(rng), size(rng)), X);
    else
      env->add(std::make_shared<fcl::Sphere<double>>(size(rng)), X);
  }
  return env;
}

struct OracleCounts {
  int accepted = 0, rejected = 0;
  bool complete = true;  ///< false: no valid start state was found (a scene that boxes the robot in)
};

/// Random valid start states and random goals; checks every answer of the validator against the
/// dense oracle (n samples) and the lastValid contract.
OracleCounts randomMotionsAgainstOracle(const std::shared_ptr<ob::SpaceInformation>& si, const RobotModel& robot,
                                        const Environment& env, int motions, int n,
                                        const std::function<void(ob::State*)>& sample) {
  OracleCounts c;
  ob::ScopedState<> a(si->getStateSpace()), b(si->getStateSpace());
  ob::State* last = si->allocState();
  for (int m = 0; m < motions; ++m) {
    int tries = 0;
    do sample(a.get());
    while (!si->isValid(a.get()) && ++tries < 1000);
    if (tries == 1000) {  // no valid start state (clutter around a fixed base): nothing to test
      c.complete = false;
      break;
    }
    sample(b.get());
    const double hit = oracleFirstCollidingSample(*si, robot, env, a.get(), b.get(), n);
    std::pair<ob::State*, double> lv(last, -1.0);
    const bool ok = si->getMotionValidator()->checkMotion(a.get(), b.get(), lv);
    if (ok) {
      ++c.accepted;
      EXPECT_LT(hit, 0.0) << "motion " << m << " accepted but the oracle collides at t = " << hit;
      continue;
    }
    ++c.rejected;
    EXPECT_FALSE(oracleCollides(robot, env, toConfiguration(*si->getStateSpace(), last))) << "motion " << m;
    if (hit >= 0.0) {
      EXPECT_LE(lv.second, hit) << "motion " << m;
    }
    EXPECT_LT(oracleFirstCollidingSample(*si, robot, env, a.get(), last, 200), 0.0)
        << "motion " << m << ": the prefix up to lastValid collides";
  }
  si->freeState(last);
  return c;
}

/// Both answers must occur (a scene where every motion is accepted, or every one rejected, tests
/// little). `all_scenes_usable`: the scene must also admit valid start states (true for the fixed
/// seed; a random seed may box the fixed-base arm in, and such a scene is skipped).
void expectBoth(const OracleCounts& c, bool all_scenes_usable, const char* what) {
  if (all_scenes_usable) {
    EXPECT_TRUE(c.complete) << what;
  }
  if (!c.complete) return;
  EXPECT_GT(c.accepted, 0) << what;
  EXPECT_GT(c.rejected, 0) << what;
}

void runRandomOracle(int motions, int n, std::uint64_t seed = 2024, bool joints_only = false,
                     bool all_scenes_usable = true) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> pos(-1.8, 1.8), yaw(-M_PI, M_PI);
  // SE(2)
  if (!joints_only) {
    auto robot = rigidRobot(RobotModel::Base::Planar);
    auto env = clutter(rng, true);
    auto si = makeSi(makeStateSpace(*robot, Eigen::Vector3d::Constant(-2), Eigen::Vector3d::Constant(2)), robot, env);
    const OracleCounts c = randomMotionsAgainstOracle(si, *robot, *env, motions, n,
                                                      [&](ob::State* s) { setSE2(s, pos(rng), pos(rng), yaw(rng)); });
    expectBoth(c, all_scenes_usable, "SE(2)");
  }
  // SE(3), slerp (OMPL's SE3StateSpace) and rational (RationalSE3StateSpace, exact ellipsoid pairs).
  for (bool rational : {false, true}) {
    if (joints_only) break;
    auto robot = rigidRobot(RobotModel::Base::Free);
    auto env = clutter(rng, false);
    auto si = makeSi(makeStateSpace(*robot, Eigen::Vector3d::Constant(-2), Eigen::Vector3d::Constant(2), rational),
                     robot, env);
    const OracleCounts c = randomMotionsAgainstOracle(si, *robot, *env, motions, n, [&](ob::State* s) {
      setSE3(s, {pos(rng), pos(rng), pos(rng)}, randomQuaternion(rng));
    });
    expectBoth(c, all_scenes_usable, rational ? "rational" : "slerp");
  }
  // Joint space: 3-link arm with a prismatic middle joint, self-collision included.
  {
    auto arm = std::make_shared<RobotModel>(RobotModel::Base::Fixed);
    arm->addBody(0, std::make_shared<fcl::Sphere<double>>(0.1));
    std::size_t l = arm->addJoint("a", JointType::Revolute, Eigen::Isometry3d::Identity(), Eigen::Vector3d::UnitZ(), -3, 3);
    arm->addBody(l, std::make_shared<fcl::Ellipsoid<double>>(0.4, 0.07, 0.07), translation(0.4, 0, 0));
    l = arm->addJoint("b", JointType::Revolute, translation(0.8, 0, 0), Eigen::Vector3d::UnitY(), -2.5, 2.5);
    arm->addBody(l, std::make_shared<fcl::Ellipsoid<double>>(0.35, 0.06, 0.06), translation(0.35, 0, 0));
    l = arm->addJoint("c", JointType::Prismatic, translation(0.7, 0, 0), Eigen::Vector3d::UnitX(), 0.0, 0.3);
    arm->addBody(l, std::make_shared<fcl::Sphere<double>>(0.08));
    l = arm->addJoint("d", JointType::Revolute, Eigen::Isometry3d::Identity(), Eigen::Vector3d::UnitZ(), -3, 3);
    arm->addBody(l, std::make_shared<fcl::Ellipsoid<double>>(0.3, 0.05, 0.05), translation(0.3, 0, 0));
    auto env = clutter(rng, false);
    auto space = makeStateSpace(*arm, {}, {});
    auto si = makeSi(space, arm, env);
    // Joint values from the test's own generator (OMPL's samplers draw from a global seed that
    // differs between runs, which made a failure of this test unreproducible).
    const ob::RealVectorBounds& bounds = space->as<ob::RealVectorStateSpace>()->getBounds();
    const OracleCounts c = randomMotionsAgainstOracle(si, *arm, *env, motions, n, [&](ob::State* s) {
      for (std::size_t i = 0; i < bounds.low.size(); ++i)
        s->as<ob::RealVectorStateSpace::StateType>()->values[i] =
            std::uniform_real_distribution<double>(bounds.low[i], bounds.high[i])(rng);
    });
    expectBoth(c, all_scenes_usable, "joints");
  }
}

TEST(ContinuousMotionValidator, NeverAcceptsAMotionTheDenseOracleFindsColliding) { runRandomOracle(25, 300); }
TEST(ContinuousMotionValidator, LongNeverAcceptsAMotionTheDenseOracleFindsColliding) { runRandomOracle(300, 3000); }
// The arm's motions in 30 more random scenes (the fixed-seed test above covers one scene per
// space; joint motions are where the validator's conservative bounds do the most work).
TEST(ContinuousMotionValidator, LongJointMotionsInManyScenes) {
  for (int k = 0; k < 30; ++k) {
    SCOPED_TRACE("seed " + std::to_string(k));
    runRandomOracle(100, 300, 1000 + k, true, false);
  }
}

TEST(StateValidityChecker, AgreesWithPairwiseExactCollideAndClearanceWithPairwiseDistance) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> pos(-1.8, 1.8);
  auto robot = rigidRobot(RobotModel::Base::Free);
  auto env = clutter(rng, false);
  auto si = makeSi(makeStateSpace(*robot, Eigen::Vector3d::Constant(-2), Eigen::Vector3d::Constant(2)), robot, env);
  ob::ScopedState<> s(si->getStateSpace());
  int colliding = 0;
  for (int i = 0; i < 300; ++i) {
    setSE3(s.get(), {pos(rng), pos(rng), pos(rng)}, randomQuaternion(rng));
    const Configuration q = toConfiguration(*si->getStateSpace(), s.get());
    const bool oracle = oracleCollides(*robot, *env, q);
    colliding += oracle;
    EXPECT_EQ(si->isValid(s.get()), !oracle) << i;
    // Clearance: the minimum over obstacles of the exact pairwise distance (positive when free).
    if (!oracle) {
      double d = std::numeric_limits<double>::infinity();
      std::vector<Eigen::Isometry3d> X;
      robot->linkPoses(q, X);
      for (const Body& b : robot->bodies(0))
        for (const auto& obj : env->objects()) {
          fcl::DistanceRequest<double> req;
          fcl::DistanceResult<double> res;
          d = std::min(d, fcl_quadric::distance(b.geometry.get(), toFcl(X[0] * b.offset), obj->collisionGeometry().get(),
                                                obj->getTransform(), req, res));
        }
      EXPECT_NEAR(si->getStateValidityChecker()->clearance(s.get()), d, 1e-9) << i;
      EXPECT_GT(d, 0.0);
    } else {
      EXPECT_LE(si->getStateValidityChecker()->clearance(s.get()), 0.0) << i;
    }
  }
  EXPECT_GT(colliding, 20);
  EXPECT_LT(colliding, 280);
}

// A composite quadric obstacle (quadric_shapes.h): a capped elliptic pillar (semi-axes 0.3 x 0.1,
// height 2) at the origin, axis z. A sphere robot (r = 0.05) crossing it along x collides (the
// discrete validator at its default resolution steps over the 0.2-thick pillar along y), one
// passing beside it does not; clearance is a certified lower bound of the closed-form distance of
// the sphere to the pillar's side (a point beside the pillar's flat face, |y| > 0.1).
TEST(Environment, AQuadricShapeObstacleStopsATunnellingMotionAndBoundsTheClearance) {
  auto robot = std::make_shared<RobotModel>(RobotModel::Base::Free);
  robot->addBody(0, std::make_shared<fcl::Sphere<double>>(0.05));
  auto env = std::make_shared<Environment>();
  env->add(std::make_shared<fcl_quadric::EllipticCylinder<double>>(0.3, 0.1, 2.0), Eigen::Isometry3d::Identity());
  const ob::StateSpacePtr space = makeStateSpace(*robot, Eigen::Vector3d::Constant(-5), Eigen::Vector3d::Constant(5), true);
  auto si = makeSi(space, robot, env);
  ob::ScopedState<> a(space), b(space);
  // Through the thin side of the pillar (along y): first contact where the sphere's front reaches
  // y = -0.1 at x = 0.
  setSE3(a.get(), {0, -1, 0}, Eigen::Quaterniond::Identity());
  setSE3(b.get(), {0, 1, 0}, Eigen::Quaterniond::Identity());
  ASSERT_TRUE(si->isValid(a.get()));
  ASSERT_TRUE(si->isValid(b.get()));
  EXPECT_FALSE(si->checkMotion(a.get(), b.get()));
  std::pair<ob::State*, double> last(si->allocState(), -1.0);
  EXPECT_FALSE(si->getMotionValidator()->checkMotion(a.get(), b.get(), last));
  const double t_star = (1.0 - 0.1 - 0.05) / 2.0;
  EXPECT_LE(last.second, t_star);
  EXPECT_GT(last.second, t_star - 1e-3);  // advancement on a lower bound: close, never past
  EXPECT_TRUE(si->isValid(last.first));
  si->freeState(last.first);
  // Beside it (x = 0.4: 0.05 from the pillar's widest point, so 0 < clearance): valid.
  setSE3(a.get(), {0.4, -1, 0}, Eigen::Quaterniond::Identity());
  setSE3(b.get(), {0.4, 1, 0}, Eigen::Quaterniond::Identity());
  EXPECT_TRUE(si->checkMotion(a.get(), b.get()));
  EXPECT_LT(oracleFirstCollidingSample(*si, *robot, *env, a.get(), b.get(), 2000), 0.0);
  // Clearance at (0, 0.5, 0): the pillar's face y = 0.1 is 0.4 away, minus the radius.
  ob::ScopedState<> s(space);
  setSE3(s.get(), {0, 0.5, 0}, Eigen::Quaterniond::Identity());
  const double c = si->getStateValidityChecker()->clearance(s.get());
  EXPECT_LE(c, 0.35 + 1e-9);
  EXPECT_GT(c, 0.3);
}

// A composite quadric robot body (an elliptic rod, semi-axes 0.05 x 0.03, length 0.3, along the
// robot's z) crossing the thin wall of ThinWall: the advancement runs on the certified lower bound
// of the rod against the wall box (regionConvexDistanceLowerBound) and stops just before the
// wall; a motion parallel to the wall, 1 cm from it, is accepted.
TEST(ContinuousMotionValidator, AQuadricShapeBodyIsStoppedByAThinWallAndPassesBesideIt) {
  ThinWall w = thinWall(true);
  auto robot = std::make_shared<RobotModel>(RobotModel::Base::Free);
  robot->addBody(0, std::make_shared<fcl_quadric::EllipticCylinder<double>>(0.05, 0.03, 0.3));
  auto si = makeSi(w.space, robot, w.env);
  ob::ScopedState<> a(w.space), b(w.space);
  setSE3(a.get(), {-1, 0, 0}, Eigen::Quaterniond::Identity());
  setSE3(b.get(), {1, 0, 0}, Eigen::Quaterniond::Identity());
  ASSERT_TRUE(si->isValid(a.get()));
  ASSERT_TRUE(si->isValid(b.get()));
  EXPECT_FALSE(si->checkMotion(a.get(), b.get()));
  std::pair<ob::State*, double> last(si->allocState(), -1.0);
  EXPECT_FALSE(si->getMotionValidator()->checkMotion(a.get(), b.get(), last));
  // First contact: the rod's face x = +0.05 reaches the wall's face wall_x - 0.005.
  const double t_star = ((w.wall_x - 0.005 - 0.05) + 1.0) / 2.0;
  EXPECT_LE(last.second, t_star);
  EXPECT_GT(last.second, t_star - 1e-3);
  EXPECT_TRUE(si->isValid(last.first));
  si->freeState(last.first);
  // Parallel to the wall, 1 cm from it: valid, and clearance a certified lower bound of 0.01.
  const double x = w.wall_x - 0.005 - 0.05 - 0.01;
  setSE3(a.get(), {x, -1.5, -1}, Eigen::Quaterniond::Identity());
  setSE3(b.get(), {x, 1.5, 1}, Eigen::Quaterniond::Identity());
  EXPECT_TRUE(si->checkMotion(a.get(), b.get()));
  const double c = si->getStateValidityChecker()->clearance(a.get());
  EXPECT_LE(c, 0.01 + 1e-9);
  EXPECT_GT(c, 0.005);
}

// Two composite models: the elliptic rod (semi-axes 0.05 x 0.03, length 0.3) against the elliptic
// pillar (0.3 x 0.1, height 2): the pillar is the convex partner of the bound.
TEST(ContinuousMotionValidator, AQuadricShapeBodyAgainstAQuadricShapeObstacle) {
  auto robot = std::make_shared<RobotModel>(RobotModel::Base::Free);
  robot->addBody(0, std::make_shared<fcl_quadric::EllipticCylinder<double>>(0.05, 0.03, 0.3));
  auto env = std::make_shared<Environment>();
  env->add(std::make_shared<fcl_quadric::EllipticCylinder<double>>(0.3, 0.1, 2.0), Eigen::Isometry3d::Identity());
  const ob::StateSpacePtr space = makeStateSpace(*robot, Eigen::Vector3d::Constant(-5), Eigen::Vector3d::Constant(5), true);
  auto si = makeSi(space, robot, env);
  ob::ScopedState<> a(space), b(space);
  setSE3(a.get(), {0, -1, 0}, Eigen::Quaterniond::Identity());
  setSE3(b.get(), {0, 1, 0}, Eigen::Quaterniond::Identity());
  std::pair<ob::State*, double> last(si->allocState(), -1.0);
  EXPECT_FALSE(si->getMotionValidator()->checkMotion(a.get(), b.get(), last));
  const double t_star = (1.0 - 0.1 - 0.03) / 2.0;  // the rod's y semi-axis 0.03 meets the face y = -0.1
  EXPECT_LE(last.second, t_star);
  EXPECT_GT(last.second, t_star - 1e-3);
  si->freeState(last.first);
  setSE3(a.get(), {0.4, -1, 0}, Eigen::Quaterniond::Identity());  // 0.05 beyond the pillar's x extent
  setSE3(b.get(), {0.4, 1, 0}, Eigen::Quaterniond::Identity());
  EXPECT_TRUE(si->checkMotion(a.get(), b.get()));
}

// A convex composite body against a thin *mesh* wall (two triangles in the plane x = 0.3): the
// advancement runs on the GJK distance of the rod to the mesh (docs/algorithms.md section 12),
// which fcl_quadric::distance refused before; it stops just before the wall, and a motion parallel
// to it, 1 cm away, is accepted with a clearance of 1 cm.
TEST(ContinuousMotionValidator, AQuadricShapeBodyIsStoppedByAThinMeshWallAndPassesBesideIt) {
  auto wall = std::make_shared<fcl::BVHModel<fcl::OBBRSS<double>>>();
  wall->beginModel();
  wall->addTriangle(Eigen::Vector3d(0.3, -3, -3), Eigen::Vector3d(0.3, 3, -3), Eigen::Vector3d(0.3, 3, 3));
  wall->addTriangle(Eigen::Vector3d(0.3, -3, -3), Eigen::Vector3d(0.3, 3, 3), Eigen::Vector3d(0.3, -3, 3));
  wall->endModel();
  auto env = std::make_shared<Environment>();
  env->add(wall, Eigen::Isometry3d::Identity());
  auto robot = std::make_shared<RobotModel>(RobotModel::Base::Free);
  robot->addBody(0, std::make_shared<fcl_quadric::EllipticCylinder<double>>(0.05, 0.03, 0.3));
  const ob::StateSpacePtr space = makeStateSpace(*robot, Eigen::Vector3d::Constant(-5), Eigen::Vector3d::Constant(5), true);
  auto si = makeSi(space, robot, env);
  ob::ScopedState<> a(space), b(space);
  setSE3(a.get(), {-1, 0, 0}, Eigen::Quaterniond::Identity());
  setSE3(b.get(), {1, 0, 0}, Eigen::Quaterniond::Identity());
  ASSERT_TRUE(si->isValid(a.get()));
  ASSERT_TRUE(si->isValid(b.get()));
  std::pair<ob::State*, double> last(si->allocState(), -1.0);
  EXPECT_FALSE(si->getMotionValidator()->checkMotion(a.get(), b.get(), last));
  const double t_star = ((0.3 - 0.05) + 1.0) / 2.0;  // the rod's face x = +0.05 reaches the wall
  EXPECT_LE(last.second, t_star);
  EXPECT_GT(last.second, t_star - 1e-6);
  EXPECT_TRUE(si->isValid(last.first));
  si->freeState(last.first);
  setSE3(a.get(), {0.24, -1.5, -1}, Eigen::Quaterniond::Identity());
  setSE3(b.get(), {0.24, 1.5, 1}, Eigen::Quaterniond::Identity());
  EXPECT_TRUE(si->checkMotion(a.get(), b.get()));
  EXPECT_NEAR(si->getStateValidityChecker()->clearance(a.get()), 0.01, 1e-9);
}

TEST(Environment, OcTreeMergedAndLeafBoxesAgreeWithTheFclOcTreeAndStopATunnellingMotion) {
  // A one-voxel (5 cm) wall of an octomap with a window; the same tree as merged boxes (default),
  // leaf boxes and one fcl::OcTree must give the same validity and clearance.
  auto tree = std::make_shared<octomap::OcTree>(0.05);
  for (double y = -0.975; y < 1.0; y += 0.05)
    for (double z = -0.975; z < 1.0; z += 0.05)
      if (!(std::abs(y) < 0.2 && std::abs(z) < 0.2)) tree->updateNode(octomap::point3d(0.025f, float(y), float(z)), true);
  tree->updateInnerOccupancy();
  auto boxes = std::make_shared<Environment>();
  auto leaves = std::make_shared<Environment>();
  auto whole = std::make_shared<Environment>();
  const std::size_t merged = boxes->addOcTree(tree);
  EXPECT_LE(merged, 8u);  // a wall with a window: a few maximal boxes
  EXPECT_GT(leaves->addOcTree(tree, Eigen::Isometry3d::Identity(), Environment::OcTreeMode::LeafBoxes), 1000u);
  EXPECT_EQ(whole->addOcTree(tree, Eigen::Isometry3d::Identity(), Environment::OcTreeMode::WholeTree), 1u);
  auto robot = rigidRobot(RobotModel::Base::Free, 0.5);
  RobotCollisionChecker a(robot, boxes), b(robot, whole), c(robot, leaves);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> pos(-0.6, 0.6);
  int colliding = 0;
  for (int i = 0; i < 200; ++i) {
    Configuration q;
    q.base.linear() = randomQuaternion(rng).toRotationMatrix();
    q.base.translation() = Eigen::Vector3d(0.3 * pos(rng), pos(rng), pos(rng));
    const bool valid = a.isValid(q);
    colliding += !valid;
    EXPECT_EQ(valid, b.isValid(q)) << i;
    EXPECT_EQ(valid, c.isValid(q)) << i;
    EXPECT_EQ(valid, !oracleCollides(*robot, *whole, q)) << i;
    if (valid) {
      EXPECT_NEAR(a.clearance(q), b.clearance(q), 1e-9) << i;
      EXPECT_NEAR(c.clearance(q), b.clearance(q), 1e-12) << i;
    }
  }
  EXPECT_GT(colliding, 10);
  EXPECT_LT(colliding, 190);
  // Through the wall beside the window: rejected; through the window: accepted.
  auto space = makeStateSpace(*robot, Eigen::Vector3d::Constant(-2), Eigen::Vector3d::Constant(2));
  auto si = makeSi(space, robot, boxes);
  ob::ScopedState<> s1(space), s2(space);
  setSE3(s1.get(), {-0.5, 0.6, 0}, Eigen::Quaterniond::Identity());
  setSE3(s2.get(), {0.5, 0.6, 0}, Eigen::Quaterniond::Identity());
  EXPECT_FALSE(si->checkMotion(s1.get(), s2.get()));
  setSE3(s1.get(), {-0.5, 0, 0}, Eigen::Quaterniond::Identity());
  setSE3(s2.get(), {0.5, 0, 0}, Eigen::Quaterniond::Identity());
  EXPECT_TRUE(si->checkMotion(s1.get(), s2.get()));
  EXPECT_LT(oracleFirstCollidingSample(*si, *robot, *whole, s1.get(), s2.get(), 500), 0.0);
}

TEST(Environment, PrunedOcTreeLeavesOfEverySizeMergeIntoTheSameSolid) {
  // A 1.6 m occupied cube on the octree grid (pruned into one leaf of 32 voxels) plus a 0.4 m
  // cube (leaves of 8 voxels, split and merged) and a few single voxels.
  auto tree = std::make_shared<octomap::OcTree>(0.05);
  for (double x = 0.025; x < 1.6; x += 0.05)
    for (double y = 0.025; y < 1.6; y += 0.05)
      for (double z = 0.025; z < 1.6; z += 0.05) tree->updateNode(octomap::point3d(float(x), float(y), float(z)), true);
  for (double x = -0.375; x < 0.0; x += 0.05)
    for (double y = -0.375; y < 0.0; y += 0.05)
      for (double z = -0.375; z < 0.0; z += 0.05) tree->updateNode(octomap::point3d(float(x), float(y), float(z)), true);
  for (double x : {-0.975, -0.575, 1.825}) tree->updateNode(octomap::point3d(float(x), 0.625f, 0.525f), true);
  tree->updateInnerOccupancy();
  tree->prune();
  auto merged = std::make_shared<Environment>();
  auto whole = std::make_shared<Environment>();
  EXPECT_LE(merged->addOcTree(tree), 10u);
  whole->addOcTree(tree, Eigen::Isometry3d::Identity(), Environment::OcTreeMode::WholeTree);
  auto robot = rigidRobot(RobotModel::Base::Free, 0.5);
  RobotCollisionChecker a(robot, merged), b(robot, whole);
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> pos(-1.2, 2.2);
  int colliding = 0;
  for (int i = 0; i < 300; ++i) {
    Configuration q;
    q.base.linear() = randomQuaternion(rng).toRotationMatrix();
    q.base.translation() = Eigen::Vector3d(pos(rng), pos(rng), pos(rng));
    const bool valid = a.isValid(q);
    colliding += !valid;
    EXPECT_EQ(valid, b.isValid(q)) << i;
    if (valid) {
      EXPECT_NEAR(a.clearance(q), b.clearance(q), 1e-9) << i;
    }
  }
  EXPECT_GT(colliding, 30);
  EXPECT_LT(colliding, 270);
}

// ---------------------------------------------------------------------------------------------
// Self-collision with allowed pairs.
// ---------------------------------------------------------------------------------------------

std::shared_ptr<RobotModel> foldingArm(bool allow_1_3) {
  // No body on the base: the only self pair is (1, 3).
  auto arm = std::make_shared<RobotModel>(RobotModel::Base::Fixed);
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
  for (int i = 0; i < 3; ++i) {
    const std::size_t l = arm->addJoint("j" + std::to_string(i), JointType::Revolute, origin, Eigen::Vector3d::UnitZ(), -3, 3);
    arm->addBody(l, std::make_shared<fcl::Ellipsoid<double>>(0.45, 0.06, 0.06), translation(0.5, 0, 0));
    origin = translation(1.0, 0, 0);
  }
  if (allow_1_3) arm->allowCollision(1, 3);
  return arm;
}

TEST(ContinuousMotionValidator, SelfCollisionOfNonAdjacentLinksHonoursAllowedPairs) {
  auto env = std::make_shared<Environment>();
  for (bool allow : {false, true}) {
    auto arm = foldingArm(allow);
    auto space = makeStateSpace(*arm, {}, {});
    auto si = makeSi(space, arm, env);
    ob::ScopedState<> a(space), b(space);
    a[0] = 0.0, a[1] = 0.0, a[2] = 0.0;
    b[0] = 0.0, b[1] = 2.9, b[2] = 2.9;  // link 3 folds back across link 1
    const double hit = oracleFirstCollidingSample(*si, *arm, *env, a.get(), b.get(), 2000);
    if (!allow) {
      ASSERT_GE(hit, 0.0) << "the fold must self-collide";
      EXPECT_FALSE(si->isValid(b.get()));
      std::pair<ob::State*, double> last(si->allocState(), -1.0);
      EXPECT_FALSE(si->getMotionValidator()->checkMotion(a.get(), b.get(), last));
      EXPECT_LE(last.second, hit);
      EXPECT_FALSE(oracleCollides(*arm, *env, toConfiguration(*space, last.first)));
      si->freeState(last.first);
    } else {
      ASSERT_LT(hit, 0.0) << "with (1, 3) allowed the fold is free";
      EXPECT_TRUE(si->isValid(b.get()));
      EXPECT_TRUE(si->checkMotion(a.get(), b.get()));
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Planning through SimpleSetup with unchanged OMPL planners.
// ---------------------------------------------------------------------------------------------

TEST(Planning, PlannersSolveAThinWallGapProblemAndTheContinuousPathIsDenselyCollisionFree) {
  auto robot = rigidRobot(RobotModel::Base::Planar);
  auto env = std::make_shared<Environment>();
  // A wall at x = 0 (2 cm thick) with a 0.4 m gap around y = 0.8.
  env->add(std::make_shared<fcl::Box<double>>(0.02, 2.2, 1.0), translation(0, -0.9, 0));
  env->add(std::make_shared<fcl::Box<double>>(0.02, 0.6, 1.0), translation(0, 1.7, 0));
  auto space = makeStateSpace(*robot, Eigen::Vector3d::Constant(-2), Eigen::Vector3d::Constant(2));
  for (int which = 0; which < 3; ++which) {
    og::SimpleSetup ss(space);
    auto checker = std::make_shared<RobotCollisionChecker>(robot, env);
    installCollisionChecking(ss.getSpaceInformation(), checker);
    ob::ScopedState<> start(space), goal(space);
    setSE2(start.get(), -1.2, -1.0, 0.3);
    setSE2(goal.get(), 1.2, -1.0, -0.4);
    ss.setStartAndGoalStates(start, goal);
    const auto& si = ss.getSpaceInformation();
    if (which == 0) ss.setPlanner(std::make_shared<og::RRTConnect>(si));
    if (which == 1) ss.setPlanner(std::make_shared<og::PRM>(si));
    if (which == 2) ss.setPlanner(std::make_shared<og::RRTstar>(si));
    const ob::PlannerStatus status = ss.solve(which == 2 ? 1.0 : 5.0);
    ASSERT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION) << ss.getPlanner()->getName();
    const og::PathGeometric& path = ss.getSolutionPath();
    for (std::size_t i = 0; i + 1 < path.getStateCount(); ++i)
      EXPECT_LT(oracleFirstCollidingSample(*si, *robot, *env, path.getState(i), path.getState(i + 1), 500), 0.0)
          << ss.getPlanner()->getName() << " edge " << i;
    EXPECT_GT(validatorOf(*si).getCheckedMotionCount(), 0u);
  }
  // The same problem with OMPL's DiscreteMotionValidator (same validity checker) also solves.
  og::SimpleSetup ss(space);
  const auto& si = ss.getSpaceInformation();
  si->setStateValidityChecker(
      std::make_shared<StateValidityChecker>(si, std::make_shared<RobotCollisionChecker>(robot, env)));
  ob::ScopedState<> start(space), goal(space);
  setSE2(start.get(), -1.2, -1.0, 0.3);
  setSE2(goal.get(), 1.2, -1.0, -0.4);
  ss.setStartAndGoalStates(start, goal);
  ss.setPlanner(std::make_shared<og::RRTConnect>(si));
  ASSERT_EQ(ss.solve(5.0), ob::PlannerStatus::EXACT_SOLUTION);
  EXPECT_NE(dynamic_cast<const ob::DiscreteMotionValidator*>(si->getMotionValidator().get()), nullptr);
}

// A non-convex link (a ring: ellipsoid minus bore) threaded on a thin mesh pole: sliding along the
// pole is valid although the pole lies inside the ring's convex cover all the way; sliding
// sideways stops where the bore wall meets the pole's edges. Before distanceLowerBound covered
// non-convex shapes against meshes, both motions threw.
TEST(ContinuousMotionValidator, ARingLinkSlidesAlongAThinMeshPoleAndStopsAgainstIt) {
  const auto pole = fcl_quadric::test::meshOf(fcl_quadric::test::poleTriangles(0.1, 3.0));
  auto env = std::make_shared<Environment>();
  env->add(pole, Eigen::Isometry3d::Identity());
  auto outer = std::make_shared<Quadric<double>>(Quadric<double>::ellipsoid(1.0, 1.0, 0.4));
  auto bore = std::make_shared<Quadric<double>>(Quadric<double>::ellipticCylinder(0.5, 0.5));
  auto ring = std::make_shared<QuadricCSG<double>>(
      QuadricRegion::Op::Difference,
      std::vector<QuadricCSG<double>::Child>{{outer, fcl::Transform3d::Identity()}, {bore, fcl::Transform3d::Identity()}});
  auto robot = std::make_shared<RobotModel>(RobotModel::Base::Free);
  robot->addBody(0, ring);
  const ob::StateSpacePtr space = makeStateSpace(*robot, Eigen::Vector3d::Constant(-5), Eigen::Vector3d::Constant(5), true);
  auto si = makeSi(space, robot, env);
  ob::ScopedState<> a(space), b(space);
  setSE3(a.get(), {0, 0, -1.5}, Eigen::Quaterniond::Identity());
  setSE3(b.get(), {0.1, 0, 1.5}, Eigen::Quaterniond::Identity());
  ASSERT_TRUE(si->isValid(a.get()));
  EXPECT_TRUE(si->checkMotion(a.get(), b.get()));
  EXPECT_GT(si->getStateValidityChecker()->clearance(a.get()), 0.35);
  // Sideways: the bore wall (radius 0.5 about the ring's centre (x, 0)) meets the pole's vertices
  // at 120 and 240 degrees, (-0.05, +-0.0866), when (x + 0.05)^2 + 0.0075 = 0.25.
  setSE3(a.get(), {0, 0, 0}, Eigen::Quaterniond::Identity());
  setSE3(b.get(), {1, 0, 0}, Eigen::Quaterniond::Identity());
  std::pair<ob::State*, double> last(si->allocState(), -1.0);
  EXPECT_FALSE(si->getMotionValidator()->checkMotion(a.get(), b.get(), last));
  const double t_star = std::sqrt(0.25 - 0.0075) - 0.05;
  EXPECT_LE(last.second, t_star);
  EXPECT_GT(last.second, t_star - 1e-6);
  EXPECT_TRUE(si->isValid(last.first));
  si->freeState(last.first);
}


}  // namespace
}  // namespace test
}  // namespace planning
}  // namespace fcl_quadric
