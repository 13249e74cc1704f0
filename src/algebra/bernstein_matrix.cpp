// Matrix polynomials in the Bernstein basis of [0, 1] (bernstein_matrix.h).
#include "algebra/bernstein_matrix.h"

#include <algorithm>

#include "fcl_quadric/algebra/bernstein_polynomial.h"

namespace fcl_quadric {
namespace detail {

std::vector<double> binomialRow(std::size_t n) {
  std::vector<double> c(n + 1);
  for (std::size_t k = 0; k <= n; ++k) c[k] = binomial(static_cast<int>(n), static_cast<int>(k));
  return c;
}

BernsteinMatrix bernsteinFromPower(const std::vector<Eigen::Matrix4d>& a) {
  if (a.empty()) return a;
  const std::size_t n = a.size() - 1;
  const std::vector<double> cn = binomialRow(n);
  BernsteinMatrix b(a.size(), Eigen::Matrix4d::Zero());
  for (std::size_t i = 0; i <= n; ++i) {
    const std::vector<double> ci = binomialRow(i);
    for (std::size_t k = 0; k <= i; ++k) b[i] += (ci[k] / cn[k]) * a[k];
  }
  return b;
}

BernsteinMatrix bernsteinProduct(const BernsteinMatrix& A, const BernsteinMatrix& B) {
  if (A.empty() || B.empty()) return {};
  const BernsteinProductWeights w(A.size() - 1, B.size() - 1);
  BernsteinMatrix r(A.size() + B.size() - 1, Eigen::Matrix4d::Zero());
  for (std::size_t i = 0; i < A.size(); ++i)
    for (std::size_t j = 0; j < B.size(); ++j) r[i + j] += w(i, j) * (A[i] * B[j]);
  return r;
}

BernsteinMatrix bernsteinCongruence(const Eigen::Matrix4d& Q, const BernsteinMatrix& P) {
  BernsteinMatrix S = bernsteinProduct(transposed(P), bernsteinProduct(BernsteinMatrix{Q}, P));
  for (Eigen::Matrix4d& M : S) M = 0.5 * (M + M.transpose()).eval();
  return S;
}

BernsteinMatrix cwiseAbs(const BernsteinMatrix& B) {
  BernsteinMatrix r;
  r.reserve(B.size());
  for (const Eigen::Matrix4d& M : B) r.push_back(M.cwiseAbs());
  return r;
}

BernsteinMatrix transposed(const BernsteinMatrix& B) {
  BernsteinMatrix r;
  r.reserve(B.size());
  for (const Eigen::Matrix4d& M : B) r.push_back(M.transpose());
  return r;
}

Eigen::Matrix4d entrywiseMax(const BernsteinMatrix& B) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
  for (const Eigen::Matrix4d& M : B) m = m.cwiseMax(M.cwiseAbs());
  return m;
}

void bernsteinRestrict(const BernsteinMatrix& B, double a, double b, BernsteinMatrix* out) {
  *out = B;
  BernsteinMatrix& c = *out;
  const std::size_t n = c.size();
  if (n <= 1) return;
  // [0, b]: the left part of the subdivision at b (c_i becomes the first point of level i).
  if (b < 1.0)
    for (std::size_t level = 1; level < n; ++level)
      for (std::size_t i = n - 1; i >= level; --i) c[i] = (1.0 - b) * c[i - 1] + b * c[i];
  // [a, b] = the right part of [0, b] subdivided at a / b.
  if (a > 0.0) {
    const double s = a / b;
    for (std::size_t level = 1; level < n; ++level)
      for (std::size_t i = 0; i + level < n; ++i) c[i] = (1.0 - s) * c[i] + s * c[i + 1];
  }
}

}  // namespace detail
}  // namespace fcl_quadric
