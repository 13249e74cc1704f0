#pragma once
/// \file root_isolation.h
/// Real root isolation and refinement for polynomials in the Bernstein basis of [a, b].
///
/// Certification model. The input coefficients are taken as exact. Every sign decision is
/// certified for the polynomial they represent:
///  - isolation and clipping run in the unit parameter s of [a, b] (so bisection points are
///    exact dyadic rationals) on double-double sub-interval coefficients with rigorous
///    absolute error bounds; a coefficient sign is used only when it exceeds its bound, and
///    Descartes' rule is applied to every polynomial within the bounds;
///  - point values (refinement, Bezier-clipping certificates) use the compensated de Casteljau
///    algorithm with an a-posteriori error bound;
///  - unit-parameter results are mapped back to t = a + s (b - a) with outward rounding, so
///    for a non-dyadic [a, b] neighbouring intervals may overlap by a few ulps (for [0, 1] the
///    mapping is exact).
/// Assumptions: no overflow, and no FMA contraction of the library's own double expressions
/// (the default for ISO C++ on GCC/Clang). Whatever cannot be certified within the width or
/// iteration limits is reported as RootKind::Unresolved, an interval that *may* contain one
/// or more roots: roots are never dropped.
///
/// Part of the algebra layer: depends on the standard library only.

#include <optional>
#include <vector>

#include "fcl_quadric/algebra/bernstein_polynomial.h"

