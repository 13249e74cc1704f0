// fcl_quadric_ompl_plan: plan an ellipsoid-modelled free-flying robot through an OctoMap with
// thin walls and narrow windows, once with fcl_quadric's ContinuousMotionValidator and once with
// OMPL's DiscreteMotionValidator at its default resolution, and replay every edge each validator
// accepted with the certified continuous check (docs/ompl.md).
//
// Usage: fcl_quadric_ompl_plan [--planner rrtconnect|rrtstar|prm] [--time SECONDS] [--seed N]
//                              [--range R] [--robot ROBOT.json] [--out PATH.json]
// --validator picks the runs; --resolution sets the discrete validator's resolution (fraction of
// the space's extent, OMPL's default 0.01). --time bounds each planning run (RRTConnect and PRM stop at the first solution, RRT* uses it
// all); --range is the planner's maximum edge length (RRTConnect / RRT*; 0 = OMPL's default).
// Prints one line per run and writes the continuous run's path (and the statistics) as JSON.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <memory>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <fcl/geometry/shape/ellipsoid.h>
#include <nlohmann/json.hpp>
#include <octomap/OcTree.h>
#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/base/ScopedState.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include "fcl_quadric/ompl/ompl_planning.h"

namespace ob = ompl::base;
namespace og = ompl::geometric;
using namespace fcl_quadric::planning;

namespace {

/// Forwards to another validator and keeps a copy of every motion it accepted (for lastValid
/// calls: the prefix from s1 to the returned last valid state, which the planner may keep).
class RecordingMotionValidator : public ob::MotionValidator {
 public:
  RecordingMotionValidator(const ob::SpaceInformationPtr& si, ob::MotionValidatorPtr inner)
      : ob::MotionValidator(si), inner_(std::move(inner)) {}
  ~RecordingMotionValidator() override {
    for (auto& e : accepted_) si_->freeState(e.first), si_->freeState(e.second);
  }
  bool checkMotion(const ob::State* s1, const ob::State* s2) const override {
    const bool ok = inner_->checkMotion(s1, s2);
    (ok ? valid_ : invalid_)++;
    if (ok) record(s1, s2);
    return ok;
  }
  bool checkMotion(const ob::State* s1, const ob::State* s2, std::pair<ob::State*, double>& lastValid) const override {
    const bool ok = inner_->checkMotion(s1, s2, lastValid);
    (ok ? valid_ : invalid_)++;
    if (ok)
      record(s1, s2);
    else if (lastValid.first != nullptr && lastValid.second > 0.0)
      record(s1, lastValid.first);
    return ok;
  }
  const std::vector<std::pair<ob::State*, ob::State*>>& accepted() const { return accepted_; }

