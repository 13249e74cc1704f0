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

bool detail::isFinitePlane(const Plane& plane) {
  const Eigen::Vector3d& n = plane.normal;
  return std::isfinite(n[0]) && std::isfinite(n[1]) && std::isfinite(n[2]) && std::isfinite(plane.offset);
}

// A non-finite plane is never certified (the comparisons of the test would raise FE_INVALID on
// NaN).
bool planeSeparates(const Plane& plane, const Ellipsoid& a, const Ellipsoid& b) {
  return detail::isFinitePlane(plane) && detail::planeSeparatesFinite(plane, a, b);
}

// The certified gap of an ellipsoid e on its side of the plane { n.x = off } (a below: sgn = +1;
// b above: sgn = -1) is g = sgn (off - n.p) - tau (|off| + sum_i |n_i p_i|), and e lies strictly
// on that side iff g > 0 and g^2 > msq (1 + 4 tau) with msq = |S R^T n|^2, the squared support
// half-width (compared in squares: no square root). |off| + sum_i |n_i p_i| is the absolute
// evaluation of off - n.p, and tau = 2^-40 covers its rounding with a wide margin. The rounding
// of R^T n is absolute (~eps |n|_1 per coordinate, tolerances.h kStoredRotationDefect), and a
// long radius multiplies it, so g also subtracts tau |n|_1 sum(r), which bounds its effect on
// the half-width. Written out by hand, both sides at once and without a branch: this is the
// whole cost of a cached-plane query.
//
// The bounds hold for any evaluation order and for fused multiply-adds (each sum of products is
// then rounded fewer times, Higham, Accuracy and Stability, §3.1), so the same source is also
// compiled with FMA enabled (planeSeparatesFma below): which of the two runs may change whether
// a plane within ~tau of tangency is certified, never a certified answer.
namespace {

inline __attribute__((always_inline)) bool planeSeparatesKernel(const Plane& plane, const Ellipsoid& a,
                                                                const Ellipsoid& b) {
  const double tau = tolerance::kCertificateRelativeBoundDouble;
  const Eigen::Vector3d& n = plane.normal;
  const double off = plane.offset;
  const Eigen::Vector3d& ca = a.center();
  const Eigen::Vector3d& cb = b.center();
  Lanes2 u[3], r[3];
  detail::bodyFrameLanes(a, b, n, u);  // R^T n
  detail::radiusLanes(a, b, r);
  const Lanes2 m0 = u[0] * r[0], m1 = u[1] * r[1], m2 = u[2] * r[2];  // S R^T n
  const Lanes2 n0 = lanes(n[0], n[0]), n1 = lanes(n[1], n[1]), n2 = lanes(n[2], n[2]);
  const Lanes2 msq = m0 * m0 + m1 * m1 + m2 * m2;
  const Lanes2 c0 = lanes(ca[0], cb[0]), c1 = lanes(ca[1], cb[1]), c2 = lanes(ca[2], cb[2]);
  const Lanes2 p0 = n0 * c0, p1 = n1 * c1, p2 = n2 * c2;
  const Lanes2 nc = p0 + p1 + p2;
  const Lanes2 abs_sum = detail::absLanes(p0) + detail::absLanes(p1) + detail::absLanes(p2);
  const double n1norm = std::fabs(n[0]) + std::fabs(n[1]) + std::fabs(n[2]);
  const Lanes2 g = lanes(1.0, -1.0) * (off - nc) - tau * (abs_sum + std::fabs(off) + n1norm * (r[0] + r[1] + r[2]));
  const auto ok = (g > 0.0) & (g * g > msq * (1.0 + 4.0 * tau));  // per lane: all ones or zero
  return (ok[0] & ok[1]) != 0;
}

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

bool detail::planeSeparatesGeneric(const Plane& plane, const Ellipsoid& a, const Ellipsoid& b) {
  return planeSeparatesKernel(plane, a, b);
}

FCL_QUADRIC_TARGET_FMA bool detail::planeSeparatesFma(const Plane& plane, const Ellipsoid& a, const Ellipsoid& b) {
  return planeSeparatesKernel(plane, a, b);
}

bool detail::cpuHasFma() { return kCpuHasFma; }

bool detail::planeSeparatesFinite(const Plane& plane, const Ellipsoid& a, const Ellipsoid& b) {
  return kCpuHasFma ? planeSeparatesFma(plane, a, b) : planeSeparatesKernel(plane, a, b);
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