namespace fcl_quadric {

/// Maximum number of sub-intervals examined by isolateRoots() and firstRoot(). When it is
/// reached, every pending sub-interval that is not certified root-free is reported as
/// RootKind::Unresolved (possibly wider than min_width): conservative, nothing is dropped.
constexpr int kMaxIsolationNodes = 1 << 17;

/// Maximum subdivision depth of isolateRoots(). The unit interval can be halved at most ~1075
/// times before midpoints stop being representable, so the width test or the representability
/// test always stops first; if the cap were reached, the interval is reported as
/// RootKind::Unresolved.
constexpr int kMaxIsolationDepth = 2100;

/// Maximum number of clipping / subdivision steps of bezierClip(). When reached, every pending
/// sub-interval that is not certified root-free is reported as RootKind::Unresolved
/// (conservative).
constexpr int kMaxBezierClipIterations = 1 << 16;

/// Bezier clipping subdivides at the midpoint instead of clipping when the clipped interval
/// keeps more than this fraction of the current one (Sederberg-Nishita use 1/2).
constexpr double kBezierClipSplitFraction = 0.5;

/// The clipped parameter range [smin, smax] (unit parameter of the current interval) is
/// widened by this much on both sides before restriction, to absorb the rounding of the
/// hull-axis intersection; it never excludes a root of any polynomial within the error bounds.
constexpr double kBezierClipRelativeMargin = 1e-12;

/// Maximum iterations of refineRoot() / refineRootBracket() / the refinement in firstRoot(),
/// and separately the maximum number of step doublings when probing around a point whose sign
/// is uncertain. Every iteration either bisects or takes a safeguarded Newton step (Newton
/// steps that do not halve the step before the last are replaced by bisection), so 2200
/// iterations shrink any finite bracket to adjacent doubles. When reached, the current
/// (valid) sign bracket is returned, as RootKind::Unresolved if it is wider than requested.
constexpr int kMaxRefineRootIterations = 2200;

/// Kind of an interval reported by the root finders.
enum class RootKind {
  /// Exactly one simple root: for lo < hi, certified by Descartes' rule (exactly one sign
  /// variation for every polynomial within the error bounds) or, in bezierClip(), by
  /// certified opposite end signs inside an interval already certified to hold exactly one
  /// root; the root lies in the open interval (lo, hi) and p(lo), p(hi) have opposite signs
  /// (up to the ulp-level outward rounding described in the file comment). For a point interval
  /// lo == hi: an exact zero at a subdivision point or at a or b with a certified nonzero
  /// derivative.
  Single,
  /// Not certified: an interval that may contain a multiple root, a cluster of roots or no
  /// root at all (also used when an iteration cap or the accuracy limit is reached, and for a
  /// point lo == hi where the value is an exact zero but the derivative is not certified
  /// nonzero). Never dropped, so callers can be conservative.
  Unresolved,
};

/// An interval [lo, hi] (lo <= hi) reported by the root finders.
struct RootInterval {
  double lo;
  double hi;
  RootKind kind;
};

/// Sign variations of the Bernstein coefficients of p (zeros ignored): an upper bound on the
/// number of roots in the open interval (a, b) counted with multiplicity, with the same parity.
/// 0 => no root in (a, b); 1 => exactly one (simple) root in (a, b). Exact for the given
/// coefficients (no arithmetic is involved).
int descartesBound(const BernsteinPolynomial& p);

/// Isolates the real roots of p in the closed interval [a, b] by recursive midpoint de
/// Casteljau subdivision (Vincent-Collins-Akritas / Descartes method in the Bernstein basis).
///
/// Returns the intervals sorted left to right, pairwise disjoint up to shared endpoints (and
/// the ulp-level overlaps of outward rounding); every real root of p in [a, b] lies in one of
/// them:
///  - Single, lo < hi: exactly one simple root in (lo, hi), p(lo) p(hi) < 0;
///  - Single, lo == hi: a simple root exactly at a subdivision point or at a or b;
///  - Unresolved: hi - lo <= min_width (when min_width is at least a few ulps of max(|a|,|b|);
///    wider only when kMaxIsolationNodes is reached); may contain a multiple root, a cluster,
///    or nothing.
/// A root that falls exactly on a subdivision point is reported once, as a point interval
/// (for a non-dyadic [a, b], as an interval a few ulps wide around it).
/// If p is identically zero, the single interval [a, b] is reported as Unresolved.
///
/// Work is bounded by kMaxIsolationNodes sub-intervals of cost O(n^2) each.
/// \throws std::invalid_argument if min_width is negative or not finite.
std::vector<RootInterval> isolateRoots(const BernsteinPolynomial& p, double min_width);

/// Bezier clipping (Sederberg & Nishita 1990): the convex hull of the control polygon
/// (i/n, c_i), widened by the coefficient error bounds, is intersected with the axis, the
/// polynomial is restricted to that range, and the current interval is split at its midpoint
/// whenever clipping keeps more than kBezierClipSplitFraction of it. Converges quadratically to
/// simple roots. Returns sorted intervals with the meaning and guarantees of isolateRoots():
/// every root lies in one of them; each has width <= tol (same ulp-level proviso as
/// isolateRoots()) or is a point; Single when certified (see RootKind), Unresolved otherwise.
///
/// Work is bounded by kMaxBezierClipIterations steps.
/// \throws std::invalid_argument if tol is not finite or tol <= 0.
std::vector<RootInterval> bezierClip(const BernsteinPolynomial& p, double tol);

/// Shrinks a sign bracket of p by safeguarded Newton/bisection (rtsafe-style) until
/// hi - lo <= tol (or lo and hi are adjacent doubles), keeping a certified sign change: the
/// bracket is only moved to points whose sign is certified by compensated evaluation with an
/// error bound. The returned bracket always contains an odd number of roots (one if the input
/// bracket held exactly one). Kind: Single when the requested width was reached (or a point
/// [x, x] at an exact zero), Unresolved when the evaluation error bound or
/// kMaxRefineRootIterations stopped it first (the bracket is then still valid, just wider).
/// \pre p.lower() <= lo < hi <= p.upper(); the computed p(lo) and p(hi) have opposite signs,
///      or one of them is exactly zero (then that endpoint is returned as a point interval).
/// \throws std::invalid_argument if lo or hi is not finite, lo >= hi, [lo, hi] is not inside
///         [a, b], tol is negative or not finite, or p(lo) and p(hi) are nonzero with the same
///         sign.
RootInterval refineRootBracket(const BernsteinPolynomial& p, double lo, double hi, double tol);

/// A root of p in the sign bracket [lo, hi] to absolute accuracy tol: returns the midpoint of
/// refineRootBracket(p, lo, hi, 2 tol) (or the exact zero it met), so |x - r| <= tol for a root
/// r in [lo, hi] whenever that bracket reached its width (see refineRootBracket() for when
/// the accuracy limit of double evaluation prevents it). Preconditions, errors and iteration
/// bound as refineRootBracket().
double refineRoot(const BernsteinPolynomial& p, double lo, double hi, double tol);

/// The smallest root of p in the closed interval [a, b], conservatively: returns
///  - std::nullopt only when [a, b] is certified root-free;
///  - otherwise x <= r, where r is the smallest root. If the first isolating interval is
///    Single, x is the lower end (rounded down) of a certified sign bracket of r refined to
///    width <= tol, or an exact zero, so r - x <= tol (unless the accuracy limit of double
///    evaluation stops the refinement first: then x is still <= r). If the first interval is
///    Unresolved, x is its lower end (a root may lie in [x, x + tol], none lies before x).
/// The value is therefore never later than the first root: suitable for a first contact time.
/// Examines sub-intervals left to right and stops at the first one that may hold a root.
/// Bounded by kMaxIsolationNodes and kMaxRefineRootIterations. If p is identically zero,
/// returns a. \throws std::invalid_argument if tol is not finite or tol <= 0.
std::optional<double> firstRoot(const BernsteinPolynomial& p, double tol);

}  // namespace fcl_quadric
