#pragma once
/// \file nearest_points.h
/// Local refinement of a pair of nearest points of two composite quadric models (quadric_region.h)
/// by Newton's method on the Karush-Kuhn-Tucker system of min |x - y|^2 over x in a, y in b
/// (docs/algorithms.md section 12c). GJK and the branch and bound of region_distance.h find the
/// nearest points only up to their stopping gaps, and near contact both stall: GJK's simplex loses
/// its direction to rounding once the gap is ~1e-6 of the solids' size, and alternating
/// projections between two nearly tangent surfaces contract by only ~1 - gap / curvature radius per
/// round. Newton's method on the KKT system converges quadratically at any gap: its tangential
/// conditioning degrades like 1 / gap, but the distance is second-order in a tangential error, so
/// it stays exact to rounding. Pure geometry (std + Eigen).

#include <optional>

#include <Eigen/Core>

#include "fcl_quadric/geometry/quadric_region.h"

namespace fcl_quadric {

namespace tolerance_nearest_points {
/// An atom's surface passes through a witness when |g| / |grad g| is at most this times the
/// pair's scale (as region_distance.h's kRegionDistanceActiveRelative).
constexpr double kActiveRelative = 1e-6;
/// Newton steps per active set; the iteration stops earlier once a step is below
/// kStepRelative times the scale.
constexpr int kMaxNewtonSteps = 24;
constexpr double kStepRelative = 1e-15;
/// A step may not increase the distance by more than this times the scale (its rounding).
constexpr double kDistanceRoundingRelative = 1e-14;
/// At the step cap, the iteration counts as converged if its last step was at most this times
/// the scale (a tangential error t changes the distance by ~ t^2 times the curvature).
constexpr double kSettledRelative = 1e-9;
/// Active sets tried (a surface dropped for a negative multiplier, or added where the point left
/// the model) before giving up.
constexpr int kMaxActiveSetRounds = 6;
/// A multiplier below minus this (the multipliers are O(1): each surface's gradient is scaled to
/// unit length) takes its surface out of the active set.
constexpr double kNegativeMultiplier = 1e-9;
/// Gauss-Newton steps moving a point onto the active surfaces (after each Newton step, and to
/// align the start).
constexpr int kProjectionSteps = 8;
/// A step longer than this times the scale is shortened to it (a start far from the minimum).
constexpr double kMaxStepRelative = 0.1;
}  // namespace tolerance_nearest_points

/// A pair of points, one on each model, and their distance.
struct NearestPoints {
  Eigen::Vector3d point_a = Eigen::Vector3d::Zero();
  Eigen::Vector3d point_b = Eigen::Vector3d::Zero();
  double distance = 0.0;  ///< |point_b - point_a|
  int iterations = 0;     ///< Newton steps over all active sets
};

/// Refines `start_a` (a point of a's boundary) and `start_b` (of b's), both in the frame of the
/// regions (a.signedAtoms() and b.signedAtoms() are used as given), towards the nearest pair of
/// points near them. The surfaces through each start point (one to three atoms: a face, an edge, a
/// vertex) form the active set; Newton's method solves
///   x - y + sum_i lambda_i grad g_i(x) = 0,   y - x + sum_j mu_j grad h_j(y) = 0,
///   g_i(x) = 0,   h_j(y) = 0
/// (g_i the active atoms of a, h_j of b, each scaled to a unit gradient at the start). A surface
/// whose multiplier comes out negative is dropped, and one a Newton step crosses out of its model
/// is added (at most kMaxActiveSetRounds sets). Two atoms of a model that are exact negations of
/// each other (a plane as two opposite half-spaces: a mesh triangle's, or a point as three such
/// pairs) are one equality constraint: one of them is active, its multiplier of either sign. Each step is retracted onto the active surfaces
/// and damped so that the points never cross.
///
/// \return the refined pair only when it is certain to be at least as good as the start: both
/// points are members of their models by the exact-sign classification
/// (QuadricRegion::classifyPoint() >= 0, so their distance bounds the true distance from above up
/// to that rounding band), the multipliers are >= 0 (a local minimum of the distance, the global
/// one when both models are convex), and the distance is not above |start_b - start_a|. nullopt
/// otherwise: no active surface at a start point, a singular or non-finite Newton system, no
/// convergence within the caps, or start points that coincide. The caller keeps its own pair then.
/// \pre the models are disjoint near the start points (a certified separated pair): the system is
///      that of the distance of separated solids. No failure mode (never throws).
std::optional<NearestPoints> refineNearestPoints(const QuadricRegion& a, const QuadricRegion& b,
                                                 const Eigen::Vector3d& start_a, const Eigen::Vector3d& start_b,
                                                 double scale);

}  // namespace fcl_quadric
