#pragma once
// Private: a finiteness test that raises no floating-point exception (Eigen's allFinite()
// computes x - x, which raises FE_INVALID on infinities; the tests trap FE_INVALID).
#include <cmath>

#include <Eigen/Core>

namespace fcl_quadric {
namespace planning {
namespace detail {

template <typename Derived>
bool allFinite(const Eigen::DenseBase<Derived>& m) {
  for (Eigen::Index c = 0; c < m.cols(); ++c)
    for (Eigen::Index r = 0; r < m.rows(); ++r)
      if (!std::isfinite(m(r, c))) return false;
  return true;
}

}  // namespace detail
}  // namespace planning
}  // namespace fcl_quadric
