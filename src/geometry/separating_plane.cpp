#include "fcl_quadric/geometry/separating_plane.h"

#include <algorithm>
#include <cmath>

#include "fcl_quadric/geometry/ellipsoid_separation.h"
#include "fcl_quadric/tolerances.h"
#include "geometry/lanes2.h"
#include "geometry/pencil.h"

// Runtime dispatch of the cached-plane kernel to an FMA build of it (x86-64, GCC or Clang, when
// the whole build does not already target FMA).
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(__FMA__)
#define FCL_QUADRIC_FMA_DISPATCH 1
#define FCL_QUADRIC_TARGET_FMA __attribute__((target("fma")))
#else
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

using detail::Lanes2;
using detail::lanes;

/// The code that reads and writes a CachedPlane's fields: its preparation and the kernel.
struct CachedPlaneAccess {
  static bool prepare(const Plane& plane, CachedPlane* out);
  static inline __attribute__((always_inline)) bool kernel(const CachedPlane& plane, const Ellipsoid& a,
                                                           const Ellipsoid& b);
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
// b above: sgn = -1) is g = sgn (off - n.p) - tau (|off| + sum_i |n_i p_i|), and e lies strictly
// on that side iff g > 0 and g^2 > msq (1 + 4 tau) with msq = |S R^T n|^2, the squared support
// half-width (compared in squares: no square root). |off| + sum_i |n_i p_i| is the absolute
// evaluation of off - n.p, and tau = 2^-40 covers its rounding with a wide margin. The rounding
// of R^T n is absolute (~eps |n|_1 per coordinate, tolerances.h kStoredRotationDefect), and a
// long radius multiplies it, so g also subtracts tau |n|_1 sum(r), which bounds its effect on
// the half-width. tau |n|_1 and tau |off| come precomputed with the plane (CachedPlane): tau is a
// power of two, so they are the exact products unless they underflow, which fromPlane()'s scaling
// (max |n_i| >= 2^-64) rules out for tau |n|_1; an underflowing tau |off| (|off| < 2^-982) is
// covered by the tau |n|_1 sum(r) term, at least 2^-104 kMinRadius. Both sides at once in two
// lanes, without a branch, ending in one movmskpd: this is the whole cost of a cached-plane query
// (docs/benchmarks.md, target (c)).
//
// The bounds hold for any evaluation order and for fused multiply-adds (each sum of products is
// then rounded fewer times, Higham, Accuracy and Stability, §3.1), so the same source is also
// compiled with FMA enabled (cachedPlaneSeparatesFma below): which of the two runs may change
// whether a plane within ~tau of tangency is certified, never a certified answer.
bool CachedPlaneAccess::kernel(const CachedPlane& plane, const Ellipsoid& a, const Ellipsoid& b) {
  const double tau = tolerance::kCertificateRelativeBoundDouble;
  const double* n = plane.normal_;
  const Eigen::Vector3d& ca = a.center();
  const Eigen::Vector3d& cb = b.center();
  const Lanes2 n0 = lanes(n[0], n[0]), n1 = lanes(n[1], n[1]), n2 = lanes(n[2], n[2]);
  const Lanes2 y[3] = {n0, n1, n2};
  Lanes2 u[3], r[3];
  detail::bodyFrameLanes(a, b, y, u);  // R^T n
  detail::radiusLanes(a, b, r);
  const Lanes2 m0 = u[0] * r[0], m1 = u[1] * r[1], m2 = u[2] * r[2];  // S R^T n
  const Lanes2 msq = m0 * m0 + m1 * m1 + m2 * m2;
  const Lanes2 p0 = n0 * lanes(ca[0], cb[0]), p1 = n1 * lanes(ca[1], cb[1]), p2 = n2 * lanes(ca[2], cb[2]);
  const Lanes2 nc = p0 + p1 + p2;
  const Lanes2 abs_sum = detail::absLanes(p0) + detail::absLanes(p1) + detail::absLanes(p2);
  const Lanes2 margin = tau * abs_sum + (plane.tau_normal_l1_ * (r[0] + r[1] + r[2]) + plane.tau_abs_offset_);
  const Lanes2 g = detail::negateLane1(plane.offset_ - nc) - margin;
  return detail::bothLanes((g > 0.0) & (g * g > msq * (1.0 + 4.0 * tau)));
}

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
constexpr bool kCpuHasFma = false;  // no dispatch: one kernel, the build's own
#endif

}  // namespace

bool detail::cachedPlaneSeparatesGeneric(const CachedPlane& plane, const Ellipsoid& a, const Ellipsoid& b) {
  return CachedPlaneAccess::kernel(plane, a, b);
}

FCL_QUADRIC_TARGET_FMA bool detail::cachedPlaneSeparatesFma(const CachedPlane& plane, const Ellipsoid& a,
                                                            const Ellipsoid& b) {
  return CachedPlaneAccess::kernel(plane, a, b);
}

bool detail::cpuHasFma() { return kCpuHasFma; }

bool CachedPlane::separates(const Ellipsoid& a, const Ellipsoid& b) const {
  return kCpuHasFma ? detail::cachedPlaneSeparatesFma(*this, a, b) : CachedPlaneAccess::kernel(*this, a, b);
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
