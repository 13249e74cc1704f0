#include "geometry/pencil.h"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <type_traits>

#include "fcl_quadric/tolerances.h"

namespace fcl_quadric {
namespace detail {

template <class T>
void completePencil(Pencil<T>& p) {
  for (int j = 0; j < 3; ++j) {
    for (int l = j; l < 3; ++l) {
      p.K[j][l] = p.L[0][j] * p.L[0][l] + p.L[1][j] * p.L[1][l] + p.L[2][j] * p.L[2][l];
      p.K[l][j] = p.K[j][l];
    }
    p.v[j] = p.L[0][j] * p.t[0] + p.L[1][j] * p.t[1] + p.L[2][j] * p.t[2];
  }
  p.s = p.t[0] * p.t[0] + p.t[1] * p.t[1] + p.t[2] * p.t[2] - T(1.0);
}

template <class T>
void computePencilCoefficients(Pencil<T>& p) {
  const auto& K = p.K;
  const auto& L = p.L;
  const T trK = K[0][0] + K[1][1] + K[2][2];
  const T sig2 = K[0][0] * K[1][1] - K[0][1] * K[0][1] + K[0][0] * K[2][2] - K[0][2] * K[0][2] +
                 K[1][1] * K[2][2] - K[1][2] * K[1][2];
  const T detL = L[0][0] * (L[1][1] * L[2][2] - L[1][2] * L[2][1]) -
                 L[0][1] * (L[1][0] * L[2][2] - L[1][2] * L[2][0]) +
                 L[0][2] * (L[1][0] * L[2][1] - L[1][1] * L[2][0]);
  const T detK = detL * detL;
  const T* v = p.v;
  const T vv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
  const T vKv = v[0] * (K[0][0] * v[0] + K[0][1] * v[1] + K[0][2] * v[2]) +
                v[1] * (K[1][0] * v[0] + K[1][1] * v[1] + K[1][2] * v[2]) +
                v[2] * (K[2][0] * v[0] + K[2][1] * v[1] + K[2][2] * v[2]);
  // Signed sums of principal minors of B~ = [K v; v^T s] weighted by J (pencil.h).
  p.E[0] = -detK;                                  // det B~ = det(N)^2 det J
  p.E[1] = p.s * sig2 - trK * vv + vKv - detK;     // sum_{i<=3} det B~_(-i) - det K
  p.E[2] = p.s * trK - vv - sig2;
  p.E[3] = p.s - trK;
  p.E[4] = T(-1.0);
  p.g[0] = detK;
  p.g[1] = sig2;
  p.g[2] = trK;
  p.g[3] = T(1.0);
  // Bernstein coefficients (beta_k = E_k / C(4,k), gamma_k = g_k / C(3,k)) and their forward
  // differences for the derivatives. Evaluation stays in the Bernstein basis: the power basis in mu
  // cancels catastrophically when the E_k span many orders of magnitude.
  // (Multiplying by rounded 1/6, 1/3 is harmless: these coefficients only steer the search and
  // the root isolation of the separating plane; the certificates never use them.)
  const T bF[5] = {p.E[0], p.E[1] * T(0.25), p.E[2] * T(1.0 / 6.0), p.E[3] * T(0.25), p.E[4]};
  for (int k = 0; k < 5; ++k) p.bernF[k] = bF[k];
  const T bG[4] = {p.g[0], p.g[1] * T(1.0 / 3.0), p.g[2] * T(1.0 / 3.0), p.g[3]};
  for (int k = 0; k < 4; ++k) p.bernG[k] = bG[k];
}

template <class T>
Pencil<T> makePencil(const Ellipsoid& a, const Ellipsoid& b) {
  Pencil<T> p;
  const Eigen::Vector3d& ra = a.radii();
  const Eigen::Vector3d& rb = b.radii();
  const Eigen::Matrix3d& RB = b.rotation();
  // A's frame map is x = R_A^-T S_A x_A + p_A (the inverse of the body map x_A = S_A^-1 R_A^T(x-p_A)).
  // In double R_A^-T is R_A (orthogonal to ~1e-16, see tolerances.h); in the extended-precision
  // stage it is formed exactly enough as cof(R_A)/det(R_A) so that the decision is consistent with
  // the ellipsoid's definition and not only with its idealised rigid pose.
  T RA[3][3];
  const Eigen::Matrix3d& Ra = a.rotation();
  if (std::is_same<T, double>::value) {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) RA[i][j] = T(Ra(i, j));
  } else {
    T cof[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
        cof[i][j] = T(Ra(i1, j1)) * T(Ra(i2, j2)) - T(Ra(i1, j2)) * T(Ra(i2, j1));
      }
    const T det = T(Ra(0, 0)) * cof[0][0] + T(Ra(0, 1)) * cof[0][1] + T(Ra(0, 2)) * cof[0][2];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) RA[i][j] = cof[i][j] / det;  // (R^-1)^T = cof(R)/det(R)
  }
  T d[3];
  for (int k = 0; k < 3; ++k) d[k] = T(a.center()[k]) - T(b.center()[k]);
  p.dsum = std::fabs(toDouble(d[0])) + std::fabs(toDouble(d[1])) + std::fabs(toDouble(d[2]));
  for (int i = 0; i < 3; ++i) {
    const T inv_rb = T(1.0) / T(rb[i]);
    const double inv_rbd = toDouble(inv_rb);
    for (int j = 0; j < 3; ++j) {
      T c = T(RB(0, i)) * RA[0][j] + T(RB(1, i)) * RA[1][j] + T(RB(2, i)) * RA[2][j];
      p.L[i][j] = c * T(ra[j]) * inv_rb;
    }
    p.t[i] = (T(RB(0, i)) * d[0] + T(RB(1, i)) * d[1] + T(RB(2, i)) * d[2]) * inv_rb;
    p.inv_rb[i] = inv_rbd;
    p.ra[i] = ra[i];
  }
  completePencil(p);
  return p;
}

