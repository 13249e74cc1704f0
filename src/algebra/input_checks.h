#pragma once
// Private: argument checks shared by the algebra layer. Each throws std::invalid_argument with a
// message naming the function and the bad value.
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <vector>

#include <Eigen/Core>

namespace fcl_quadric {
namespace detail {

/// Every coefficient finite, by std::isfinite: Eigen's allFinite() computes x - x, which raises
/// FE_INVALID on an infinity (the test binaries trap it).
template <typename Derived>
bool allFinite(const Eigen::DenseBase<Derived>& m) {
  for (Eigen::Index c = 0; c < m.cols(); ++c)
    for (Eigen::Index r = 0; r < m.rows(); ++r)
      if (!std::isfinite(m(r, c))) return false;
  return true;
}

inline void checkFiniteValue(const char* where, const char* what, double v) {
  if (!std::isfinite(v)) {
    std::ostringstream os;
    os << where << ": non-finite " << what << " (" << v << ")";
    throw std::invalid_argument(os.str());
  }
}

/// Every coefficient finite; if `non_empty`, at least one coefficient.
inline void checkCoefficients(const char* where, const std::vector<double>& c, bool non_empty) {
  if (non_empty && c.empty()) throw std::invalid_argument(std::string(where) + ": empty coefficient vector");
  for (std::size_t i = 0; i < c.size(); ++i) {
    if (!std::isfinite(c[i])) {
      std::ostringstream os;
      os << where << ": non-finite coefficient c[" << i << "] = " << c[i];
      throw std::invalid_argument(os.str());
    }
  }
}

/// Every entry of M finite; the message names the function, the matrix and the bad entry.
template <typename Derived>
void checkFiniteMatrix(const char* where, const char* what, const Eigen::MatrixBase<Derived>& M) {
  for (Eigen::Index i = 0; i < M.rows(); ++i) {
    for (Eigen::Index j = 0; j < M.cols(); ++j) {
      if (!std::isfinite(M(i, j))) {
        std::ostringstream os;
        os << where << ": non-finite entry (" << i << ", " << j << ") = " << M(i, j) << " of " << what;
        throw std::invalid_argument(os.str());
      }
    }
  }
}

/// A 4x4 quadric matrix: every entry finite (checked entry by entry: Eigen's allFinite() computes
/// x - x, which raises FE_INVALID on an infinity) and symmetric to 1e-12 relative to its largest
/// entry. A zero matrix passes (callers that reject it say so).
inline void checkQuadricMatrix(const Eigen::Matrix4d& Q) {
  for (int i = 0; i < 16; ++i) {
    if (!std::isfinite(Q.data()[i])) {
      std::ostringstream os;
      os << "quadric matrix must be finite, got\n" << Q;
      throw std::invalid_argument(os.str());
    }
  }
  const double scale = Q.cwiseAbs().maxCoeff();
  const double asym = (Q - Q.transpose()).cwiseAbs().maxCoeff();
  if (asym > 1e-12 * scale) {
    std::ostringstream os;
    os << "quadric matrix must be symmetric (max |Q - Q^T| = " << asym << ", relative tolerance 1e-12), got\n" << Q;
    throw std::invalid_argument(os.str());
  }
}

}  // namespace detail
}  // namespace fcl_quadric
