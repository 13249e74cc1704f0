#include "fcl_quadric/algebra/polynomial_matrix3.h"

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

std::size_t index3(int i, int j) { return static_cast<std::size_t>(3 * i + j); }

void checkIndex3(int i, int j) {
  if (i < 0 || i > 2 || j < 0 || j > 2) {
    throw std::invalid_argument("PolynomialMatrix3: index (" + std::to_string(i) + ", " + std::to_string(j) +
                                ") outside [0, 2]");
  }
}

/// Determinant of a row-major 3x3 array by cofactor expansion along the first row.
template <typename T>
T cofactorDeterminant(const std::array<T, 9>& a) {
  auto e = [&a](int i, int j) -> const T& { return a[index3(i, j)]; };
  const T c0 = e(1, 1) * e(2, 2) - e(1, 2) * e(2, 1);
  const T c1 = e(1, 2) * e(2, 0) - e(1, 0) * e(2, 2);
  const T c2 = e(1, 0) * e(2, 1) - e(1, 1) * e(2, 0);
  return e(0, 0) * c0 + e(0, 1) * c1 + e(0, 2) * c2;
}

}  // namespace

PolynomialMatrix3::PolynomialMatrix3() = default;

PolynomialMatrix3::PolynomialMatrix3(const Eigen::Matrix3d& M) {
  checkFiniteMatrix("PolynomialMatrix3", "M", M);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) entries_[index3(i, j)] = Polynomial::constant(M(i, j));
  }
}

PolynomialMatrix3 PolynomialMatrix3::fromCoefficients(const std::vector<Eigen::Matrix3d>& matrices) {
  for (std::size_t k = 0; k < matrices.size(); ++k) {
    const std::string what = "M_" + std::to_string(k);
    checkFiniteMatrix("PolynomialMatrix3::fromCoefficients", what.c_str(), matrices[k]);
  }
  PolynomialMatrix3 r;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      std::vector<double> c(std::max<std::size_t>(matrices.size(), 1), 0.0);
      for (std::size_t k = 0; k < matrices.size(); ++k) c[k] = matrices[k](i, j);
      r.entries_[index3(i, j)] = Polynomial(std::move(c));
    }
  }
  return r;
}

PolynomialMatrix3 PolynomialMatrix3::linear(const Eigen::Matrix3d& M0, const Eigen::Matrix3d& M1) {
  return fromCoefficients({M0, M1});
}

const Polynomial& PolynomialMatrix3::operator()(int i, int j) const {
  checkIndex3(i, j);
  return entries_[index3(i, j)];
}

Polynomial& PolynomialMatrix3::operator()(int i, int j) {
  checkIndex3(i, j);
  return entries_[index3(i, j)];
}

int PolynomialMatrix3::maxDegree() const {
  int d = 0;
  for (const Polynomial& p : entries_) d = std::max(d, p.degree());
  return d;
}

Eigen::Matrix3d PolynomialMatrix3::evaluate(double t) const {
  Eigen::Matrix3d M;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) M(i, j) = entries_[index3(i, j)](t);
  }
  return M;
}

PolynomialMatrix3 PolynomialMatrix3::transpose() const {
  PolynomialMatrix3 r;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) r.entries_[index3(j, i)] = entries_[index3(i, j)];
  }
  return r;
}

PolynomialMatrix3 PolynomialMatrix3::operator+(const PolynomialMatrix3& other) const {
  PolynomialMatrix3 r(*this);
  for (std::size_t k = 0; k < 9; ++k) r.entries_[k] += other.entries_[k];
  return r;
}

PolynomialMatrix3 PolynomialMatrix3::operator-(const PolynomialMatrix3& other) const {
  PolynomialMatrix3 r(*this);
  for (std::size_t k = 0; k < 9; ++k) r.entries_[k] -= other.entries_[k];
  return r;
}

PolynomialMatrix3 PolynomialMatrix3::operator*(const PolynomialMatrix3& other) const {
  PolynomialMatrix3 r;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      Polynomial s;
      for (int k = 0; k < 3; ++k) s += entries_[index3(i, k)] * other.entries_[index3(k, j)];
      r.entries_[index3(i, j)] = s;
    }
  }
  return r;
}

PolynomialMatrix3 PolynomialMatrix3::operator*(double s) const {
  if (!std::isfinite(s)) {
    std::ostringstream os;
    os << "PolynomialMatrix3::operator*: non-finite scalar (" << s << ")";
    throw std::invalid_argument(os.str());
  }
  PolynomialMatrix3 r(*this);
  for (Polynomial& p : r.entries_) p *= s;
  return r;
}

PolynomialMatrix3 PolynomialMatrix3::operator*(const Polynomial& q) const {
  PolynomialMatrix3 r(*this);
  for (Polynomial& p : r.entries_) p *= q;
  return r;
}

Polynomial PolynomialMatrix3::determinant() const { return cofactorDeterminant(entries_); }

PolynomialMatrix3 PolynomialMatrix3::adjugate() const {
  auto e = [this](int i, int j) -> const Polynomial& { return entries_[index3(i, j)]; };
  PolynomialMatrix3 r;
  // adj(M)(j, i) = cofactor C(i, j) = (-1)^(i+j) minor(i, j); cyclic index form gives the signs.
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3;
    const int i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3;
      const int j2 = (j + 2) % 3;
      r.entries_[index3(j, i)] = e(i1, j1) * e(i2, j2) - e(i1, j2) * e(i2, j1);
    }
  }
  return r;
}

Polynomial pencilDeterminant3(const Eigen::Matrix3d& A, const Eigen::Matrix3d& B) {
  checkFiniteMatrix("pencilDeterminant3", "A", A);
  checkFiniteMatrix("pencilDeterminant3", "B", B);
  return PolynomialMatrix3::linear(-B, A).determinant();
}

Eigen::MatrixXd pencilDeterminant3(const PolynomialMatrix3& A, const PolynomialMatrix3& B) {
  std::array<Bivariate, 9> entries;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) entries[index3(i, j)] = Bivariate{-B(i, j), A(i, j)};
  }
  const Bivariate det = cofactorDeterminant(entries);
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
