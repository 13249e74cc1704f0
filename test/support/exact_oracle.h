#pragma once
// Exact rational oracle for the static ellipsoid tests. Independent of the library's algorithm:
// it builds the primal quadric matrices A = N^T J N (N = [S^-1 R^T, -S^-1 R^T p; 0 1],
// J = diag(1,1,1,-1)) exactly in GMP rationals from the double inputs, gets the coefficients of
// f(lambda) = det(lambda A - B) by exact evaluation at five points and Lagrange interpolation,
// and counts distinct negative roots with an exact Sturm sequence (Theorem 4.1).
#include <array>

#include <gmpxx.h>

#include "fcl_quadric/geometry/ellipsoid.h"
#include "fcl_quadric/geometry/ellipsoid_separation.h"

namespace fcl_quadric {
namespace test {

using Rational = mpq_class;
using RationalPolynomial = std::vector<Rational>;  // low -> high

/// Exact det(lambda A' - B') for A' = k P_a A, B' = k P_b B: the primal matrices scaled by the
/// positive constants P = (r1 r2 r3)^2 and a common power of two k that makes them integral. Same
/// root signs and multiplicities as det(lambda A - B) (lambda is rescaled by P_a/P_b > 0).
std::array<Rational, 5> exactCharacteristicPolynomial(const Ellipsoid& a, const Ellipsoid& b);

/// Exact coefficients of f(lambda) = det(lambda A - B) itself (the scalings undone).
std::array<Rational, 5> exactCharacteristicPolynomialUnscaled(const Ellipsoid& a, const Ellipsoid& b);

/// Number of distinct real roots of p in the open interval (lo, hi) (exact Sturm sequence);
/// lo = -infinity when lo_infinite.
int exactDistinctRootsBelow(const RationalPolynomial& p, const Rational& hi);

/// Exact classification (Theorem 4.1): two distinct negative roots -> Separated, one distinct
/// (a double root) -> Touching, none -> Overlapping.
Separation exactClassify(const Ellipsoid& a, const Ellipsoid& b);

/// Exact q_e(x) = |S^-1 R^T (x - p)|^2 - 1 of the solid as the library defines it (ellipsoid.h),
/// in rationals from the stored doubles: negative inside, zero on the surface.
Rational exactImplicit(const Ellipsoid& e, const Eigen::Vector3d& x);

}  // namespace test
}  // namespace fcl_quadric
