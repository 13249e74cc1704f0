// RobotModel: builder, forward kinematics, reach bounds; robotModelFromJson.
#include "fcl_quadric/ompl/robot_model.h"
#include "finite.h"
#include "geometry_checks.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/sphere.h>
#include <nlohmann/json.hpp>

namespace fcl_quadric {
namespace planning {

namespace {

bool finite(const Eigen::Isometry3d& X) { return detail::allFinite(X.matrix()); }

bool rigid(const Eigen::Isometry3d& X) {
  const Eigen::Matrix3d R = X.linear();
  return (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() <= 1e-9 && R.determinant() > 0.0;
}

void checkPose(const Eigen::Isometry3d& X, const std::string& what) {
  if (!finite(X)) throw std::invalid_argument("RobotModel: " + what + " is not finite");
  if (!rigid(X)) throw std::invalid_argument("RobotModel: " + what + " is not a rigid transform (rotation part not orthonormal with det 1)");
}

std::string num(double v) {
  std::ostringstream os;
  os.precision(17);
  os << v;
  return os.str();
}

}  // namespace

RobotModel::RobotModel(Base base) : base_(base), bodies_(1) {}

void RobotModel::setFixedBasePose(const Eigen::Isometry3d& pose) {
  checkPose(pose, "fixed base pose");
  fixed_base_pose_ = pose;
}

std::size_t RobotModel::addJoint(const std::string& name, JointType type, const Eigen::Isometry3d& origin,
                                 const Eigen::Vector3d& axis, double lower, double upper) {
  if (base_ != Base::Fixed)
    throw std::invalid_argument("RobotModel::addJoint(\"" + name +
                                "\"): joints need a Fixed base (a Planar / Free robot is one rigid body)");
  if (name.empty()) throw std::invalid_argument("RobotModel::addJoint: empty joint name");
  for (const Joint& j : joints_)
    if (j.name == name) throw std::invalid_argument("RobotModel::addJoint: duplicate joint name \"" + name + "\"");
  checkPose(origin, "origin of joint \"" + name + "\"");
  if (!detail::allFinite(axis) || axis.norm() < 1e-12)
    throw std::invalid_argument("RobotModel::addJoint(\"" + name + "\"): axis must be finite and non-zero");
  if (!std::isfinite(lower) || !std::isfinite(upper) || lower > upper)
    throw std::invalid_argument("RobotModel::addJoint(\"" + name + "\"): limits must be finite with lower <= upper, got [" +
                                num(lower) + ", " + num(upper) + "]");
  Joint j;
  j.name = name;
  j.type = type;
  j.origin = origin;
  j.axis = axis.normalized();
  j.lower = lower;
  j.upper = upper;
  joints_.push_back(j);
  bodies_.emplace_back();
  rebuildPairs();
  return bodies_.size() - 1;
}

void RobotModel::addBody(std::size_t link, std::shared_ptr<fcl::CollisionGeometry<double>> geometry,
                         const Eigen::Isometry3d& offset) {
  if (link >= bodies_.size())
    throw std::invalid_argument("RobotModel::addBody: link " + std::to_string(link) + " out of range (robot has " +
                                std::to_string(bodies_.size()) + " links)");
  if (!geometry) throw std::invalid_argument("RobotModel::addBody: null geometry for link " + std::to_string(link));
  detail::checkSupportedGeometry(*geometry, "RobotModel::addBody: body on link " + std::to_string(link));
  checkPose(offset, "body offset on link " + std::to_string(link));
  // A sphere body is stored as the ellipsoid with equal radii: QuadricSolver then answers it with
  // the exact ellipsoid algorithms against every shape (FCL's signed sphere-box distance, for
  // one, is libccd's iterative GJK), which the motion certificate relies on.
  if (const auto* sphere = dynamic_cast<const fcl::Sphere<double>*>(geometry.get()))
    geometry = std::make_shared<fcl::Ellipsoid<double>>(sphere->radius, sphere->radius, sphere->radius);
  Body b;
  b.geometry = geometry;
  b.offset = offset;
  if (const auto* e = dynamic_cast<const fcl::Ellipsoid<double>*>(geometry.get())) {
    b.ball_centre = offset.translation();
    b.ball_radius = e->radii.maxCoeff();
  } else if (const auto* s = dynamic_cast<const fcl::Sphere<double>*>(geometry.get())) {
    b.ball_centre = offset.translation();
    b.ball_radius = s->radius;
  } else {
    geometry->computeLocalAABB();
    b.ball_centre = offset * geometry->aabb_center;
    b.ball_radius = geometry->aabb_radius;
  }
  if (!detail::allFinite(b.ball_centre) || !std::isfinite(b.ball_radius) || b.ball_radius < 0.0)
    throw std::invalid_argument("RobotModel::addBody: geometry on link " + std::to_string(link) +
                                " has a non-finite bounding ball (radius " + num(b.ball_radius) + ")");
  bodies_[link].push_back(b);
  rebuildPairs();
}

void RobotModel::allowCollision(std::size_t a, std::size_t b) {
  if (a >= bodies_.size() || b >= bodies_.size() || a == b)
    throw std::invalid_argument("RobotModel::allowCollision: bad link pair (" + std::to_string(a) + ", " +
                                std::to_string(b) + ") for a robot with " + std::to_string(bodies_.size()) + " links");
  allowed_.emplace_back(std::min(a, b), std::max(a, b));
  rebuildPairs();
}

void RobotModel::rebuildPairs() {
  self_pairs_.clear();
  for (std::size_t a = 0; a < bodies_.size(); ++a)
    for (std::size_t b = a + 2; b < bodies_.size(); ++b) {
      if (bodies_[a].empty() || bodies_[b].empty()) continue;
      if (std::find(allowed_.begin(), allowed_.end(), std::make_pair(a, b)) != allowed_.end()) continue;
      self_pairs_.emplace_back(a, b);
    }
}

void RobotModel::linkPoses(const Configuration& q, std::vector<Eigen::Isometry3d>& poses) const {
  poses.resize(bodies_.size());
  if (base_ != Base::Fixed) {
    if (!finite(q.base)) throw std::invalid_argument("RobotModel::linkPoses: base pose is not finite");
    poses[0] = q.base;
    return;
  }
  if (q.joints.size() != joints_.size())
    throw std::invalid_argument("RobotModel::linkPoses: configuration has " + std::to_string(q.joints.size()) +
                                " joint values, the robot has " + std::to_string(joints_.size()) + " joints");
  poses[0] = fixed_base_pose_;
  for (std::size_t i = 0; i < joints_.size(); ++i) {
    const Joint& j = joints_[i];
    const double v = q.joints[i];
    if (!std::isfinite(v))
      throw std::invalid_argument("RobotModel::linkPoses: value of joint \"" + j.name + "\" is not finite");
    Eigen::Isometry3d J = Eigen::Isometry3d::Identity();
    if (j.type == JointType::Revolute)
      J.linear() = Eigen::AngleAxisd(v, j.axis).toRotationMatrix();
    else
      J.translation() = v * j.axis;
    poses[i + 1] = poses[i] * j.origin * J;
  }
}

double RobotModel::chainLength(std::size_t joint, std::size_t link) const {
  if (joint >= joints_.size() || link <= joint || link >= bodies_.size())
    throw std::invalid_argument("RobotModel::chainLength: need joint < link < linkCount(), got joint " +
                                std::to_string(joint) + ", link " + std::to_string(link));
  double L = 0.0;
  for (std::size_t i = joint + 1; i < link; ++i) {
    L += joints_[i].origin.translation().norm();
    if (joints_[i].type == JointType::Prismatic) L += std::max(std::abs(joints_[i].lower), std::abs(joints_[i].upper));
  }
  return L;
}

void RobotModel::validate() const {
  bool any = false;
  for (const auto& l : bodies_) any = any || !l.empty();
  if (!any) throw std::invalid_argument("RobotModel: the robot has no collision body");
  if (base_ == Base::Fixed && joints_.empty())
    throw std::invalid_argument("RobotModel: a Fixed-base robot needs at least one joint");
}

// ---------------------------------------------------------------------------------------------
// JSON
// ---------------------------------------------------------------------------------------------
namespace {

using nlohmann::json;

[[noreturn]] void bad(const std::string& pointer, const std::string& what) {
  throw std::invalid_argument("robot JSON " + pointer + ": " + what);
}

double number(const json& j, const std::string& ptr) {
  if (!j.is_number()) bad(ptr, "expected a number, got " + j.dump());
  const double v = j.get<double>();
  if (!std::isfinite(v)) bad(ptr, "not finite");
  return v;
}

Eigen::Vector3d vec3(const json& parent, const char* key, const std::string& ptr, const Eigen::Vector3d& dflt) {
  if (!parent.contains(key)) return dflt;
  const json& j = parent.at(key);
  const std::string p = ptr + "/" + key;
  if (!j.is_array() || j.size() != 3) bad(p, "expected an array of 3 numbers, got " + j.dump());
  return {number(j[0], p + "/0"), number(j[1], p + "/1"), number(j[2], p + "/2")};
}

Eigen::Isometry3d pose(const json& j, const std::string& ptr) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = vec3(j, "translation", ptr, Eigen::Vector3d::Zero());
  const Eigen::Vector3d rpy = vec3(j, "rpy", ptr, Eigen::Vector3d::Zero());
  X.linear() = (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  return X;
}

double positive(const json& parent, const char* key, const std::string& ptr) {
  if (!parent.contains(key)) bad(ptr, std::string("missing \"") + key + "\"");
  const double v = number(parent.at(key), ptr + "/" + key);
  if (!(v > 0.0)) bad(ptr + "/" + key, "must be positive, got " + num(v));
  return v;
}

std::shared_ptr<fcl::CollisionGeometry<double>> shape(const json& j, const std::string& ptr) {
  if (!j.contains("shape") || !j.at("shape").is_string()) bad(ptr, "missing string \"shape\"");
  const std::string s = j.at("shape").get<std::string>();
  if (s == "ellipsoid") {
    const Eigen::Vector3d r = vec3(j, "radii", ptr, Eigen::Vector3d::Zero());
    if (!(r.minCoeff() > 0.0)) bad(ptr + "/radii", "radii must be positive");
    return std::make_shared<fcl::Ellipsoid<double>>(r);
  }
  if (s == "sphere") return std::make_shared<fcl::Sphere<double>>(positive(j, "radius", ptr));
  if (s == "box") {
    const Eigen::Vector3d e = vec3(j, "size", ptr, Eigen::Vector3d::Zero());
    if (!(e.minCoeff() > 0.0)) bad(ptr + "/size", "sizes must be positive");
    return std::make_shared<fcl::Box<double>>(e);
  }
  if (s == "capsule") return std::make_shared<fcl::Capsule<double>>(positive(j, "radius", ptr), positive(j, "length", ptr));
  if (s == "cylinder")
    return std::make_shared<fcl::Cylinder<double>>(positive(j, "radius", ptr), positive(j, "length", ptr));
  bad(ptr + "/shape", "unknown shape \"" + s + "\" (ellipsoid, sphere, box, capsule, cylinder)");
}

}  // namespace

RobotModel robotModelFromJson(const std::string& json_text) {
  json doc;
  try {
    doc = json::parse(json_text);
  } catch (const json::parse_error& e) {
    throw std::invalid_argument(std::string("robot JSON: parse error: ") + e.what());
  } catch (const json::exception& e) {  // e.g. out_of_range 406: a number such as 1e999 overflows a double
    throw std::invalid_argument(std::string("robot JSON: ") + e.what());
  }
  if (!doc.is_object()) bad("", "the document must be an object");
  RobotModel::Base base = RobotModel::Base::Free;
  if (doc.contains("base")) {
    const json& b = doc.at("base");
    const std::string s = b.is_string() ? b.get<std::string>() : b.dump();
    if (s == "fixed")
      base = RobotModel::Base::Fixed;
    else if (s == "planar")
      base = RobotModel::Base::Planar;
    else if (s == "free")
      base = RobotModel::Base::Free;
    else
      bad("/base", "expected \"fixed\", \"planar\" or \"free\", got " + b.dump());
  }
  RobotModel model(base);
  if (doc.contains("base_pose")) model.setFixedBasePose(pose(doc.at("base_pose"), "/base_pose"));
  if (doc.contains("joints")) {
    const json& js = doc.at("joints");
    if (!js.is_array()) bad("/joints", "expected an array");
    for (std::size_t i = 0; i < js.size(); ++i) {
      const json& j = js[i];
      const std::string p = "/joints/" + std::to_string(i);
      if (!j.is_object()) bad(p, "expected an object");
      const std::string name = j.contains("name") && j.at("name").is_string() ? j.at("name").get<std::string>() : "";
      std::string type = j.contains("type") && j.at("type").is_string() ? j.at("type").get<std::string>() : "";
      if (type != "revolute" && type != "prismatic") bad(p + "/type", "expected \"revolute\" or \"prismatic\"");
      if (!j.contains("limits") || !j.at("limits").is_array() || j.at("limits").size() != 2)
        bad(p + "/limits", "expected [lower, upper]");
      const double lo = number(j.at("limits")[0], p + "/limits/0");
      const double hi = number(j.at("limits")[1], p + "/limits/1");
      try {
        model.addJoint(name, type == "revolute" ? JointType::Revolute : JointType::Prismatic, pose(j, p),
                       vec3(j, "axis", p, Eigen::Vector3d::UnitZ()), lo, hi);
      } catch (const std::invalid_argument& e) {
        bad(p, e.what());
      }
    }
  }
  if (!doc.contains("bodies") || !doc.at("bodies").is_array()) bad("/bodies", "expected an array of bodies");
  const json& bs = doc.at("bodies");
  for (std::size_t i = 0; i < bs.size(); ++i) {
    const json& b = bs[i];
    const std::string p = "/bodies/" + std::to_string(i);
    if (!b.is_object()) bad(p, "expected an object");
    double link = b.contains("link") ? number(b.at("link"), p + "/link") : 0.0;
    if (link < 0 || link != std::floor(link) || link >= static_cast<double>(model.linkCount()))
      bad(p + "/link", "expected a link index in [0, " + std::to_string(model.linkCount()) + "), got " + num(link));
    try {
      model.addBody(static_cast<std::size_t>(link), shape(b, p), pose(b, p));
    } catch (const std::invalid_argument& e) {
      if (std::string(e.what()).rfind("robot JSON", 0) == 0) throw;
      bad(p, e.what());
    }
  }
  if (doc.contains("allowed_collisions")) {
    const json& ac = doc.at("allowed_collisions");
    if (!ac.is_array()) bad("/allowed_collisions", "expected an array of [a, b] pairs");
    for (std::size_t i = 0; i < ac.size(); ++i) {
      const std::string p = "/allowed_collisions/" + std::to_string(i);
      if (!ac[i].is_array() || ac[i].size() != 2 || !ac[i][0].is_number_unsigned() || !ac[i][1].is_number_unsigned())
        bad(p, "expected a pair of link indices, got " + ac[i].dump());
      try {
        model.allowCollision(ac[i][0].get<std::size_t>(), ac[i][1].get<std::size_t>());
      } catch (const std::invalid_argument& e) {
        bad(p, e.what());
      }
    }
  }
  model.validate();
  return model;
}

}  // namespace planning
}  // namespace fcl_quadric
