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
// Prints one line per run and writes both runs' paths (and the statistics) as JSON, and a picture
// of the room and the paths (--picture, default ompl_plan_path.png; "" for none; needs the CLI's
// Cairo helpers, i.e. FCL_QUADRIC_BUILD_CLI).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iomanip>
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
#ifdef FCL_QUADRIC_PLAN_PICTURE
#include <Eigen/Eigenvalues>

#include "fcl_quadric/picture.h"
#endif

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

/// A wall of the room: one voxel thick at x = wall_x (its voxels span [x, x + res]), with one
/// window centred at (y, z) of half-sizes (hy, hz).
struct Wall {
  double x, y, z, hy, hz;
};
// Wall 1: a window 0.5 m (y) x 0.2 m (z) around (0.8, 1.5); wall 2: 0.2 m (y) x 0.5 m (z) around
// (-0.7, 0.5).
constexpr Wall kWalls[2] = {{-0.6, 0.8, 1.5, 0.25, 0.1}, {0.6, -0.7, 0.5, 0.1, 0.25}};

/// A 6 x 4 x 2 m room (OctoMap, 5 cm voxels) split by the two walls.
std::shared_ptr<octomap::OcTree> makeRoom(double res) {
  auto tree = std::make_shared<octomap::OcTree>(res);
  auto occupy = [&](double x, double y, double z) { tree->updateNode(octomap::point3d(float(x), float(y), float(z)), true); };
  const double h = res / 2;
  for (double y = -2.0 + h; y < 2.0; y += res)
    for (double z = h; z < 2.0; z += res)
      for (const Wall& w : kWalls)
        if (!(std::abs(y - w.y) < w.hy && std::abs(z - w.z) < w.hz)) occupy(w.x + h, y, z);
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
  std::vector<std::size_t> colliding_edges;  // indices of path edges the certified replay rejects
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
      if (!exact.check(p.getState(i), p.getState(i + 1), true).valid) {
        ++s.path_edges_colliding;
        s.colliding_edges.push_back(i);
      }
    for (std::size_t i = 0; i < p.getStateCount(); ++i) {
      const auto* st = p.getState(i)->as<ob::SE3StateSpace::StateType>();
      s.path.push_back({st->getX(), st->getY(), st->getZ(), st->rotation().x, st->rotation().y, st->rotation().z,
                        st->rotation().w});
    }
  }
  return s;
}


