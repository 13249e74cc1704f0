#include "fcl_quadric/continuous/ccd_function.h"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/LU>

#include "fcl_quadric/algebra/bernstein_polynomial.h"
#include "fcl_quadric/tolerances.h"

namespace fcl_quadric {

namespace {

// A polynomial in the scaled Bernstein basis of [0, 1]: p(t) = sum_i d[i] (1-t)^(n-i) t^i,
// n = d.size() - 1. In double, or in long double for the precision check.
using Scaled = std::vector<double>;
using ScaledL = std::vector<long double>;

// Product of two polynomials in the scaled Bernstein basis (a convolution). Each output
// coefficient is summed in a register, in the order of increasing i as a row-by-row
// accumulation would: the same roundings, without storing and reloading c[i + j] for every
// term (for long double, 80-bit x87 memory traffic; perf, bench_ccd Arm/U-5).
template <class V>
V convolve(const V& a, const V& b) {
  if (a.empty() || b.empty()) return V(a.size() + b.size() > 0 ? a.size() + b.size() - 1 : 0, 0.0);
  const std::size_t na = a.size(), nb = b.size();
  V c(na + nb - 1);
  for (std::size_t k = 0; k < c.size(); ++k) {
    typename V::value_type acc = 0.0;
    const std::size_t lo = k >= nb ? k - nb + 1 : 0, hi = std::min(k, na - 1);
    for (std::size_t i = lo; i <= hi; ++i) {
      if (a[i] != 0.0) acc += a[i] * b[k - i];
    }
    c[k] = acc;
  }
  return c;
}

// Rows 0..kMaxRow of Pascal's triangle, computed once (exact up to row 56; beyond, correctly
// rounded sums). continuousCollideEllipsoids() rejects pairs of a higher degree up front
// (ccdFunctionDegree()), so the throw below is a last guard.
constexpr int kMaxRow = tolerance::kCcdMaxDegree;
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
template <class V>
V elevate(const V& a, int degree) {
  const int r = degree - (static_cast<int>(a.size()) - 1);
  if (r <= 0) return a;
  const std::vector<double>& row = binomialRow(r);
  return convolve(a, V(row.begin(), row.end()));
}

// c += s a, the shorter of the two first elevated to the other's degree. In place: F's
// expansion runs five 4 x 4 determinants twice (double and long double) per segment, and the
// allocations of a copying sum took a quarter of the CCD's time (perf, bench_ccd Arm/U-5).
// The same operations as c = 1 * c + s * a on elevated copies: bit for bit the same results.
template <class V>
void addScaled(V& c, double s, const V& a) {
  if (c.size() < a.size()) c = elevate(c, static_cast<int>(a.size()) - 1);
  if (a.size() < c.size()) {
    const V ea = elevate(a, static_cast<int>(c.size()) - 1);
    for (std::size_t i = 0; i < c.size(); ++i) c[i] += s * ea[i];
  } else {
    for (std::size_t i = 0; i < c.size(); ++i) c[i] += s * a[i];
  }
}

Scaled toScaled(const Polynomial& p, int degree) {
  return BernsteinPolynomial::fromPower(p, 0.0, 1.0, degree).toScaled();
}

int structuralDegree(const Polynomial& p) { return std::max(p.effectiveDegree(), 0); }

// det of a 4x4 matrix of scaled Bernstein polynomials by Laplace expansion along rows {0, 1}.
template <class V>
V determinant4(const std::array<V, 16>& m) {
  auto at = [&](int i, int j) -> const V& { return m[4 * i + j]; };
  auto minor2 = [&](int r0, int r1, int c0, int c1) {
    V m = convolve(at(r0, c0), at(r1, c1));
    addScaled(m, -1.0, convolve(at(r0, c1), at(r1, c0)));
    return m;
  };
  V det{0.0};
  static constexpr int kPairs[6][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2}, {1, 2, 0, 3}, {1, 3, 0, 2}, {2, 3, 0, 1}};
  for (const auto& pr : kPairs) {
    const double sign = ((1 + pr[0] + pr[1]) % 2 == 0) ? 1.0 : -1.0;  // (-1)^(0+1+c0+c1)
    addScaled(det, sign, convolve(minor2(0, 1, pr[0], pr[1]), minor2(2, 3, pr[2], pr[3])));
  }
  return det;
}

template <class V>
V scaledToBernstein(const V& d) {
  const int n = static_cast<int>(d.size()) - 1;
  const std::vector<double>& row = binomialRow(n);
  V c(d.size());
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

namespace {

// Rows of F at the abscissae u = k / 4 (Bernstein in t, elevated to a common degree).
template <class V>
std::array<V, 5> rowsAtAbscissae(const std::array<V, 16>& a, const std::array<V, 16>& b) {
  std::array<V, 5> rows;
  int degree = 0;
  std::array<V, 16> m;  // reused for every abscissa
  for (int k = 0; k <= 4; ++k) {
    const double u = k / 4.0;
    for (int e = 0; e < 16; ++e) {
      m[e].resize(a[e].size());
      for (std::size_t i = 0; i < a[e].size(); ++i) m[e][i] = (u - 1.0) * a[e][i] - u * b[e][i];
    }
    rows[k] = determinant4(m);
    degree = std::max(degree, static_cast<int>(rows[k].size()) - 1);
  }
  for (V& r : rows) r = scaledToBernstein(elevate(r, degree));
  return rows;
}

template <class V>
Eigen::MatrixXd interpolateInU(const std::array<V, 5>& rows) {
  const Eigen::Index n = static_cast<Eigen::Index>(rows[0].size());
  using MatrixL = Eigen::Matrix<typename V::value_type, Eigen::Dynamic, Eigen::Dynamic>;
  MatrixL values(5, n);
  for (int k = 0; k <= 4; ++k)
    for (Eigen::Index j = 0; j < n; ++j) values(k, j) = rows[k][static_cast<std::size_t>(j)];
  MatrixL coefficients = uInterpolation().cast<typename V::value_type>() * values;
  coefficients.row(0) = values.row(0);  // exact: F(0, t) = det A(t)
  coefficients.row(4) = values.row(4);  // exact: F(1, t) = det B(t)
  return coefficients.template cast<double>();
}

// Power basis p_0..p_m to the scaled Bernstein basis of degree n on [0, 1]:
// d_j = sum_{i <= j} C(n - i, j - i) p_i (positive integer weights).
ScaledL toScaledExtended(const std::vector<long double>& p, int n) {
  ScaledL d(static_cast<std::size_t>(n) + 1, 0.0L);
  for (int i = 0; i < static_cast<int>(p.size()) && i <= n; ++i) {
    const std::vector<double>& row = binomialRow(n - i);
    for (int j = i; j <= n; ++j) d[j] += static_cast<long double>(row[j - i]) * p[i];
  }
  return d;
}

int structuralDegree(const std::vector<Matrix4ld>& C, int i, int j) {
  for (int k = static_cast<int>(C.size()) - 1; k > 0; --k)
    if (C[k](i, j) != 0.0L) return k;
  return 0;
}

}  // namespace

BivariateBernstein ccdFunction(const PolynomialMatrix4& A, const PolynomialMatrix4& B) {
  std::array<Scaled, 16> a, b;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      const int d = std::max(structuralDegree(A(i, j)), structuralDegree(B(i, j)));
      a[4 * i + j] = toScaled(A(i, j).trimmed(), d);
      b[4 * i + j] = toScaled(B(i, j).trimmed(), d);
    }
  }
  return BivariateBernstein(interpolateInU(rowsAtAbscissae(a, b)));
}

