#pragma once
/// \file signed_distance.h
/// Signed distance between two ellipsoids with witness points and normal.

#include <Eigen/Core>

#include "fcl_quadric/geometry/ellipsoid.h"
#include "fcl_quadric/geometry/ellipsoid_separation.h"

namespace fcl_quadric {

struct SignedDistanceResult {
  /// > 0: Euclidean distance; < 0: minus the penetration depth (length of the shortest translation
  /// of b that removes the overlap); 0 within the touching band. Its sign never contradicts
  /// `status` (the algebraic classification decides it): > 0 only when Separated, < 0 only when
  /// Overlapping. It is also 0 for a Separated or Overlapping pair whose distance or depth is
  /// below the rounding of its own evaluation (~1e-16 of the scale |p_b - p_a| + r_a,max +
  /// r_b,max), where the computed value has the other sign (docs/tolerances.md, item 5).
  double distance = 0.0;
  Eigen::Vector3d point_a = Eigen::Vector3d::Zero();  ///< on the surface of a (world frame)
  Eigen::Vector3d point_b = Eigen::Vector3d::Zero();  ///< on the surface of b (world frame)
  /// Unit normal pointing from a to b: translating b by -distance * normal makes them touch.
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();
  Separation status = Separation::Touching;
  int iterations = 0;
  bool converged = false;
};

/// Signed distance of ellipsoids a and b: the maximum over unit n of -h_a(n) - h_b(-n), h the
/// support function (for separated pairs the Euclidean distance; for overlapping pairs minus the
/// penetration depth). Riemannian Newton on the unit sphere with backtracking, warm-started from
/// `warm_normal` (if non-null and non-zero), from the separating plane of Theorem 4.6 for
/// separated pairs, and for overlapping pairs from several seeds (penetration depth can have
/// local optima) of which the best is kept. Each ascent stops at a gradient of at most
/// tolerance::kDistanceGradientTolerance of the scale, at its rounding floor
/// (tolerance::kDistanceStallSteps steps that gain no more than rounding), or at
/// tolerance::kMaxDistanceNewtonIterations, where the best iterate is returned with
/// converged = false.
SignedDistanceResult signedDistance(const Ellipsoid& a, const Ellipsoid& b,
                                    const Eigen::Vector3d* warm_normal = nullptr);

/// The same, reusing a classification already computed by classifyEllipsoids(a, b) (callers that
/// classify first, such as the FCL solver, save one classification). \pre cert is
/// classifyEllipsoids(a, b) for these a and b (in this order).
SignedDistanceResult signedDistance(const Ellipsoid& a, const Ellipsoid& b, const SeparationCertificate& cert,
                                    const Eigen::Vector3d* warm_normal = nullptr);

}  // namespace fcl_quadric
