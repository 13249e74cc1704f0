#include "fcl_quadric/geometry/ellipsoid_capsule.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "fcl_quadric/geometry/ellipsoid_polytope.h"
#include "fcl_quadric/tolerances.h"

namespace fcl_quadric {

SignedDistanceResult signedDistanceEllipsoidCapsule(const Ellipsoid& e, double radius, double length,
                                                    const Eigen::Matrix3d& R_WC, const Eigen::Vector3d& p_WC) {
  for (const auto& [what, v] : {std::pair<const char*, double>{"radius", radius}, {"length", length}}) {
    if (!std::isfinite(v) || !(v >= 0.0)) {
      std::ostringstream os;
      os << "capsule " << what << " must be finite and >= 0, got " << v;
      throw std::invalid_argument(os.str());
    }
  }
  detail::checkRotation(R_WC, "capsule rotation");
  detail::checkFinite(p_WC, "capsule centre");
  const Eigen::Vector3d axis = R_WC.col(2) * (0.5 * length);
  const Eigen::Vector3d a = p_WC - axis, b = p_WC + axis;
  SignedDistanceResult d = signedDistanceEllipsoidTriangle(e, a, b, b);  // the segment (exact status)
  if (d.status == Separation::Separated) {
    const double gap = d.distance - radius;
    const double band = tolerance::kCertificateRelativeBoundDouble * (d.distance + radius);
    d.status = gap > band ? Separation::Separated : (gap < -band ? Separation::Overlapping : Separation::Touching);
  } else if (radius > 0.0) {
    d.status = Separation::Overlapping;  // the segment meets the ellipsoid, the ball adds volume
  }
  d.distance = d.status == Separation::Touching ? 0.0 : d.distance - radius;
  d.point_b -= radius * d.normal;  // capsule surface point facing the ellipsoid
  return d;
}

}  // namespace fcl_quadric
