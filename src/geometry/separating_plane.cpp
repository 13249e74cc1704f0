#include "fcl_quadric/geometry/separating_plane.h"

#include <algorithm>
#include <cmath>

#include "fcl_quadric/geometry/ellipsoid_separation.h"
#include "fcl_quadric/tolerances.h"
#include "geometry/lanes2.h"
#include "geometry/pencil.h"

// The cached-plane kernel in AVX registers with fused multiply-adds (x86-64, GCC or Clang): built
// for the whole program when it targets AVX and FMA, otherwise as a second build of the function
// chosen at run time (FCL_QUADRIC_FMA_DISPATCH) when the CPU has both.
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define FCL_QUADRIC_AVX_KERNEL 1
#include <immintrin.h>
#if defined(__AVX__) && defined(__FMA__)
#define FCL_QUADRIC_FMA_DISPATCH 0
#define FCL_QUADRIC_TARGET_FMA
#else
#define FCL_QUADRIC_FMA_DISPATCH 1
#define FCL_QUADRIC_TARGET_FMA __attribute__((target("avx,fma")))
#endif
#else
#define FCL_QUADRIC_AVX_KERNEL 0
#define FCL_QUADRIC_FMA_DISPATCH 0
#define FCL_QUADRIC_TARGET_FMA
#endif

namespace fcl_quadric {

namespace {

/// The two roots of |X0 + tau D|^2 = 1 (real by construction when X0 is inside the unit ball).
bool unitSphereChord(const Eigen::Vector3d& X0, const Eigen::Vector3d& D, double* t1, double* t2) {
  const double a = D.squaredNorm(), b = X0.dot(D), c = X0.squaredNorm() - 1.0;
  const double disc = b * b - a * c;
  if (!(a > 0.0) || !(disc >= 0.0)) return false;
  // Stable quadratic formula.
  const double q = -(b + std::copysign(std::sqrt(disc), b));
  double r1 = q / a, r2 = (q != 0.0) ? c / q : -r1;
  if (r1 > r2) std::swap(r1, r2);
  *t1 = r1;
  *t2 = r2;
  return true;
}

/// Theorem 4.6 construction in a's unit frame (the pencil of (a, b), a the unit ball).
bool theorem46Plane(const Ellipsoid& a, const Ellipsoid& b, SeparatingPlane* out) {
  detail::Pencil<double> p = detail::makePencil<double>(a, b);
  detail::computePencilCoefficients(p);
  int iterations = 0;
  const double mu_star = detail::maximisePsi(p, detail::initialMu(p), &iterations);
  if (!(detail::evaluateF(p, mu_star) > 0.0)) return false;  // roots not separable in double
  // F(0) = -det K < 0, F(1) = -1 < 0: one root on each side of mu*.
  const double mu2 = detail::rootOfF(p, 0.0, mu_star);  // eigenvector V2, inside b
  const double mu3 = detail::rootOfF(p, mu_star, 1.0);  // eigenvector V3, inside a
  double v2[3], v3[3];
  detail::witness(p, mu2, v2);
  detail::witness(p, mu3, v3);
  const Eigen::Vector3d V2(v2[0], v2[1], v2[2]), V3(v3[0], v3[1], v3[2]);
  const Eigen::Vector3d D = V2 - V3;
  // Chord of a (unit ball) on the line X(tau) = V3 + tau D: P_R^A is its end towards V2.
  double ta1, ta2;
  if (!unitSphereChord(V3, D, &ta1, &ta2)) return false;
  // Chord of b: |L X + t| = 1, i.e. the unit-sphere chord of Y0 + tau DY in b's unit frame.
  Eigen::Matrix3d L;
  Eigen::Vector3d t;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) L(i, j) = p.L[i][j];
    t[i] = p.t[i];
  }
  double tb1, tb2;
  if (!unitSphereChord(L * V3 + t, L * D, &tb1, &tb2)) return false;
  if (!(ta2 < tb1)) return false;  // the chords must be disjoint, a's before b's
  const Eigen::Vector3d P = V3 + ta2 * D;          // on a, unit frame
  const Eigen::Vector3d Q = V3 + tb1 * D;          // on b, a's unit frame
  const Eigen::Vector3d uQ = L * Q + t;            // on b, b's unit frame
  const Eigen::Vector3d PW = detail::unitFrameToWorld(a, P);
  const Eigen::Vector3d QW = detail::unitFrameToWorld(a, Q);
  // World normals: grad of |S^-1 R^T (x - p)|^2 is 2 R S^-1 u.
  const Eigen::Vector3d nA = (a.rotation() * P.cwiseQuotient(a.radii())).normalized();
  const Eigen::Vector3d nB = (b.rotation() * uQ.cwiseQuotient(b.radii())).normalized();
  const Eigen::Vector3d n = nA - nB;
  const double len = n.norm();
  if (!(len > 0.0)) return false;
  out->plane.normal = n / len;
  out->plane.offset = (nA.dot(PW) - nB.dot(QW)) / len;
  out->tangent_a = PW;
  out->tangent_b = b.center() + b.rotation() * uQ.cwiseProduct(b.radii());
  out->from_theorem_4_6 = true;
  return true;
}

}  // namespace

