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
/// nothing; a dependent subset is covered by a smaller one. The subsets are enumerated directly
/// (n + n(n-1)/2 + n(n-1)(n-2)/6 of them), not through the 2^n masks of all subsets.
template <class Column, class Use>
void forEachNonNegativeCombination(int n, const Column& column, const Eigen::Vector3d& e, const Use& use) {
  auto tryIdx = [&](const int idx[3], int k) {
    Eigen::Matrix<double, 3, Eigen::Dynamic> G(3, k);
    for (int j = 0; j < k; ++j) G.col(j) = column(idx[j]);
    Eigen::VectorXd mu;
    if (!colPivQrSolve(G, e, &mu)) return;  // dependent columns
    if (!allFinite(mu) || (mu.array() < 0.0).any()) return;
    use(idx, k, G, mu);
  };
  for (int i = 0; i < n; ++i) {
    const int one[3] = {i, 0, 0};
    tryIdx(one, 1);
    for (int j = i + 1; j < n; ++j) {
      const int two[3] = {i, j, 0};
      tryIdx(two, 2);
      for (int l = j + 1; l < n; ++l) {
        const int three[3] = {i, j, l};
        tryIdx(three, 3);
      }
    }
  }
}

}  // namespace detail
}  // namespace fcl_quadric
