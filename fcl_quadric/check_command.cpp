#include "fcl_quadric/check_command.h"

#include "fcl_quadric/fcl_fallback.h"
#include "fcl_quadric/geometry/ellipsoid_polytope.h"
#include "fcl_quadric/geometry/signed_distance.h"

namespace fcl_quadric {
namespace cli {

namespace {

nlohmann::ordered_json toJson(const Eigen::Vector3d& v) { return nlohmann::ordered_json::array({v[0], v[1], v[2]}); }

}  // namespace

PairReport exactPairReport(const Ellipsoid& a, const Ellipsoid& b) {
  const SeparationCertificate certificate = classifyEllipsoids(a, b);
  const SignedDistanceResult distance = signedDistance(a, b);
  PairReport report;
  report.method = PairMethod::Exact;
  report.status = certificate.status;
  report.collide = certificate.status != Separation::Separated;
  report.signed_distance = distance.distance;
  report.point_a = distance.point_a;
  report.point_b = distance.point_b;
  report.normal = distance.normal;
  return report;
}

PairReport exactBoxReport(const Ellipsoid& e, const SceneObject& box, bool box_first) {
  const Eigen::Vector3d half = 0.5 * box.shape.dimensions;  // the scene stores full side lengths
  const Eigen::Matrix3d R = box.pose.linear();
  const Eigen::Vector3d p = box.pose.translation();
  const Separation status = classifyEllipsoidBox(e, half, R, p).status;
  const SignedDistanceResult d = signedDistanceEllipsoidBox(e, half, R, p);  // normal from e to the box
  PairReport report;
  report.method = PairMethod::Exact;
  report.status = status;
  report.collide = status != Separation::Separated;
  report.signed_distance = d.distance;
  report.point_a = box_first ? d.point_b : d.point_a;
  report.point_b = box_first ? d.point_a : d.point_b;
  report.normal = box_first ? Eigen::Vector3d(-d.normal) : d.normal;
  return report;
}

PairReport evaluatePair(const SceneObject& a, const SceneObject& b) {
  const bool ea = isEllipsoidal(a.shape), eb = isEllipsoidal(b.shape);
  if (ea && eb) return exactPairReport(toEllipsoid(a), toEllipsoid(b));
  if (ea) return exactBoxReport(toEllipsoid(a), b, /*box_first=*/false);
  if (eb) return exactBoxReport(toEllipsoid(b), a, /*box_first=*/true);
  return fclPairReport(a, b);  // box-box
}

nlohmann::ordered_json checkScene(const Scene& scene) {
  nlohmann::ordered_json pairs = nlohmann::ordered_json::array();
  for (const auto& [i, j] : scene.pairs) {
    const SceneObject& a = scene.objects.at(i);
    const SceneObject& b = scene.objects.at(j);
    const PairReport r = evaluatePair(a, b);
    nlohmann::ordered_json entry;
    entry["a"] = a.name;
    entry["b"] = b.name;
    entry["status"] = toString(r.status);
    entry["collide"] = r.collide;
    entry["signed_distance"] = r.signed_distance;
    entry["points"] = nlohmann::ordered_json::array({toJson(r.point_a), toJson(r.point_b)});
    entry["normal"] = toJson(r.normal);
    entry["method"] = toString(r.method);
    pairs.push_back(std::move(entry));
  }
  nlohmann::ordered_json document;
  document["pairs"] = std::move(pairs);
  return document;
}

void runCheck(const std::string& scene_path, std::ostream& out) {
  const Scene scene = readSceneFile(scene_path);
  if (scene.dimension != 3) throw SceneError("/dimension", "check handles 3D scenes; a 2D scene of ellipses is for ccd");
  const std::string text = checkScene(scene).dump(2);
  out << text << '\n';
}

}  // namespace cli
}  // namespace fcl_quadric
