#include "fcl_quadric/algebra/bernstein_polynomial.h"

#include "algebra/bernstein_matrix.h"
#include "algebra/input_checks.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

namespace fcl_quadric {
namespace detail {

namespace {

double binomialLoop(int n, int k) {
  k = std::min(k, n - k);
  double r = 1.0;
  // r_i = C(n - k + i, i) is an integer at every step; exact while below 2^53.
  for (int i = 1; i <= k; ++i) r = r * static_cast<double>(n - k + i) / static_cast<double>(i);
  return r;
}

// Rows 0..kTableRows-1 of Pascal's triangle, computed once by the same loop (identical values):
// the basis conversions call binomial() O(n^2) times, which profiling showed at ~20 % of a
// continuous-collision query.
constexpr int kTableRows = 160;
const std::vector<double>& binomialTable() {
  static const std::vector<double> table = [] {
    std::vector<double> t;
    t.reserve(kTableRows * (kTableRows + 1) / 2);
    for (int n = 0; n < kTableRows; ++n)
      for (int k = 0; k <= n; ++k) t.push_back(binomialLoop(n, k));
    return t;
  }();
  return table;
}

}  // namespace

const double* binomialTableRow(std::size_t n) {
  if (n >= static_cast<std::size_t>(kTableRows)) return nullptr;
  return binomialTable().data() + n * (n + 1) / 2;
}

double binomial(int n, int k) {
  if (k < 0 || k > n) return 0.0;
  if (n < kTableRows) return binomialTable()[static_cast<std::size_t>(n * (n + 1) / 2 + k)];
  if (n > kMaxBernsteinDegree) {
    // Beyond it C(n, k) overflows (n > 1029) and the conversions would divide inf by inf: NaN
    // coefficients, which a sign test can mistake for a certificate (found in session 34: a
    // degree-1024 cull polynomial of the CCD "certified" a colliding pair separate).
    throw std::invalid_argument("Bernstein basis: degree " + std::to_string(n) + " exceeds kMaxBernsteinDegree = " +
                                std::to_string(kMaxBernsteinDegree));
  }
  return binomialLoop(n, k);
}

void checkInterval(const char* where, double a, double b) {
  if (!std::isfinite(a) || !std::isfinite(b) || !(a < b)) {
    std::ostringstream os;
    os << where << ": invalid interval [" << a << ", " << b << "] (bounds must be finite with a < b)";
    throw std::invalid_argument(os.str());
  }
}

double deCasteljauEvaluate(const std::vector<double>& c, double s) {
  std::vector<double> w(c);
  const double r = 1.0 - s;
  for (std::size_t level = w.size() - 1; level > 0; --level) {
    for (std::size_t i = 0; i < level; ++i) w[i] = r * w[i] + s * w[i + 1];
  }
  return w[0];
}

void deCasteljauSplit(const std::vector<double>& c, double s, std::vector<double>* left,
                      std::vector<double>* right) {
  const std::size_t n1 = c.size();
  std::vector<double> w(c);
  std::vector<double> l(n1);
  std::vector<double> rgt(n1);
  const double r = 1.0 - s;
  l[0] = w[0];
  rgt[n1 - 1] = w[n1 - 1];
  for (std::size_t level = n1 - 1; level > 0; --level) {
    for (std::size_t i = 0; i < level; ++i) w[i] = r * w[i] + s * w[i + 1];
    l[n1 - level] = w[0];
    rgt[level - 1] = w[level - 1];
  }
  if (left != nullptr) *left = std::move(l);
  if (right != nullptr) *right = std::move(rgt);
}

namespace {
// In place, the coefficients on [0, s] (the left part of deCasteljauSplit): after level j, c[i]
// holds the triangle's entry (j, i - j) for i >= j, computed as r * (j-1, i-j) + s * (j-1, i-j+1),
// the operands and order of deCasteljauSplit's w[i] = r * w[i] + s * w[i + 1]. Lane l's
// coefficient i is c[i * stride + l]; the innermost loop runs over the lanes (contiguous).
void leftInPlace(double* c, std::size_t n1, std::ptrdiff_t stride, std::size_t lanes, double s) {
  const double r = 1.0 - s;
  for (std::size_t level = 1; level < n1; ++level) {
    for (std::size_t i = n1 - 1; i >= level; --i) {
      double* dst = c + static_cast<std::ptrdiff_t>(i) * stride;
      const double* src = dst - stride;
      for (std::size_t l = 0; l < lanes; ++l) dst[l] = r * src[l] + s * dst[l];
    }
  }
}
// In place, the coefficients on [s, 1]: after level j, c[i] holds the entry (j, i) for i <= n - j.
void rightInPlace(double* c, std::size_t n1, std::ptrdiff_t stride, std::size_t lanes, double s) {
  const double r = 1.0 - s;
  for (std::size_t level = n1 - 1; level > 0; --level) {
    for (std::size_t i = 0; i < level; ++i) {
      double* dst = c + static_cast<std::ptrdiff_t>(i) * stride;
      const double* src = dst + stride;
      for (std::size_t l = 0; l < lanes; ++l) dst[l] = r * dst[l] + s * src[l];
    }
  }
}
}  // namespace

void restrictInPlace(double* c, std::size_t n1, std::ptrdiff_t stride, std::size_t lanes, double a, double b,
                     double lo, double hi) {
  if (lo == a && hi == b) return;
  if (hi != a) {
    // Left part on [a, hi], then the right part of that at lo.
    if (hi != b) leftInPlace(c, n1, stride, lanes, (hi - a) / (b - a));
    if (lo != a) rightInPlace(c, n1, stride, lanes, (lo - a) / (hi - a));
  } else {
    // hi == a, so lo < a: right part on [lo, b] first, then its left part at hi.
    rightInPlace(c, n1, stride, lanes, (lo - a) / (b - a));
    leftInPlace(c, n1, stride, lanes, (hi - lo) / (b - lo));
  }
}

std::vector<double> powerToBernsteinUnit(const std::vector<double>& q, int n) {
  std::vector<double> c(static_cast<std::size_t>(n) + 1, 0.0);
  const int m = static_cast<int>(q.size()) - 1;
  for (int i = 0; i <= n; ++i) {
    double sum = 0.0;
    for (int k = 0; k <= std::min(i, m); ++k) {
      sum += binomial(i, k) / binomial(n, k) * q[static_cast<std::size_t>(k)];
    }
    c[static_cast<std::size_t>(i)] = sum;
  }
  return c;
}

std::vector<double> bernsteinToPowerUnit(const std::vector<double>& c) {
  const int n = static_cast<int>(c.size()) - 1;
  std::vector<double> q(c.size(), 0.0);
  for (int k = 0; k <= n; ++k) {
    double sum = 0.0;
    for (int i = 0; i <= k; ++i) {
      const double term = binomial(k, i) * c[static_cast<std::size_t>(i)];
      sum += ((k - i) % 2 == 0) ? term : -term;
    }
    q[static_cast<std::size_t>(k)] = binomial(n, k) * sum;
  }
  return q;
}

int signVariations(const std::vector<double>& c) {
  int count = 0;
  int last = 0;
  for (double v : c) {
    const int s = (v > 0.0) - (v < 0.0);
    if (s == 0) continue;
    if (last != 0 && s != last) ++count;
    last = s;
  }
  return count;
}

}  // namespace detail

namespace {

using detail::checkFiniteValue;

void checkBernsteinCoefficients(const char* where, const std::vector<double>& c) {
  detail::checkCoefficients(where, c, /*non_empty=*/true);
}

void checkSameInterval(const char* where, double a0, double b0, double a1, double b1) {
  if (a0 != a1 || b0 != b1) {
    std::ostringstream os;
    os.precision(17);
    os << where << ": interval mismatch [" << a0 << ", " << b0 << "] vs [" << a1 << ", " << b1 << "]";
    throw std::invalid_argument(os.str());
  }
}

}  // namespace

BernsteinPolynomial::BernsteinPolynomial() : coefficients_(1, 0.0), a_(0.0), b_(1.0) {}

BernsteinPolynomial::BernsteinPolynomial(std::vector<double> coefficients, double a, double b)
    : coefficients_(std::move(coefficients)), a_(a), b_(b) {
  checkBernsteinCoefficients("BernsteinPolynomial", coefficients_);
  detail::checkInterval("BernsteinPolynomial", a, b);
}

BernsteinPolynomial::BernsteinPolynomial(std::vector<double> coefficients, double a, double b, Unchecked)
    : coefficients_(std::move(coefficients)), a_(a), b_(b) {}

BernsteinPolynomial BernsteinPolynomial::fromPower(const Polynomial& p, double a, double b, int degree) {
  detail::checkInterval("BernsteinPolynomial::fromPower", a, b);
  if (degree < -1 || (degree >= 0 && degree < p.effectiveDegree())) {
    std::ostringstream os;
    os << "BernsteinPolynomial::fromPower: degree mismatch: requested degree " << degree
       << " but the polynomial has degree " << p.effectiveDegree();
    throw std::invalid_argument(os.str());
  }
  const int n = degree == -1 ? p.degree() : degree;
  Polynomial q = p.trimmed();
  if (a != 0.0 || b != 1.0) q = q.composeAffine(b - a, a);
  return BernsteinPolynomial(detail::powerToBernsteinUnit(q.coefficients(), n), a, b, Unchecked{});
}

BernsteinPolynomial BernsteinPolynomial::fromScaled(const std::vector<double>& scaled, double a, double b) {
  checkBernsteinCoefficients("BernsteinPolynomial::fromScaled", scaled);
  detail::checkInterval("BernsteinPolynomial::fromScaled", a, b);
  const int n = static_cast<int>(scaled.size()) - 1;
  std::vector<double> c(scaled.size());
  for (int i = 0; i <= n; ++i) {
    c[static_cast<std::size_t>(i)] = scaled[static_cast<std::size_t>(i)] / detail::binomial(n, i);
  }
  return BernsteinPolynomial(std::move(c), a, b, Unchecked{});
}

double BernsteinPolynomial::coefficient(int i) const {
  if (i < 0 || i > degree()) {
    throw std::invalid_argument("BernsteinPolynomial::coefficient: index " + std::to_string(i) +
                                " outside [0, " + std::to_string(degree()) + "]");
  }
  return coefficients_[static_cast<std::size_t>(i)];
}

double BernsteinPolynomial::evaluate(double t) const {
  checkFiniteValue("BernsteinPolynomial::evaluate", "argument t", t);
  if (t == a_) return coefficients_.front();
  if (t == b_) return coefficients_.back();
  return detail::deCasteljauEvaluate(coefficients_, (t - a_) / (b_ - a_));
}

std::pair<BernsteinPolynomial, BernsteinPolynomial> BernsteinPolynomial::subdivide(double t) const {
  checkFiniteValue("BernsteinPolynomial::subdivide", "parameter t", t);
  if (!(a_ < t && t < b_)) {
    std::ostringstream os;
    os.precision(17);
    os << "BernsteinPolynomial::subdivide: parameter " << t << " not strictly inside (" << a_ << ", " << b_ << ")";
    throw std::invalid_argument(os.str());
  }
  std::vector<double> left;
  std::vector<double> right;
  detail::deCasteljauSplit(coefficients_, (t - a_) / (b_ - a_), &left, &right);
  return {BernsteinPolynomial(std::move(left), a_, t, Unchecked{}),
          BernsteinPolynomial(std::move(right), t, b_, Unchecked{})};
}

BernsteinPolynomial BernsteinPolynomial::restrict(double c, double d) const {
  detail::checkInterval("BernsteinPolynomial::restrict", c, d);
  std::vector<double> out(coefficients_);
  detail::restrictInPlace(out.data(), out.size(), 1, 1, a_, b_, c, d);
  return BernsteinPolynomial(std::move(out), c, d, Unchecked{});
}

BernsteinPolynomial BernsteinPolynomial::derivative() const {
  const int n = degree();
  if (n == 0) return BernsteinPolynomial(std::vector<double>(1, 0.0), a_, b_, Unchecked{});
  std::vector<double> d(static_cast<std::size_t>(n));
  const double scale = static_cast<double>(n) / (b_ - a_);
  for (std::size_t i = 0; i < d.size(); ++i) d[i] = scale * (coefficients_[i + 1] - coefficients_[i]);
  return BernsteinPolynomial(std::move(d), a_, b_, Unchecked{});
}

BernsteinPolynomial BernsteinPolynomial::elevate() const {
  const std::size_t n1 = coefficients_.size();  // n + 1
  std::vector<double> e(n1 + 1);
  e[0] = coefficients_.front();
  e[n1] = coefficients_.back();
  const double inv = 1.0 / static_cast<double>(n1);
  for (std::size_t i = 1; i < n1; ++i) {
    const double w = static_cast<double>(i) * inv;
    e[i] = w * coefficients_[i - 1] + (1.0 - w) * coefficients_[i];
  }
  return BernsteinPolynomial(std::move(e), a_, b_, Unchecked{});
}

BernsteinPolynomial BernsteinPolynomial::elevateTo(int target) const {
  if (target < degree()) {
    throw std::invalid_argument("BernsteinPolynomial::elevateTo: degree mismatch: target " + std::to_string(target) +
                                " is below the degree " + std::to_string(degree()));
  }
  BernsteinPolynomial r(*this);
  while (r.degree() < target) r = r.elevate();  // runs target - degree() times
  return r;
}

int BernsteinPolynomial::signVariations() const { return detail::signVariations(coefficients_); }

double BernsteinPolynomial::minCoefficient() const {
  return *std::min_element(coefficients_.begin(), coefficients_.end());
}

double BernsteinPolynomial::maxCoefficient() const {
  return *std::max_element(coefficients_.begin(), coefficients_.end());
}

bool BernsteinPolynomial::isZero() const {
  return std::all_of(coefficients_.begin(), coefficients_.end(), [](double v) { return v == 0.0; });
}

Polynomial BernsteinPolynomial::toPower() const {
  Polynomial q(detail::bernsteinToPowerUnit(coefficients_));
  if (a_ == 0.0 && b_ == 1.0) return q;
  const double inv = 1.0 / (b_ - a_);
  return q.composeAffine(inv, -a_ * inv);
}

std::vector<double> BernsteinPolynomial::toScaled() const {
  const int n = degree();
  std::vector<double> d(coefficients_.size());
  for (int i = 0; i <= n; ++i) {
    d[static_cast<std::size_t>(i)] = detail::binomial(n, i) * coefficients_[static_cast<std::size_t>(i)];
  }
  return d;
}

BernsteinPolynomial BernsteinPolynomial::operator-() const {
  std::vector<double> c(coefficients_);
  for (double& v : c) v = -v;
  return BernsteinPolynomial(std::move(c), a_, b_, Unchecked{});
}

namespace {
void checkSameDegree(const char* where, int m, int n) {
  if (m != n) {
    throw std::invalid_argument(std::string(where) + ": degree mismatch " + std::to_string(m) + " vs " +
                                std::to_string(n) + " (elevate the lower one first)");
  }
}
}  // namespace

BernsteinPolynomial BernsteinPolynomial::operator+(const BernsteinPolynomial& other) const {
  checkSameDegree("BernsteinPolynomial::operator+", degree(), other.degree());
  checkSameInterval("BernsteinPolynomial::operator+", a_, b_, other.a_, other.b_);
  std::vector<double> c(coefficients_);
  for (std::size_t i = 0; i < c.size(); ++i) c[i] += other.coefficients_[i];
  return BernsteinPolynomial(std::move(c), a_, b_, Unchecked{});
}

BernsteinPolynomial BernsteinPolynomial::operator-(const BernsteinPolynomial& other) const {
  checkSameDegree("BernsteinPolynomial::operator-", degree(), other.degree());
  checkSameInterval("BernsteinPolynomial::operator-", a_, b_, other.a_, other.b_);
  std::vector<double> c(coefficients_);
  for (std::size_t i = 0; i < c.size(); ++i) c[i] -= other.coefficients_[i];
  return BernsteinPolynomial(std::move(c), a_, b_, Unchecked{});
}

BernsteinPolynomial BernsteinPolynomial::operator*(double s) const {
  checkFiniteValue("BernsteinPolynomial::operator*", "scalar", s);
  std::vector<double> c(coefficients_);
  for (double& v : c) v *= s;
  return BernsteinPolynomial(std::move(c), a_, b_, Unchecked{});
}

BernsteinPolynomial operator*(const BernsteinPolynomial& p, const BernsteinPolynomial& q) {
  checkSameInterval("operator*(BernsteinPolynomial, BernsteinPolynomial)", p.a_, p.b_, q.a_, q.b_);
  // Product of scaled forms is a plain convolution; unscale by C(m+n, k).
  const std::vector<double> ps = p.toScaled();
  const std::vector<double> qs = q.toScaled();
  const int mn = p.degree() + q.degree();
  std::vector<double> c(static_cast<std::size_t>(mn) + 1, 0.0);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    for (std::size_t j = 0; j < qs.size(); ++j) c[i + j] += ps[i] * qs[j];
  }
  for (int k = 0; k <= mn; ++k) c[static_cast<std::size_t>(k)] /= detail::binomial(mn, k);
  return BernsteinPolynomial(std::move(c), p.a_, p.b_, BernsteinPolynomial::Unchecked{});
}

}  // namespace fcl_quadric
