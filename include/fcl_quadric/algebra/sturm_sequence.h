#pragma once
/// \file sturm_sequence.h
/// Sturm sequences of univariate polynomials in double precision.
///
/// Floating-point caveat: the count returned by countDistinctRoots() is exact only when the
/// sequence is well conditioned: the remainders that separate distinct roots must stand out
/// from the rounding noise of the Euclidean algorithm (see kSturmNoiseSafetyFactor), and the
/// evaluation points must not lie within rounding noise of a root of p. Roots too close to be
/// separated are merged into one (multiple) root; a multiple root is recognised when its
/// remainder sinks below the noise. Noise grows with the degree and with small intermediate
/// remainders, so degrees above ~10 with multiple roots may be miscounted. Use an
/// exact-rational Sturm sequence when a certified count is needed (the tests contain one built
/// on GMP rationals).
///
/// Part of the algebra layer: depends on the standard library only.

#include <vector>

#include "fcl_quadric/algebra/polynomial.h"

namespace fcl_quadric {

/// Remainders are computed in double; each member p_k carries an estimate noise_k of the
/// relative rounding noise of its (normalised) coefficients: noise_0 = 0 (the input is exact),
/// noise_1 = 4u, and a remainder of p_{k-1} by p_k has noise (noise_{k-1} + noise_k + 4(n+1)u)
/// relative to the division's scale (the larger of max|dividend| and
/// max|quotient| * max|divisor|), amplified by 1/rho when the remainder, of relative size rho,
/// is normalised. A remainder coefficient at most kSturmNoiseSafetyFactor times that noise (and
/// at least kSturmRelativeZeroThreshold) times the scale is treated as an exact zero: leading
/// coefficients below it are dropped, and a remainder with every coefficient below it ends the
/// sequence (its last member is then taken as gcd(p, p')). Too small a factor lets rounding
/// noise create spurious members after a multiple root; too large a one merges close roots.
constexpr double kSturmNoiseSafetyFactor = 64.0;

/// In variationsAt(), a member's value counts as zero when it is within its Horner error bound
/// plus this factor times its noise estimate times sum |c_i| |x|^i (smaller than
/// kSturmNoiseSafetyFactor: a value misjudged as zero next to a multiple root only moves the
/// count by a root that lies within the noise anyway, while one misjudged far from it can
/// flip a sign).
constexpr double kSturmValueNoiseFactor = 4.0;

/// Floor of the relative zero threshold of a remainder (see kSturmNoiseSafetyFactor).
constexpr double kSturmRelativeZeroThreshold = 1e-13;

/// Sturm sequence p_0 = p, p_1 = p', p_{k+1} = -rem(p_{k-1}, p_k), stopping at the first
/// remainder that is zero in the sense of kSturmNoiseSafetyFactor. p_0 is the trimmed input, kept
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
  /// Estimated relative rounding noise of each member's coefficients (0 for p_0).
  const std::vector<double>& noiseEstimates() const { return noise_; }
  /// Number of members.
  int size() const { return static_cast<int>(sequence_.size()); }

  /// V(x+): sign changes of (p_0, ..., p_k) just to the right of x. A member whose value at x
  /// is within its uncertainty is treated as zero and contributes the sign of its first
  /// derivative at x that exceeds the uncertainty (at most deg p_k extra evaluations; the
  /// constant top derivative always decides). The uncertainty is the Horner running error
  /// bound (Polynomial::evaluateWithBound), plus, for the computed members p_1..p_k,
  /// kSturmValueNoiseFactor * noise_k * sum_i |c_i| |x|^i for the rounding of their
  /// coefficients (noise_k as described at kSturmNoiseSafetyFactor).
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
  std::vector<double> noise_;
};

}  // namespace fcl_quadric
