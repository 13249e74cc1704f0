#pragma once
/// \file bernstein_matrix.h
/// 4x4 matrix polynomials on [0, 1] in the Bernstein basis: a list of n + 1 coefficient matrices
/// for degree n, B(u) = sum_i B_i C(n, i) u^i (1 - u)^(n - i). The continuous engines keep the
/// relative motion of two bodies and the moving quadrics it poses in this form (the reduction,
/// docs/algorithms.md section 10b, and the space-time search, section 10).
///
/// Why not the power basis: products and degree elevation in the Bernstein basis have positive
/// weights, so their rounding stays relative to the polynomials' values on [0, 1], and evaluation
/// and subdivision (de Casteljau) are convex combinations. Power coefficients of a rotation's
/// rational motion cancel: for two bodies that both turn, the coefficient magnitudes of a posed
/// quadric P^T Q P summed to 10^3-10^4 times its largest value on [0, 1] (measured on random
/// pairs), which cost the reduction up to 12 digits (docs/reliability.md finding 45). Internal
/// (src/); Eigen's core only.

#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace fcl_quadric {
namespace detail {

using BernsteinMatrix = std::vector<Eigen::Matrix4d>;

/// Binomial coefficients C(n, 0..n) (detail::binomial: its cached table and its degree check).
std::vector<double> binomialRow(std::size_t n);

/// C(n, 0..n) in place: row n of detail::binomial's cached table (the same doubles), or nullptr
/// when n is beyond the table's rows.
const double* binomialTableRow(std::size_t n);

/// The product weight of B_i^r B_j^s = w B_{i+j}^{r+s}: C(r, i) C(s, j) / C(r + s, i + j).
/// The rows point into the cached table (no allocation per product, the reduction's polynomial
/// determinants form thousands); rows beyond it are computed and kept here.
class BernsteinProductWeights {
 public:
  BernsteinProductWeights(std::size_t r, std::size_t s) : cr_(row(r, 0)), cs_(row(s, 1)), crs_(row(r + s, 2)) {}
  BernsteinProductWeights(const BernsteinProductWeights&) = delete;
  BernsteinProductWeights& operator=(const BernsteinProductWeights&) = delete;
  double operator()(std::size_t i, std::size_t j) const { return cr_[i] * cs_[j] / crs_[i + j]; }

 private:
  const double* row(std::size_t n, int slot) {
    if (const double* p = binomialTableRow(n)) return p;
    own_[slot] = binomialRow(n);
    return own_[slot].data();
  }
  std::vector<double> own_[3];  // declared first: constructed before the row pointers into it
  const double* cr_;
  const double* cs_;
  const double* crs_;
};

/// Power-basis coefficients on [0, 1] (a motion's coefficient matrices: M(u) = sum_k a_k u^k) to
/// the Bernstein basis of the same degree: b_i = sum_{k <= i} C(i, k) / C(n, k) a_k. Empty stays
/// empty. The weights are positive, so bernsteinFromPower of the entrywise |a_k| bounds the
/// conversion's rounding (a few ulps of it per coefficient).
BernsteinMatrix bernsteinFromPower(const std::vector<Eigen::Matrix4d>& power);

/// A(u) B(u), of degree deg A + deg B (empty if either is).
BernsteinMatrix bernsteinProduct(const BernsteinMatrix& A, const BernsteinMatrix& B);

/// P(u)^T Q P(u), symmetrised: the quadric Q posed by P, of degree 2 deg P.
BernsteinMatrix bernsteinCongruence(const Eigen::Matrix4d& Q, const BernsteinMatrix& P);

/// Entrywise |B_i| and B_i^T of every coefficient.
BernsteinMatrix cwiseAbs(const BernsteinMatrix& B);
BernsteinMatrix transposed(const BernsteinMatrix& B);

/// The entrywise maximum of the coefficients: a bound of |B(u)| entrywise on [0, 1] (convex hull).
Eigen::Matrix4d entrywiseMax(const BernsteinMatrix& B);

/// The coefficients of B restricted to [a, b] within [0, 1] (0 <= a < b <= 1; de Casteljau
/// subdivision at b, then at a / b: convex combinations only), written to *out (resized).
void bernsteinRestrict(const BernsteinMatrix& B, double a, double b, BernsteinMatrix* out);

/// de Casteljau evaluation at u (convex combinations only for u in [0, 1]); any coefficient type
/// with + and scalar *. \pre !b.empty().
template <class T>
T bernsteinAt(std::vector<T> b, double u) {
  for (std::size_t n = b.size(); n-- > 1;)
    for (std::size_t i = 0; i < n; ++i) b[i] = (1.0 - u) * b[i] + u * b[i + 1];
  return b[0];
}

}  // namespace detail
}  // namespace fcl_quadric