double planeEllipsoidGap(const Plane& plane, const Ellipsoid& e) {
  return -plane.offset - e.support(-plane.normal);
}

Plane planeWithNormal(const Eigen::Vector3d& n, const Ellipsoid& a, const Ellipsoid& b) {
  Plane p;
  p.normal = n.normalized();
  p.offset = 0.5 * (a.support(p.normal) - b.support(-p.normal));
  return p;
}

Plane certificatePlane(const SeparationCertificate& cert, const Ellipsoid& a, const Ellipsoid& b) {
  // A pre-test's witness is on the mid-plane of the gap along its normal (lineDecision() and
  // followUpTests() in ellipsoid_separation.cpp); the pencil's is its minimax point.
  if (cert.precision_stage != -1) return planeWithNormal(cert.normal, a, b);
  Plane p;
  p.normal = cert.normal;
  p.offset = cert.normal.dot(cert.witness);
  return p;
}

using detail::Lanes2;
using detail::lanes;

/// The code that reads and writes a CachedPlane's fields: its preparation and the kernel.
struct CachedPlaneAccess {
  static bool prepare(const Plane& plane, CachedPlane* out);
  static inline __attribute__((always_inline)) bool kernel(const CachedPlane& plane, const Ellipsoid& a,
                                                           const Ellipsoid& b);
#if FCL_QUADRIC_AVX_KERNEL
  FCL_QUADRIC_TARGET_FMA static bool kernelFma(const CachedPlane& plane, const Ellipsoid& a, const Ellipsoid& b);
#endif
};

// The record of `plane` in *out, or false when the plane can never be certified (fromPlane()).
bool CachedPlaneAccess::prepare(const Plane& plane, CachedPlane* out) {
  const Eigen::Vector3d& n = plane.normal;
  if (!(std::isfinite(n[0]) && std::isfinite(n[1]) && std::isfinite(n[2]) && std::isfinite(plane.offset))) {
    return false;
  }
  const double big = std::max(std::fabs(n[0]), std::max(std::fabs(n[1]), std::fabs(n[2])));
  if (!(big > 0.0)) return false;  // a zero normal never separates
  // A normal far from unit length is scaled by a power of two (exact) into [1, 2): with the radii
  // in [kMinRadius, kMaxLength], max |n_i| in [2^-64, 2^64] keeps every square of the test (the
  // support's m_j^2 >= (kMinRadius 2^-64)^2 / 3) far above the subnormal range, where rounding
  // would stop being relative. Normals in that range, unit ones included, are stored unchanged.
  double scaled[3] = {n[0], n[1], n[2]};
  double offset = plane.offset;
  if (big < 0x1p-64 || big > 0x1p64) {
    int e = 0;
    std::frexp(big, &e);  // big = f 2^e, f in [0.5, 1)
    const int k = 1 - e;
    for (double& x : scaled) x = std::ldexp(x, k);
    offset = std::ldexp(offset, k);
    if (!std::isfinite(offset)) return false;  // beyond every centre: cannot separate a from b
  }
  const double tau = tolerance::kCertificateRelativeBoundDouble;
  for (int i = 0; i < 3; ++i) out->normal_[i] = scaled[i];
  out->offset_ = offset;
  out->tau_normal_l1_ = tau * (std::fabs(scaled[0]) + std::fabs(scaled[1]) + std::fabs(scaled[2]));
  out->tau_abs_offset_ = tau * std::fabs(offset);
  return true;
}