template <class T>
PencilValues<T> evaluatePencil(const Pencil<T>& p, const T& mu) {
  // Bernstein basis values of degree 2, 3, 4 at mu.
  const T s = mu, r = T(1.0) - mu;
  const T s2 = s * s, r2 = r * r, sr = s * r;
  const T B2[3] = {r2, T(2.0) * sr, s2};
  const T B3[4] = {r2 * r, T(3.0) * sr * r, T(3.0) * sr * s, s2 * s};
  const T B4[5] = {r2 * r2, T(4.0) * sr * r2, T(6.0) * s2 * r2, T(4.0) * sr * s2, s2 * s2};
  const T* b = p.bernF;  // Bernstein coefficients of F (degree 4)
  const T* g = p.bernG;  // Bernstein coefficients of G (degree 3)
  PencilValues<T> v;
  v.F = b[0] * B4[0] + b[1] * B4[1] + b[2] * B4[2] + b[3] * B4[3] + b[4] * B4[4];
  v.dF = T(4.0) * ((b[1] - b[0]) * B3[0] + (b[2] - b[1]) * B3[1] + (b[3] - b[2]) * B3[2] + (b[4] - b[3]) * B3[3]);
  v.d2F = T(12.0) * ((b[2] - T(2.0) * b[1] + b[0]) * B2[0] + (b[3] - T(2.0) * b[2] + b[1]) * B2[1] +
                     (b[4] - T(2.0) * b[3] + b[2]) * B2[2]);
  v.G = g[0] * B3[0] + g[1] * B3[1] + g[2] * B3[2] + g[3] * B3[3];
  v.dG = T(3.0) * ((g[1] - g[0]) * B2[0] + (g[2] - g[1]) * B2[1] + (g[3] - g[2]) * B2[2]);
  v.d2G = T(6.0) * ((g[2] - T(2.0) * g[1] + g[0]) * r + (g[3] - T(2.0) * g[2] + g[1]) * s);
  return v;
}

template <class T>
T evaluateF(const Pencil<T>& p, const T& mu) {
  const T s = mu, r = T(1.0) - mu;
  const T s2 = s * s, r2 = r * r;
  return p.E[0] * r2 * r2 + p.E[1] * s * r2 * r + p.E[2] * s2 * r2 + p.E[3] * s2 * s * r + p.E[4] * s2 * s2;
}