CheckedCcdFunction ccdFunctionChecked(const PolynomialMatrix4& A, const PolynomialMatrix4& B,
                                      const std::vector<Matrix4ld>& Ak, const std::vector<Matrix4ld>& Bk) {
  std::array<Scaled, 16> a, b;
  std::array<ScaledL, 16> al, bl;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      const int d = std::max({structuralDegree(A(i, j)), structuralDegree(B(i, j)), structuralDegree(Ak, i, j),
                              structuralDegree(Bk, i, j)});
      const int e = 4 * i + j;
      a[e] = toScaled(A(i, j).trimmed(), d);
      b[e] = toScaled(B(i, j).trimmed(), d);
      std::vector<long double> pa(Ak.size()), pb(Bk.size());
      for (std::size_t k = 0; k < Ak.size(); ++k) pa[k] = Ak[k](i, j);
      for (std::size_t k = 0; k < Bk.size(); ++k) pb[k] = Bk[k](i, j);
      al[e] = toScaledExtended(pa, d);
      bl[e] = toScaledExtended(pb, d);
    }
  }
  const Eigen::MatrixXd Fd = interpolateInU(rowsAtAbscissae(a, b));
  Eigen::MatrixXd Fl = interpolateInU(rowsAtAbscissae(al, bl));
  // The extended computation has 11 more significand bits: its error is estimated as 2^-11 of
  // the difference, times 8 for safety, smoothed over neighbouring coefficients (a coefficient
  // where the two happen to agree must not look exact), plus the final rounding to double.
  const Eigen::MatrixXd diff = (Fd - Fl).cwiseAbs();
  const Eigen::Index n = diff.cols(), last = diff.rows() - 1;
  const double eps = std::numeric_limits<double>::epsilon();
  Eigen::MatrixXd error(diff.rows(), n), end_error(2, n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const Eigen::Index lo = std::max<Eigen::Index>(0, j - 2), hi = std::min<Eigen::Index>(n - 1, j + 2);
    const double local = diff.middleCols(lo, hi - lo + 1).maxCoeff();
    for (Eigen::Index i = 0; i < diff.rows(); ++i) error(i, j) = local / 256.0 + 4.0 * eps * std::abs(Fl(i, j));
    // The end rows on their own (CheckedCcdFunction::end_error).
    for (Eigen::Index k = 0; k < 2; ++k) {
      const Eigen::Index i = k == 0 ? 0 : last;
      end_error(k, j) = diff.row(i).segment(lo, hi - lo + 1).maxCoeff() / 256.0 + 4.0 * eps * std::abs(Fl(i, j));
    }
  }
  return {BivariateBernstein(std::move(Fl)), std::move(error), std::move(end_error)};
}

}  // namespace fcl_quadric
