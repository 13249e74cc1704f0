#pragma once
/// \file sturm_sequence.h
/// Sturm sequences of univariate polynomials in double precision.
///
/// Floating-point caveat: the count returned by countDistinctRoots() is exact only when the
/// sequence is well conditioned, i.e. when the roots of p are well separated relative to
/// kSturmRelativeZeroThreshold and the evaluation points are not extremely close to a root of
/// some member of the sequence. For roots closer than roughly sqrt(kSturmRelativeZeroThreshold)
/// (relative to the coefficient scale) the double sequence may treat a cluster as one multiple
/// root. Use an exact-rational Sturm sequence when a certified count is needed (the tests
/// contain one built on GMP rationals).
///
/// Part of the algebra layer: depends on the standard library only.

#include <vector>

#include "fcl_quadric/algebra/polynomial.h"

namespace fcl_quadric {

/// A remainder coefficient whose magnitude is <= this times the scale of the division (the
/// largest of max|dividend| and max|quotient| * max|divisor|, all members being normalised to
/// max|coefficient| = 1) is treated as an exact zero: leading coefficients below the threshold
/// are dropped, and a remainder with every coefficient below it terminates the sequence (the
/// last member is then taken as gcd(p, p')). Too small a value lets rounding noise create
/// spurious sign changes after a multiple root; too large a value merges close roots. 1e-10
/// is ~10^6 unit roundoffs: enough headroom for the error growth of a degree <= 20 sequence.
constexpr double kSturmRelativeZeroThreshold = 1e-10;

/// Sturm sequence p_0 = p, p_1 = p', p_{k+1} = -rem(p_{k-1}, p_k), stopping at the first
/// remainder that is zero under kSturmRelativeZeroThreshold. p_0 is the trimmed input, kept
/// exact; every later member is scaled by a positive factor to max|coefficient| = 1, which
/// does not change any sign.
///
/// Each division lowers the degree by at least one, so the construction performs at most
/// deg p divisions: the loop is bounded by the degree and needs no separate cap.
///
/// For the exact sequence, the number of distinct real roots in (a, b] is V(a+) - V(b+), where
/// V(x+) counts the sign changes of the signs of p_0, ..., p_k just to the right of x (zeros
/// dropped). V(x+) = V(x) unless x is a multiple root of p, where every member vanishes; using
/// the right limit makes the count correct also when a or b is a (multiple) root.
class SturmSequence {
 public:
  /// Builds the sequence of `p` (trimmed first).
  /// \throws std::invalid_argument if p is the zero polynomial (every point is a root).
  explicit SturmSequence(const Polynomial& p);

  /// The members p_0 (the trimmed input), p_1, ..., p_k (normalised).
  const std::vector<Polynomial>& polynomials() const { return sequence_; }
  /// Number of members.
  int size() const { return static_cast<int>(sequence_.size()); }

  /// V(x+): sign changes of (p_0, ..., p_k) just to the right of x. A member whose value at x
  /// is within its uncertainty is treated as zero and contributes the sign of its first
  /// derivative at x that exceeds the uncertainty (at most deg p_k extra evaluations; the
  /// constant top derivative always decides). The uncertainty is the Horner running error
  /// bound (Polynomial::evaluateWithBound), plus, for the computed members p_1..p_k,
  /// kSturmRelativeZeroThreshold * sum_i |c_i| |x|^i for the rounding of their coefficients.
  /// So an exactly representable (multiple) root at x is handled as in exact arithmetic,
  /// while a point within rounding noise of a root may be counted on either side of it (near
  /// a zero of an intermediate member the choice does not change the count). x may be
  /// +-infinity (then the signs of the leading terms are used, see
  /// variationsAtPositiveInfinity()).
  /// \throws std::invalid_argument if x is NaN.
  int variationsAt(double x) const;
  /// V(+infinity): sign changes of the leading coefficients.
  int variationsAtPositiveInfinity() const;
  /// V(-infinity): sign changes of (-1)^deg(p_k) * leading(p_k).
  int variationsAtNegativeInfinity() const;

  /// Number of distinct real roots of p in the half-open interval (a, b], computed as
  /// V(a+) - V(b+); a = -infinity and b = +infinity are allowed (countDistinctRoots(-inf, +inf)
  /// counts all distinct real roots). Exact for a well-conditioned sequence (see the file
  /// comment). \throws std::invalid_argument if a or b is NaN or a >= b (empty or inverted
  /// interval).
  int countDistinctRoots(double a, double b) const;

  /// Number of distinct real roots of p (V(-infinity) - V(+infinity)).
  int countAllDistinctRoots() const;

 private:
  std::vector<Polynomial> sequence_;
};

}  // namespace fcl_quadric
