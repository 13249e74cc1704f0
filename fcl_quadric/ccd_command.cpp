#include "fcl_quadric/ccd_command.h"

#include <algorithm>

#include "fcl_quadric/check_command.h"
#include "fcl_quadric/continuous/dimension_reduction_ccd.h"
#include "fcl_quadric/continuous/region_ccd.h"

namespace fcl_quadric {
namespace cli {

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

SceneError degreeLimitError(const Scene& scene, std::size_t i, std::size_t j, const CcdDegreeError& e) {
  auto degree = [&](std::size_t k) {
    int d = -1;  // an object without a motion ranks below any moving one
    if (scene.objects[k].motion)
      for (const MotionMatrix& m : scene.objects[k].motion->pieces()) d = std::max(d, m.degree());
    return d;
  };
  const std::size_t k = degree(j) > degree(i) ? j : i;
  const std::size_t other = k == i ? j : i;
  const SceneObject& o = scene.objects[k];
  // Polynomial motions are the ones without a linear translation (those from poses have one).
  const bool polynomial = o.motion && !o.motion->pieces().empty() && !o.motion->pieces().front().linearTranslation();
  return SceneError("/objects/" + std::to_string(k) + (polynomial ? "/motion/matrix" : "/motion"),
                    "paired with \"" + scene.objects[other].name + "\": " + e.what());
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
    entry["unresolved"] = r.capped;
    pairs.push_back(std::move(entry));
  }
  nlohmann::ordered_json document;
  document["pairs"] = std::move(pairs);
  return document;
}

}  // namespace

namespace {

PiecewiseMotion motionOf(const SceneObject& object) {
  if (object.motion) return *object.motion;
  return PiecewiseMotion(MotionMatrix::constant(object.pose.linear(), object.pose.translation()));
}

// A pair with a quadric shape or a box: the certified space-time search of region_ccd.h (first
// contact only; the contacting boundary elements labelled per object).
nlohmann::ordered_json regionPair(const SceneObject& a, const SceneObject& b, RegionCcdSolver solver) {
  const auto [ra, ba] = asRegion(a.shape);
  const auto [rb, bb] = asRegion(b.shape);
  if (!ba && !bb) throw SceneError("/pairs", "objects " + a.name + " and " + b.name + " are both unbounded (half-spaces)");
  const MovingRegion ma{ra, ba, motionOf(a)}, mb{rb, bb, motionOf(b)};
  nlohmann::ordered_json entry;
  entry["a"] = a.name;
  entry["b"] = b.name;
  std::string undecided_reason;
  if (solver == RegionCcdSolver::DimensionReduction) {
    if (ba && bb) {
      const ReductionCcdResult d = continuousCollideRegionsByReduction(ma, mb);
      if (d.status == ReductionStatus::Decided) {
        entry["collide"] = d.collide;
        entry["first_contact_time"] = d.collide ? nlohmann::ordered_json(d.time) : nlohmann::ordered_json(nullptr);
        entry["contact_point"] = d.collide ? toJson(d.point) : nlohmann::ordered_json(nullptr);
        entry["overlap_intervals"] = nullptr;
        entry["near_tangent"] = false;  // every candidate is verified through both CSG trees
        entry["unresolved"] = false;
        entry["elements"] = d.collide ? nlohmann::ordered_json::array({d.label_a, d.label_b}) : nlohmann::ordered_json::array();
        entry["method"] = "dimension_reduction";
        return entry;
      }
      undecided_reason = d.reason;
    } else {
      undecided_reason = "an unbounded object (half-space)";
    }
  }
  const RegionCcdResult r = continuousCollideRegions(ma, mb);
  entry["collide"] = r.collide;
  entry["first_contact_time"] = r.collide ? nlohmann::ordered_json(r.time) : nlohmann::ordered_json(nullptr);
  entry["contact_point"] = r.collide ? toJson(r.point) : nlohmann::ordered_json(nullptr);
  entry["overlap_intervals"] = nullptr;  // the region CCD finds the first contact only
  entry["near_tangent"] = r.near_tangent || r.capped;
  entry["unresolved"] = r.capped;
  nlohmann::ordered_json elements = nlohmann::ordered_json::array();
  if (r.collide) {
    auto label = [](const QuadricRegion& region, const std::optional<Box3>& box, const std::vector<int>& active) {
      if (active.empty()) return std::string();
      const Box3 search = box ? *box : Box3{Eigen::Vector3d::Constant(-1e3), Eigen::Vector3d::Constant(1e3)};
      return boundaryElementLabel(boundaryElements(region, search, static_cast<int>(std::min<std::size_t>(active.size(), 3))), active);
    };
    elements.push_back(label(ra, ba, r.active_a));
    elements.push_back(label(rb, bb, r.active_b));
  }
  entry["elements"] = std::move(elements);
  if (solver == RegionCcdSolver::DimensionReduction) {
    entry["method"] = "space_time";
    entry["undecided_reason"] = undecided_reason;
  }
  return entry;
}

}  // namespace

nlohmann::ordered_json ccdScene(const Scene& scene, RegionCcdSolver solver) {
  if (scene.dimension == 2) return ccdScene2(scene);
  CcdOptions options;
  options.all_intervals = scene.ccd.all_intervals;
  options.interpolation = scene.ccd.affine ? CcdInterpolation::Affine : CcdInterpolation::Rigid;
  nlohmann::ordered_json pairs = nlohmann::ordered_json::array();
  for (const auto& [i, j] : scene.pairs) {
    const SceneObject& a = scene.objects.at(i);
    const SceneObject& b = scene.objects.at(j);
    if (!isEllipsoidal(a.shape) || !isEllipsoidal(b.shape)) {
      try {
        pairs.push_back(regionPair(a, b, solver));
      } catch (const CcdDegreeError& e) {
        throw degreeLimitError(scene, i, j, e);
      }
      continue;
    }
    EllipsoidCcdResult r;
    try {
      r = continuousCollideEllipsoids(movingEllipsoid(a, i), movingEllipsoid(b, j), options);
    } catch (const CcdDegreeError& e) {
      throw degreeLimitError(scene, i, j, e);
    }
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
    entry["unresolved"] = r.unresolved;
    pairs.push_back(std::move(entry));
  }
  nlohmann::ordered_json document;
  document["pairs"] = std::move(pairs);
  return document;
}

void runCcd(const std::string& scene_path, std::ostream& out, RegionCcdSolver solver) {
  const Scene scene = readSceneFile(scene_path);
  out << ccdScene(scene, solver).dump(2) << '\n';
}

}  // namespace cli
}  // namespace fcl_quadric