std::optional<CachedPlane> CachedPlane::fromPlane(const Plane& plane) {
  CachedPlane c;
  if (!CachedPlaneAccess::prepare(plane, &c)) return std::nullopt;
  return c;
}

Plane CachedPlane::plane() const {
  Plane p;
  p.normal = Eigen::Vector3d(normal_[0], normal_[1], normal_[2]);
  p.offset = offset_;
  return p;
}

// The certified gap of an ellipsoid e on its side of the plane { n.x = off } (a below: sgn = +1;
// b above: sgn = -1) is g = sgn (off - n.p) - tau (|n|_1 extent + |off|), extent = |p|_1 + sum(r)
// (Ellipsoid::extent()), and e lies strictly on that side iff g > 0 and g^2 > msq (1 + 4 tau) with
// msq = |S R^T n|^2, the squared support half-width (compared in squares: no square root).
// The margin covers two roundings with a wide margin (tau = 2^-40, against errors of a few eps =
// 2^-52):
//   - of off - n.p: at most ~3 eps (|off| + sum_i |n_i p_i|), and sum_i |n_i p_i| <= |n|_1 |p|_1;
//   - of R^T n, absolute (~eps |n|_1 per coordinate, tolerances.h kStoredRotationDefect), which a
//     long radius multiplies: its effect on the half-width is below ~eps |n|_1 sum(r).
// extent's own rounding (relative, below 6 eps) changes the margin by a negligible fraction.
// tau |n|_1 and tau |off| come precomputed with the plane (CachedPlane): tau is a power of two,
// so they are the exact products unless they underflow, which fromPlane()'s scaling
// (max |n_i| >= 2^-64) rules out for tau |n|_1; an underflowing tau |off| (|off| < 2^-982) is
// covered by the tau |n|_1 sum(r) part, at least 2^-104 kMinRadius. Both sides at once, without a
// branch, ending in one movmskpd: this is the whole cost of a cached-plane query
// (docs/benchmarks.md, target (c)).
//
// The bounds hold for any evaluation order and for fused multiply-adds (each sum of products is
// then rounded fewer times, Higham, Accuracy and Stability, §3.1), so there are two builds of the
// test: the generic one below in two SSE2 lanes (a, b), and an AVX/FMA one
// (cachedPlaneSeparatesFma) that reads each pose by rows: which of the two runs may change
// whether a plane within ~tau of tangency is certified, never a certified answer.
bool CachedPlaneAccess::kernel(const CachedPlane& plane, const Ellipsoid& a, const Ellipsoid& b) {
  const double tau = tolerance::kCertificateRelativeBoundDouble;
  const double* n = plane.normal_;
  const Lanes2 n0 = lanes(n[0], n[0]), n1 = lanes(n[1], n[1]), n2 = lanes(n[2], n[2]);
  const Lanes2 y[3] = {n0, n1, n2};
  Lanes2 u[3], r[3];
  detail::bodyFrameLanes(a, b, y, u);  // R^T n
  detail::radiusLanes(a, b, r);
  const Lanes2 m0 = u[0] * r[0], m1 = u[1] * r[1], m2 = u[2] * r[2];  // S R^T n
  const Lanes2 msq = m0 * m0 + m1 * m1 + m2 * m2;
  const Ellipsoid::Pose& pa = a.pose();
  const Ellipsoid::Pose& pb = b.pose();
  const Lanes2 nc = n0 * lanes(pa(0, 3), pb(0, 3)) + n1 * lanes(pa(1, 3), pb(1, 3)) + n2 * lanes(pa(2, 3), pb(2, 3));
  const Lanes2 margin = plane.tau_normal_l1_ * lanes(a.extent(), b.extent()) + plane.tau_abs_offset_;
  const Lanes2 g = detail::negateLane1(plane.offset_ - nc) - margin;
  return detail::bothLanes((g > 0.0) & (g * g > msq * (1.0 + 4.0 * tau)));
}

