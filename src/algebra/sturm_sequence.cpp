#include "fcl_quadric/algebra/sturm_sequence.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace fcl_quadric {
namespace {

/// p scaled to max|coefficient| = 1 (p nonzero).
Polynomial normalised(const Polynomial& p) { return p * (1.0 / p.maxAbsCoefficient()); }

int sign(double v) { return (v > 0.0) - (v < 0.0); }

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
  for (;;) {
    double bound = 0.0;
    const double v = d.evaluateWithBound(x, &bound);
    if (relative_tol > 0.0) bound += relative_tol * absoluteSum(d, x);
    if (std::abs(v) > bound || d.degree() == 0) return sign(v);
    d = d.derivative();
  }
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
  const Polynomial p0 = p.trimmed();
  if (p0.isZero()) {
    throw std::invalid_argument("SturmSequence: the zero polynomial has infinitely many roots");
  }
  sequence_.push_back(p0);  // kept exact: its sign decisions use only the evaluation error
  if (p0.degree() == 0) return;
  sequence_.push_back(normalised(sequence_.back().derivative().trimmed()));
  // Each iteration lowers the degree by at least one: at most deg p - 1 further members.
  while (sequence_.back().degree() > 0) {
    const Polynomial& dividend = sequence_[sequence_.size() - 2];
    const Polynomial& divisor = sequence_.back();
    const PolynomialDivision qr = divide(dividend, divisor);
    const double scale = std::max(dividend.maxAbsCoefficient(), qr.quotient.maxAbsCoefficient() * divisor.maxAbsCoefficient());
    const double threshold = kSturmRelativeZeroThreshold * scale;
    std::vector<double> r = qr.remainder.coefficients();
    while (!r.empty() && std::abs(r.back()) <= threshold) r.pop_back();
    if (r.empty()) break;  // remainder is zero: the last member is gcd(p, p')
    for (double& v : r) v = -v;
    sequence_.push_back(normalised(Polynomial(std::move(r))));
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
    // p_0 is the caller's polynomial (exact coefficients); later members carry the rounding of
    // the construction, bounded in relative terms by the zero threshold.
    s.push_back(rightLimitSign(sequence_[k], x, k == 0 ? 0.0 : kSturmRelativeZeroThreshold));
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
