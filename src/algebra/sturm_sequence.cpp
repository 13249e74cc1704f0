#include "fcl_quadric/algebra/sturm_sequence.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "algebra/sign.h"

namespace fcl_quadric {
namespace {

/// p scaled to max|coefficient| = 1 (p nonzero); divides coefficient-wise so that a tiny
/// maximum cannot overflow a reciprocal.
Polynomial normalised(const Polynomial& p) {
  const double m = p.maxAbsCoefficient();
  std::vector<double> c = p.coefficients();
  for (double& v : c) v /= m;
  return Polynomial(std::move(c));
}

using detail::sign;

/// sum_i |c_i| |x|^i.
double absoluteSum(const Polynomial& q, double x) {
  const std::vector<double>& c = q.coefficients();
  const double ax = std::abs(x);
  double r = 0.0;
  for (std::size_t i = c.size(); i-- > 0;) r = r * ax + std::abs(c[i]);
  return r;
}

/// Sign of q just to the right of x. q(x) counts as zero when |q(x)| is within the Horner
/// running error bound plus relative_tol * sum |c_i| |x|^i (the uncertainty of q's own
/// coefficients); then the first derivative that is not zero in this sense decides (at most
/// deg q differentiations; the constant top derivative is decisive).
int rightLimitSign(const Polynomial& q, double x, double relative_tol) {
  Polynomial d = q;
  const int n = q.degree();
  for (int k = 0; k < n; ++k, d = d.derivative()) {
    double bound = 0.0;
    const double v = d.evaluateWithBound(x, &bound);
    if (relative_tol > 0.0) bound += relative_tol * absoluteSum(d, x);
    if (std::abs(v) > bound) return sign(v);
  }
  return sign(d.leadingCoefficient());  // the n-th derivative: a nonzero constant
}

int countChanges(const std::vector<int>& signs) {
  int count = 0;
  int last = 0;
  for (int s : signs) {
    if (s == 0) continue;
    if (last != 0 && s != last) ++count;
    last = s;
  }
  return count;
}

}  // namespace

SturmSequence::SturmSequence(const Polynomial& p) {
  constexpr double u = 1.1102230246251565e-16;  // unit roundoff
  const Polynomial p0 = p.trimmed();
  if (p0.isZero()) {
    throw std::invalid_argument("SturmSequence: the zero polynomial has infinitely many roots");
  }
  sequence_.push_back(p0);  // kept exact: its sign decisions use only the evaluation error
  noise_.push_back(0.0);
  if (p0.degree() == 0) return;
  sequence_.push_back(normalised(sequence_.back().derivative().trimmed()));
  noise_.push_back(4.0 * u);  // integer multiples and one normalisation
  // Each step lowers the degree by at least one, so deg p - 1 steps always suffice.
  for (int step = 0; step + 1 < p0.degree() && sequence_.back().degree() > 0; ++step) {
    const std::size_t k = sequence_.size() - 1;
    const Polynomial& dividend = sequence_[k - 1];
    const Polynomial& divisor = sequence_[k];
    const PolynomialDivision qr = divide(dividend, divisor);
    const double scale =
        std::max(dividend.maxAbsCoefficient(), qr.quotient.maxAbsCoefficient() * divisor.maxAbsCoefficient());
    // Estimated rounding noise of the remainder, relative to scale: inherited relative errors of
    // both operands plus the rounding of the long division.
    const double noise = noise_[k - 1] + noise_[k] + 4.0 * static_cast<double>(dividend.degree() + 1) * u;
    const double threshold = std::max(kSturmRelativeZeroThreshold, kSturmNoiseSafetyFactor * noise) * scale;
    std::vector<double> r = qr.remainder.coefficients();
    while (!r.empty() && std::abs(r.back()) <= threshold) r.pop_back();
    if (r.empty()) break;  // remainder is zero: the last member is gcd(p, p')
    for (double& v : r) v = -v;
    Polynomial next = Polynomial(std::move(r));
    // Normalising a remainder of relative size rho amplifies its relative noise by 1 / rho.
    const double rho = next.maxAbsCoefficient() / scale;
    sequence_.push_back(normalised(next));
    noise_.push_back(noise / rho + 2.0 * u);
  }
}

int SturmSequence::variationsAtPositiveInfinity() const {
  std::vector<int> s;
  s.reserve(sequence_.size());
  for (const Polynomial& q : sequence_) s.push_back(sign(q.leadingCoefficient()));
  return countChanges(s);
}

int SturmSequence::variationsAtNegativeInfinity() const {
  std::vector<int> s;
  s.reserve(sequence_.size());
  for (const Polynomial& q : sequence_) {
    const int lead = sign(q.leadingCoefficient());
    s.push_back(q.degree() % 2 == 0 ? lead : -lead);
  }
  return countChanges(s);
}

int SturmSequence::variationsAt(double x) const {
  if (std::isnan(x)) throw std::invalid_argument("SturmSequence::variationsAt: argument is NaN");
  if (std::isinf(x)) return x > 0.0 ? variationsAtPositiveInfinity() : variationsAtNegativeInfinity();
  std::vector<int> s;
  s.reserve(sequence_.size());
  for (std::size_t k = 0; k < sequence_.size(); ++k) {
    // p_0 is the caller's polynomial (exact coefficients, zero noise); later members carry the
    // estimated rounding noise of the construction.
    s.push_back(rightLimitSign(sequence_[k], x, kSturmValueNoiseFactor * noise_[k]));
  }
  return countChanges(s);
}

int SturmSequence::countDistinctRoots(double a, double b) const {
  if (std::isnan(a) || std::isnan(b) || !(a < b)) {
    std::ostringstream os;
    os.precision(17);
    os << "SturmSequence::countDistinctRoots: empty or inverted interval (" << a << ", " << b << "]";
    throw std::invalid_argument(os.str());
  }
  return variationsAt(a) - variationsAt(b);
}

int SturmSequence::countAllDistinctRoots() const {
  return variationsAtNegativeInfinity() - variationsAtPositiveInfinity();
}

}  // namespace fcl_quadric
