#pragma once
// Private: the pencil of two ellipsoids in the unit frame of the first (docs/algorithms.md §1).
//
// Let A be the first ellipsoid. In A's unit frame, x_A = S_A^-1 R_A^T (x - p_A), A is the unit
// ball and the second ellipsoid is B = { x : |L x + t| <= 1 } with
//     L = S_B^-1 R_B^T R_A S_A,   t = S_B^-1 R_B^T (p_A - p_B).
// With J = diag(1,1,1,-1) and N = [L t; 0 1] the homogeneous matrices are J and B~ = N^T J N, and
// f(lambda) = det(lambda J - B~) has the roots of det(lambda A - B) (congruence by A's frame map,
// Choi 2008 §4.1.2). Writing lambda = -mu/(1-mu) for mu in [0,1):
//     F(mu) = det(mu J + (1-mu) B~) = sum_k E_k mu^k (1-mu)^(4-k)            (scaled Bernstein)
//     G(mu) = det(mu I + (1-mu) K)   = sum_k g_k mu^k (1-mu)^(3-k),  K = L^T L,
// where E_k are the signed sums of principal minors of B~ (the power coefficients of f(-nu) in
// nu = -lambda) and psi(mu) = F(mu)/G(mu) = min_x [mu q_A(x) + (1-mu) q_B(x)] is concave on
// [0,1] with psi(0) = psi(1) = -1. Remark 4.3 (f(lambda0) > 0 for some lambda0 < 0 iff separate)
// becomes: A, B separate iff max psi > 0. The minimiser x(mu) = -(1-mu) W^-1 v, W = mu I + (1-mu)K,
// v = L^T t, is the witness point; at the maximiser mu*, q_A(x*) = q_B(x*) = psi(mu*) (envelope
// theorem), and for touching ellipsoids x* is the contact point of Theorem 4.4 (the null vector of
// lambda0 A - B is (x*, 1)).
#include <array>

#include "fcl_quadric/algebra/double_double.h"
#include "fcl_quadric/geometry/ellipsoid.h"

namespace fcl_quadric {
namespace detail {

template <class T>
struct Pencil {
  T L[3][3];
  T t[3];
  T K[3][3];  // symmetric
  T v[3];
  T s;        // |t|^2 - 1
  T E[5];     // scaled Bernstein coefficients of F
  T g[4];     // scaled Bernstein coefficients of G
  T bernF[5];    // Bernstein coefficients of F (degree 4)
  T bernG[4];    // Bernstein coefficients of G (degree 3)
  double ra[3];      // radii of A
  double inv_rb[3];  // 1 / radii of B
  double dsum;       // |p_A - p_B|_1: with ra, inv_rb the magnitude scales of L and t
};

/// L, t, K, v, s (not the coefficients: see computePencilCoefficients).
template <class T>
Pencil<T> makePencil(const Ellipsoid& a, const Ellipsoid& b);

/// Fill K, v and s from p.L and p.t (shared with the affine entry point).
template <class T>
void completePencil(Pencil<T>& p);

/// Fill E, g and the Bernstein coefficients of F and G (needed by maximisePsi, evaluatePencil,
/// evaluateF and rootOfF; the certificates need only L, t, K, v). Kept separate because most
/// pairs are decided at the starting guess, before any of these are needed.
template <class T>
void computePencilCoefficients(Pencil<T>& p);

template <class T>
struct PencilValues {
  T F, dF, d2F, G, dG, d2G;
};

template <class T>
PencilValues<T> evaluatePencil(const Pencil<T>& p, const T& mu);

/// F(mu) in the scaled Bernstein form (the stable evaluation used for certificates).
template <class T>
T evaluateF(const Pencil<T>& p, const T& mu);

/// Witness x(mu) = -(1-mu) W^-1 v in A's unit frame.
template <class T>
void witness(const Pencil<T>& p, const T& mu, T x[3]);

/// Values at a witness point x (A's unit frame) with the magnitudes that bound their rounding:
/// q_A = |x|^2 - 1, q_B = |Lx + t|^2 - 1, Q = mu q_A + (1-mu) q_B, and r = grad Q / 2. Because Q
/// is a convex quadratic with Hessian 2W, W = mu I + (1-mu) L^T L >= mu I, its minimum psi(mu)
/// satisfies psi(mu) >= Q(x) - |r|^2 / mu for every x: a rigorous lower bound for any witness.
struct WitnessValues {
  double qa, qb, Q;
  double scale_a, scale_b, scale_Q;   // absolute-value evaluations (rounding scale)
  double residual2;                   // |r|^2 as computed
  double residual_scale2;             // |magnitude of r's evaluation|^2
};
template <class T>
WitnessValues witnessValues(const Pencil<T>& p, const T& mu, const T x[3]);
/// The scales (absolute-value evaluations) of the values above; computed only when a
/// certificate's sign pattern makes them worth computing.
template <class T>
void witnessScales(const Pencil<T>& p, double mu, const T x[3], WitnessValues* w);

/// Starting guess for maximisePsi: the maximiser for two balls of the sizes of A and B.
double initialMu(const Pencil<double>& p);

/// Safeguarded Newton for the maximiser of psi on [0,1] (root of P = F'G - FG', which has the sign
/// of psi'). Starts at mu0 in (0,1); at most tolerance::kMaxPencilNewtonIterations steps; on
/// reaching the cap the current bracket midpoint is returned (the certificates below are valid at
/// any mu, so a poor maximiser can only send the decision to the next precision stage).
/// With stop_when_promising, it returns the first iterate after mu0 at which a certificate can
/// succeed (F > 0, or both q_A and q_B negative at the witness).
template <class T>
T maximisePsi(const Pencil<T>& p, double mu0, int* iterations, bool stop_when_promising = false);

/// A root of F in [lo, hi] where F(lo) and F(hi) have opposite signs (safeguarded Newton with a
/// bisection bracket, capped at tolerance::kMaxRootBracketIterations).
double rootOfF(const Pencil<double>& p, double lo, double hi);

/// Map a point from A's unit frame to the world frame.
Eigen::Vector3d unitFrameToWorld(const Ellipsoid& a, const Eigen::Vector3d& x);

/// Deterministic canonical order of a pair (so classify(a,b) == classify(b,a) bit for bit):
/// returns true when b should play the role of the unit-frame ellipsoid.
bool swapForCanonicalOrder(const Ellipsoid& a, const Ellipsoid& b);

}  // namespace detail
}  // namespace fcl_quadric