template <class T>
void witness(const Pencil<T>& p, const T& mu, T x[3]) {
  const T r = T(1.0) - mu;
  T W[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) W[i][j] = r * p.K[i][j] + (i == j ? mu : T(0.0));
  // adjugate of the symmetric W
  const T a00 = W[1][1] * W[2][2] - W[1][2] * W[1][2];
  const T a01 = W[0][2] * W[1][2] - W[0][1] * W[2][2];
  const T a02 = W[0][1] * W[1][2] - W[0][2] * W[1][1];
  const T a11 = W[0][0] * W[2][2] - W[0][2] * W[0][2];
  const T a12 = W[0][1] * W[0][2] - W[0][0] * W[1][2];
  const T a22 = W[0][0] * W[1][1] - W[0][1] * W[0][1];
  const T det = W[0][0] * a00 + W[0][1] * a01 + W[0][2] * a02;
  const T f = -r / det;
  const T* v = p.v;
  x[0] = f * (a00 * v[0] + a01 * v[1] + a02 * v[2]);
  x[1] = f * (a01 * v[0] + a11 * v[1] + a12 * v[2]);
  x[2] = f * (a02 * v[0] + a12 * v[1] + a22 * v[2]);
}

template <class T>
WitnessValues witnessValues(const Pencil<T>& p, const T& mu, const T x[3]) {
  WitnessValues w;
  const T qa = x[0] * x[0] + x[1] * x[1] + x[2] * x[2] - T(1.0);
  T y[3];
  T qb = T(-1.0);
  for (int i = 0; i < 3; ++i) {
    y[i] = p.L[i][0] * x[0] + p.L[i][1] * x[1] + p.L[i][2] * x[2] + p.t[i];
    qb = qb + y[i] * y[i];
  }
  w.qa = toDouble(qa);
  w.qb = toDouble(qb);
  // Q(x) = mu q_A + (1-mu) q_B and r = grad Q / 2 = mu x + (1-mu) L^T y.
  const T r1 = T(1.0) - mu;
  w.Q = toDouble(mu * qa + r1 * qb);
  w.residual2 = 0.0;
  for (int j = 0; j < 3; ++j) {
    const double rj = toDouble(mu * x[j] + r1 * (p.L[0][j] * y[0] + p.L[1][j] * y[1] + p.L[2][j] * y[2]));
    w.residual2 += rj * rj;
  }
  return w;
}

template <class T>
void witnessScales(const Pencil<T>& p, double mu, const T x[3], WitnessValues* w) {
  // Entrywise magnitudes: |L_ij| and its rounding are both <= r_A,j / r_B,i (|(R_B^T R_A)_ij| <= 1),
  // |t_i| and its rounding <= |p_A - p_B|_1 / r_B,i; we use twice those.
  double ax[3];
  for (int i = 0; i < 3; ++i) ax[i] = std::fabs(toDouble(x[i]));
  w->scale_a = ax[0] * ax[0] + ax[1] * ax[1] + ax[2] * ax[2] + 1.0;
  const double h = 2.0 * (p.ra[0] * ax[0] + p.ra[1] * ax[1] + p.ra[2] * ax[2] + p.dsum);
  double ay[3], s_ay = 0.0;
  w->scale_b = 1.0;
  for (int i = 0; i < 3; ++i) {
    ay[i] = h * p.inv_rb[i];  // >= |L_i. x| + |t_i| plus their rounding
    w->scale_b += ay[i] * ay[i];
    s_ay += ay[i] * p.inv_rb[i];
  }
  const double rd = 1.0 - mu;
  w->scale_Q = mu * w->scale_a + rd * w->scale_b;
  w->residual_scale2 = 0.0;
  for (int j = 0; j < 3; ++j) {
    const double mag = mu * ax[j] + rd * 2.0 * p.ra[j] * s_ay;
    w->residual_scale2 += mag * mag;
  }
}

double initialMu(const Pencil<double>& p) {
  // For two balls of radii 1 and rho the maximiser is mu* = 1/(1 + rho) (the pencil's minimiser
  // is then the tangency point). Estimate B's size in A's unit frame from tr K = sum 1/sigma_i^2.
  const double trK = p.K[0][0] + p.K[1][1] + p.K[2][2];
  const double rho = std::sqrt(3.0 / trK);
  return 1.0 / (1.0 + rho);
}