#if FCL_QUADRIC_AVX_KERNEL
/// The same test in AVX registers, one ellipsoid per register: the pose rows
/// (R(i,0), R(i,1), R(i,2), p_i) make n_0 row_0 + n_1 row_1 + n_2 row_2 = (R^T n, n.p) three fused
/// multiply-adds with no shuffle, and four unpacks and three extracts pair a's and b's results
/// into the lanes of the generic kernel's tail (the generic kernel needs 16 inserts for that).
FCL_QUADRIC_TARGET_FMA bool CachedPlaneAccess::kernelFma(const CachedPlane& plane, const Ellipsoid& a,
                                                         const Ellipsoid& b) {
  const double tau = tolerance::kCertificateRelativeBoundDouble;
  const __m256d n0 = _mm256_broadcast_sd(&plane.normal_[0]);
  const __m256d n1 = _mm256_broadcast_sd(&plane.normal_[1]);
  const __m256d n2 = _mm256_broadcast_sd(&plane.normal_[2]);
  const double* ra = a.pose().data();
  const double* rb = b.pose().data();
  // (u_0, u_1, u_2, n.p) = n_0 row_0 + n_1 row_1 + n_2 row_2, u = R^T n.
  const __m256d ua = _mm256_fmadd_pd(
      n2, _mm256_loadu_pd(ra + 8), _mm256_fmadd_pd(n1, _mm256_loadu_pd(ra + 4), _mm256_mul_pd(n0, _mm256_loadu_pd(ra))));
  const __m256d ub = _mm256_fmadd_pd(
      n2, _mm256_loadu_pd(rb + 8), _mm256_fmadd_pd(n1, _mm256_loadu_pd(rb + 4), _mm256_mul_pd(n0, _mm256_loadu_pd(rb))));
  const __m256d sa = _mm256_loadu_pd(a.shapeData());  // (r_0, r_1, r_2, extent)
  const __m256d sb = _mm256_loadu_pd(b.shapeData());
  const __m256d ul = _mm256_unpacklo_pd(ua, ub);  // (ua_0, ub_0, ua_2, ub_2)
  const __m256d uh = _mm256_unpackhi_pd(ua, ub);  // (ua_1, ub_1, nc_a, nc_b)
  const __m256d sl = _mm256_unpacklo_pd(sa, sb);  // (ra_0, rb_0, ra_2, rb_2)
  const __m256d sh = _mm256_unpackhi_pd(sa, sb);  // (ra_1, rb_1, extent_a, extent_b)
  const __m256d ml = _mm256_mul_pd(ul, sl);       // (ma_0, mb_0, ma_2, mb_2), m = S R^T n
  const __m128d m0 = _mm256_castpd256_pd128(ml);
  const __m128d m2 = _mm256_extractf128_pd(ml, 1);
  const __m128d m1 = _mm_mul_pd(_mm256_castpd256_pd128(uh), _mm256_castpd256_pd128(sh));
  const __m128d msq = _mm_fmadd_pd(m2, m2, _mm_fmadd_pd(m1, m1, _mm_mul_pd(m0, m0)));
  const __m128d nc = _mm256_extractf128_pd(uh, 1);
  const __m128d extent = _mm256_extractf128_pd(sh, 1);
  const __m128d margin =
      _mm_fmadd_pd(_mm_set1_pd(plane.tau_normal_l1_), extent, _mm_set1_pd(plane.tau_abs_offset_));
  // g = (off - nc_a, nc_b - off) - margin: lane 1's sign flipped (exact).
  const __m128d side = _mm_xor_pd(_mm_sub_pd(_mm_set1_pd(plane.offset_), nc), _mm_set_pd(-0.0, 0.0));
  const __m128d g = _mm_sub_pd(side, margin);
  const __m128d ok = _mm_and_pd(_mm_cmpgt_pd(g, _mm_setzero_pd()),
                                _mm_cmpgt_pd(_mm_mul_pd(g, g), _mm_mul_pd(msq, _mm_set1_pd(1.0 + 4.0 * tau))));
  return _mm_movemask_pd(ok) == 3;
}
#endif

