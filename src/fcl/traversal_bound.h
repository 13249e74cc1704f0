#pragma once
// Private: what fcl_quadric's own traversals (mesh_collision.cpp, mesh_distance.cpp,
// octree_collision.cpp, octree_distance.cpp) compute of the shape: its radii, its placement in the
// frame of the mesh or tree, and the lower bound of its distance to a box that the distance
// traversals use to order and prune nodes.
#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Core>
#include <fcl/common/types.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/sphere.h>

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

inline Eigen::Vector3d shapeRadii(const fcl::Ellipsoid<double>& e) { return e.radii; }
inline Eigen::Vector3d shapeRadii(const fcl::Sphere<double>& s) { return Eigen::Vector3d::Constant(s.radius); }

/// The ellipsoid of `radii` posed tf_shape, placed in the frame tf_frame, whose linear part is a
/// rotation R_f (within tolerance::kRotationOrthogonality: the defect moves the placement by far
/// less than the padding): axes R_f^T R_s, centre R_f^T (p_s - p_f), and scale
/// |p_f|_max + |p_s|_max + |centre|_max + max radius.
inline PlacedEllipsoid placeInFrame(const fcl::Transform3<double>& tf_frame, const fcl::Transform3<double>& tf_shape,
                                    const Eigen::Vector3d& radii) {
  PlacedEllipsoid e;
  e.R = tf_frame.linear().transpose() * tf_shape.linear();
  e.p = tf_frame.linear().transpose() * (tf_shape.translation() - tf_frame.translation());
  e.radii = radii;
  e.scale = tf_frame.translation().cwiseAbs().maxCoeff() + tf_shape.translation().cwiseAbs().maxCoeff() +
            e.p.cwiseAbs().maxCoeff() + radii.maxCoeff();
  return e;
}

}  // namespace detail
}  // namespace fcl_quadric
