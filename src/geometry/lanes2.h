#pragma once
/// \file lanes2.h
/// Two doubles in one SSE2 register (a GCC / Clang vector extension): lane 0 carries ellipsoid a,
/// lane 1 ellipsoid b, so a test on a pair costs one pass of arithmetic instead of two. Each lane
/// performs exactly the scalar operations, in the same order, so the results are bit for bit those
/// of a scalar evaluation. Used by the pre-tests of the static classification and by the
/// cached-plane test (internal; Eigen only).

#include <cmath>

#include <Eigen/Core>

#include "fcl_quadric/geometry/ellipsoid.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace fcl_quadric {
namespace detail {

typedef double Lanes2 __attribute__((vector_size(16)));
/// The result of comparing two Lanes2 (all ones or zero per lane), and their bits.
typedef long long Mask2 __attribute__((vector_size(16)));

inline Lanes2 lanes(double x, double y) { return Lanes2{x, y}; }

/// sqrt per lane.
inline Lanes2 sqrtLanes(Lanes2 x) {
#if defined(__SSE2__)
  return Lanes2(_mm_sqrt_pd(__m128d(x)));  // one instruction for both (GCC does not pair the two)
#else
  return Lanes2{std::sqrt(x[0]), std::sqrt(x[1])};
#endif
}

/// (x[0], -x[1]): lane 1's sign bit flipped (one xorpd; exact).
inline Lanes2 negateLane1(Lanes2 x) {
  const Mask2 sign = {0, static_cast<long long>(0x8000000000000000ULL)};
  return Lanes2(Mask2(x) ^ sign);
}

/// True when both lanes of a comparison are true (one movmskpd).
inline bool bothLanes(Mask2 m) {
#if defined(__SSE2__)
  return _mm_movemask_pd(__m128d(m)) == 3;
#else
  return (m[0] & m[1]) != 0;
#endif
}

/// u[j] = (R_a^T y_a)_j in lane 0 and (R_b^T y_b)_j in lane 1 for a vector per lane (y[i] holds
/// coordinate i of y_a and y_b), each the sum R(0,j) y_0 + R(1,j) y_1 + R(2,j) y_2 in that order.
inline void bodyFrameLanes(const Ellipsoid& a, const Ellipsoid& b, const Lanes2 y[3], Lanes2 u[3]) {
  const Ellipsoid::Pose& Ra = a.pose();  // R(i, j) = pose(i, j) for j < 3
  const Ellipsoid::Pose& Rb = b.pose();
  for (int j = 0; j < 3; ++j)
    u[j] = lanes(Ra(0, j), Rb(0, j)) * y[0] + lanes(Ra(1, j), Rb(1, j)) * y[1] + lanes(Ra(2, j), Rb(2, j)) * y[2];
}

/// u[j] = (R_a^T v)_j in lane 0 and (R_b^T v)_j in lane 1, each the sum R(0,j) v_0 + R(1,j) v_1 +
/// R(2,j) v_2 in that order: v in the body frames of a and b.
inline void bodyFrameLanes(const Ellipsoid& a, const Ellipsoid& b, const Eigen::Vector3d& v, Lanes2 u[3]) {
  const Lanes2 y[3] = {lanes(v[0], v[0]), lanes(v[1], v[1]), lanes(v[2], v[2])};
  bodyFrameLanes(a, b, y, u);
}

/// x[i] = (R_a w_a)_i in lane 0 and (R_b w_b)_i in lane 1: body-frame vectors back in the world
/// frame, each sum R(i,0) w_0 + R(i,1) w_1 + R(i,2) w_2 in that order.
inline void worldFrameLanes(const Ellipsoid& a, const Ellipsoid& b, const Lanes2 w[3], Lanes2 x[3]) {
  const Ellipsoid::Pose& Ra = a.pose();  // R(i, j) = pose(i, j) for j < 3
  const Ellipsoid::Pose& Rb = b.pose();
  for (int i = 0; i < 3; ++i)
    x[i] = lanes(Ra(i, 0), Rb(i, 0)) * w[0] + lanes(Ra(i, 1), Rb(i, 1)) * w[1] + lanes(Ra(i, 2), Rb(i, 2)) * w[2];
}

/// max per lane.
inline Lanes2 maxLanes(Lanes2 x, Lanes2 y) {
#if defined(__SSE2__)
  return Lanes2(_mm_max_pd(__m128d(x), __m128d(y)));
#else
  return Lanes2{std::fmax(x[0], y[0]), std::fmax(x[1], y[1])};
#endif
}

/// The radii of a and b, radius j in r[j].
inline void radiusLanes(const Ellipsoid& a, const Ellipsoid& b, Lanes2 r[3]) {
  for (int j = 0; j < 3; ++j) r[j] = lanes(a.radii()[j], b.radii()[j]);
}

}  // namespace detail
}  // namespace fcl_quadric
