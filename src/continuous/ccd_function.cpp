#include "fcl_quadric/continuous/ccd_function.h"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>
#include <cmath>
#include <vector>

#include <Eigen/LU>

#include "fcl_quadric/algebra/bernstein_polynomial.h"

namespace fcl_quadric {

namespace {

// A polynomial in the scaled Bernstein basis of [0, 1]: p(t) = sum_i d[i] (1-t)^(n-i) t^i,
// n = d.size() - 1.
using Scaled = std::vector<double>;

Scaled convolve(const Scaled& a, const Scaled& b) {
  Scaled c(a.size() + b.size() - 1, 0.0);
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i] == 0.0) continue;
    for (std::size_t j = 0; j < b.size(); ++j) c[i + j] += a[i] * b[j];
  }
  return c;
}

// Rows 0..kMaxRow of Pascal's triangle, computed once (exact up to row 56; beyond, correctly
// rounded sums; the CCD degrees stay far below kMaxRow).
constexpr int kMaxRow = 400;
const std::vector<double>& binomialRow(int r) {
  static const std::vector<std::vector<double>> rows = [] {
    std::vector<std::vector<double>> t(kMaxRow + 1);
    for (int n = 0; n <= kMaxRow; ++n) {  // Pascal's rule: exact integers while below 2^53
      t[n].assign(n + 1, 1.0);
      for (int k = 1; k < n; ++k) t[n][k] = t[n - 1][k - 1] + t[n - 1][k];
    }
    return t;
  }();
  if (r > kMaxRow) throw std::invalid_argument("ccdFunction: degree " + std::to_string(r) + " exceeds " + std::to_string(kMaxRow));
  return rows[r];
}

// Degree elevation to `degree`: multiplication by ((1-t) + t)^r, i.e. convolution with the
// binomial row of r.
Scaled elevate(const Scaled& a, int degree) {
  const int r = degree - (static_cast<int>(a.size()) - 1);
  if (r <= 0) return a;
  return convolve(a, binomialRow(r));
}

Scaled axpby(double alpha, const Scaled& a, double beta, const Scaled& b) {
  const int n = static_cast<int>(std::max(a.size(), b.size())) - 1;
  const Scaled ea = elevate(a, n), eb = elevate(b, n);
  Scaled c(n + 1);
  for (int i = 0; i <= n; ++i) c[i] = alpha * ea[i] + beta * eb[i];
  return c;
}

Scaled toScaled(const Polynomial& p, int degree) {
  return BernsteinPolynomial::fromPower(p, 0.0, 1.0, degree).toScaled();
}

int structuralDegree(const Polynomial& p) { return std::max(p.effectiveDegree(), 0); }

// det of a 4x4 matrix of scaled Bernstein polynomials by Laplace expansion along rows {0, 1}.
Scaled determinant4(const std::array<Scaled, 16>& m) {
  auto at = [&](int i, int j) -> const Scaled& { return m[4 * i + j]; };
  auto minor2 = [&](int r0, int r1, int c0, int c1) {
    return axpby(1.0, convolve(at(r0, c0), at(r1, c1)), -1.0, convolve(at(r0, c1), at(r1, c0)));
  };
  Scaled det{0.0};
  static constexpr int kPairs[6][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2}, {1, 2, 0, 3}, {1, 3, 0, 2}, {2, 3, 0, 1}};
  for (const auto& pr : kPairs) {
    const double sign = ((1 + pr[0] + pr[1]) % 2 == 0) ? 1.0 : -1.0;  // (-1)^(0+1+c0+c1)
    det = axpby(1.0, det, sign, convolve(minor2(0, 1, pr[0], pr[1]), minor2(2, 3, pr[2], pr[3])));
  }
  return det;
}

std::vector<double> scaledToBernstein(const Scaled& d) {
  const int n = static_cast<int>(d.size()) - 1;
  const std::vector<double>& row = binomialRow(n);
  std::vector<double> c(d.size());
  for (int i = 0; i <= n; ++i) c[i] = d[i] / row[i];
  return c;
}

// Inverse of the collocation matrix V(k, i) = B_i^4(k / 4): maps values at u = k/4 to the
// Bernstein coefficients in u.
const Eigen::Matrix<double, 5, 5>& uInterpolation() {
  static const Eigen::Matrix<double, 5, 5> inv = [] {
    Eigen::Matrix<double, 5, 5> V;
    for (int k = 0; k <= 4; ++k) {
      const double u = k / 4.0;
      for (int i = 0; i <= 4; ++i) V(k, i) = detail::binomial(4, i) * std::pow(u, i) * std::pow(1.0 - u, 4 - i);
    }
    Eigen::Matrix<double, 5, 5> result = V.inverse();
    return result;
  }();
  return inv;
}

}  // namespace

BernsteinPolynomial bernsteinDeterminant(const PolynomialMatrix4& M) {
  std::array<Scaled, 16> m;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) m[4 * i + j] = toScaled(M(i, j).trimmed(), structuralDegree(M(i, j)));
  return BernsteinPolynomial(scaledToBernstein(determinant4(m)), 0.0, 1.0);
}

BivariateBernstein ccdFunction(const PolynomialMatrix4& A, const PolynomialMatrix4& B) {
  std::array<Scaled, 16> a, b;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      const int d = std::max(structuralDegree(A(i, j)), structuralDegree(B(i, j)));
      a[4 * i + j] = toScaled(A(i, j).trimmed(), d);
      b[4 * i + j] = toScaled(B(i, j).trimmed(), d);
    }
  }
  std::array<std::vector<double>, 5> rows;
  int degree = 0;
  for (int k = 0; k <= 4; ++k) {
    const double u = k / 4.0;
    std::array<Scaled, 16> m;
    for (int e = 0; e < 16; ++e) {
      m[e].resize(a[e].size());
      for (std::size_t i = 0; i < a[e].size(); ++i) m[e][i] = (u - 1.0) * a[e][i] - u * b[e][i];
    }
    rows[k] = determinant4(m);
    degree = std::max(degree, static_cast<int>(rows[k].size()) - 1);
  }
  Eigen::MatrixXd values(5, degree + 1);
  for (int k = 0; k <= 4; ++k) {
    const std::vector<double> c = scaledToBernstein(elevate(rows[k], degree));
    for (int j = 0; j <= degree; ++j) values(k, j) = c[j];
  }
  Eigen::MatrixXd coefficients = uInterpolation() * values;
  coefficients.row(0) = values.row(0);  // exact: F(0, t) = det A(t)
  coefficients.row(4) = values.row(4);  // exact: F(1, t) = det B(t)
  return BivariateBernstein(std::move(coefficients));
}

}  // namespace fcl_quadric
