#pragma once
/// \file ccd_function.h
/// The CCD function of two moving quadrics (Choi 2008, thesis §5.3):
///
///   F(u, t) = det((u - 1) A(t) - u B(t)),   (u, t) in [0, 1] x [0, 1],
///
/// the characteristic polynomial f(lambda; t) = det(lambda A(t) - B(t)) after the substitution
/// lambda = (u - 1) / u, which maps lambda in (-inf, 0] to u in (0, 1] (F = u^4 f). For two
/// ellipsoids F(0, t) = det A(t) < 0 and F(1, t) = det B(t) < 0, and by Theorem 5.1 the ellipsoids
/// are separate at t iff u -> F(u, t) has two distinct roots in (0, 1), i.e. iff max_u F(u, t) > 0;
/// externally tangent iff the maximum is 0; overlapping iff it is negative.
///
/// Construction (thesis §2.5.3 / §5.3 use the Bernstein form for robustness): every entry of A(t)
/// and B(t) is converted to the scaled Bernstein basis of [0, 1] at its own degree (low degree,
/// well conditioned); the determinant is expanded in that basis (products of scaled Bernstein
/// polynomials are plain convolutions and all degree elevations multiply by binomial rows, so no
/// power-basis cancellation occurs) at the five abscissae u = 0, 1/4, 1/2, 3/4, 1, and the five
/// univariate results are interpolated into the Bernstein basis in u (F has degree 4 in u; the
/// rows at u = 0 and u = 1 are exact copies of det A and det B). Degree in t: the structural
/// degree of the expansion (e.g. 18 for two rigid motions from poses, 6 for the affine
/// interpolant of §5.2).
///
/// Part of the continuous-collision layer: standard library and Eigen only.

#include "fcl_quadric/algebra/bivariate_bernstein.h"
#include "fcl_quadric/algebra/polynomial_matrix.h"
#include "fcl_quadric/continuous/motion_matrix.h"

namespace fcl_quadric {

/// F(u, t) = det((u - 1) A(t) - u B(t)) in the Bernstein basis of [0, 1] x [0, 1] (rows: u index
/// 0..4, columns: t index). \throws std::invalid_argument if an entry has a non-finite
/// coefficient or the degree in t exceeds 400.
BivariateBernstein ccdFunction(const PolynomialMatrix4& A, const PolynomialMatrix4& B);

/// F computed twice (docs/algorithms.md section 8, "precision check"): in double from A and B,
/// and in extended precision (long double) from the power-basis coefficient matrices Ak, Bk of
/// the same quadrics (computed in extended precision by the caller). The extended F is returned,
/// rounded to double; `error` estimates its error per coefficient from the difference of the two
/// (2^-11 of it, with a safety factor 8, smoothed over neighbouring coefficients) plus the final
/// rounding. An estimate, not a bound: it is what the CCD uses for motions whose conditioning
/// puts F's double rounding above the touching band, where the fixed relative band of
/// kCcdTouchingRelative would certify rounding noise.
struct CheckedCcdFunction {
  BivariateBernstein F;
  Eigen::MatrixXd error;  // same shape as F.coefficients(), entries >= 0
  /// The same estimate for the end rows u = 0 and u = 1 (det A(t) and det B(t); 2 rows), each
  /// smoothed over its own neighbouring coefficients only. `error` smooths over every row, so the
  /// interior rows' differences, up to the thin bodies' aspect ratios to the fourth power larger
  /// than the ends, hide whether the ends are negative (Theorem 5.1's sign precondition,
  /// docs/reliability.md finding 21). Used only for that precondition.
  Eigen::MatrixXd end_error;
};
/// \throws std::invalid_argument as ccdFunction.
CheckedCcdFunction ccdFunctionChecked(const PolynomialMatrix4& A, const PolynomialMatrix4& B,
                                      const std::vector<Matrix4ld>& Ak, const std::vector<Matrix4ld>& Bk);

/// det M(t) of a polynomial matrix, computed in the scaled Bernstein basis as above and returned
/// in the Bernstein basis of [0, 1] at its structural degree. \throws std::invalid_argument if the
/// degree exceeds the binomial table (400) or a coefficient is not finite.
BernsteinPolynomial bernsteinDeterminant(const PolynomialMatrix4& M);

}  // namespace fcl_quadric
