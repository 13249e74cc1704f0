#include "fcl_quadric/algebra/symmetric_eigen.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace fcl_quadric {

namespace {

// Sum of squares of the strictly upper triangle.
double offDiagonalSquared(const Eigen::MatrixXd& a) {
  double s = 0.0;
  for (Eigen::Index q = 1; q < a.cols(); ++q) {
    for (Eigen::Index p = 0; p < q; ++p) s += a(p, q) * a(p, q);
  }
  return s;
}

}  // namespace

SymmetricEigenDecomposition symmetricEigen(const Eigen::MatrixXd& input) {
  if (input.rows() != input.cols()) {
    std::ostringstream os;
    os << "symmetricEigen: matrix is not square (" << input.rows() << " x " << input.cols() << ")";
    throw std::invalid_argument(os.str());
  }
  const Eigen::Index n = input.rows();
  for (Eigen::Index j = 0; j < n; ++j) {
    for (Eigen::Index i = 0; i < n; ++i) {
      if (!std::isfinite(input(i, j))) {
        std::ostringstream os;
        os << "symmetricEigen: non-finite entry (" << i << ", " << j << ") = " << input(i, j);
        throw std::invalid_argument(os.str());
      }
    }
  }
  SymmetricEigenDecomposition out;
  out.values = Eigen::VectorXd::Zero(n);
  out.vectors = Eigen::MatrixXd::Identity(n, n);
  if (n == 0) return out;

  // Work on A / s with s = max |a_ij| (no overflow or underflow in the sums of squares below).
  const double scale = input.cwiseAbs().maxCoeff();
  if (scale == 0.0) return out;
  Eigen::MatrixXd a = (0.5 / scale) * (input + input.transpose());
  Eigen::MatrixXd& v = out.vectors;

  // Stop once the off-diagonal part is below 2^-53 ||A||_F: further rotations only move the
  // eigenvalues by rounding.
  const double target = std::ldexp(a.squaredNorm(), -106);
  double off = offDiagonalSquared(a);
  while (off > target && out.sweeps < kJacobiMaxSweeps) {
    ++out.sweeps;
    for (Eigen::Index p = 0; p + 1 < n; ++p) {
      for (Eigen::Index q = p + 1; q < n; ++q) {
        const double apq = a(p, q);
        if (apq == 0.0) continue;
        // The 2 x 2 symmetric Schur decomposition (G&VL Algorithm 8.5.1): the rotation
        // [c s; -s c] that zeroes a(p, q), with the smaller of the two angles (|t| <= 1).
        const double tau = (a(q, q) - a(p, p)) / (2.0 * apq);
        const double t = (tau >= 0.0 ? 1.0 : -1.0) / (std::fabs(tau) + std::hypot(1.0, tau));
        const double c = 1.0 / std::sqrt(1.0 + t * t), s = t * c;
        for (Eigen::Index k = 0; k < n; ++k) {  // A <- A J
          const double akp = a(k, p), akq = a(k, q);
          a(k, p) = c * akp - s * akq;
          a(k, q) = s * akp + c * akq;
        }
        for (Eigen::Index k = 0; k < n; ++k) {  // A <- J^T A
          const double apk = a(p, k), aqk = a(q, k);
          a(p, k) = c * apk - s * aqk;
          a(q, k) = s * apk + c * aqk;
        }
        a(p, q) = a(q, p) = 0.0;  // zero by construction; rounding would leave ~eps
        for (Eigen::Index k = 0; k < n; ++k) {  // V <- V J
          const double vkp = v(k, p), vkq = v(k, q);
          v(k, p) = c * vkp - s * vkq;
          v(k, q) = s * vkp + c * vkq;
        }
      }
    }
    off = offDiagonalSquared(a);
  }
  out.off_diagonal = scale * std::sqrt(2.0 * off);

  std::vector<Eigen::Index> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  std::stable_sort(order.begin(), order.end(), [&a](Eigen::Index i, Eigen::Index j) { return a(i, i) < a(j, j); });
  Eigen::MatrixXd sorted(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    out.values[i] = scale * a(order[i], order[i]);
    sorted.col(i) = v.col(order[i]);
  }
  out.vectors = sorted;
  return out;
}

}  // namespace fcl_quadric
