#pragma once
/// \file characteristic_polynomial.h
/// The characteristic polynomial f(lambda) = det(lambda A - B) of two ellipsoids
/// (Choi 2008 §4.1.1-4.1.3; Wang et al. 2004 §3 with the opposite sign convention).

#include <array>

#include <Eigen/Core>

#include "fcl_quadric/geometry/ellipsoid.h"
#include "fcl_quadric/geometry/ellipsoid_separation.h"

namespace fcl_quadric {

/// Coefficients c[0..4] (low to high degree) of f(lambda) = det(lambda A' - B') where A' =
/// diag(1/a^2, 1/b^2, 1/c^2, -1) is A in its canonical frame and B' = M^T B M with M = M_A, i.e.
/// exactly the quartic of thesis §4.1.3 computed by its Generate-Characteristic-Polynomial
/// routine (29 additions, 39 multiplications for the coefficients) for rigid poses. f has the same
/// roots as det(lambda A - B) (M_A is rigid, det M_A = 1); c[4] = -1/(a^2 b^2 c^2) < 0 and
/// c[0] = det(-B') < 0 (Remark 4.3). Never throws for valid Ellipsoid objects.
std::array<double, 5> characteristicPolynomial(const Ellipsoid& a, const Ellipsoid& b);

/// The affine case of §4.1.2: ellipsoids given as images M_A, M_B (4x4, last row [0 0 0 1],
/// invertible linear part) of the *unit ball*. Returns det(lambda A - B) up to the positive factor
/// det(M_A)^2 (same roots and signs). Throws std::invalid_argument on a singular or non-finite map.
std::array<double, 5> characteristicPolynomialAffine(const Eigen::Matrix4d& M_A, const Eigen::Matrix4d& M_B);

/// Classification from the coefficients by the signed subresultant sequence of thesis §4.5
/// (summary §4.5.3), evaluated in double: an independent path, tested to agree with
/// classifyEllipsoids() away from tangency. `f` must come from characteristicPolynomial().
/// \throws std::invalid_argument if a coefficient is not finite or f[4] == 0 (not the quartic of
/// two ellipsoids).
Separation classifyBySubresultants(const std::array<double, 5>& f);

}  // namespace fcl_quadric
