// The only translation unit of the program that instantiates FCL's collision and distance
// templates (~30 s to compile): keep FCL out of every other file.
#include "fcl_quadric/fcl_fallback.h"

#include <memory>

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

namespace fcl_quadric {
namespace cli {

namespace {

std::shared_ptr<fcl::CollisionGeometryd> makeGeometry(const Shape& shape) {
  const Eigen::Vector3d& d = shape.dimensions;
  switch (shape.type) {
    case ShapeType::Ellipsoid: return std::make_shared<fcl::Ellipsoidd>(d[0], d[1], d[2]);
    case ShapeType::Sphere: return std::make_shared<fcl::Sphered>(d[0]);
    case ShapeType::Box: return std::make_shared<fcl::Boxd>(d[0], d[1], d[2]);
    case ShapeType::Ellipse: break;  // 2D scenes never reach FCL (check rejects them)
    case ShapeType::EllipticCylinder:
    case ShapeType::Cylinder:
    case ShapeType::Halfspace:
    case ShapeType::Quadric:
    case ShapeType::Csg: break;  // quadric shapes go to quadricRegionReport, never to FCL
  }
  return nullptr;
}

/// Sets *out to the unit vector along v; false (and *out untouched) when v is too short to have
/// a direction at this scale.
bool unit(const Eigen::Vector3d& v, double scale, Eigen::Vector3d* out) {
  const double n = v.norm();
  if (!(n > 1e-12 * scale)) return false;
  *out = v / n;
  return true;
}

}  // namespace

PairReport fclPairReport(const SceneObject& a, const SceneObject& b) {
  const auto geometry_a = makeGeometry(a.shape);
  const auto geometry_b = makeGeometry(b.shape);
  const fcl::Transform3d& X_a = a.pose;
  const fcl::Transform3d& X_b = b.pose;

  fcl::CollisionRequestd collision_request;
  collision_request.enable_contact = true;
  collision_request.num_max_contacts = 1;
  collision_request.gjk_solver_type = fcl::GST_LIBCCD;
  fcl::CollisionResultd collision_result;
  fcl::collide(geometry_a.get(), X_a, geometry_b.get(), X_b, collision_request, collision_result);

  fcl::DistanceRequestd distance_request(/*enable_nearest_points=*/true, /*enable_signed_distance=*/true);
  distance_request.gjk_solver_type = fcl::GST_LIBCCD;
  distance_request.distance_tolerance = 1e-9;
  fcl::DistanceResultd distance_result;
  fcl::distance(geometry_a.get(), X_a, geometry_b.get(), X_b, distance_request, distance_result);

  PairReport report;
  report.method = PairMethod::Fcl;
  report.collide = collision_result.isCollision();
  report.status = report.collide ? Separation::Overlapping : Separation::Separated;
  report.signed_distance = distance_result.min_distance;
  report.point_a = distance_result.nearest_points[0];
  report.point_b = distance_result.nearest_points[1];

  // Scale for "the witness points coincide": the size of the configuration.
  const double scale = a.shape.dimensions.maxCoeff() + b.shape.dimensions.maxCoeff() +
                       (X_b.translation() - X_a.translation()).norm();
  const Eigen::Vector3d gap = report.point_b - report.point_a;
  Eigen::Vector3d normal;
  if (unit(report.signed_distance >= 0.0 ? gap : Eigen::Vector3d(-gap), scale, &normal)) {
    report.normal = normal;
  } else if (collision_result.numContacts() > 0 &&
             unit(collision_result.getContact(0).normal, 1.0, &normal)) {
    report.normal = normal;  // FCL's contact normal points from o1 to o2
  } else if (unit(X_b.translation() - X_a.translation(), scale, &normal)) {
    report.normal = normal;
  }
  return report;
}

}  // namespace cli
}  // namespace fcl_quadric
