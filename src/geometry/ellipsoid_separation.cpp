#include "fcl_quadric/geometry/ellipsoid_separation.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "fcl_quadric/tolerances.h"
#include "geometry/lanes2.h"
#include "geometry/pencil.h"

namespace fcl_quadric {

const char* toString(Separation s) {
  switch (s) {
    case Separation::Separated: return "separate";
    case Separation::Touching: return "touching";
    case Separation::Overlapping: return "overlapping";
  }
  return "unknown";
}

namespace {

/// What a pre-test writes when it decides: the status only (StatusOnly, the boolean queries:
/// separationStatus(), ellipsoidsCollide()) or the whole certificate with its witness and normal
/// (classifyEllipsoids()). The decisions are the same computation either way; the status-only
/// instantiation just leaves out the witness and normal arithmetic and the certificate's stores.
struct StatusOnly {
  Separation status = Separation::Touching;
};

template <class Out>
constexpr bool kWantsWitness = std::is_same_v<Out, SeparationCertificate>;

/// One precision stage of the certified decision (docs/algorithms.md §1). With x = x(mu) the
/// pencil witness and Q, r as in detail::WitnessValues:
///  - Separated   if Q - tau scale_Q - (|r| + tau |r|_scale)^2 / mu > 0: then psi(mu) > 0, i.e. the
///                positive combination mu q_A + (1-mu) q_B is positive everywhere, so no point is
///                in both solids (Theorem 4.1 via Remark 4.3 in the mu-form of pencil.h);
///  - Overlapping if q_A(x) < -tau scale_a and q_B(x) < -tau scale_b: x is inside both;
///  - otherwise undecided (returns false).
/// tau bounds the relative rounding of the stage's arithmetic (tolerances.h).
template <class T>
bool certify(const detail::Pencil<T>& p, const T& mu, double tau, SeparationCertificate* out, T x[3]) {
  detail::witness(p, mu, x);
  detail::WitnessValues w = detail::witnessValues(p, mu, x);
  const double mud = toDouble(mu);
  out->mu = mud;
  out->psi = w.Q;
  const bool maybe_separated = mud > 0.0 && w.Q > 0.0;
  const bool maybe_overlapping = w.qa < 0.0 && w.qb < 0.0;
  if (!maybe_separated && !maybe_overlapping) return false;
  detail::witnessScales(p, mud, x, &w);
  if (maybe_separated) {
    const double rn = std::sqrt(w.residual2) + tau * std::sqrt(w.residual_scale2);
    const double lower = w.Q - tau * w.scale_Q - rn * rn / mud;
    if (lower > 0.0) {
      out->status = Separation::Separated;
      return true;
    }
  }
  if (maybe_overlapping && w.qa < -tau * w.scale_a && w.qb < -tau * w.scale_b) {
    out->status = Separation::Overlapping;
    return true;
  }
  return false;
}


using detail::Lanes2;
using detail::lanes;

/// Separation along a direction m (any finite length, 0 included, which never separates):
/// h_a(m) + h_b(-m) < m.(p_b - p_a) with h(m) = m.p + |S R^T m| the support function, both
/// supports in one pass of lanes (r: the radii lanes; *h receives the centred supports |S R^T m|
/// of a and b, for the witness, and *u the body-frame directions R^T m, so that supportMidpoint()
/// along m need not compute them again). Every rounded quantity (m.d, |S R^T m|) is a sum or norm
/// whose rounding is below 8 eps times its absolute evaluation: sum|m_i d_i| for m.d, and
/// |m|_1 sum(r) for |S R^T m| (R^T m is rounded absolutely, ~eps |m|, and a long radius multiplies
/// that; tolerances.h, kStoredRotationDefect), so the relative margin tau = 2^-40 over their sum
/// covers it.
inline bool separatedAlong(const Eigen::Vector3d& m, const Eigen::Vector3d& d, const Ellipsoid& a, const Ellipsoid& b,
                           const Lanes2 r[3], double tau, Lanes2* h, Lanes2 u[3]) {
  detail::bodyFrameLanes(a, b, m, u);
  const Lanes2 s0 = u[0] * r[0], s1 = u[1] * r[1], s2 = u[2] * r[2];
  *h = detail::sqrtLanes(s0 * s0 + s1 * s1 + s2 * s2);
  const Lanes2 rsum = r[0] + r[1] + r[2];
  const double ha = (*h)[0], hb = (*h)[1];
  const double md = m.dot(d);
  const double scale = m.cwiseAbs().dot(d.cwiseAbs()) + ha + hb + m.cwiseAbs().sum() * (rsum[0] + rsum[1]);
  return md - ha - hb > tau * scale;
}

/// x strictly inside a and inside b: per lane (e = a, b), q_e(x) = |S^-1 R^T (x - p)|^2 - 1 <
/// -tau (1 + (|x|_1 + |p|_1) / r_min), with q the reciprocal radii lanes. The rounding of x - p is
/// below eps (|x|_1 + |p|_1) per coordinate, that of the rotation and of the reciprocals a few eps
/// of |S^-1 R^T (x - p)| <= 1 (otherwise the test fails anyway), so the margin covers the
/// rounding of q_e(x) for any x with a relative factor of > 1000.
bool strictlyInsideBoth(const Ellipsoid& a, const Ellipsoid& b, const Lanes2 q[3], const Eigen::Vector3d& x,
                        double tau) {
  const Eigen::Vector3d& pa = a.center();
  const Eigen::Vector3d& pb = b.center();
  Lanes2 y[3], z[3];
  for (int i = 0; i < 3; ++i) y[i] = lanes(x[i], x[i]) - lanes(pa[i], pb[i]);
  detail::bodyFrameLanes(a, b, y, z);
  const Lanes2 t0 = z[0] * q[0], t1 = z[1] * q[1], t2 = z[2] * q[2];
  const Lanes2 value = (t0 * t0 + t1 * t1 + t2 * t2) - 1.0;
  const double x1 = std::fabs(x[0]) + std::fabs(x[1]) + std::fabs(x[2]);
  const Lanes2 p1 = lanes(pa.cwiseAbs().sum(), pb.cwiseAbs().sum());
  const Lanes2 spread = (x1 + p1) * detail::maxLanes(detail::maxLanes(q[0], q[1]), q[2]);
  const auto inside = value < -tau * (1.0 + spread);  // per lane: all ones or zero
  return (inside[0] & inside[1]) != 0;
}

/// The midpoint of the support points p_a + R_a S_a (S_a u_a / h_a) of a along w and
/// p_b - R_b S_b (S_b u_b / h_b) of b along -w, with u = R^T w in lanes and h = |S u|, both
/// already computed by the caller's test along w (lineTests() or separatedAlong(), the same
/// expression bit for bit). Scale-free in w; h = 0 only on underflow, floored at DBL_MIN instead
/// of a division by zero.
/// offset[i] receives the support points' offsets from the centres, R S (S u / h) (lane 0: a's
/// along w, lane 1: b's along w, so b's support point along -w is p_b - offset lane 1).
inline void supportMidpoint(const Ellipsoid& a, const Ellipsoid& b, const Lanes2 u[3], const Lanes2 r[3],
                            Lanes2 h, Eigen::Vector3d* x, Lanes2 offset[3]) {
  const Lanes2 s0 = u[0] * r[0], s1 = u[1] * r[1], s2 = u[2] * r[2];
  const Lanes2 inv_h = 1.0 / detail::maxLanes(h, lanes(DBL_MIN, DBL_MIN));
  const Lanes2 t[3] = {s0 * r[0] * inv_h, s1 * r[1] * inv_h, s2 * r[2] * inv_h};
  detail::worldFrameLanes(a, b, t, offset);
  const Eigen::Vector3d& pa = a.center();
  const Eigen::Vector3d& pb = b.center();
  for (int i = 0; i < 3; ++i) (*x)[i] = 0.5 * ((pa[i] + offset[i][0]) + (pb[i] - offset[i][1]));
}

inline void supportMidpoint(const Ellipsoid& a, const Ellipsoid& b, const Lanes2 u[3], const Lanes2 r[3],
                            Lanes2 h, Eigen::Vector3d* x) {
  Lanes2 offset[3];
  supportMidpoint(a, b, u, r, h, x, offset);
}

/// What the centre-line tests compute on v for both ellipsoids at once (lane 0: a, lane 1: b):
/// u = R^T v, the radii r, their reciprocals q = 1 / r and the centred supports h = |S u|.
struct LineLanes {
  Lanes2 u[3], r[3], q[3], h;
};

/// 1 / r with one division per ellipsoid: k = 1 / (r0 r1 r2), then 1 / r0 = r1 r2 k, ...; each
/// within 3 ulps of the correctly rounded reciprocal, far inside the 2^-40 margins; the product
/// r0 r1 r2 stays within [1e-300, 1e300].
__attribute__((always_inline)) inline void lineLanes(const Ellipsoid& a, const Ellipsoid& b, const Eigen::Vector3d& v,
                                                     LineLanes* L) {
  detail::bodyFrameLanes(a, b, v, L->u);  // R^T v
  detail::radiusLanes(a, b, L->r);
  const Lanes2 r0 = L->r[0], r1 = L->r[1], r2 = L->r[2];
  const Lanes2 r12 = r1 * r2;
  const Lanes2 k = 1.0 / (r0 * r12);
  L->q[0] = r12 * k;
  L->q[1] = r0 * r2 * k;
  L->q[2] = r0 * r1 * k;
}

/// Tests 1 and 2 below are homogeneous in the direction of the centre line, so they run on
/// v = d = p_b - p_a itself (no square root or division) while |d| is in [1e-50, 1e50], where
/// the products stay in the normal range of doubles for sizes in [kMinRadius, kMaxLength]; on
/// v = d / |d| outside it. With |v| = |d| / s and the centred support h(v) = |S R^T v| = |v| h(n):
///  - supports disjoint along n:  h_a(v) + h_b(v) < |d| |v|;
///  - centre segment covered:     rho_a + rho_b > |d| with rho = |v| / l, l = |S^-1 R^T v|,
///                                i.e. l_a + l_b > s l_a l_b.
/// l lies within |v| [1e-100, 1e100] sqrt(3): within [1e-150, 1e150] sqrt(3) on the unscaled path
/// and [1e-100, 1e100] sqrt(3) on the scaled one, so the product l_a l_b stays normal.
struct LineValues {
  double h[2];  ///< h_a(v), h_b(v)
  double l[2];  ///< l_a, l_b
};

/// Tests 1 and 2 on v with |d| |v| = d_times_v and s = |d| / |v|, both ellipsoids at once (lane 0
/// for a, lane 1 for b) and without a branch: on random pairs the outcome of each test is
/// unpredictable, and a mispredicted branch costs more than the arithmetic. Returns Separated or
/// Overlapping when one of them decides, Touching when neither does; stores h and l in *values
/// if values is not null. Always inlined, so that the lanes stay in registers.
__attribute__((always_inline)) inline Separation lineTests(const Ellipsoid& a, const Ellipsoid& b,
                                                             const Eigen::Vector3d& v, double d_times_v, double s,
                                                             LineValues* values, LineLanes* lanes_out) {
  LineLanes& L = *lanes_out;
  lineLanes(a, b, v, &L);
  const Lanes2 u0 = L.u[0], u1 = L.u[1], u2 = L.u[2], r0 = L.r[0], r1 = L.r[1], r2 = L.r[2];
  const Lanes2 q0 = L.q[0], q1 = L.q[1], q2 = L.q[2];
  const Lanes2 s0 = u0 * r0, s1 = u1 * r1, s2 = u2 * r2;
  const Lanes2 i0 = u0 * q0, i1 = u1 * q1, i2 = u2 * q2;
  const Lanes2 h = detail::sqrtLanes(s0 * s0 + s1 * s1 + s2 * s2);
  const Lanes2 l = detail::sqrtLanes(i0 * i0 + i1 * i1 + i2 * i2);
  L.h = h;
  if (values != nullptr) {
    values->h[0] = h[0];
    values->h[1] = h[1];
    values->l[0] = l[0];
    values->l[1] = l[1];
  }
  // Upper bounds of the exact h and l. The rounding of u = R^T v is absolute, up to
  // gamma_3 |v|_1 per coordinate (plus the stored rotation's defect, tolerances.h), and a thin
  // ellipsoid multiplies it by its long radius: relative to h it grows with the aspect ratio
  // (1e-11 at 1:10^6). Hence the absolute terms tau |v|_1 sum(r) and tau |v|_1 sum(1/r) on top of
  // the relative margin tau of the norms, sums and comparisons.
  const double tau = tolerance::kCertificateRelativeBoundDouble;
  const double slack = tau * (std::fabs(v[0]) + std::fabs(v[1]) + std::fabs(v[2]));
  const Lanes2 h_up = h + slack * (r0 + r1 + r2);
  const Lanes2 l_up = l + slack * (q0 + q1 + q2);
  const bool separated = h_up[0] + h_up[1] < d_times_v * (1.0 - tau);
  const bool overlapping = l_up[0] + l_up[1] > s * (1.0 + tau) * (l_up[0] * l_up[1]);
  // Separated (0), Touching (1: neither test decides) or Overlapping (2), without a branch (both
  // tests are certified, so they never both hold); the caller's one branch is on "decided".
  static_assert(int(Separation::Separated) == 0 && int(Separation::Touching) == 1 &&
                int(Separation::Overlapping) == 2, "lineTests() computes the enum's values");
  return static_cast<Separation>((1 + int(overlapping)) * int(!separated));
}

/// The biased exponent e + 1023 of a positive normal double x = f 2^e, f in [1, 2).
inline uint64_t biasedExponent(double x) {
  uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  return bits >> 52;
}

/// 2^(b - 1023), exactly, for a biased exponent b in [1, 2046].
inline double powerOfTwo(uint64_t b) {
  const uint64_t bits = b << 52;
  double x;
  std::memcpy(&x, &bits, sizeof x);
  return x;
}

/// The most Newton steps of test 6 (followUpTests()), and the longest step (the trust region of
/// supportGapNewtonStep(), tangent to the unit sphere). Measured in session 25 on the pairs that
/// reach test 6, counting those left to the pencil: three steps with the cap 0.4 leave 4 of the
/// 100,000 ANCHORS pairs (three gradient steps, test 6 until then, left 425; uncapped Newton
/// steps 93); on 20,000 random pairs of aspect ratio up to 10 / 100 / 1000, 125 / 3,152 / 5,311
/// (gradient steps 1,324 / 5,588 / 8,138; uncapped 922 / 5,943 / 8,941; caps 0.3 and 0.5 were
/// each worse on one of the sets).
constexpr int kSupportGapSteps = 3;
constexpr double kNewtonMaxStep = 0.4;

/// One Newton step of test 6 on the support gap f(w) = w.d - h_a(w) - h_b(w), from the unit
/// direction w (the maximiser of f over directions is the common normal of Theorem 4.6's plane
/// when the solids are disjoint). With o_e the support points' offsets along w (`offset`, lane 0
/// for a, lane 1 for b) and h_e = |S_e R_e^T w| (`h`):
///   grad f = d - (o_a + o_b),   Hessian of h_e = (M_e - o_e o_e^T) / h_e,  M_e = R_e S_e^2 R_e^T.
/// h is homogeneous of degree 1, so w spans the Hessians' null space; the step solves
/// (H + (tr H / 2) w w^T) delta = grad f - (grad f . w) w with H the sum of the two Hessians,
/// whose solution is tangent to the sphere, and *next = w + delta. Returns false (no step) when
/// that 3x3 system is singular, out of range, or its solution not finite. The step only
/// proposes a direction: the caller certifies any decision along it. Swapping a and b swaps the two Hessians (summed
/// in either order to the same bits) and negates w, d and the offsets exactly, hence delta and
/// *next: symmetric bit for bit; a power-of-two scale of the pair scales H and grad f alike and
/// leaves delta unchanged.
bool supportGapNewtonStep(const Ellipsoid& a, const Ellipsoid& b, const Eigen::Vector3d& d, const Eigen::Vector3d& w,
                          const Lanes2 offset[3], Lanes2 h, Eigen::Vector3d* next) {
  // The six entries of the symmetric H, (0,0) (1,1) (2,2) (0,1) (0,2) (1,2), both ellipsoids at
  // once (lane 0: a, lane 1: b): M(i, j) = sum_k (R(i, k) r_k^2) R(j, k) from the pose's rows.
  const Ellipsoid::Pose& Pa = a.pose();
  const Ellipsoid::Pose& Pb = b.pose();
  Lanes2 R[3][3], T[3][3];
  for (int k = 0; k < 3; ++k) {
    const Lanes2 r = lanes(a.radii()[k], b.radii()[k]);
    const Lanes2 q = r * r;
    for (int i = 0; i < 3; ++i) {
      R[i][k] = lanes(Pa(i, k), Pb(i, k));
      T[i][k] = R[i][k] * q;
    }
  }
  const Lanes2 inv_h = 1.0 / detail::maxLanes(h, lanes(DBL_MIN, DBL_MIN));
  static constexpr int kRow[6] = {0, 1, 2, 0, 0, 1}, kCol[6] = {0, 1, 2, 1, 2, 2};
  double H[6];
  for (int n = 0; n < 6; ++n) {
    const int i = kRow[n], j = kCol[n];
    const Lanes2 M = T[i][0] * R[j][0] + T[i][1] * R[j][1] + T[i][2] * R[j][2];
    const Lanes2 He = (M - offset[i] * offset[j]) * inv_h;
    H[n] = He[0] + He[1];
  }
  const double c = 0.5 * ((H[0] + H[1]) + H[2]);  // tr H / 2
  H[0] += c * (w[0] * w[0]);
  H[1] += c * (w[1] * w[1]);
  H[2] += c * (w[2] * w[2]);
  H[3] += c * (w[0] * w[1]);
  H[4] += c * (w[0] * w[2]);
  H[5] += c * (w[1] * w[2]);
  Eigen::Vector3d g;
  for (int i = 0; i < 3; ++i) g[i] = d[i] - (offset[i][0] + offset[i][1]);
  Eigen::Vector3d gt = g - g.dot(w) * w;
  // Scale the system by the power of two sigma that brings max |H| into [1, 2): exact, so delta
  // does not change, and the cofactors and the determinant below neither overflow (an inf - inf
  // would be a NaN) nor underflow. |H| is at most ~1e300 for sizes in [kMinRadius, kMaxLength],
  // |grad f| at most ~1e100 on this path; outside [1e-150, 1e150] no step is taken.
  double h_max = 0.0;
  for (double x : H) h_max = std::max(h_max, std::fabs(x));
  if (!(h_max > 1e-150 && h_max < 1e150)) return false;
  const double sigma = powerOfTwo(2046 - biasedExponent(h_max));  // 2^-e for h_max = f 2^e
  for (double& x : H) x *= sigma;
  gt *= sigma;
  // Cramer's rule with the cofactors of the symmetric H (no pivoting: the same bits for the same H).
  const double c00 = H[1] * H[2] - H[5] * H[5], c01 = H[5] * H[4] - H[3] * H[2], c02 = H[3] * H[5] - H[1] * H[4];
  const double det = H[0] * c00 + H[3] * c01 + H[4] * c02;
  if (!(std::fabs(det) > 1e-200)) return false;  // singular to working precision (or NaN): no division
  const double c11 = H[0] * H[2] - H[4] * H[4], c12 = H[3] * H[4] - H[0] * H[5], c22 = H[0] * H[1] - H[3] * H[3];
  const double k = 1.0 / det;
  const Eigen::Vector3d delta(k * (c00 * gt[0] + c01 * gt[1] + c02 * gt[2]),
                              k * (c01 * gt[0] + c11 * gt[1] + c12 * gt[2]),
                              k * (c02 * gt[0] + c12 * gt[1] + c22 * gt[2]));
  if (!delta.allFinite()) return false;
  // Trust region: a step longer than kNewtonMaxStep (an angle of ~22 degrees) is shortened to it.
  // Far from the maximiser the quadratic model of an elongated ellipsoid's support overshoots.
  const double length = delta.norm();
  *next = w + (length > kNewtonMaxStep ? (kNewtonMaxStep / length) * delta : delta);
  return true;
}

/// Tests 3 to 6 of centreLineTest(), for the pairs tests 1 and 2 leave open (~11% of the
/// random pairs of the benchmarks), on the lanes L that lineTests() computed on v (d itself when
/// unscaled, else d / s; D2 = |d|^2).
template <class Out>
bool followUpTests(const Ellipsoid& a, const Ellipsoid& b, const Eigen::Vector3d& d, double D2, bool unscaled,
                   const LineLanes& L, Out* out) {
  const double tau = tolerance::kCertificateRelativeBoundDouble;
  // 3. Outward normal of a at p_a + rho_a n is R_a S_a^-1 (S_a^-1 R_a^T n) = R_a (u_a ./ r_a^2) / |v|;
  // the outward normal of b at p_b - rho_b n is -R_b (u_b ./ r_b^2) / |v|, so -b's is
  // +R_b (u_b ./ r_b^2) / |v|: one formula for both lanes. A factor kv close to 1 / |v| keeps
  // their squared norms in range as on the unit direction. On the unscaled path (v = d) it is
  // the power of two 2^-floor(e/2) for |d|^2 = f 2^e, f in [1, 2): |d| kv is in [1, 2 sqrt(2)).
  // A power of two scales exactly, so m below does not depend on it (up to the rounding of
  // w), and a few integer operations on the bits of D2 replace a square root and a division
  // that would stand first in the chain of test 3 (~30 cycles; D2 in [1e-100, 1e100] here).
  double kv = 1.0;
  if (unscaled) {
    // Biased exponent B = e + 1023, so floor(e / 2) = ((B + 1) >> 1) - 512 in unsigned arithmetic
    // and kv's biased exponent is 1023 - floor(e / 2) = 1535 - ((B + 1) >> 1), in [857, 1190].
    kv = powerOfTwo(1535 - ((biasedExponent(D2) + 1) >> 1));
  }
  Lanes2 w[3], normal[3];
  for (int j = 0; j < 3; ++j) w[j] = L.u[j] * L.q[j] * (L.q[j] * kv);
  detail::worldFrameLanes(a, b, w, normal);
  // m = n_a / |n_a| + n_b / |n_b|. A zero length (not expected: v != 0) gives m = 0 through the
  // floor DBL_MIN instead of a NaN, and m = 0 never separates.
  const Lanes2 len = detail::sqrtLanes(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
  const Lanes2 inv_len = 1.0 / detail::maxLanes(len, lanes(DBL_MIN, DBL_MIN));
  Eigen::Vector3d m;
  for (int i = 0; i < 3; ++i) {
    const Lanes2 unit = normal[i] * inv_len;
    m[i] = unit[0] + unit[1];
  }
  Lanes2 hm, um[3];
  bool separated = separatedAlong(m, d, a, b, L.r, tau, &hm, um);
  // 4. The midpoint of the support points of a along v and of b along -v, strictly inside both?
  // Computed whatever test 3 found: on random pairs its outcome is unpredictable, and the two
  // independent chains of square roots and divisions overlap.
  Eigen::Vector3d x;
  supportMidpoint(a, b, L.u, L.r, L.h, &x);
  bool inside = strictlyInsideBoth(a, b, L.q, x, tau);
  if (!(separated | inside)) {
    // 5. As 4, with the support points along m (test 3's direction, closer to the common normal
    // where the solids overlap off the centre line): decides about 45% of the overlapping pairs
    // that would otherwise go to the pencil (1,060 of 2,363 among the 100,000 ANCHORS pairs).
    Lanes2 offset[3];
    supportMidpoint(a, b, um, L.r, hm, &x, offset);
    inside = strictlyInsideBoth(a, b, L.q, x, tau);
    if (!inside && unscaled) {
      // 6. Newton steps on the support gap f(w) = w.d - |S_a R_a^T w| - |S_b R_b^T w| (concave
      // and homogeneous; positive exactly for the directions that separate), at most
      // kSupportGapSteps steps from m (supportGapNewtonStep(), from test 5's offsets and
      // supports for w = m). After each step, tests 3 and 5 along the new w. On the ANCHORS
      // pairs the three steps decide all but 4 of the 2,371 pairs that would go to the pencil.
      // Until session 25 these were three gradient steps, w' = w / |w| + (5/8) grad f / |d|,
      // which left 425 (kSupportGapSteps has the counts on other sets; docs/benchmarks.md,
      // session 25, the times). Each w is scaled to max |w_i| = 1,
      // which keeps every product of the tests in range whatever the sizes (the scaled path, |d|
      // outside [1e-50, 1e50], skips this test). Swapping a and b negates m, d and the sum of
      // the offsets exactly, hence every step: symmetric bit for bit like the other tests.
      Eigen::Vector3d w = m;
      for (int step = 0; step < kSupportGapSteps; ++step) {
        const double kw = 1.0 / std::sqrt(std::max(w.squaredNorm(), DBL_MIN));
        if (!supportGapNewtonStep(a, b, d, w * kw, offset, hm * kw, &w)) break;
        w *= 1.0 / std::max(w.cwiseAbs().maxCoeff(), DBL_MIN);
        separated = separatedAlong(w, d, a, b, L.r, tau, &hm, um);
        if (separated) {
          m = w;
          break;
        }
        supportMidpoint(a, b, um, L.r, hm, &x, offset);
        inside = strictlyInsideBoth(a, b, L.q, x, tau);
        if (inside) break;
      }
    }
  }
  if constexpr (kWantsWitness<Out>) {
    if (separated) {
      out->status = Separation::Separated;
      const double m2 = m.squaredNorm();
      out->normal = m * (1.0 / std::sqrt(m2));
      out->witness = 0.5 * (a.center() + b.center()) + (0.5 * (hm[0] - hm[1]) / m2) * m;  // on the mid-plane of the gap
    } else if (inside) {
      out->status = Separation::Overlapping;
      out->normal = d * (1.0 / std::sqrt(D2));
      out->witness = x;
    }
    out->precision_stage = -1;
  } else {
    // Separated (0) or Overlapping (2) without a branch (both tests are certified, so they never
    // both hold); meaningful only when a test decided.
    out->status = static_cast<Separation>(2 * int(!separated));
  }
  return separated | inside;
}

/// Writes the certificate of a decision of test 1 or 2 (status `st`): the normal n = d / |d| and
/// a witness on the centre line. Separated: on the mid-plane of the gap between the supports.
/// Overlapping: the midpoint of the common part of the two chords of the centre line, a's
/// [p_a - rho_a n, p_a + rho_a n] and b's [p_b - rho_b n, p_b + rho_b n] (b's centre when b's
/// chord lies inside a's). Written about the midpoint of the centres, where the chords are
/// [-D/2 - rho_a, -D/2 + rho_a] and [D/2 - rho_b, D/2 + rho_b] (D = |d|), so that swapping a and b
/// negates every coordinate and gives the same point bit for bit. Returns false (no certificate
/// written) when that witness is not certified strictly inside both solids: test 2's decision
/// is certified, but a nearly tangent pair's common chord can be shorter than the rounding of a
/// witness far from the origin; the caller then goes on to the other tests.
template <class Out>
bool lineDecision(Separation st, const Ellipsoid& a, const Ellipsoid& b, const Eigen::Vector3d& d, double v_norm,
                  const LineValues& w, const LineLanes& L, Out* out) {
  const double D = d.norm();
  const Eigen::Vector3d n = d * (1.0 / D);
  double shift;
  if (st == Separation::Separated) {
    shift = 0.5 * ((w.h[0] - w.h[1]) / v_norm);
  } else {
    const double rho_a = v_norm / w.l[0], rho_b = v_norm / w.l[1];
    const double lo = std::max(-0.5 * D - rho_a, 0.5 * D - rho_b), hi = std::min(-0.5 * D + rho_a, 0.5 * D + rho_b);
    shift = 0.5 * (lo + hi);
  }
  const Eigen::Vector3d x = 0.5 * (a.center() + b.center()) + shift * n;
  if (st == Separation::Overlapping &&
      !strictlyInsideBoth(a, b, L.q, x, tolerance::kCertificateRelativeBoundDouble))
    return false;
  out->status = st;
  out->normal = n;
  out->witness = x;
  out->precision_stage = -1;
  return true;
}

/// The centre-line tests outside |d| in [1e-50, 1e50] (rare): on the unit direction, or at once
/// when the centres (nearly) coincide.
template <class Out>
bool scaledCentreLineTest(const Ellipsoid& a, const Ellipsoid& b, const Eigen::Vector3d& d, double D2, Out* out) {
  // |d| < 1e-150 < 2 kMinRadius: each centre is inside the other solid (certain, no rounding:
  // D2 < 1e-300 bounds |d| < 1.1e-150 even with D2's rounding or underflow).
  static_assert(tolerance::kMinRadius >= 1e-140, "the coincident-centre shortcut needs radii >= 1e-140");
  if (D2 < 1e-300) {
    out->status = Separation::Overlapping;
    if constexpr (kWantsWitness<Out>) {
      out->witness = 0.5 * (a.center() + b.center());
      out->normal = Eigen::Vector3d::UnitX();
      out->precision_stage = -1;
    }
    return true;
  }
  const double s = std::sqrt(D2);
  const Eigen::Vector3d v = d * (1.0 / s);  // |v| = 1 to 2 ulps: covered by the 2^-40 margins
  LineValues w;
  LineLanes L;
  const Separation st = lineTests(a, b, v, s, s, kWantsWitness<Out> ? &w : nullptr, &L);
  if (st != Separation::Touching) {
    if constexpr (kWantsWitness<Out>) {
      if (lineDecision(st, a, b, d, 1.0, w, L, out)) return true;
    } else {
      out->status = st;
      return true;
    }
  }
  return followUpTests(a, b, d, D2, false, L, out);
}

/// The pre-tests along the centre line n = (p_b - p_a)/|p_b - p_a| (docs/algorithms.md §1,
/// "Pre-tests"):
///  1. Separated if the supports along n are disjoint: h_a(n) + h_b(-n) < n.(p_b - p_a), with
///     h = n.p + |S R^T n|. It implies every bounding-ball separation.
///  2. Overlapping if the segment between the centres is covered: rho_a + rho_b > |p_b - p_a|,
///     where rho = 1/|S^-1 R^T n| is the distance from the centre to the surface along n. It implies
///     every inscribed-ball overlap.
///  3. Separated along m = n_a + n_b, the sum of the unit outward normals of a and -b at the
///     points where the centre line leaves a and enters b (a Gauss-map step towards the common
///     normal of Theorem 4.6's plane): certified by separatedAlong().
///  4. Overlapping if the midpoint of the support points of a along n and of b along -n is
///     strictly inside both (strictlyInsideBoth()).
///  5. (when 3 and 4 fail) As 4, with the support points along m.
///  6. (when 3, 4 and 5 fail) Tests 3 and 5 along w, after each of up to three gradient-ascent
///     steps of the support gap from m (followUpTests()).
/// Every test is certified (a relative margin of 2^-40 over the absolute evaluation) and
/// symmetric in (a, b) bit for bit: swapping negates d, v, n and m exactly and swaps the lanes,
/// which leaves every sum and product of the two lanes, every norm, decision and witness (written
/// about the midpoint of the centres) unchanged.
template <class Out>
__attribute__((always_inline)) inline bool centreLineTest(const Ellipsoid& a, const Ellipsoid& b, Out* out) {
  const Eigen::Vector3d d = b.center() - a.center();
  const double D2 = d.squaredNorm();
  // No bounding-ball test in front (session 23): test 1 implies it, and on random pairs its branch
  // mispredicts for about a third of them, which cost more than the line tests it skips
  // (docs/algorithms.md §1, "Pre-tests").
  if (!(D2 > 1e-100 && D2 < 1e100)) return scaledCentreLineTest(a, b, d, D2, out);
  LineValues w;
  LineLanes L;
  const Separation st = lineTests(a, b, d, D2, 1.0, kWantsWitness<Out> ? &w : nullptr, &L);
  if (st != Separation::Touching) {
    if constexpr (kWantsWitness<Out>) {
      if (lineDecision(st, a, b, d, std::sqrt(D2), w, L, out)) return true;
    } else {
      out->status = st;
      return true;
    }
  }
  return followUpTests(a, b, d, D2, true, L, out);
}

/// The classification after the pre-tests left it open: the pencil in double, then in
/// double-double (docs/algorithms.md §1).
SeparationCertificate classifyByPencil(const Ellipsoid& a, const Ellipsoid& b) {
  SeparationCertificate cert;
  const bool swap = detail::swapForCanonicalOrder(a, b);
  const Ellipsoid& A = swap ? b : a;
  const Ellipsoid& B = swap ? a : b;
  const double r_max = std::max(a.maxRadius(), b.maxRadius());
  const double r_min = std::min(a.radii().minCoeff(), b.radii().minCoeff());
  if (r_max > tolerance::kPencilMaxSizeRatio * r_min) {
    // Sizes too far apart for the pencil's products (tolerances.h): conservative contact, with a
    // finite witness (B's centre or A's support point towards it) and normal.
    cert.status = Separation::Touching;
    cert.precision_stage = 2;
    cert.psi = 0.0;
    cert.mu = 0.5;
    cert.witness = A.supportPoint(B.center() - A.center());
    const Eigen::Vector3d d = b.center() - a.center();
    const double dn = d.norm();
    cert.normal = (std::isfinite(dn) && dn > 0.0) ? Eigen::Vector3d(d / dn) : Eigen::Vector3d::UnitX();
    return cert;
  }

  // Stage 0: double.
  detail::Pencil<double> p = detail::makePencil<double>(A, B);
  // Most pairs are far from tangency: try the certificates at the starting guess first and run
  // the Newton search for the maximiser only when they do not decide.
  double mu = detail::initialMu(p);
  double x[3];
  bool decided = certify<double>(p, mu, tolerance::kCertificateRelativeBoundDouble, &cert, x);
  if (!decided) {
    // Newton towards the maximiser, stopping at the first iterate where a certificate can succeed;
    // if it still does not (near tangency), converge fully and try once more.
    detail::computePencilCoefficients(p);
    int iterations = 0;
    mu = detail::maximisePsi(p, mu, &iterations, /*stop_when_promising=*/true);
    cert.iterations = iterations;
    decided = certify<double>(p, mu, tolerance::kCertificateRelativeBoundDouble, &cert, x);
    if (!decided) {
      mu = detail::maximisePsi(p, mu, &iterations);
      cert.iterations += iterations;
      decided = certify<double>(p, mu, tolerance::kCertificateRelativeBoundDouble, &cert, x);
    }
  }
  if (decided) {
    cert.precision_stage = 0;
    const Eigen::Vector3d xu(x[0], x[1], x[2]);
    cert.witness = detail::unitFrameToWorld(A, xu);
    // grad q_A at the witness, R_A S_A^-1 x in world coordinates; it points from A towards B.
    const Eigen::Vector3d n = A.rotation() * xu.cwiseQuotient(A.radii());
    cert.normal = (swap ? -n : n).normalized();
    return cert;
  }

  // Stage 1: double-double, polishing the maximiser from the double estimate.
  detail::Pencil<DoubleDouble> pd = detail::makePencil<DoubleDouble>(A, B);
  detail::computePencilCoefficients(pd);
  int it_dd = 0;
  const DoubleDouble mud = detail::maximisePsi(pd, mu, &it_dd);
  cert.iterations += it_dd;
  DoubleDouble xd[3];
  decided = certify<DoubleDouble>(pd, mud, tolerance::kCertificateRelativeBoundDoubleDouble, &cert, xd);
  cert.precision_stage = decided ? 1 : 2;
  if (!decided) {
    cert.status = Separation::Touching;  // within the band: err toward contact
    // Sizes ~1e25 apart and more overflow the pencil (docs/tolerances.md); never hand out NaN
    // (found by fuzz_static: radii 1e-100 against 1e100 gave psi = NaN).
    if (std::isnan(cert.psi)) cert.psi = 0.0;
    if (std::isnan(cert.mu)) cert.mu = 0.5;
  }
  cert.witness = detail::unitFrameToWorld(A, Eigen::Vector3d(toDouble(xd[0]), toDouble(xd[1]), toDouble(xd[2])));
  if (!cert.witness.allFinite()) cert.witness = A.supportPoint(B.center() - A.center());
  cert.normal = a.normalAt(cert.witness);
  if (!cert.normal.allFinite() || cert.normal.squaredNorm() == 0.0) {
    const Eigen::Vector3d d = b.center() - a.center();
    cert.normal = d.allFinite() && d.squaredNorm() > 0.0 ? d.normalized() : Eigen::Vector3d::UnitX();
  }
  return cert;
}

}  // namespace

SeparationCertificate classifyEllipsoids(const Ellipsoid& a, const Ellipsoid& b) {
  SeparationCertificate cert;
  // The pre-tests are symmetric in (a, b) by construction, so only the pencil needs the
  // canonical order.
  if (centreLineTest(a, b, &cert)) return cert;
  return classifyByPencil(a, b);
}

Separation separationStatus(const Ellipsoid& a, const Ellipsoid& b) {
  StatusOnly s;
  if (centreLineTest(a, b, &s)) return s.status;
  return classifyByPencil(a, b).status;
}

}  // namespace fcl_quadric
