#pragma once
/// \file bernstein_polynomial.h
/// Univariate polynomials in the Bernstein basis of an interval [a, b].
///
/// p(t) = sum_{i=0}^{n} c_i B_i^n(s),  B_i^n(s) = C(n,i) (1-s)^(n-i) s^i,  s = (t-a)/(b-a).
///
/// Properties used by the root finders (root_isolation.h): p(a) = c_0, p(b) = c_n, and for
/// t in [a,b] the graph (t, p(t)) lies in the convex hull of the control points
/// (a + (i/n)(b-a), c_i); hence min_i c_i <= p(t) <= max_i c_i on [a,b].
///
/// Part of the algebra layer: depends on the standard library only.

#include <utility>
#include <vector>

#include "fcl_quadric/algebra/polynomial.h"

namespace fcl_quadric {

/// Largest degree of the Bernstein-basis conversions (fromPower(), fromScaled(), toPower(),
/// toScaled(), products, degree elevation): their weights are binomial coefficients C(n, k),
/// which overflow a double beyond n = 1029 (C(1030, 515) > 1.8e308), and the conversion would
/// then produce NaN coefficients. A conversion of higher degree throws std::invalid_argument
/// naming the degree instead. 1000 keeps every intermediate product of the binomial loop finite.
constexpr int kMaxBernsteinDegree = 1000;

/// A polynomial of degree n (formal) in the Bernstein basis of [a, b], a < b, both finite.
///
/// Bad input: a non-finite coefficient or bound, an empty coefficient vector, or a >= b throws
/// std::invalid_argument naming the offending value. No member function iterates beyond the
/// O(n^2) loops of de Casteljau's algorithm (no iteration caps are needed).
class BernsteinPolynomial {
 public:
  /// The zero polynomial of degree 0 on [0, 1].
  BernsteinPolynomial();

  /// From Bernstein coefficients c_0..c_n on [a, b].
  /// \throws std::invalid_argument if `coefficients` is empty, a coefficient is not finite,
  ///         a or b is not finite, or a >= b (empty or inverted interval).
  explicit BernsteinPolynomial(std::vector<double> coefficients, double a = 0.0, double b = 1.0);

  /// Exact (in exact arithmetic) conversion of a power-form polynomial in t to the Bernstein
  /// basis of [a, b]: substitutes t = a + (b-a) s (Polynomial::composeAffine) and applies
  /// c_i = sum_{k<=i} C(i,k)/C(n,k) q_k. The conversion is well conditioned for [a,b] near
  /// [0,1]; far from the origin the substitution amplifies rounding like any basis change.
  /// \param degree target degree n; -1 (default) means p.degree(). A larger degree gives the
  ///        degree-elevated representation.
  /// \throws std::invalid_argument on a bad interval (as the constructor) or if
  ///         0 <= degree < p.effectiveDegree() (degree mismatch) or degree < -1.
  static BernsteinPolynomial fromPower(const Polynomial& p, double a = 0.0, double b = 1.0, int degree = -1);

  /// From *scaled* Bernstein coefficients d_i = C(n,i) c_i, i.e.
  /// p(t) = sum_i d_i (1-s)^(n-i) s^i. Validation as the constructor.
  static BernsteinPolynomial fromScaled(const std::vector<double>& scaled, double a = 0.0, double b = 1.0);

  /// Formal degree n (number of coefficients minus one).
  int degree() const { return static_cast<int>(coefficients_.size()) - 1; }
  double lower() const { return a_; }
  double upper() const { return b_; }
  double width() const { return b_ - a_; }
  const std::vector<double>& coefficients() const { return coefficients_; }
  /// c_i. \throws std::invalid_argument unless 0 <= i <= degree().
  double coefficient(int i) const;

  /// p(t) by de Casteljau's algorithm (backward stable for t in [a,b]; t outside [a,b]
  /// extrapolates, with error growing like |s|^n). \throws std::invalid_argument if t is not
  /// finite.
  double evaluate(double t) const;
  double operator()(double t) const { return evaluate(t); }

  /// Splits at the absolute parameter t, a < t < b, by de Casteljau's algorithm: returns the
  /// representations on [a, t] and on [t, b] (same degree). The value at t is computed once and
  /// shared: first.coefficients().back() == second.coefficients().front() bit for bit.
  /// \throws std::invalid_argument if t is not finite or not strictly inside (a, b).
  std::pair<BernsteinPolynomial, BernsteinPolynomial> subdivide(double t) const;

  /// The same polynomial represented on [c, d] (two de Casteljau splits; exact in exact
  /// arithmetic). [c,d] inside [a,b] is the stable case; outside it extrapolates.
  /// restrict(a, b) returns *this unchanged and restrict(a, t) equals subdivide(t).first.
  /// \throws std::invalid_argument if c or d is not finite or c >= d.
  BernsteinPolynomial restrict(double c, double d) const;

  /// p'(t) in the Bernstein basis of [a, b]: degree n-1 with coefficients
  /// n (c_{i+1} - c_i) / (b - a). The derivative of a degree-0 polynomial is the zero
  /// polynomial of degree 0.
  BernsteinPolynomial derivative() const;

