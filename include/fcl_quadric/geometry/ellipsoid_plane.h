#pragma once
/// \file ellipsoid_plane.h
/// Ellipsoid against a plane or a half-space: "Contact detection between an ellipsoid and a
/// combination of quadrics", Theorem 13 and Corollary 14 (formulas rebuilt, docs/algorithms.md §4).
///
/// In the ellipsoid's unit frame u = S^-1 R^T (x - p) the plane n.x = d becomes m.u = e with
/// m = S R^T n and e = d - n.p. With the plane's matrix P = [0 n/2; n^T/2 -d] (X^T P X = n.x - d)
/// the characteristic polynomial is, up to a positive factor,
///     f(lambda) = det(lambda A - P) = -lambda^2 (lambda^2 - e lambda + |m|^2 / 4):
/// a double root 0 (Theorem 13) and a quadratic whose discriminant e^2 - |m|^2 is negative iff the
/// plane cuts the ellipsoid transversally (Corollary 14 (1)); otherwise the two roots have the sign
/// of e (Descartes), i.e. they are negative iff the ellipsoid lies on the positive side n.x > d
/// (Corollary 14 (2)). |m| = |S R^T n| is the ellipsoid's half-width along n and e the offset of
/// the plane from its centre, so every decision is a certified comparison of |n.p - d| with |m|.

#include <array>

#include <Eigen/Core>

#include "fcl_quadric/geometry/ellipsoid.h"

namespace fcl_quadric {

enum class PlaneRelation {
  PositiveSide,  ///< the ellipsoid lies strictly in n.x > d
  NegativeSide,  ///< the ellipsoid lies strictly in n.x < d
  Touching,      ///< tangent within the tolerance band (counts as contact)
  Transversal,   ///< the plane cuts the interior
};
/// "positive side", "negative side", "touching" or "transversal"; "unknown" for a value outside
/// the enum.
const char* toString(PlaneRelation r);

struct EllipsoidPlaneResult {
  PlaneRelation relation = PlaneRelation::Touching;
  /// Signed offset of the centre, n.p - d, and the half-width |S R^T n| along n (for unit n these
  /// are Euclidean lengths).
  double centre_offset = 0.0;
  double half_width = 0.0;
  /// Support points of the ellipsoid in directions +n and -n (on its surface).
  Eigen::Vector3d farthest_positive = Eigen::Vector3d::Zero();
  Eigen::Vector3d farthest_negative = Eigen::Vector3d::Zero();
};

/// Coefficients {c0, c1, c2} of the quadratic factor c2 lambda^2 + c1 lambda + c0 of
/// det(lambda A - P) / (-lambda^2) up to a positive factor: {|m|^2/4, -e, 1} (Corollary 14).
/// \throws std::invalid_argument on a zero or non-finite normal or a non-finite offset (as
/// classifyEllipsoidPlane).
std::array<double, 3> ellipsoidPlaneQuadratic(const Ellipsoid& e, const Eigen::Vector3d& n, double d);

/// Relative position of ellipsoid e and the plane n.x = d (n need not be unit, must be finite and
/// non-zero; d finite). Certified: within a relative band of 2^-40 of tangency -> Touching.
/// \throws std::invalid_argument on a zero or non-finite normal or a non-finite offset.
EllipsoidPlaneResult classifyEllipsoidPlane(const Ellipsoid& e, const Eigen::Vector3d& n, double d);

/// The half-space { x : n.x <= d } (FCL's fcl::Halfspace convention) against ellipsoid e.
/// Collides iff the lowest point along n is at or below the plane: n.p - |S R^T n| <= d (certified;
/// the touching band counts as collision). For unit n, penetration depth = d - (n.p - |S R^T n|)
/// (negative: separation distance), deepest point = support point in -n.
struct EllipsoidHalfspaceResult {
  bool collide = false;
  double penetration_depth = 0.0;  ///< for unit n; < 0 means separated by that distance
  Eigen::Vector3d deepest_point = Eigen::Vector3d::Zero();
};
/// \throws std::invalid_argument on a zero or non-finite normal or a non-finite offset (as
/// classifyEllipsoidPlane).
EllipsoidHalfspaceResult ellipsoidHalfspace(const Ellipsoid& e, const Eigen::Vector3d& n, double d);

}  // namespace fcl_quadric
