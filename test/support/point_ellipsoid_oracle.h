#pragma once
/// \file point_ellipsoid_oracle.h
/// The signed distance of a point to an ellipse or ellipsoid surface in 50 digits
/// (boost::multiprecision), for the tests of the double solver (point_ellipsoid.h) and of the
/// kernels built on it: Eberly's secular equation sum (e_i y_i / (e_i^2 + t))^2 = 1 bisected on
/// (-e_min^2, inf) by 240 halvings of a bracket where the sum is >= 1 at the left end (the
/// shortest axis's term alone reaches 1 there) and <= 1 at the right.

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Core>
#include <boost/multiprecision/cpp_bin_float.hpp>

namespace fcl_quadric {
namespace test {

/// The signed distance (< 0 inside) of y to { sum x_i^2 / e_i^2 = 1 }. \pre the coordinate of y
/// along the shortest axis is not 0 (else the nearest point may leave the principal plane, a case
/// the solver handles in closed form and this oracle does not).
template <int N>
double pointEllipsoidOracle(const Eigen::Matrix<double, N, 1>& e, const Eigen::Matrix<double, N, 1>& y) {
  using Big = boost::multiprecision::cpp_bin_float_50;
  Big E[N], Y[N];
  int n = 0;  // the shortest axis
  for (int i = 0; i < N; ++i) {
    E[i] = e[i];
    Y[i] = abs(Big(y[i]));
    if (e[i] < e[n]) n = i;
  }
  auto sum = [&](const Big& t) {
    Big s = 0;
    for (int i = 0; i < N; ++i) {
      const Big u = E[i] * Y[i] / (E[i] * E[i] + t);
      s += u * u;
    }
    return s;
  };
  Big c2 = 0, form = 0;
  for (int i = 0; i < N; ++i) {
    c2 += E[i] * E[i] * Y[i] * Y[i];
    form += (Y[i] / E[i]) * (Y[i] / E[i]);
  }
  Big lo = E[n] * Y[n] - E[n] * E[n];
  Big hi = sqrt(c2) - E[n] * E[n];
  for (int k = 0; k < 240; ++k) {
    const Big mid = (lo + hi) / 2;
    (sum(mid) > 1 ? lo : hi) = mid;
  }
  const Big t = (lo + hi) / 2;
  Big d2 = 0;
  for (int i = 0; i < N; ++i) {
    const Big x = E[i] * E[i] * Y[i] / (E[i] * E[i] + t);
    d2 += (x - Y[i]) * (x - Y[i]);
  }
  const double d = static_cast<double>(sqrt(d2));
  return form < 1 ? -d : d;
}

/// The distances |x - y| of the critical points of the distance from y to the surface at the roots
/// of the secular equation g(t) = sum (e_i y_i / (e_i^2 + t))^2 - 1 (every root, on every interval
/// between its poles -e_i^2), in 50 digits and in increasing order. *margin is the smallest |g| at
/// the minima between two poles: how near the case is to a double root, where a double solver
/// may rightly find two roots or none. \pre distinct radii, every coordinate of y non-zero (the
/// points with t = -e_i^2 of a zero coordinate are not listed).
template <int N>
std::vector<double> criticalDistancesOracle(const Eigen::Matrix<double, N, 1>& e, const Eigen::Matrix<double, N, 1>& y,
                                            double* margin) {
  using Big = boost::multiprecision::cpp_bin_float_50;
  Big E2[N], Y[N], C[N], c_norm2 = 0;
  int order[N];
  for (int i = 0; i < N; ++i) {
    E2[i] = Big(e[i]) * Big(e[i]);
    Y[i] = Big(y[i]);
    C[i] = abs(Big(e[i]) * Y[i]);
    c_norm2 += C[i] * C[i];
    order[i] = i;
  }
  const Big c_norm = sqrt(c_norm2);
  std::sort(order, order + N, [&](int i, int j) { return e[i] > e[j]; });  // poles -e_i^2 increasing
  auto g = [&](const Big& t) {
    Big s = -1;
    for (int i = 0; i < N; ++i) s += C[i] * C[i] / ((E2[i] + t) * (E2[i] + t));
    return s;
  };
  auto dg = [&](const Big& t) {
    Big s = 0;
    for (int i = 0; i < N; ++i) s -= 2 * C[i] * C[i] / ((E2[i] + t) * (E2[i] + t) * (E2[i] + t));
    return s;
  };
  // Bisection on [lo, hi] for a root of g, increasing there (rising = true) or decreasing.
  auto bisect = [&](Big lo, Big hi, bool rising) {
    for (int k = 0; k < 200; ++k) {
      const Big mid = (lo + hi) / 2;
      ((g(mid) > 0) == rising ? hi : lo) = mid;
    }
    return (lo + hi) / 2;
  };
  std::vector<Big> roots;
  const int first = order[0], last = order[N - 1];
  roots.push_back(bisect(-E2[first] - c_norm, -E2[first] - C[first], true));
  *margin = 1e300;
  for (int k = 0; k + 1 < N; ++k) {
    const Big a = -E2[order[k]] + C[order[k]], b = -E2[order[k + 1]] - C[order[k + 1]];
    if (!(a < b)) continue;
    Big lo = a, hi = b;
    for (int it = 0; it < 200; ++it) {
      const Big mid = (lo + hi) / 2;
      (dg(mid) < 0 ? lo : hi) = mid;
    }
    const Big tm = (lo + hi) / 2, gm = g(tm);
    *margin = std::min(*margin, static_cast<double>(abs(gm)));
    if (gm < 0) {
      roots.push_back(bisect(a, tm, false));
      roots.push_back(bisect(tm, b, true));
    }
  }
  roots.push_back(bisect(-E2[last] + C[last], -E2[last] + c_norm, false));
  std::vector<double> out;
  for (const Big& t : roots) {
    Big d2 = 0;
    for (int i = 0; i < N; ++i) {
      const Big x = E2[i] * Y[i] / (E2[i] + t);
      d2 += (x - Y[i]) * (x - Y[i]);
    }
    out.push_back(static_cast<double>(sqrt(d2)));
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace test
}  // namespace fcl_quadric