  /// Degree elevation by one: same polynomial, degree n+1,
  /// c'_i = (i/(n+1)) c_{i-1} + (1 - i/(n+1)) c_i.
  BernsteinPolynomial elevate() const;

  /// Repeated elevation to `degree`. \throws std::invalid_argument if degree < this->degree().
  BernsteinPolynomial elevateTo(int degree) const;

  /// Sign variations of c_0..c_n, zeros ignored. Descartes' rule in the Bernstein basis: the
  /// number of roots in the *open* interval (a, b), counted with multiplicity, is at most this
  /// count and has the same parity.
  int signVariations() const;

  /// min_i c_i and max_i c_i: bounds of p on [a, b] by the convex hull property.
  double minCoefficient() const;
  double maxCoefficient() const;

  /// True when every coefficient is exactly zero.
  bool isZero() const;

  /// Conversion to the power basis in the absolute variable t (exact in exact arithmetic):
  /// q_k = C(n,k) sum_{i<=k} (-1)^(k-i) C(k,i) c_i in s, then s = (t-a)/(b-a).
  Polynomial toPower() const;

  /// Scaled Bernstein coefficients d_i = C(n,i) c_i (p(t) = sum_i d_i (1-s)^(n-i) s^i).
  std::vector<double> toScaled() const;

  /// Unary minus, sum and difference. Operands of a sum or difference must have the same
  /// degree and the same interval (bitwise); elevate first otherwise.
  /// \throws std::invalid_argument on a degree or interval mismatch.
  BernsteinPolynomial operator-() const;
  BernsteinPolynomial operator+(const BernsteinPolynomial& other) const;
  BernsteinPolynomial operator-(const BernsteinPolynomial& other) const;
  /// Scalar multiple. \throws std::invalid_argument if `s` is not finite.
  BernsteinPolynomial operator*(double s) const;

 private:
  struct Unchecked {};
  BernsteinPolynomial(std::vector<double> coefficients, double a, double b, Unchecked);

  std::vector<double> coefficients_;
  double a_;
  double b_;

  friend BernsteinPolynomial operator*(const BernsteinPolynomial& p, const BernsteinPolynomial& q);
};

/// Product of two Bernstein polynomials on the same interval (bitwise equal bounds); degree
/// m + n, coefficients sum_{i+j=k} C(m,i) C(n,j) / C(m+n,k) p_i q_j.
/// \throws std::invalid_argument if the intervals differ.
BernsteinPolynomial operator*(const BernsteinPolynomial& p, const BernsteinPolynomial& q);

namespace detail {

/// Binomial coefficient C(n, k) in double (exact while it is below 2^53; n <= 56 always is).
/// Returns 0 for k < 0 or k > n. \pre n >= 0. \throws std::invalid_argument if
/// n > kMaxBernsteinDegree (every basis conversion above that degree goes through here).
double binomial(int n, int k);

/// Throws std::invalid_argument naming `where` unless a and b are finite and a < b.
void checkInterval(const char* where, double a, double b);

/// De Casteljau evaluation of the Bernstein coefficients `c` (on [0,1]) at the unit parameter s.
/// \pre !c.empty(). Work space is allocated internally.
double deCasteljauEvaluate(const std::vector<double>& c, double s);

/// De Casteljau split of `c` (on [0,1]) at the unit parameter s: `left` receives the
/// coefficients on [0, s] and `right` those on [s, 1] (either may be nullptr). The shared value
/// left->back() == right->front() is the same computed double. \pre !c.empty().
void deCasteljauSplit(const std::vector<double>& c, double s, std::vector<double>* left,
                      std::vector<double>* right);

/// In place and without allocation: `lanes` polynomials of n1 coefficients each, lane l's
/// coefficient i at c[i * stride + l] (stride >= lanes), Bernstein on [a, b], become those of the
/// same polynomials on [lo, hi] (any finite interval, lo < hi; stable inside [a, b]). The same
/// arithmetic as BernsteinPolynomial::restrict (two de Casteljau splits, none where an end is
/// kept), so the results are the same doubles. Used on the columns of bivariate coefficient
/// matrices (lanes = 1) and across their rows (the lanes contiguous, so the loop vectorises).
/// \pre n1 >= 1.
void restrictInPlace(double* c, std::size_t n1, std::ptrdiff_t stride, std::size_t lanes, double a, double b,
                     double lo, double hi);

/// Power coefficients q_k (in s) -> Bernstein coefficients on [0,1] of degree n >= deg q.
std::vector<double> powerToBernsteinUnit(const std::vector<double>& q, int n);

/// Bernstein coefficients on [0,1] -> power coefficients in s (same length).
std::vector<double> bernsteinToPowerUnit(const std::vector<double>& c);

/// Number of sign changes in `c`, zeros ignored.
int signVariations(const std::vector<double>& c);

}  // namespace detail
}  // namespace fcl_quadric
