#pragma once
// Private: the lower bound of the distance between an ellipsoid and a box that fcl_quadric's own
// distance traversals (mesh_distance.cpp, octree_distance.cpp) use to order and prune nodes.
#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Core>

#include "fcl_quadric/tolerances.h"

namespace fcl_quadric {
namespace detail {

/// An ellipsoid placed in the frame of the boxes it is compared with: axes R (columns), centre p,
/// radii r; `scale` the magnitude of the coordinates that placed it (for the padding).
struct PlacedEllipsoid {
  Eigen::Matrix3d R;
  Eigen::Vector3d p, radii;
  double scale = 0.0;

  /// A lower bound of the distance from the ellipsoid to the box of centre c, axes A (columns,
  /// orthonormal) and half-extents e (box_scale bounds |c| and e for the padding): the largest of
  /// the gaps |a.(c - p)| - sum_k e_k |a.A_k| - |S R^T a| along seven unit axes a (the box's
  /// three, the ellipsoid's three, and the line of the centres), less
  /// tolerance::kTraversalPruningPadding of the scale; 0 when none is positive. A projection onto
  /// a unit axis does not increase distances, so each gap bounds the distance from the ellipsoid
  /// to every point of the box; the padding covers the rounding of the gaps and of the placement.
  double boxBound(const Eigen::Matrix3d& A, const Eigen::Vector3d& c, const Eigen::Vector3d& e,
                  double box_scale) const {
    const Eigen::Vector3d d = c - p;
    const Eigen::Matrix3d B = R.transpose() * A;  // B(j, k) = ellipsoid axis j . box axis k
    double gap = -std::numeric_limits<double>::infinity();
    const Eigen::Vector3d d_box = A.transpose() * d;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d b = B.col(k).cwiseProduct(radii);
      gap = std::max(gap, std::fabs(d_box[k]) - e[k] - b.norm());
    }
    const Eigen::Vector3d d_ellipsoid = R.transpose() * d;
    const Eigen::Vector3d box_half = B.cwiseAbs() * e;
    for (int j = 0; j < 3; ++j) gap = std::max(gap, std::fabs(d_ellipsoid[j]) - box_half[j] - radii[j]);
    const double D = d.norm();
    if (D > 0.0) {
      // Along u = d / |d|: box part sum_k e_k |u.A_k| = (|A^T d| . e) / |d|; ellipsoid part
      // |S R^T u| = |S R^T d| / |d|.
      gap = std::max(gap, D - d_box.cwiseAbs().dot(e) / D - d_ellipsoid.cwiseProduct(radii).norm() / D);
    }
    return std::max(0.0, gap - tolerance::kTraversalPruningPadding * (scale + box_scale));
  }
};

}  // namespace detail
}  // namespace fcl_quadric
