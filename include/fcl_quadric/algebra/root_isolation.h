#pragma once
/// \file root_isolation.h
/// Real root isolation and refinement for polynomials in the Bernstein basis of [a, b].
///
/// Certification model: decisions are exact for the *computed* Bernstein coefficients of each
/// sub-interval (obtained by de Casteljau subdivision, whose rounding is of the order of the
/// unit roundoff times the coefficient magnitude). Roots are never dropped silently: whatever
/// cannot be certified within the width or iteration limits is reported as
/// RootKind::Unresolved, an interval that *may* contain one or more roots.
///
/// Part of the algebra layer: depends on the standard library only.

#include <optional>
#include <vector>

#include "fcl_quadric/algebra/bernstein_polynomial.h"

namespace fcl_quadric {

/// Maximum number of sub-intervals examined by isolateRoots() and firstRoot(). When it is
/// reached, every pending sub-interval that still has a sign variation is reported as
/// RootKind::Unresolved (possibly wider than min_width): conservative, nothing is dropped.
constexpr int kMaxIsolationNodes = 1 << 17;

/// Maximum subdivision depth of isolateRoots(). 2100 halvings shrink any finite interval of
/// doubles to adjacent doubles, so with min_width > 0 the width test always stops first; when
/// it is reached the interval is reported as RootKind::Unresolved.
constexpr int kMaxIsolationDepth = 2100;

/// Maximum number of clipping / subdivision steps of bezierClip(). When reached, every pending
/// sub-interval with a sign variation is reported as RootKind::Unresolved (conservative).
constexpr int kMaxBezierClipIterations = 1 << 16;

/// Bezier clipping subdivides at the midpoint instead of clipping when the clipped interval
/// keeps more than this fraction of the current one (Sederberg-Nishita use 1/2).
constexpr double kBezierClipSplitFraction = 0.5;

/// The clipped parameter range [smin, smax] (unit parameter of the current interval) is
/// widened by this much on both sides before restriction, to absorb the rounding of the
/// hull-axis intersection; it never excludes a root of the computed control polygon.
constexpr double kBezierClipRelativeMargin = 1e-12;

/// Maximum iterations of refineRoot() / refineRootBracket(). Every iteration either bisects or
/// takes a safeguarded Newton step, and Newton steps that do not halve the step length are
/// replaced by bisection, so 2200 iterations are enough to shrink any finite bracket to
/// adjacent doubles. When reached, the current (valid) sign bracket is returned, which may be
/// wider than the requested tolerance.
constexpr int kMaxRefineRootIterations = 2200;

/// Kind of an interval reported by the root finders.
enum class RootKind {
  /// Exactly one simple root: certified either by exactly one sign variation of the Bernstein
  /// coefficients with nonzero values at both ends (the root is in the open interval (lo, hi),
  /// and p(lo), p(hi) have opposite signs), or, for a point interval lo == hi, by an exact zero
  /// of the computed value with a nonzero derivative coefficient.
  Single,
  /// Not certified: an interval of width <= the requested width that may contain a multiple
  /// root, a cluster of roots or no root at all (also used when an iteration cap is reached, or
  /// a point interval lo == hi where the computed value and derivative are both zero). Never
  /// dropped, so callers can be conservative.
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
/// 0 => no root in (a, b); 1 => exactly one (simple) root in (a, b).
int descartesBound(const BernsteinPolynomial& p);

/// Isolates the real roots of p in the closed interval [a, b] by recursive midpoint de
/// Casteljau subdivision (Vincent-Collins-Akritas / Descartes method in the Bernstein basis).
///
/// Returns the intervals sorted left to right, pairwise disjoint except possibly for shared
/// endpoints; every root of p in [a, b] lies in exactly one of them:
///  - Single, lo < hi: exactly one simple root in (lo, hi), p(lo) p(hi) < 0;
///  - Single, lo == hi: a simple root exactly at a subdivision point or at a or b (computed
///    value exactly zero);
///  - Unresolved: hi - lo <= min_width (except when a cap is reached, see
///    kMaxIsolationNodes), may contain a multiple root or a cluster, or nothing.
/// A root that falls exactly on a subdivision point is reported once, as a point interval.
/// If p is identically zero, the single interval [a, b] is reported as Unresolved.
///
/// Work is bounded by kMaxIsolationNodes sub-intervals of cost O(n^2) each.
/// \throws std::invalid_argument if min_width is negative or not finite.
std::vector<RootInterval> isolateRoots(const BernsteinPolynomial& p, double min_width);

/// Bezier clipping (Sederberg & Nishita 1990): the convex hull of the control polygon
/// (i/n, c_i) is intersected with the axis, the polynomial is restricted to that range, and
/// the current interval is split at its midpoint whenever clipping keeps more than
/// kBezierClipSplitFraction of it. Returns sorted intervals of width <= tol (or points) with
/// the same meaning and guarantees as isolateRoots(): Single when the final interval is
/// certified by one sign variation with nonzero end values (or is an exact zero with nonzero
/// derivative), Unresolved otherwise. Converges quadratically to simple roots.
///
/// Work is bounded by kMaxBezierClipIterations steps.
/// \throws std::invalid_argument if tol is not finite or tol <= 0.
std::vector<RootInterval> bezierClip(const BernsteinPolynomial& p, double tol);

/// Shrinks a sign bracket of p by safeguarded Newton/bisection until hi - lo <= tol (or until
/// lo and hi are adjacent doubles), keeping p(lo) and p(hi) of opposite signs. If an exact zero
/// is met, returns the point interval [x, x]. The result is always Single.
/// \pre p.lower() <= lo < hi <= p.upper(); p(lo) and p(hi) of opposite signs or one of them
///      exactly zero (then that endpoint is returned as a point interval).
/// \throws std::invalid_argument if lo or hi is not finite, lo >= hi, [lo, hi] is not inside
///         [a, b], tol is negative or not finite, or p(lo) and p(hi) are nonzero with the same
///         sign. Bounded by kMaxRefineRootIterations (then the current bracket is returned).
RootInterval refineRootBracket(const BernsteinPolynomial& p, double lo, double hi, double tol);

/// A root of p in the sign bracket [lo, hi] to absolute accuracy tol: returns x with
/// |x - r| <= tol for a root r in [lo, hi] (the midpoint of refineRootBracket(p, lo, hi, 2 tol),
/// or the exact zero it met). Preconditions, errors and bound as refineRootBracket().
double refineRoot(const BernsteinPolynomial& p, double lo, double hi, double tol);

/// The smallest root of p in the closed interval [a, b], conservatively: returns
///  - std::nullopt only when every sub-interval is certified root-free;
///  - otherwise x <= r with r - x <= tol, where r is the smallest root (the lower end of a
///    refined sign bracket of width <= tol, or an exact zero); if the first interval is
///    Unresolved, its lower end (a root may lie there, none lies before it).
/// The value is therefore never later than the first root: suitable for a first contact time.
/// Examines sub-intervals left to right and stops at the first one that may hold a root.
/// Bounded by kMaxIsolationNodes and kMaxRefineRootIterations. If p is identically zero,
/// returns a. \throws std::invalid_argument if tol is not finite or tol <= 0.
std::optional<double> firstRoot(const BernsteinPolynomial& p, double tol);

}  // namespace fcl_quadric
