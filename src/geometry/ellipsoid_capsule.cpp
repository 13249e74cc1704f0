#include "fcl_quadric/geometry/ellipsoid_capsule.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "fcl_quadric/geometry/ellipsoid_polytope.h"
#include "fcl_quadric/geometry/sphere_solid.h"
#include "fcl_quadric/tolerances.h"

namespace fcl_quadric {

SignedDistanceResult signedDistanceEllipsoidCapsule(const Ellipsoid& e, double radius, double length,
                                                    const Eigen::Matrix3d& R_WC, const Eigen::Vector3d& p_WC) {
  if (isSphere(e)) return signedDistanceSphereCapsule(e.center(), e.radii()[0], radius, length, R_WC, p_WC);
  detail::checkLength(radius, "capsule radius");
  detail::checkLength(length, "capsule length");
  detail::checkRotation(R_WC, "capsule rotation");
  detail::checkPosition(p_WC, "capsule centre");
  const Eigen::Vector3d axis = R_WC.col(2) * (0.5 * length);
  const Eigen::Vector3d a = p_WC - axis, b = p_WC + axis;
  SignedDistanceResult d = signedDistanceEllipsoidTriangle(e, a, b, b);  // the segment (exact status)
  if (d.status != Separation::Overlapping) {
    // d.distance = phi(n) = min(n.a, n.b) - n.c - |S R^T n| is a lower bound of the segment's
    // distance (any n gives one), rounded by tau times its absolute evaluation, which includes
    // |n|_1 sum(r) (tolerances.h, "Supports"): enough to certify separation, not overlap.
    const double tau = tolerance::kCertificateRelativeBoundDouble;
    const Eigen::Vector3d& n = d.normal;
    const double band = tau * (std::fabs(d.distance) + radius + std::max(std::fabs(n.dot(a)), std::fabs(n.dot(b))) +
                               std::fabs(n.dot(e.center())) + n.cwiseAbs().sum() * e.radii().sum());
    if (d.status == Separation::Separated && d.distance - radius > band) {
      d.status = Separation::Separated;
    } else {
      // Overlap needs an upper bound of the distance: a point y certified inside the ellipsoid
      // (its surface point pulled towards the centre past the rounding of the unit frame,
      // tolerances.h kUnitFrameRoundingBound) within r of the segment's point.
      const Eigen::Vector3d rel = d.point_a - e.center();
      const double eta =
          detail::unitFrameRounding(e, d.point_a.cwiseAbs().sum() + 2.0 * e.center().cwiseAbs().sum());
      const double margin = 4.0 * eta + 4.0 * tau;
      const Eigen::Vector3d y = e.center() + (1.0 - 2.0 * margin) * rel;
      const double upper = (d.point_b - y).norm();
      const bool inside = e.implicit(y) < -margin;
      const bool covered = upper + tau * (d.point_b.cwiseAbs().sum() + y.cwiseAbs().sum() + upper) < radius;
      d.status = inside && covered ? Separation::Overlapping : Separation::Touching;
    }
  } else if (radius > 0.0) {
    d.status = Separation::Overlapping;  // the segment meets the ellipsoid, the ball adds volume
  }
  d.distance = d.status == Separation::Touching ? 0.0 : d.distance - radius;
  d.point_b -= radius * d.normal;  // capsule surface point facing the ellipsoid
  return d;
}

}  // namespace fcl_quadric
