#include "fcl_quadric/algebra/polynomial_matrix.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "algebra/input_checks.h"
#include "algebra/lambda_polynomial.h"

namespace fcl_quadric {
namespace {

using detail::Bivariate;
using detail::operator*;
using detail::operator+;
using detail::operator-;
using detail::checkFiniteMatrix;

void checkIndex(int i, int j) {
  if (i < 0 || i > 3 || j < 0 || j > 3) {
    throw std::invalid_argument("PolynomialMatrix4: index (" + std::to_string(i) + ", " + std::to_string(j) +
                                ") outside [0, 3]");
  }
}

/// Determinant of a row-major 4x4 array by Laplace expansion along rows (0,1) against the
/// complementary minors of rows (2,3).
template <typename T>
T laplaceDeterminant(const std::array<T, 16>& a) {
  auto e = [&a](int i, int j) -> const T& { return a[static_cast<std::size_t>(4 * i + j)]; };
  const T s0 = e(0, 0) * e(1, 1) - e(0, 1) * e(1, 0);
  const T s1 = e(0, 0) * e(1, 2) - e(0, 2) * e(1, 0);
  const T s2 = e(0, 0) * e(1, 3) - e(0, 3) * e(1, 0);
  const T s3 = e(0, 1) * e(1, 2) - e(0, 2) * e(1, 1);
  const T s4 = e(0, 1) * e(1, 3) - e(0, 3) * e(1, 1);
  const T s5 = e(0, 2) * e(1, 3) - e(0, 3) * e(1, 2);
  const T c5 = e(2, 2) * e(3, 3) - e(2, 3) * e(3, 2);
  const T c4 = e(2, 1) * e(3, 3) - e(2, 3) * e(3, 1);
  const T c3 = e(2, 1) * e(3, 2) - e(2, 2) * e(3, 1);
  const T c2 = e(2, 0) * e(3, 3) - e(2, 3) * e(3, 0);
  const T c1 = e(2, 0) * e(3, 2) - e(2, 2) * e(3, 0);
  const T c0 = e(2, 0) * e(3, 1) - e(2, 1) * e(3, 0);
  return s0 * c5 - s1 * c4 + s2 * c3 + s3 * c2 - s4 * c1 + s5 * c0;
}

}  // namespace

PolynomialMatrix4::PolynomialMatrix4() = default;

PolynomialMatrix4::PolynomialMatrix4(const Eigen::Matrix4d& M) {
  checkFiniteMatrix("PolynomialMatrix4", "M", M);
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) entries_[static_cast<std::size_t>(4 * i + j)] = Polynomial::constant(M(i, j));
  }
}

PolynomialMatrix4 PolynomialMatrix4::fromCoefficients(const std::vector<Eigen::Matrix4d>& matrices) {
  PolynomialMatrix4 r;
  for (std::size_t k = 0; k < matrices.size(); ++k) {
    const std::string what = "M_" + std::to_string(k);
    checkFiniteMatrix("PolynomialMatrix4::fromCoefficients", what.c_str(), matrices[k]);
  }
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      std::vector<double> c(std::max<std::size_t>(matrices.size(), 1), 0.0);
      for (std::size_t k = 0; k < matrices.size(); ++k) c[k] = matrices[k](i, j);
      r.entries_[static_cast<std::size_t>(4 * i + j)] = Polynomial(std::move(c));
    }
  }
  return r;
}

PolynomialMatrix4 PolynomialMatrix4::linear(const Eigen::Matrix4d& M0, const Eigen::Matrix4d& M1) {
  return fromCoefficients({M0, M1});
}

const Polynomial& PolynomialMatrix4::operator()(int i, int j) const {
  checkIndex(i, j);
  return entries_[static_cast<std::size_t>(4 * i + j)];
}

Polynomial& PolynomialMatrix4::operator()(int i, int j) {
  checkIndex(i, j);
  return entries_[static_cast<std::size_t>(4 * i + j)];
}

int PolynomialMatrix4::maxDegree() const {
  int d = 0;
  for (const Polynomial& p : entries_) d = std::max(d, p.degree());
  return d;
}

Eigen::Matrix4d PolynomialMatrix4::evaluate(double t) const {
  Eigen::Matrix4d M;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) M(i, j) = entries_[static_cast<std::size_t>(4 * i + j)](t);
  }
  return M;
}

PolynomialMatrix4 PolynomialMatrix4::transpose() const {
  PolynomialMatrix4 r;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) r.entries_[static_cast<std::size_t>(4 * j + i)] = entries_[static_cast<std::size_t>(4 * i + j)];
  }
  return r;
}

PolynomialMatrix4 PolynomialMatrix4::operator+(const PolynomialMatrix4& other) const {
  PolynomialMatrix4 r(*this);
  for (std::size_t k = 0; k < 16; ++k) r.entries_[k] += other.entries_[k];
  return r;
}

PolynomialMatrix4 PolynomialMatrix4::operator-(const PolynomialMatrix4& other) const {
  PolynomialMatrix4 r(*this);
  for (std::size_t k = 0; k < 16; ++k) r.entries_[k] -= other.entries_[k];
  return r;
}

PolynomialMatrix4 PolynomialMatrix4::operator*(const PolynomialMatrix4& other) const {
  PolynomialMatrix4 r;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      Polynomial s;
      for (int k = 0; k < 4; ++k) {
        s += entries_[static_cast<std::size_t>(4 * i + k)] * other.entries_[static_cast<std::size_t>(4 * k + j)];
      }
      r.entries_[static_cast<std::size_t>(4 * i + j)] = s;
    }
  }
  return r;
}

PolynomialMatrix4 PolynomialMatrix4::operator*(double s) const {
  if (!std::isfinite(s)) {
    std::ostringstream os;
    os << "PolynomialMatrix4::operator*: non-finite scalar (" << s << ")";
    throw std::invalid_argument(os.str());
  }
  PolynomialMatrix4 r(*this);
  for (Polynomial& p : r.entries_) p *= s;
  return r;
}

PolynomialMatrix4 PolynomialMatrix4::operator*(const Polynomial& q) const {
  PolynomialMatrix4 r(*this);
  for (Polynomial& p : r.entries_) p *= q;
  return r;
}

Polynomial PolynomialMatrix4::determinant() const { return laplaceDeterminant(entries_); }

Polynomial pencilDeterminant(const Eigen::Matrix4d& A, const Eigen::Matrix4d& B) {
  checkFiniteMatrix("pencilDeterminant", "A", A);
  checkFiniteMatrix("pencilDeterminant", "B", B);
  return PolynomialMatrix4::linear(-B, A).determinant();
}

Eigen::MatrixXd pencilDeterminant(const PolynomialMatrix4& A, const PolynomialMatrix4& B) {
  std::array<Bivariate, 16> entries;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) entries[static_cast<std::size_t>(4 * i + j)] = Bivariate{-B(i, j), A(i, j)};
  }
  const Bivariate det = laplaceDeterminant(entries);
  int cols = 1;
  for (const Polynomial& p : det) cols = std::max(cols, p.degree() + 1);
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(det.size()), cols);
  for (std::size_t k = 0; k < det.size(); ++k) {
    const std::vector<double>& c = det[k].coefficients();
    for (std::size_t j = 0; j < c.size(); ++j) P(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(j)) = c[j];
  }
  return P;
}

}  // namespace fcl_quadric
