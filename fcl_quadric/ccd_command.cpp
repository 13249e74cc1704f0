#include "fcl_quadric/ccd_command.h"

namespace fcl_quadric {
namespace cli {

namespace {

nlohmann::ordered_json toJson(const Eigen::Vector3d& v) { return nlohmann::ordered_json::array({v[0], v[1], v[2]}); }

}  // namespace

MovingEllipsoid movingEllipsoid(const SceneObject& object, std::size_t index) {
  if (!isEllipsoidal(object.shape)) {
    throw SceneError("/objects/" + std::to_string(index) + "/shape",
                     std::string("ccd handles ellipsoids and spheres; object \"") + object.name + "\" is a " +
                         toString(object.shape.type));
  }
  const Ellipsoid body(object.shape.dimensions, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
  if (object.motion) return MovingEllipsoid{body, *object.motion};
  return MovingEllipsoid{body, PiecewiseMotion(MotionMatrix::constant(object.pose.linear(), object.pose.translation()))};
}

MovingEllipse2 movingEllipse2(const SceneObject& object) {
  return MovingEllipse2(object.shape.dimensions[0], object.shape.dimensions[1], object.motion2);
}

namespace {

nlohmann::ordered_json ccdScene2(const Scene& scene) {
  nlohmann::ordered_json pairs = nlohmann::ordered_json::array();
  const EllipseCcdQuery query = scene.ccd.all_intervals ? EllipseCcdQuery::AllContacts : EllipseCcdQuery::FirstContact;
  for (const auto& [i, j] : scene.pairs) {
    const SceneObject& a = scene.objects.at(i);
    const SceneObject& b = scene.objects.at(j);
    const MovingEllipse2 ea = movingEllipse2(a), eb = movingEllipse2(b);
    const EllipseCcdResult r = collideMovingEllipses(ea, eb, query);
    nlohmann::ordered_json entry;
    entry["a"] = a.name;
    entry["b"] = b.name;
    entry["collide"] = r.collide;
    entry["first_contact_time"] = r.first_contact ? nlohmann::ordered_json(*r.first_contact) : nullptr;
    entry["contact_point"] = r.first_contact_point_valid
                                 ? nlohmann::ordered_json::array({r.first_contact_point[0], r.first_contact_point[1]})
                                 : nlohmann::ordered_json(nullptr);
    nlohmann::ordered_json intervals = nlohmann::ordered_json::array();
    if (scene.ccd.all_intervals) {
      for (const auto& [t0, t1] : r.collision_intervals) intervals.push_back({t0, t1});
    } else if (r.first_contact) {
      intervals.push_back({*r.first_contact, *r.first_contact});
    }
    entry["overlap_intervals"] = std::move(intervals);
    bool unverified = r.capped;
    for (const EllipseContact& c : r.contacts) unverified = unverified || !c.verified;
    entry["near_tangent"] = unverified;
    pairs.push_back(std::move(entry));
  }
  nlohmann::ordered_json document;
  document["pairs"] = std::move(pairs);
  return document;
}

}  // namespace

nlohmann::ordered_json ccdScene(const Scene& scene) {
  if (scene.dimension == 2) return ccdScene2(scene);
  CcdOptions options;
  options.all_intervals = scene.ccd.all_intervals;
  options.interpolation = scene.ccd.affine ? CcdInterpolation::Affine : CcdInterpolation::Rigid;
  nlohmann::ordered_json pairs = nlohmann::ordered_json::array();
  for (const auto& [i, j] : scene.pairs) {
    const SceneObject& a = scene.objects.at(i);
    const SceneObject& b = scene.objects.at(j);
    const EllipsoidCcdResult r = continuousCollideEllipsoids(movingEllipsoid(a, i), movingEllipsoid(b, j), options);
    nlohmann::ordered_json entry;
    entry["a"] = a.name;
    entry["b"] = b.name;
    entry["collide"] = r.collide;
    entry["first_contact_time"] = r.first_contact_time ? nlohmann::ordered_json(*r.first_contact_time) : nullptr;
    entry["contact_point"] = r.collide ? toJson(r.contact_point) : nlohmann::ordered_json(nullptr);
    nlohmann::ordered_json intervals = nlohmann::ordered_json::array();
    for (const CcdInterval& c : r.collision_intervals) intervals.push_back({c.begin, c.end});
    entry["overlap_intervals"] = std::move(intervals);
    entry["near_tangent"] = r.near_tangent || r.unresolved;
    pairs.push_back(std::move(entry));
  }
  nlohmann::ordered_json document;
  document["pairs"] = std::move(pairs);
  return document;
}

void runCcd(const std::string& scene_path, std::ostream& out) {
  const Scene scene = readSceneFile(scene_path);
  out << ccdScene(scene).dump(2) << '\n';
}

}  // namespace cli
}  // namespace fcl_quadric