#ifdef FCL_QUADRIC_PLAN_PICTURE
/// The room and the paths in three orthographic views: top (x, y), side (x, z), and along x
/// (y, z), where both walls overlap and their windows are outlined. Occupied voxels in grey, the
/// continuous validator's path in blue and the discrete one's dashed in orange, with the edges the
/// certified replay rejects in red. The robot's ellipsoids (projected outlines) are drawn at the
/// start, the goal, and where each path crosses a wall plane, at the pose of the planner's own
/// interpolation (linear position, normalised linear quaternion: RationalSE3StateSpace). Uses the
/// CLI's Cairo helpers (fcl_quadric/picture.h).
void writePicture(const std::string& file, const octomap::OcTree& room, const RobotModel& robot,
                  const std::vector<RunStats>& runs) {
  namespace cli = fcl_quadric::cli;
  struct View {
    int u, v;  // world axes shown horizontally and vertically
    const char* title;
  };
  const View views[3] = {{0, 1, "top view (x right, y up)"}, {0, 2, "side view (x right, z up)"},
                         {1, 2, "along x (y right, z up): walls overlap, windows outlined"}};
  const double lo[3] = {-3, -2, 0}, hi[3] = {3, 2, 2};
  const double scale = 110.0, margin = 36.0, gap = 40.0, title_h = 22.0;
  double width = margin, height = 0;
  double x0[3];
  for (int k = 0; k < 3; ++k) {
    x0[k] = width;
    width += (hi[views[k].u] - lo[views[k].u]) * scale + (k < 2 ? gap : margin);
    height = std::max(height, (hi[views[k].v] - lo[views[k].v]) * scale);
  }
  const double legend_h = 28.0;
  const double total_h = margin + title_h + height + legend_h + margin;
  const cli::Rgb wall{0.3, 0.31, 0.35};
  const cli::Rgb continuous{0.1, 0.35, 0.85}, discrete{0.95, 0.55, 0.1}, clash{0.85, 0.1, 0.1};
  cli::writePicture(file, static_cast<int>(width), static_cast<int>(total_h), [&](cairo_t* cr) {
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    for (int k = 0; k < 3; ++k) {
      const View& w = views[k];
      const double top = margin + title_h;
      auto X = [&](double a) { return x0[k] + (a - lo[w.u]) * scale; };
      auto Y = [&](double b) { return top + (hi[w.v] - b) * scale; };
      cli::setColour(cr, cli::kText);
      cli::setFont(cr, 13, true);
      cli::text(cr, w.title, x0[k], margin + 12);
      // Frame of the room.
      cairo_set_line_width(cr, 1.0);
      cli::setColour(cr, cli::kText, 0.6);
      cairo_rectangle(cr, X(lo[w.u]), Y(hi[w.v]), (hi[w.u] - lo[w.u]) * scale, (hi[w.v] - lo[w.v]) * scale);
      cairo_stroke(cr);
      // Occupied voxels (projected; light alpha, so that overlaps darken).
      for (auto it = room.begin_leafs(); it != room.end_leafs(); ++it) {
        if (!room.isNodeOccupied(*it)) continue;
        const double c[3] = {it.getX(), it.getY(), it.getZ()};
        const double h = 0.5 * it.getSize();
        cli::setColour(cr, wall, k == 2 ? 0.1 : 0.08);
        cairo_rectangle(cr, X(c[w.u] - h), Y(c[w.v] + h), 2 * h * scale, 2 * h * scale);
        cairo_fill(cr);
      }
      if (k == 2) {  // the windows, outlined and labelled
        for (int i = 0; i < 2; ++i) {
          const Wall& wl = kWalls[i];
          cli::setColour(cr, cli::kText);
          cairo_set_line_width(cr, 1.5);
          cairo_rectangle(cr, X(wl.y - wl.hy), Y(wl.z + wl.hz), 2 * wl.hy * scale, 2 * wl.hz * scale);
          cairo_stroke(cr);
          cli::setFont(cr, 11);
          std::ostringstream label;
          label << "window of wall " << i + 1 << " (x = " << wl.x << ")";
          // Wall 1's label above its window, wall 2's below (clear of the start marker).
          const double ly = i == 0 ? Y(wl.z + wl.hz) - 5 : Y(wl.z - wl.hz) + 14;
          cli::haloText(cr, label.str(), X(wl.y - wl.hy), ly, cli::kText);
        }
      }
      // Paths: discrete first, continuous on top.
      for (auto order : {1, 0}) {
        if (order >= static_cast<int>(runs.size())) continue;
        const RunStats& r = runs[order];
        if (!r.solved || r.path.size() < 2) continue;
        const bool is_continuous = r.validator == "continuous";
        for (std::size_t i = 0; i + 1 < r.path.size(); ++i) {
          const bool bad = std::find(r.colliding_edges.begin(), r.colliding_edges.end(), i) != r.colliding_edges.end();
          cli::setColour(cr, bad ? clash : (is_continuous ? continuous : discrete));
          cairo_set_line_width(cr, bad ? 3.0 : 2.0);
          if (!is_continuous && !bad) {
            const double dash[] = {6.0, 4.0};
            cairo_set_dash(cr, dash, 2, 0);
          }
          cairo_move_to(cr, X(r.path[i][w.u]), Y(r.path[i][w.v]));
          cairo_line_to(cr, X(r.path[i + 1][w.u]), Y(r.path[i + 1][w.v]));
          cairo_stroke(cr);
          cairo_set_dash(cr, nullptr, 0, 0);
        }
        // Poses to draw: the ends, and each crossing of a wall plane (x = wall centre) on an edge.
        std::vector<std::vector<double>> poses{r.path.front(), r.path.back()};
        for (std::size_t i = 0; i + 1 < r.path.size(); ++i) {
          const std::vector<double>&a = r.path[i], &b = r.path[i + 1];
          for (const Wall& wl : kWalls) {
            const double xw = wl.x + 0.025;
            if ((a[0] - xw) * (b[0] - xw) >= 0.0) continue;
            const double t = (xw - a[0]) / (b[0] - a[0]);
            std::vector<double> q(7);
            for (int j = 0; j < 7; ++j) q[j] = (1 - t) * a[j] + t * b[j];  // quaternions: same hemisphere
            poses.push_back(q);
          }
        }
        const cli::Rgb& body_colour = is_continuous ? continuous : discrete;
        // The robot's ellipsoids: the projection of {x : (x-c)^T S^-1 (x-c) <= 1},
        // S = R diag(r^2) R^T, is the ellipse of the 2x2 block of S.
        for (const auto& q : poses) {
          Eigen::Isometry3d base = Eigen::Isometry3d::Identity();
          base.translation() = Eigen::Vector3d(q[0], q[1], q[2]);
          base.linear() = Eigen::Quaterniond(q[6], q[3], q[4], q[5]).normalized().toRotationMatrix();
          for (const Body& b : robot.bodies(0)) {
            const auto* e = dynamic_cast<const fcl::Ellipsoid<double>*>(b.geometry.get());
            if (e == nullptr) continue;
            const Eigen::Isometry3d Xb = base * b.offset;
            const Eigen::Matrix3d S = Xb.linear() * e->radii.cwiseAbs2().asDiagonal() * Xb.linear().transpose();
            Eigen::Matrix2d S2;
            S2 << S(w.u, w.u), S(w.u, w.v), S(w.v, w.u), S(w.v, w.v);
            Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(S2);
            const Eigen::Vector2d ax = es.eigenvalues().cwiseMax(0.0).cwiseSqrt();
            const double angle = std::atan2(es.eigenvectors()(1, 0), es.eigenvectors()(0, 0));
            cairo_save(cr);
            cairo_translate(cr, X(Xb.translation()[w.u]), Y(Xb.translation()[w.v]));
            cairo_rotate(cr, -angle);  // picture y points down
            cairo_scale(cr, std::max(ax[0] * scale, 0.3), std::max(ax[1] * scale, 0.3));
            cairo_arc(cr, 0, 0, 1, 0, 2 * M_PI);
            cairo_restore(cr);
            cli::setColour(cr, body_colour, 0.2);
            cairo_fill_preserve(cr);
            cli::setColour(cr, body_colour, 0.9);
            cairo_set_line_width(cr, 0.8);
            cairo_stroke(cr);
          }
        }
      }
      // Start and goal.
      for (const auto& [p, label] : {std::pair(Eigen::Vector3d(-2.5, -1.0, 0.6), "start"),
                                     std::pair(Eigen::Vector3d(2.5, 1.0, 1.4), "goal")}) {
        cli::setColour(cr, cli::kText);
        cairo_arc(cr, X(p[w.u]), Y(p[w.v]), 4, 0, 2 * M_PI);
        cairo_fill(cr);
        cli::setFont(cr, 11);
        cli::haloText(cr, label, X(p[w.u]) + 7, Y(p[w.v]) - 6, cli::kText);
      }
    }
    // Legend.
    const double ly = margin + title_h + height + 20;
    double lx = margin;
    cli::setFont(cr, 12);
    auto item = [&](const cli::Rgb& c, bool dashed, const std::string& label) {
      cli::setColour(cr, c);
      cairo_set_line_width(cr, 2.0);
      if (dashed) {
        const double dash[] = {6.0, 4.0};
        cairo_set_dash(cr, dash, 2, 0);
      }
      cairo_move_to(cr, lx, ly - 4);
      cairo_line_to(cr, lx + 28, ly - 4);
      cairo_stroke(cr);
      cairo_set_dash(cr, nullptr, 0, 0);
      cli::setColour(cr, cli::kText);
      cli::text(cr, label, lx + 34, ly);
      lx += 34 + cli::textWidth(cr, label) + 24;
    };
    for (const RunStats& r : runs) {
      std::ostringstream label;
      label << r.validator << " validator: " << (r.solved ? "" : "no solution, ") << r.path_edges << " edges, length "
            << std::fixed << std::setprecision(2) << r.length << ", " << r.path_edges_colliding << " colliding";
      item(r.validator == "continuous" ? continuous : discrete, r.validator != "continuous", label.str());
    }
    item(clash, false, "edge that clips a wall (certified replay)");
  });
}
#endif

}  // namespace

int main(int argc, char** argv) {
  std::string planner = "rrtconnect", out_path = "ompl_plan_path.json", robot_path, picture_path = "ompl_plan_path.png";
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
      else if (a == "--picture")
        picture_path = value();
      else {
        std::fprintf(stderr,
                     "usage: fcl_quadric_ompl_plan [--planner rrtconnect|rrtstar|prm] [--time S] [--range R] [--seed N] "
                     "[--validator both|continuous|discrete] [--resolution F] [--robot ROBOT.json] [--out PATH.json] "
                     "[--picture PATH.png|.svg]\n");
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
    std::vector<RunStats> runs;
    for (bool continuous : {true, false}) {
      if (which != "both" && which != (continuous ? "continuous" : "discrete")) continue;
      runs.push_back(run(continuous, planner, time_limit, range, resolution, checker));
      const RunStats& s = runs.back();
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
#ifdef FCL_QUADRIC_PLAN_PICTURE
    if (!picture_path.empty()) {
      writePicture(picture_path, *room, *robot, runs);
      std::printf("picture written to %s\n", picture_path.c_str());
    }
#endif
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fcl_quadric_ompl_plan: error: %s\n", e.what());
    return 2;
  }
  return 0;
}