template <class T>
T maximisePsi(const Pencil<T>& p, double mu0, int* iterations, bool stop_when_promising) {
  // P(mu) = F'G - FG' has the sign of psi' (G > 0 on [0,1]); psi is concave, so P is positive
  // left of the maximiser and negative right of it: keep that bracket, take Newton steps inside
  // it and bisect otherwise. Stop once a Newton step is below kPencilNewtonStep: the next error
  // is then of the order of its square, far below what the certificates need (psi is flat at
  // its maximum: an argument error e costs ~psi''e^2/2).
  const double tol = std::is_same<T, double>::value ? tolerance::kPencilNewtonStep : 1e-24;
  T lo(0.0), hi(1.0), mu(mu0);
  *iterations = 0;
  for (int it = 0; it < tolerance::kMaxPencilNewtonIterations; ++it) {
    *iterations = it + 1;
    const PencilValues<T> e = evaluatePencil(p, mu);
    const T Pv = e.dF * e.G - e.F * e.dG;
    const T dP = e.d2F * e.G - e.F * e.d2G;
    if (stop_when_promising && it > 0) {
      // psi = F/G and psi' = P/G^2 give q_A = psi + (1-mu) psi' and q_B = psi - mu psi' at the
      // witness x(mu) (envelope theorem): stop as soon as a certificate can succeed here.
      const double F = toDouble(e.F), G = toDouble(e.G), psi = F / G, dpsi = toDouble(Pv) / (G * G);
      const double m = toDouble(mu);
      if (F > 0.0 || (psi + (1.0 - m) * dpsi < 0.0 && psi - m * dpsi < 0.0)) return mu;
    }
    if (Pv > T(0.0)) lo = mu; else if (Pv < T(0.0)) hi = mu; else return mu;
    T next;
    bool newton_ok = dP < T(0.0);
    if (newton_ok) {
      next = mu - Pv / dP;
      newton_ok = next > lo && next < hi;
    }
    if (!newton_ok) next = (lo + hi) * T(0.5);
    const double step = std::fabs(toDouble(next - mu));
    mu = next;
    if ((newton_ok && step <= tol) || toDouble(hi - lo) <= tol) break;
  }
  return mu;
}

double rootOfF(const Pencil<double>& p, double lo, double hi) {
  double flo = evaluateF(p, lo);
  double x = 0.5 * (lo + hi);
  for (int it = 0; it < tolerance::kMaxRootBracketIterations; ++it) {
    const PencilValues<double> e = evaluatePencil(p, x);
    const double fx = evaluateF(p, x);
    if (fx == 0.0) return x;
    if ((fx > 0.0) == (flo > 0.0)) { lo = x; flo = fx; } else { hi = x; }
    double next = (e.dF != 0.0) ? x - fx / e.dF : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    const double step = std::fabs(next - x);
    x = next;
    if (step <= 1e-16 * std::max(1.0, std::fabs(x)) || hi - lo <= 4e-16) break;
  }
  return x;
}

Eigen::Vector3d unitFrameToWorld(const Ellipsoid& a, const Eigen::Vector3d& x) {
  return a.center() + a.rotation() * x.cwiseProduct(a.radii());
}

bool swapForCanonicalOrder(const Ellipsoid& a, const Ellipsoid& b) {
  // The larger-volume ellipsoid becomes the unit ball; ties broken lexicographically on the data.
  const double va = a.radii().prod(), vb = b.radii().prod();
  if (va != vb) return vb > va;
  auto key = [](const Ellipsoid& e) {
    std::array<double, 15> k;
    for (int i = 0; i < 3; ++i) { k[i] = e.radii()[i]; k[3 + i] = e.center()[i]; }
    for (int i = 0; i < 9; ++i) k[6 + i] = e.rotation()(i % 3, i / 3);  // column-major order
    return k;
  };
  return key(b) > key(a);
}

#define FCL_QUADRIC_INSTANTIATE_PENCIL(T)                                                        \
  template Pencil<T> makePencil<T>(const Ellipsoid&, const Ellipsoid&);                          \
  template void completePencil<T>(Pencil<T>&);                                                   \
  template void computePencilCoefficients<T>(Pencil<T>&);                                        \
  template PencilValues<T> evaluatePencil<T>(const Pencil<T>&, const T&);                        \
  template T evaluateF<T>(const Pencil<T>&, const T&);                                           \
  template void witness<T>(const Pencil<T>&, const T&, T*);                                      \
  template WitnessValues witnessValues<T>(const Pencil<T>&, const T&, const T*);                 \
  template void witnessScales<T>(const Pencil<T>&, double, const T*, WitnessValues*);            \
  template T maximisePsi<T>(const Pencil<T>&, double, int*, bool);

FCL_QUADRIC_INSTANTIATE_PENCIL(double)
FCL_QUADRIC_INSTANTIATE_PENCIL(DoubleDouble)
#undef FCL_QUADRIC_INSTANTIATE_PENCIL

}  // namespace detail
}  // namespace fcl_quadric
