#include "fcl_quadric/geometry/region_distance_bound.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "fcl_quadric/algebra/quadric_matrix.h"
#include "fcl_quadric/geometry/ellipsoid_polytope.h"
#include "fcl_quadric/tolerances.h"

namespace fcl_quadric {

namespace {

void checkBox(const Box3& box, const std::string& what) {
  bool finite = true;
  for (int i = 0; i < 3; ++i) finite = finite && std::isfinite(box.lo[i]) && std::isfinite(box.hi[i]);
  if (!finite || box.empty()) throw std::invalid_argument(what + " is empty or not finite");
}

void checkCap(double cap, const std::string& who) {
  if (std::isnan(cap) || cap < 0.0) {  // isnan first: an ordered comparison with NaN raises FE_INVALID
    throw std::invalid_argument(who + ": cap must be >= 0, got " + std::to_string(cap));
  }
}

/// The largest delta in [lo, hi] (to 2^-kRegionDistanceBisections of the range) for which
/// separated(delta) is certified, lo being a certified bound already; hi itself if separated(hi).
template <class Separated>
double bisectBound(double lo, double hi, Separated&& separated) {
  if (!(hi > lo)) return lo;
  if (separated(hi)) return hi;
  for (int k = 0; k < tolerance_region::kRegionDistanceBisections; ++k) {
    const double mid = 0.5 * (lo + hi);
    (separated(mid) ? lo : hi) = mid;
  }
  return lo;
}

}  // namespace

double ellipsoidRegionDistanceLowerBound(const Ellipsoid& e, const QuadricRegion& region, const Box3& region_box,
                                         const Eigen::Matrix3d& R, const Eigen::Vector3d& p, double cap) {
  const std::string who = "ellipsoidRegionDistanceLowerBound";
  checkCap(cap, who);
  checkBox(region_box, who + ": the region's box");
  detail::checkFinite(p, "ellipsoidRegionDistanceLowerBound: region translation");
  detail::checkRotation(R, "ellipsoidRegionDistanceLowerBound: region rotation");
  // The region lies in its box: the distance to the box is a lower bound.
  const Eigen::Vector3d half = region_box.halfWidth().cwiseMax(tolerance::kMinRadius);
  const SignedDistanceResult to_box = signedDistanceEllipsoidBox(e, half, R, p + R * region_box.center());
  const double lo = std::clamp(to_box.distance, 0.0, cap);
  if (lo >= cap) return cap;
  // The ellipsoid scaled about its centre by s = 1 + delta / r_min, in the region's frame
  // (x_R = R^T (R_e x + c_e - p)), certified separate => the distance is >= delta (file comment).
  const double r_min = e.radii().minCoeff();
  const Eigen::Matrix3d R_RE = R.transpose() * e.rotation();
  const Eigen::Vector3d p_RE = R.transpose() * (e.center() - p);
  auto separated = [&](double delta) {
    const Eigen::Vector3d radii = (1.0 + delta / r_min) * e.radii();
    return collideRegions(region, region_box, QuadricRegion::atom(quadric::ellipsoid(radii)), Box3{-radii, radii},
                          R_RE, p_RE)
               .relation == RegionRelation::Separated;
  };
  if (!separated(0.0)) return lo;  // 0 unless the box already separates
  // Search where the bound matters: a cap far beyond the pair's size is cut to the size (a
  // separated test there still returns a valid, smaller bound); keep the scaled radii within the
  // range Ellipsoid accepts (tolerances.h).
  const double span = 2.0 * (region_box.halfWidth().norm() + e.maxRadius());
  double hi = std::min(cap, lo + span);
  hi = std::min(hi, (tolerance::kMaxLength / e.maxRadius() - 1.0) * r_min);
  return bisectBound(lo, hi, separated);
}

double regionConvexDistanceLowerBound(const QuadricRegion& a, const Box3& a_box, const QuadricRegion& b,
                                      const Box3& b_box, double b_inradius, const Eigen::Matrix3d& R_AB,
                                      const Eigen::Vector3d& p_AB, double cap) {
  const std::string who = "regionConvexDistanceLowerBound";
  checkCap(cap, who);
  if (!std::isfinite(b_inradius) || !(b_inradius > 0.0)) {
    throw std::invalid_argument(who + ": b_inradius must be finite and > 0, got " + std::to_string(b_inradius));
  }
  checkBox(a_box, who + ": a's box");
  checkBox(b_box, who + ": b's box");
  // The ball of radius b_inradius about b's origin lies in b, hence in its box.
  for (int i = 0; i < 3; ++i) {
    if (!(b_box.lo[i] <= -b_inradius && b_box.hi[i] >= b_inradius)) {
      throw std::invalid_argument(who + ": b's box does not contain the ball of radius b_inradius = " +
                                  std::to_string(b_inradius) + " about b's origin");
    }
  }
  detail::checkFinite(p_AB, "regionConvexDistanceLowerBound: translation");
  detail::checkRotation(R_AB, "regionConvexDistanceLowerBound: rotation");
  auto separated = [&](double delta) {
    const double s = 1.0 + delta / b_inradius;
    const QuadricRegion scaled = b.transformedAffine(s * Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
    return collideRegions(a, a_box, scaled, Box3{s * b_box.lo, s * b_box.hi}, R_AB, p_AB).relation ==
           RegionRelation::Separated;
  };
  if (cap == 0.0 || !separated(0.0)) return 0.0;
  // As above: search up to the pair's size, and keep the scaled solid within kMaxLength.
  const double reach = b_box.hi.cwiseAbs().cwiseMax(b_box.lo.cwiseAbs()).norm();
  double hi = std::min(cap, 2.0 * (a_box.halfWidth().norm() + reach));
  hi = std::min(hi, (tolerance::kMaxLength / reach - 1.0) * b_inradius);
  return bisectBound(0.0, hi, separated);
}

}  // namespace fcl_quadric