 private:
  // PRM checks motions from two threads (roadmap growth and its solution thread's goal milestones).
  void record(const ob::State* a, const ob::State* b) const {
    std::lock_guard<std::mutex> lock(mutex_);
    accepted_.emplace_back(si_->cloneState(a), si_->cloneState(b));
  }
  mutable std::mutex mutex_;
  ob::MotionValidatorPtr inner_;
  mutable std::vector<std::pair<ob::State*, ob::State*>> accepted_;
};

/// A 6 x 4 x 2 m room (OctoMap, 5 cm voxels) split by two one-voxel-thick walls, each with one
/// narrow window.
std::shared_ptr<octomap::OcTree> makeRoom(double res) {
  auto tree = std::make_shared<octomap::OcTree>(res);
  auto occupy = [&](double x, double y, double z) { tree->updateNode(octomap::point3d(float(x), float(y), float(z)), true); };
  const double h = res / 2;
  for (double y = -2.0 + h; y < 2.0; y += res)
    for (double z = h; z < 2.0; z += res) {
      // Wall 1 at x = -0.6: a window 0.2 m (z) x 0.5 m (y) around (y, z) = (0.8, 1.5).
      if (!(std::abs(y - 0.8) < 0.25 && std::abs(z - 1.5) < 0.1)) occupy(-0.6 + h, y, z);
      // Wall 2 at x = 0.6: a window 0.5 m (z) x 0.2 m (y) around (y, z) = (-0.7, 0.5).
      if (!(std::abs(y + 0.7) < 0.1 && std::abs(z - 0.5) < 0.25)) occupy(0.6 + h, y, z);
    }
  tree->updateInnerOccupancy();
  return tree;
}

/// A small drone: a flat ellipsoid hull and a long thin ellipsoid boom across it.
std::shared_ptr<RobotModel> makeDrone() {
  auto robot = std::make_shared<RobotModel>(RobotModel::Base::Free);
  robot->addBody(0, std::make_shared<fcl::Ellipsoid<double>>(0.09, 0.09, 0.04));
  robot->addBody(0, std::make_shared<fcl::Ellipsoid<double>>(0.015, 0.3, 0.01));
  return robot;
}

struct RunStats {
  std::string validator;
  bool solved = false;
  double time = 0.0, length = 0.0;
  unsigned checks = 0;
  std::size_t accepted = 0, accepted_colliding = 0, path_edges = 0, path_edges_colliding = 0;
  std::vector<std::vector<double>> path;
};

ob::PlannerPtr makePlanner(const std::string& name, const ob::SpaceInformationPtr& si, double range) {
  if (name == "rrtconnect") {
    auto p = std::make_shared<og::RRTConnect>(si);
    if (range > 0.0) p->setRange(range);
    return p;
  }
  if (name == "rrtstar") {
    auto p = std::make_shared<og::RRTstar>(si);
    if (range > 0.0) p->setRange(range);
    return p;
  }
  if (name == "prm") return std::make_shared<og::PRM>(si);
  throw std::invalid_argument("--planner: expected rrtconnect, rrtstar or prm, got " + name);
}

RunStats run(bool continuous, const std::string& planner, double time_limit, double range, double resolution,
             const std::shared_ptr<RobotCollisionChecker>& checker) {
  auto space = makeStateSpace(checker->robot(), Eigen::Vector3d(-3, -2, 0), Eigen::Vector3d(3, 2, 2), true);
  og::SimpleSetup ss(space);
  const ob::SpaceInformationPtr& si = ss.getSpaceInformation();
  si->setStateValidityChecker(std::make_shared<StateValidityChecker>(si, checker));
  ob::MotionValidatorPtr inner;
  if (continuous)
    inner = std::make_shared<ContinuousMotionValidator>(si, checker);
  else
    inner = std::make_shared<ob::DiscreteMotionValidator>(si);
  // The discrete validator's resolution, as a fraction of the space's extent (OMPL: 0.01).
  if (!continuous && resolution > 0.0) si->setStateValidityCheckingResolution(resolution);
  auto recorder = std::make_shared<RecordingMotionValidator>(si, inner);
  si->setMotionValidator(recorder);
  ob::ScopedState<ob::SE3StateSpace> start(space), goal(space);
  start->setXYZ(-2.5, -1.0, 0.6);
  start->rotation().setIdentity();
  goal->setXYZ(2.5, 1.0, 1.4);
  goal->rotation().setIdentity();
  ss.setStartAndGoalStates(start, goal);
  ss.setPlanner(makePlanner(planner, si, range));
  ss.setup();
  const auto t0 = std::chrono::steady_clock::now();
  const ob::PlannerStatus status = ss.solve(time_limit);
  RunStats s;
  s.validator = continuous ? "continuous" : "discrete";
  s.time = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  s.solved = status == ob::PlannerStatus::EXACT_SOLUTION;
  s.checks = recorder->getCheckedMotionCount();
  // Replay every accepted motion with the certified continuous check.
  ContinuousMotionValidator exact(si, checker);
  s.accepted = recorder->accepted().size();
  for (const auto& e : recorder->accepted())
    if (!exact.check(e.first, e.second, true).valid) {
      ++s.accepted_colliding;
      if (continuous) {  // cannot happen unless the validator is wrong: show the motion
        std::fprintf(stderr, "continuous validator accepted a motion its replay rejects:\n");
        si->printState(e.first, std::cerr);
        si->printState(e.second, std::cerr);
      }
    }
  if (s.solved) {
    const og::PathGeometric& p = ss.getSolutionPath();
    s.length = p.length();
    s.path_edges = p.getStateCount() - 1;
    for (std::size_t i = 0; i + 1 < p.getStateCount(); ++i)
      if (!exact.check(p.getState(i), p.getState(i + 1), true).valid) ++s.path_edges_colliding;
    for (std::size_t i = 0; i < p.getStateCount(); ++i) {
      const auto* st = p.getState(i)->as<ob::SE3StateSpace::StateType>();
      s.path.push_back({st->getX(), st->getY(), st->getZ(), st->rotation().x, st->rotation().y, st->rotation().z,
                        st->rotation().w});
    }
  }
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  std::string planner = "rrtconnect", out_path = "ompl_plan_path.json", robot_path;
  double time_limit = 60.0, range = 0.5, resolution = 0.0;
  std::string which = "both";
  unsigned long seed = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "fcl_quadric_ompl_plan: %s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    try {
      if (a == "--planner")
        planner = value();
      else if (a == "--time")
        time_limit = std::stod(value());
      else if (a == "--validator")
        which = value();
      else if (a == "--resolution")
        resolution = std::stod(value());
      else if (a == "--range")
        range = std::stod(value());
      else if (a == "--seed")
        seed = std::stoul(value());
      else if (a == "--out")
        out_path = value();
      else if (a == "--robot")
        robot_path = value();
      else {
        std::fprintf(stderr,
                     "usage: fcl_quadric_ompl_plan [--planner rrtconnect|rrtstar|prm] [--time S] [--range R] [--seed N] "
                     "[--validator both|continuous|discrete] [--resolution F] [--robot ROBOT.json] [--out PATH.json]\n");
        return 2;
      }
    } catch (const std::exception&) {
      std::fprintf(stderr, "fcl_quadric_ompl_plan: bad value for %s\n", a.c_str());
      return 2;
    }
  }
  if (!(time_limit > 0.0)) {
    std::fprintf(stderr, "fcl_quadric_ompl_plan: --time must be positive\n");
    return 2;
  }
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  ompl::RNG::setSeed(seed);
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  try {
    std::shared_ptr<RobotModel> robot;
    if (robot_path.empty()) {
      robot = makeDrone();
    } else {
      std::ifstream in(robot_path);
      if (!in) throw std::invalid_argument("cannot read " + robot_path);
      std::stringstream text;
      text << in.rdbuf();
      robot = std::make_shared<RobotModel>(robotModelFromJson(text.str()));
      if (robot->base() != RobotModel::Base::Free) throw std::invalid_argument("the robot must have a free base");
    }
    auto env = std::make_shared<Environment>();
    auto room = makeRoom(0.05);
    std::size_t occupied = 0;
    for (auto it = room->begin_leafs(); it != room->end_leafs(); ++it) occupied += room->isNodeOccupied(*it);
    env->addOcTree(room);  // merged into maximal boxes (Environment::OcTreeMode::MergedBoxes)
    auto checker = std::make_shared<RobotCollisionChecker>(robot, env);
    std::printf("environment: OctoMap, %zu occupied 5 cm leaves merged into %zu boxes, walls 5 cm thick with 0.2 m "
                "windows; planner %s, %.1f s, range %.2f, seed %lu\n",
                occupied, env->size(), planner.c_str(), time_limit, range, seed);
    nlohmann::ordered_json doc;
    doc["planner"] = planner;
    doc["seed"] = seed;
    doc["range"] = range;
    doc["state_space"] = "RationalSE3 (x, y, z, qx, qy, qz, qw)";
    for (bool continuous : {true, false}) {
      if (which != "both" && which != (continuous ? "continuous" : "discrete")) continue;
      const RunStats s = run(continuous, planner, time_limit, range, resolution, checker);
      std::printf("%-10s solved=%d time=%.3f s path_length=%.4f path_edges=%zu motion_checks=%u accepted_motions=%zu "
                  "accepted_but_colliding=%zu path_edges_colliding=%zu\n",
                  s.validator.c_str(), s.solved, s.time, s.length, s.path_edges, s.checks, s.accepted,
                  s.accepted_colliding, s.path_edges_colliding);
      nlohmann::ordered_json r;
      r["solved"] = s.solved;
      r["planning_time_s"] = s.time;
      r["path_length"] = s.length;
      r["motion_checks"] = s.checks;
      r["accepted_motions"] = s.accepted;
      r["accepted_but_colliding"] = s.accepted_colliding;
      r["path_edges_colliding"] = s.path_edges_colliding;
      r["path"] = s.path;
      doc[s.validator] = r;
    }
    std::ofstream out(out_path);
    out << doc.dump(2) << "\n";
    if (!out) throw std::runtime_error("cannot write " + out_path);
    std::printf("path written to %s\n", out_path.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fcl_quadric_ompl_plan: error: %s\n", e.what());
    return 2;
  }
  return 0;
}