namespace {

#if FCL_QUADRIC_FMA_DISPATCH
/// The CPU runs FMA and AVX and the OS saves their registers (libgcc's feature check includes
/// XGETBV). Initialised before main(); read as false before then, which selects the generic
/// kernel: a call from another static initialiser is still answered correctly.
const bool kCpuHasFma = [] {
  __builtin_cpu_init();  // required when this initialiser runs before libgcc's own
  return __builtin_cpu_supports("fma") && __builtin_cpu_supports("avx");
}();
#else
constexpr bool kCpuHasFma = FCL_QUADRIC_AVX_KERNEL;  // no dispatch: the build has AVX and FMA, or no x86-64
#endif

}  // namespace

bool detail::cachedPlaneSeparatesGeneric(const CachedPlane& plane, const Ellipsoid& a, const Ellipsoid& b) {
  return CachedPlaneAccess::kernel(plane, a, b);
}

bool detail::cachedPlaneSeparatesFma(const CachedPlane& plane, const Ellipsoid& a, const Ellipsoid& b) {
#if FCL_QUADRIC_AVX_KERNEL
  return CachedPlaneAccess::kernelFma(plane, a, b);
#else
  return CachedPlaneAccess::kernel(plane, a, b);
#endif
}

bool detail::cpuHasFma() { return kCpuHasFma; }

bool CachedPlane::separates(const Ellipsoid& a, const Ellipsoid& b) const {
#if FCL_QUADRIC_AVX_KERNEL
  if (kCpuHasFma) return CachedPlaneAccess::kernelFma(*this, a, b);
#endif
  return CachedPlaneAccess::kernel(*this, a, b);
}

bool planeSeparates(const Plane& plane, const Ellipsoid& a, const Ellipsoid& b) {
  CachedPlane c;
  return CachedPlaneAccess::prepare(plane, &c) && c.separates(a, b);
}

std::optional<SeparatingPlane> separatingPlane(const Ellipsoid& a, const Ellipsoid& b) {
  const SeparationCertificate cert = classifyEllipsoids(a, b);
  if (cert.status != Separation::Separated) return std::nullopt;
  SeparatingPlane sp;
  if (theorem46Plane(a, b, &sp) && planeSeparates(sp.plane, a, b)) {
    sp.certified = true;
    return sp;
  }
  // Fallback (near tangency): the certificate's normal, placed midway (planeWithNormal()).
  sp = SeparatingPlane{};
  sp.plane = planeWithNormal(cert.normal, a, b);
  sp.tangent_a = a.supportPoint(sp.plane.normal);
  sp.tangent_b = b.supportPoint(-sp.plane.normal);
  sp.certified = planeSeparates(sp.plane, a, b);
  return sp;
}

}  // namespace fcl_quadric
