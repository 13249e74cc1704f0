#pragma once
// ConvexSupport::RegionData: what ConvexSupport::fromRegion computes once for an enumerated
// (Region) support, shared by the support queries (convex_support.cpp) and the certified
// bounding box (convex_region_box.cpp). Internal to the library.
#include <cstddef>
#include <limits>
#include <vector>

#include <Eigen/Core>

#include "fcl_quadric/geometry/convex_support.h"

namespace fcl_quadric {

/// What fromRegion() computes once (convex_support.h, region_): the curved atom {x^T A x + 2 b.x +
/// c <= 0} if any (normalised by its largest eigenvalue), the planes h.x <= d (unit h), and the
/// eigen-decompositions of the curved atom and of its section by each plane (x = x0 + U y), so
/// that a support query costs only arithmetic.
struct ConvexSupport::RegionData {
  bool has_curved = false;
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  double c = 0.0;
  std::vector<Eigen::Vector3d> plane_h;
  std::vector<double> plane_d;
  /// For each plane, a bound q on the quadratic part its atom carried (isPlanarAtom's relative
  /// tolerance, kept only where it is negligible over the box): the atom is h.x - d + e(x) <= 0
  /// with |e(x)| <= q |x|^2. 0 for the box's faces.
  std::vector<double> plane_quad;
  /// The first `own_planes` planes are the region's own half-spaces; the rest are the bounding
  /// box's faces (ConvexSupport::regionBox certifies with the region's own constraints only).
  std::size_t own_planes = 0;
  /// The planes (and their sections) the support enumeration runs over: all of them when the box
  /// clips the region, the first `own_planes` when it contains it (BoxRole::Contains).
  std::size_t support_planes = 0;
  struct Curved {
    Eigen::Vector3d lam = Eigen::Vector3d::Zero(), bz = Eigen::Vector3d::Zero();
    Eigen::Matrix3d V = Eigen::Matrix3d::Identity();
    double b_tol = 0.0;
  } curved;
  struct Section {
    Eigen::Matrix<double, 3, 2> U = Eigen::Matrix<double, 3, 2>::Zero();
    Eigen::Vector3d x0 = Eigen::Vector3d::Zero();
    Eigen::Vector2d lam = Eigen::Vector2d::Zero(), bz = Eigen::Vector2d::Zero();
    Eigen::Matrix2d V = Eigen::Matrix2d::Identity();
    double c = 0.0, b_tol = 0.0;
    /// A cone's section: r = b^T A^-1 b - c of the section's conic, formed as delta^2 sigma from
    /// the apex's offset delta from the plane (smoothMax's `r_given`); NaN otherwise.
    double r = std::numeric_limits<double>::quiet_NaN();
  };
  std::vector<Section> sections;
  /// An indefinite curved atom (acceptIndefinite()): a cone nappe (`cone`, whose `apex` is a
  /// support candidate) or a two-sheet hyperboloid's sheet.
  bool cone = false;
  Eigen::Vector3d apex = Eigen::Vector3d::Zero();
  /// A two-sheet hyperboloid's r = -f(x0) (acceptIndefinite(), smoothMax's `r_given`); NaN else.
  double r = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace fcl_quadric
