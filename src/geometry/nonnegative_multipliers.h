#pragma once
// Private: the multiplier search that the two weak-duality certificates share
// (ConvexSupport::dualSupportBound in convex_region_box.cpp, the planes' linear program in
// region_dual_bound.cpp; docs/algorithms.md sections 9 and 12).

#include <Eigen/Dense>

#include "algebra/dense_decompositions.h"
#include "algebra/input_checks.h"

namespace fcl_quadric {
namespace detail {

/// For every subset of one to three of the n vectors column(i) that are independent, the
/// least-squares multipliers mu of e = G mu (G their columns); calls use(idx, k, G, mu) for each
/// where none is negative. Three vectors span the space (Caratheodory), so larger subsets add
/// nothing; a dependent subset is covered by a smaller one. n at most 30 (a bit mask).
template <class Column, class Use>
void forEachNonNegativeCombination(int n, const Column& column, const Eigen::Vector3d& e, const Use& use) {
  for (int mask = 1; mask < (1 << n); ++mask) {
    int idx[3], k = 0;
    for (int i = 0; i < n && k <= 3; ++i)
      if (mask & (1 << i)) {
        if (k < 3) idx[k] = i;
        ++k;
      }
    if (k > 3) continue;
    Eigen::Matrix<double, 3, Eigen::Dynamic> G(3, k);
    for (int j = 0; j < k; ++j) G.col(j) = column(idx[j]);
    Eigen::VectorXd mu;
    if (!colPivQrSolve(G, e, &mu)) continue;  // dependent columns
    if (!allFinite(mu) || (mu.array() < 0.0).any()) continue;
    use(idx, k, G, mu);
  }
}

}  // namespace detail
}  // namespace fcl_quadric
