#pragma once
/// \file ellipsoid_quadric.h
/// A small ellipsoid against any quadric: "Contact detection between an ellipsoid and a
/// combination of quadrics" (seed paper), Definition 1 (smallness), Lemma 3 / Lemma 4 / Theorem 5
/// (smallness from curvatures and axes), Theorem 2 and Corollary 9 (transversal contact iff the
/// characteristic polynomial has non-real roots), Remark 8 (non-real roots imply transversal
/// contact for any pair of quadrics). The paper's formulas were lost in extraction; they are
/// rebuilt here and in docs/algorithms.md section 11, and checked numerically in
/// test/geometry/ellipsoid_quadric_test.cpp (curvature bounds against sampled normal
/// curvatures, every verdict against the certified region engine of section 9).
///
/// This is a fast *filter*: it answers only when its certificate holds and reports Undecided
/// otherwise (tangency within the rounding band, a quadric too close to a degenerate type, an
/// ellipsoid that is not small), and callers fall back to the exact region engine. It never
/// guesses.
///
/// Conventions: the solid of the quadric is { X^T Q X <= 0 } (X = (x, 1)); f(lambda) =
/// det(lambda A - Q) with A the ellipsoid's matrix (thesis ch.4 sign convention).

#include <array>
#include <limits>

#include <Eigen/Core>

#include "fcl_quadric/geometry/ellipsoid.h"

namespace fcl_quadric {

/// Euclidean type of a quadric surface (Table 1 of the seed paper), from the invariants of its
/// matrix. Cone, IntersectingPlanes, Plane and Other (empty, imaginary, a double plane, or too
/// close to a type change to be classified) are never "small" partners.
enum class QuadricSurfaceType {
  Ellipsoid,
  HyperboloidOneSheet,
  HyperboloidTwoSheets,
  EllipticParaboloid,
  HyperbolicParaboloid,
  EllipticCylinder,
  HyperbolicCylinder,
  ParabolicCylinder,
  ParallelPlanes,
  Cone,
  IntersectingPlanes,
  Plane,
  Other,
};
/// "ellipsoid", "hyperboloid of one sheet", ...; "unknown" for a value outside the enum.
const char* toString(QuadricSurfaceType t);

/// What the smallness condition needs to know about a quadric surface (rigid invariants).
struct QuadricSurfaceShape {
  QuadricSurfaceType type = QuadricSurfaceType::Other;
  /// Largest |normal curvature| over the whole surface (Lemma 3's kappa_max of the quadric): at
  /// the vertices, e.g. b1 / b3^2 for an ellipsoid with semi-axes b1 >= b2 >= b3.
  double max_curvature = std::numeric_limits<double>::infinity();
  /// Shortest chord between two disjoint parts of the surface that a small ellipsoid could bridge
  /// (section 2.1's size conditions): the vertex distance 2 b1 of a hyperboloid of two sheets or a
  /// hyperbolic cylinder, the gap of parallel planes; +infinity for the other types (their size
  /// condition follows from the curvature condition).
  double min_gap = std::numeric_limits<double>::infinity();
  /// Positive eigenvalues of Q (its inertia, by Sylvester's law from the completed squares: a
  /// rigid invariant, unlike the eigenvalues themselves); -1 when the type is Other or Plane.
  int positive_eigenvalues = -1;
};

/// Type and smallness data of the surface X^T Q X = 0 (Q symmetric 4x4, finite). Eigenvalues of
/// the quadratic part below kQuadricTypeRelativeZero of the largest are zero, and those within
/// kQuadricTypeAmbiguity of that threshold make the type Other (not classifiable with
/// confidence); the same for the linear term along a degenerate direction.
/// \throws std::invalid_argument if Q is not finite or its quadratic part is not symmetric.
QuadricSurfaceShape classifyQuadricSurface(const Eigen::Matrix4d& Q);

/// Relative zero and ambiguity thresholds of classifyQuadricSurface().
constexpr double kQuadricTypeRelativeZero = 1e-12;
constexpr double kQuadricTypeAmbiguity = 1e-7;
/// The smallness inequalities are required with this relative margin (the paper allows
/// equality; the margin keeps the rounding of the invariants on the safe side).
constexpr double kSmallnessRelativeMargin = 1e-9;

/// Definition 1 via Lemma 3 and Lemma 4 (rebuilt): e is small with respect to the surface iff
/// the surface's largest normal curvature is at most e's smallest one, a3 / a1^2 (radii
/// a1 >= a2 >= a3), and e's diameter 2 a1 is at most the surface's min_gap. No failure mode
/// (Cone, IntersectingPlanes, Plane and Other are never small).
bool isSmall(const Ellipsoid& e, const QuadricSurfaceShape& q);

enum class EllipsoidQuadricRelation {
  Outside,      ///< certified: the solid ellipsoid and the solid X^T Q X <= 0 are disjoint
  Inside,       ///< certified: the ellipsoid lies in the interior of the solid
  Transversal,  ///< certified: the surfaces cross (so the solids share interior points)
  Undecided,    ///< no certificate (tangency within the rounding band, not small, degenerate)
};
/// "outside", "inside", "transversal" or "undecided"; "unknown" for a value outside the enum.
const char* toString(EllipsoidQuadricRelation r);

struct EllipsoidQuadricResult {
  EllipsoidQuadricRelation relation = EllipsoidQuadricRelation::Undecided;
  QuadricSurfaceShape surface;
  bool small = false;
  /// Coefficients (low to high) of det(lambda J - B) with J = diag(1,1,1,-1) and B = Q in the
  /// ellipsoid's unit frame, normalised to max |B_ij| = 1: the same roots as det(lambda A - Q) up
  /// to one positive factor, and the same signs.
  std::array<double, 5> f{};
  /// Rigorous absolute error bounds of f's coefficients (rounding of B and of the minors).
  std::array<double, 5> f_error{};
  /// Quartic discriminant of f as an enclosure [lo, hi].
  double discriminant_lo = 0.0, discriminant_hi = 0.0;
  /// Four simple real roots and a small ellipsoid: the positive roots of f counted by the sign
  /// changes of its coefficients (Theorem 12); -1 when not computed or a sign is not certified.
  int positive_roots = -1;
};

/// Corollary 9 with the complete discrimination system of the quartic (Delta, P, D): certified
/// sign decisions on enclosures of Delta = disc(f), P = 8ac - 3b^2 and D (coefficients a..e of
/// f from the top):
///   Delta < 0                       -> two simple real roots and one non-real pair: Transversal
///   Delta > 0 and (P > 0 or D > 0)  -> two non-real pairs: Transversal (Remark 8)
///   Delta > 0, P < 0, D < 0         -> four simple real roots: no transversal contact and, since
///                                      they are simple, no tangency (Theorem 2, needs isSmall);
///                                      Inside/Outside by Theorem 12 (Table 4 rebuilt): the sign
///                                      changes of f's coefficients count its positive roots,
///                                      n+(Q) + 1 inside (X^T Q X < 0), n+(Q) - 1 outside, n+(Q)
///                                      = surface.positive_eigenvalues; the certified sign of Q
///                                      at e's centre must agree (else Undecided)
/// and Undecided otherwise. Never throws for a finite symmetric Q and a valid Ellipsoid.
/// \throws std::invalid_argument as classifyQuadricSurface().
EllipsoidQuadricResult classifyEllipsoidQuadric(const Ellipsoid& e, const Eigen::Matrix4d& Q);

}  // namespace fcl_quadric
