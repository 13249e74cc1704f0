#include "fcl_quadric/algebra/polynomial.h"

#include "fcl_quadric/tolerances.h"

#include "algebra/input_checks.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

namespace fcl_quadric {
namespace {

using tolerance::kUnitRoundoff;

using detail::checkFiniteValue;

void checkPowerCoefficients(const char* where, const std::vector<double>& c) {
  detail::checkCoefficients(where, c, /*non_empty=*/false);
}

std::size_t trimmedSize(const std::vector<double>& c) {
  std::size_t n = c.size();
  while (n > 1 && c[n - 1] == 0.0) --n;
  return n;
}

}  // namespace

Polynomial::Polynomial() : coefficients_(1, 0.0) {}

Polynomial::Polynomial(std::vector<double> coefficients) : coefficients_(std::move(coefficients)) {
  if (coefficients_.empty()) coefficients_.assign(1, 0.0);
  checkPowerCoefficients("Polynomial", coefficients_);
}

Polynomial::Polynomial(std::initializer_list<double> coefficients)
    : Polynomial(std::vector<double>(coefficients)) {}

Polynomial::Polynomial(std::vector<double> coefficients, Unchecked) : coefficients_(std::move(coefficients)) {
  if (coefficients_.empty()) coefficients_.assign(1, 0.0);
}

Polynomial Polynomial::constant(double value) {
  checkFiniteValue("Polynomial::constant", "value", value);
  return Polynomial(std::vector<double>(1, value), Unchecked{});
}

Polynomial Polynomial::monomial(int power, double coefficient) {
  if (power < 0) {
    throw std::invalid_argument("Polynomial::monomial: negative power " + std::to_string(power));
  }
  checkFiniteValue("Polynomial::monomial", "coefficient", coefficient);
  std::vector<double> c(static_cast<std::size_t>(power) + 1, 0.0);
  c.back() = coefficient;
  return Polynomial(std::move(c), Unchecked{});
}

Polynomial Polynomial::fromRoots(const std::vector<double>& roots, double leading) {
  checkFiniteValue("Polynomial::fromRoots", "leading coefficient", leading);
  for (double r : roots) checkFiniteValue("Polynomial::fromRoots", "root", r);
  // c holds prod_{k < j} (x - r_k), low -> high; multiply in place by (x - r_j).
  std::vector<double> c(1, leading);
  c.reserve(roots.size() + 1);
  for (double r : roots) {
    c.push_back(0.0);
    for (std::size_t i = c.size() - 1; i > 0; --i) c[i] = c[i - 1] - r * c[i];
    c[0] = -r * c[0];
  }
  return Polynomial(std::move(c), Unchecked{});
}

int Polynomial::effectiveDegree() const {
  const std::size_t n = trimmedSize(coefficients_);
  if (n == 1 && coefficients_[0] == 0.0) return -1;
  return static_cast<int>(n) - 1;
}

bool Polynomial::isZero() const {
  return std::all_of(coefficients_.begin(), coefficients_.end(), [](double v) { return v == 0.0; });
}

double Polynomial::coefficient(int i) const {
  if (i < 0) throw std::invalid_argument("Polynomial::coefficient: negative index " + std::to_string(i));
  return i <= degree() ? coefficients_[static_cast<std::size_t>(i)] : 0.0;
}

void Polynomial::setCoefficient(int i, double value) {
  if (i < 0) throw std::invalid_argument("Polynomial::setCoefficient: negative index " + std::to_string(i));
  checkFiniteValue("Polynomial::setCoefficient", "value", value);
  const std::size_t k = static_cast<std::size_t>(i);
  if (k >= coefficients_.size()) coefficients_.resize(k + 1, 0.0);
  coefficients_[k] = value;
}

double Polynomial::maxAbsCoefficient() const {
  double m = 0.0;
  for (double v : coefficients_) m = std::max(m, std::abs(v));
  return m;
}

double Polynomial::operator()(double x) const {
  checkFiniteValue("Polynomial::operator()", "argument x", x);
  double y = coefficients_.back();
  for (std::size_t i = coefficients_.size() - 1; i-- > 0;) y = y * x + coefficients_[i];
  return y;
}

double Polynomial::evaluateWithBound(double x, double* abs_error_bound) const {
  checkFiniteValue("Polynomial::evaluateWithBound", "argument x", x);
  const std::size_t n = coefficients_.size() - 1;
  double y = coefficients_.back();
  double mu = 0.5 * std::abs(y);
  const double ax = std::abs(x);
  for (std::size_t i = n; i-- > 0;) {
    y = y * x + coefficients_[i];
    mu = ax * mu + std::abs(y);
  }
  if (abs_error_bound != nullptr) {
    if (!std::isfinite(mu)) {  // overflow: no meaningful bound
      *abs_error_bound = std::numeric_limits<double>::infinity();
    } else {
      const double first_order = kUnitRoundoff * std::max(2.0 * mu - std::abs(y), 0.0);
      *abs_error_bound = first_order * (1.0 + 4.0 * static_cast<double>(n + 2) * kUnitRoundoff);
    }
  }
  return y;
}

Polynomial Polynomial::derivative() const {
  const std::size_t n = coefficients_.size();
  if (n == 1) return Polynomial();
  std::vector<double> d(n - 1);
  for (std::size_t i = 1; i < n; ++i) d[i - 1] = static_cast<double>(i) * coefficients_[i];
  return Polynomial(std::move(d), Unchecked{});
}

Polynomial Polynomial::trimmed() const {
  return Polynomial(std::vector<double>(coefficients_.begin(),
                                        coefficients_.begin() + static_cast<std::ptrdiff_t>(trimmedSize(coefficients_))),
                    Unchecked{});
}

Polynomial Polynomial::composeAffine(double alpha, double beta) const {
  checkFiniteValue("Polynomial::composeAffine", "alpha", alpha);
  checkFiniteValue("Polynomial::composeAffine", "beta", beta);
  // Horner on polynomials: q <- q * (alpha t + beta) + c_i, from the leading coefficient down.
  const std::size_t n = coefficients_.size();
  std::vector<double> q(n, 0.0);
  q[0] = coefficients_.back();
  std::size_t len = 1;  // current number of meaningful entries of q
  for (std::size_t i = n - 1; i-- > 0;) {
    // q <- q * (alpha t + beta): new[k] = beta q[k] + alpha q[k-1].
    q[len] = alpha * q[len - 1];
    for (std::size_t k = len - 1; k > 0; --k) q[k] = beta * q[k] + alpha * q[k - 1];
    q[0] = beta * q[0] + coefficients_[i];
    ++len;
  }
  return Polynomial(std::move(q), Unchecked{});
}

Polynomial Polynomial::operator-() const {
  std::vector<double> c(coefficients_);
  for (double& v : c) v = -v;
  return Polynomial(std::move(c), Unchecked{});
}

Polynomial& Polynomial::operator+=(const Polynomial& other) {
  if (other.coefficients_.size() > coefficients_.size()) coefficients_.resize(other.coefficients_.size(), 0.0);
  for (std::size_t i = 0; i < other.coefficients_.size(); ++i) coefficients_[i] += other.coefficients_[i];
  return *this;
}

Polynomial& Polynomial::operator-=(const Polynomial& other) {
  if (other.coefficients_.size() > coefficients_.size()) coefficients_.resize(other.coefficients_.size(), 0.0);
  for (std::size_t i = 0; i < other.coefficients_.size(); ++i) coefficients_[i] -= other.coefficients_[i];
  return *this;
}

Polynomial& Polynomial::operator*=(const Polynomial& other) {
  const std::size_t na = coefficients_.size();
  const std::size_t nb = other.coefficients_.size();
  std::vector<double> c(na + nb - 1, 0.0);
  for (std::size_t i = 0; i < na; ++i) {
    for (std::size_t j = 0; j < nb; ++j) c[i + j] += coefficients_[i] * other.coefficients_[j];
  }
  coefficients_ = std::move(c);
  return *this;
}

Polynomial& Polynomial::operator*=(double scalar) {
  checkFiniteValue("Polynomial::operator*", "scalar", scalar);
  for (double& v : coefficients_) v *= scalar;
  return *this;
}

bool Polynomial::operator==(const Polynomial& other) const {
  const std::size_t na = trimmedSize(coefficients_);
  const std::size_t nb = trimmedSize(other.coefficients_);
  return na == nb && std::equal(coefficients_.begin(), coefficients_.begin() + static_cast<std::ptrdiff_t>(na),
                                other.coefficients_.begin());
}

Polynomial operator+(const Polynomial& a, const Polynomial& b) {
  Polynomial r(a);
  r += b;
  return r;
}

Polynomial operator-(const Polynomial& a, const Polynomial& b) {
  Polynomial r(a);
  r -= b;
  return r;
}

Polynomial operator*(const Polynomial& a, const Polynomial& b) {
  Polynomial r(a);
  r *= b;
  return r;
}

Polynomial operator*(const Polynomial& a, double s) {
  Polynomial r(a);
  r *= s;
  return r;
}

Polynomial operator*(double s, const Polynomial& a) { return a * s; }

PolynomialDivision divide(const Polynomial& numerator, const Polynomial& denominator) {
  const Polynomial d = denominator.trimmed();
  if (d.isZero()) throw std::invalid_argument("divide: the denominator is the zero polynomial");
  std::vector<double> r = numerator.trimmed().coefficients_;
  const std::size_t m = d.coefficients_.size() - 1;  // deg d
  if (r.size() - 1 < m) {
    return PolynomialDivision{Polynomial(), Polynomial(std::move(r), Polynomial::Unchecked{})};
  }
  const std::size_t n = r.size() - 1;  // deg numerator >= m
  const double lead = d.coefficients_.back();
  std::vector<double> q(n - m + 1, 0.0);
  for (std::size_t k = n - m + 1; k-- > 0;) {
    const double qk = r[m + k] / lead;
    q[k] = qk;
    r[m + k] = 0.0;  // eliminated exactly by construction
    for (std::size_t j = 0; j < m; ++j) r[j + k] -= qk * d.coefficients_[j];
  }
  r.resize(std::max<std::size_t>(m, 1));
  if (m == 0) r[0] = 0.0;
  Polynomial remainder = Polynomial(std::move(r), Polynomial::Unchecked{}).trimmed();
  return PolynomialDivision{Polynomial(std::move(q), Polynomial::Unchecked{}), std::move(remainder)};
}

}  // namespace fcl_quadric
