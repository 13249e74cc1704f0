#pragma once
/// \file point_ellipsoid_oracle.h
/// The signed distance of a point to an ellipse or ellipsoid surface in 50 digits
/// (boost::multiprecision), for the tests of the double solver (point_ellipsoid.h) and of the
/// kernels built on it: Eberly's secular equation sum (e_i y_i / (e_i^2 + t))^2 = 1 bisected on
/// (-e_min^2, inf) by 240 halvings of a bracket where the sum is >= 1 at the left end (the
/// shortest axis's term alone reaches 1 there) and <= 1 at the right.

#include <algorithm>
#include <cmath>

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

}  // namespace test
}  // namespace fcl_quadric
