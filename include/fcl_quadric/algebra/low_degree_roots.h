#pragma once
/// \file low_degree_roots.h
/// All complex roots of a real polynomial of degree at most 3, for callers that need the
/// near-real complex pairs too (a multiple root perturbed by rounding splits into a pair with a
/// small imaginary part). Certified real-root counting and isolation live in sturm_sequence.h
/// and root_isolation.h; this is a numerical solver.
///
/// Method: a cubic has a real root; it is bracketed in Fujiwara's bound and bisected to
/// adjacent doubles (at most kCubicBisectionSteps steps), the cubic is deflated by it to a
/// quadratic both forward and backward, the quadratics' roots (stable formula) are polished by
/// kCubicNewtonSteps Newton steps on the cubic itself, and the pair with the smaller residual
/// is kept.
/// Replaces the eigenvalues of the companion matrix (Eigen::EigenSolver), which cost 10-25 s
/// of compile time per translation unit (see symmetric_eigen.h).
///
/// Part of the algebra layer: depends on the standard library only.

#include <complex>
#include <vector>

namespace fcl_quadric {

/// Bisection cap of the real root of a cubic: enough halvings to go from the root bound to
/// adjacent doubles anywhere in the double range (2^1024 down to 2^-1074 takes < 2,200).
constexpr int kCubicBisectionSteps = 2200;
/// Polynomials whose root bound is within 2^+-300 are solved unscaled (the monic coefficients
/// and the cubic on its bound stay below 2^900); beyond, x = 2^k y scales the roots to below 2.
constexpr int kLowDegreeNoScaleExponent = 300;
/// Newton steps polishing the roots of the deflated quadratic on the cubic.
constexpr int kCubicNewtonSteps = 3;

/// Roots of c[0] + c[1] x + ... + c[d] x^d, d = c.size() - 1 after trailing (highest-degree)
/// zero coefficients are dropped; d <= 3 required. Returns d roots with multiplicity, complex
/// pairs adjacent; real roots have imaginary part exactly 0. Constant (or empty) input: no
/// roots. Limit of the scaling: when the roots spread over more than ~2^1000 (e.g. 1e150 and
/// 1e-150 in one cubic), the constant term of the scaled polynomial underflows and the smallest
/// roots come back as 0. Throws std::invalid_argument naming the value for a non-finite coefficient or a
/// degree above 3.
std::vector<std::complex<double>> lowDegreeRoots(std::vector<double> c);

}  // namespace fcl_quadric
