#include "fcl_quadric/geometry/ellipsoid_region_distance.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "fcl_quadric/algebra/quadric_matrix.h"
#include "fcl_quadric/geometry/ellipsoid_polytope.h"
#include "fcl_quadric/tolerances.h"

namespace fcl_quadric {

namespace {

/// Is the ellipsoid e, scaled by s about its centre, certified separate from the region?
bool scaledSeparated(const Ellipsoid& e, double s, const QuadricRegion& region, const Box3& region_box,
                     const Eigen::Matrix3d& R, const Eigen::Vector3d& p) {
  const Eigen::Vector3d radii = s * e.radii();
  const QuadricRegion body = QuadricRegion::atom(quadric::ellipsoid(radii));
  const Box3 body_box{-radii, radii};
  // The ellipsoid's pose in the region's frame: x_R = R^T (R_e x + c_e - p).
  const Eigen::Matrix3d R_RE = R.transpose() * e.rotation();
  const Eigen::Vector3d p_RE = R.transpose() * (e.center() - p);
  return collideRegions(region, region_box, body, body_box, R_RE, p_RE).relation == RegionRelation::Separated;
}

}  // namespace

double ellipsoidRegionDistanceLowerBound(const Ellipsoid& e, const QuadricRegion& region, const Box3& region_box,
                                         const Eigen::Matrix3d& R, const Eigen::Vector3d& p, double cap) {
  if (std::isnan(cap) || cap < 0.0) {  // isnan first: an ordered comparison with NaN raises FE_INVALID
    throw std::invalid_argument("ellipsoidRegionDistanceLowerBound: cap must be >= 0, got " + std::to_string(cap));
  }
  bool finite_box = true;
  for (int i = 0; i < 3; ++i) finite_box = finite_box && std::isfinite(region_box.lo[i]) && std::isfinite(region_box.hi[i]);
  if (!finite_box || region_box.empty()) {
    throw std::invalid_argument("ellipsoidRegionDistanceLowerBound: the region's box is empty or not finite");
  }
  detail::checkFinite(p, "ellipsoidRegionDistanceLowerBound: region translation");
  detail::checkRotation(R, "ellipsoidRegionDistanceLowerBound: region rotation");
  // The region lies in its box: the distance to the box is a lower bound.
  const Eigen::Vector3d half = region_box.halfWidth().cwiseMax(tolerance::kMinRadius);
  const SignedDistanceResult to_box = signedDistanceEllipsoidBox(e, half, R, p + R * region_box.center());
  double lo = std::clamp(to_box.distance, 0.0, cap);
  if (lo >= cap) return cap;
  if (!scaledSeparated(e, 1.0, region, region_box, R, p)) return lo;  // 0 unless the box already separates
  // Bisection on delta: the scaled ellipsoid s = 1 + delta / r_min certified separate => the
  // distance is >= delta (file comment).
  const double r_min = e.radii().minCoeff();
  double hi = cap;
  // Search where the bound matters: a cap far beyond the pair's size (or none) is cut to the
  // size; a separated test there still returns a valid (smaller) bound.
  const double span = 2.0 * (region_box.halfWidth().norm() + e.maxRadius());
  if (!(hi <= lo + span)) hi = lo + span;
  // Keep the scaled radii within the range Ellipsoid accepts (tolerances.h).
  hi = std::min(hi, (tolerance::kMaxLength / e.maxRadius() - 1.0) * r_min);
  if (!(hi > lo)) return lo;
  if (scaledSeparated(e, 1.0 + hi / r_min, region, region_box, R, p)) return hi;
  for (int k = 0; k < tolerance_region::kRegionDistanceBisections; ++k) {
    const double mid = 0.5 * (lo + hi);
    if (scaledSeparated(e, 1.0 + mid / r_min, region, region_box, R, p)) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return lo;
}

}  // namespace fcl_quadric
