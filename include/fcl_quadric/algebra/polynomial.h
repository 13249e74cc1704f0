#pragma once
/// \file polynomial.h
/// Univariate polynomials with double coefficients in the power (monomial) basis.
///
/// Part of the algebra layer: depends on the standard library only.
///
/// Conventions shared by the whole algebra layer:
///  - coefficients are stored low -> high degree: p(x) = sum_i c[i] x^i;
///  - every input coefficient, scalar and argument must be finite; a non-finite value throws
///    std::invalid_argument whose message names the function and the bad value. Intermediate
///    overflow of arithmetic on finite polynomials is *not* detected (it yields +-inf
///    coefficients, exactly as double arithmetic would);
///  - no function performs an unbounded iteration: all loops here run over coefficients.

#include <initializer_list>
#include <vector>

namespace fcl_quadric {

struct PolynomialDivision;

/// p(x) = sum_{i=0}^{n} c_i x^i with finite double coefficients, stored low -> high.
///
/// The stored coefficient vector is never empty. Its length minus one is the *formal* degree
/// returned by degree(); the leading stored coefficient may be zero (e.g. after a subtraction
/// that cancels). trimmed() removes exact-zero leading coefficients; effectiveDegree() is the
/// degree of the trimmed polynomial (-1 for the zero polynomial).
class Polynomial {
 public:
  /// The zero polynomial (one coefficient, 0.0; formal degree 0).
  Polynomial();

  /// From coefficients low -> high. An empty vector gives the zero polynomial.
  /// \throws std::invalid_argument if a coefficient is not finite (message names its index and
  ///         value).
  explicit Polynomial(std::vector<double> coefficients);

  /// Same as the vector constructor: Polynomial{c0, c1, c2} is c0 + c1 x + c2 x^2.
  Polynomial(std::initializer_list<double> coefficients);

  /// The constant polynomial `value`. \throws std::invalid_argument if `value` is not finite.
  static Polynomial constant(double value);

  /// coefficient * x^power. \pre power >= 0, coefficient finite; otherwise throws
  /// std::invalid_argument.
  static Polynomial monomial(int power, double coefficient = 1.0);

  /// leading * prod_k (x - roots[k]), expanded in double by repeated multiplication with linear
  /// factors (formal degree roots.size()). \throws std::invalid_argument if a root or `leading`
  /// is not finite.
  static Polynomial fromRoots(const std::vector<double>& roots, double leading = 1.0);

  /// Formal degree: number of stored coefficients minus one (>= 0). The leading stored
  /// coefficient may be zero; see effectiveDegree().
  int degree() const { return static_cast<int>(coefficients_.size()) - 1; }

  /// Degree after removing exact-zero leading coefficients; -1 for the zero polynomial.
  int effectiveDegree() const;

  /// True when every coefficient is exactly zero.
  bool isZero() const;

  /// Coefficient of x^i; 0.0 for i > degree(). \throws std::invalid_argument if i < 0.
  double coefficient(int i) const;

  /// Sets the coefficient of x^i, growing the formal degree with zeros when i > degree().
  /// \throws std::invalid_argument if i < 0 or `value` is not finite.
  void setCoefficient(int i, double value);

  /// The stored coefficients, low -> high (size degree() + 1).
  const std::vector<double>& coefficients() const { return coefficients_; }

  /// The stored leading coefficient c_{degree()} (may be zero; see trimmed()).
  double leadingCoefficient() const { return coefficients_.back(); }

  /// max_i |c_i| (0 for the zero polynomial).
  double maxAbsCoefficient() const;

  /// p(x) by Horner's rule (degree() multiply-adds).
  /// \throws std::invalid_argument if x is not finite.
  double operator()(double x) const;

  /// p(x) by Horner's rule together with a running a-posteriori bound on its rounding error
  /// (Higham, "Accuracy and Stability of Numerical Algorithms", 2nd ed., Algorithm 5.1):
  /// |returned - p(x)| <= *abs_error_bound, where p(x) is the exact value for the stored double
  /// coefficients and double x. Higham's bound is first order in the unit roundoff u; we inflate
  /// it by the factor (1 + 4 (n + 2) u) so that it also covers the rounding committed while
  /// accumulating the bound. It assumes no underflow (subnormal intermediate results); if the
  /// evaluation overflows, the bound is +infinity.
  /// \param abs_error_bound output, may be nullptr (then only the value is computed).
  /// \throws std::invalid_argument if x is not finite.
  double evaluateWithBound(double x, double* abs_error_bound) const;

  /// p'(x), formal degree max(degree() - 1, 0). The derivative of a constant is the zero
  /// polynomial.
  Polynomial derivative() const;

  /// Copy without exact-zero leading coefficients (at least one coefficient is kept, so the
  /// zero polynomial stays {0}).
  Polynomial trimmed() const;

  /// q(t) = p(alpha * t + beta), same formal degree, computed by Horner's rule on polynomials
  /// (O(n^2) operations, exact in exact arithmetic).
  /// \throws std::invalid_argument if alpha or beta is not finite.
  Polynomial composeAffine(double alpha, double beta) const;

  Polynomial operator-() const;
  Polynomial& operator+=(const Polynomial& other);
  Polynomial& operator-=(const Polynomial& other);
  Polynomial& operator*=(const Polynomial& other);
  /// \throws std::invalid_argument if `scalar` is not finite.
  Polynomial& operator*=(double scalar);

  /// Exact equality of the coefficient vectors after trimming (so {1, 0} == {1}).
  bool operator==(const Polynomial& other) const;
  bool operator!=(const Polynomial& other) const { return !(*this == other); }

 private:
  /// Unchecked construction from coefficients the caller knows to be valid (non-empty).
  struct Unchecked {};
  Polynomial(std::vector<double> coefficients, Unchecked);

  std::vector<double> coefficients_;

  friend PolynomialDivision divide(const Polynomial& numerator, const Polynomial& denominator);
};

/// Sum; formal degree is the larger of the two.
Polynomial operator+(const Polynomial& a, const Polynomial& b);
/// Difference; formal degree is the larger of the two.
Polynomial operator-(const Polynomial& a, const Polynomial& b);
/// Product (convolution of the coefficient vectors); formal degree a.degree() + b.degree().
Polynomial operator*(const Polynomial& a, const Polynomial& b);
/// Scalar multiple. \throws std::invalid_argument if `s` is not finite.
Polynomial operator*(const Polynomial& a, double s);
/// Scalar multiple. \throws std::invalid_argument if `s` is not finite.
Polynomial operator*(double s, const Polynomial& a);

/// Result of Euclidean division numerator = quotient * denominator + remainder.
struct PolynomialDivision {
  Polynomial quotient;   ///< formal degree max(deg n - deg d, 0) (trimmed degrees)
  Polynomial remainder;  ///< trimmed; degree < deg d (the zero polynomial {0} when d is constant)
};

/// Euclidean long division in double. Both operands are trimmed first; the divisor's (nonzero)
/// leading coefficient is the pivot. If deg numerator < deg denominator the quotient is zero and
/// the remainder is the numerator. The loop runs deg n - deg d + 1 times (no iteration cap needed).
/// \throws std::invalid_argument if `denominator` is the zero polynomial.
PolynomialDivision divide(const Polynomial& numerator, const Polynomial& denominator);

}  // namespace fcl_quadric
