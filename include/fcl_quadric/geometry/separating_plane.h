#pragma once
/// \file separating_plane.h
/// Separating planes of disjoint ellipsoids (Choi 2008 Theorems 4.5, 4.6; Wang et al. 2004
/// Theorem 2) and the plane/ellipsoid tests that inter-frame coherence relies on (§4.3).

#include <optional>

#include <Eigen/Core>

#include "fcl_quadric/geometry/ellipsoid.h"
#include "fcl_quadric/geometry/ellipsoid_separation.h"

namespace fcl_quadric {

/// The plane { x : normal . x = offset } with a unit normal. By convention the first ellipsoid of
/// a pair lies on the negative side (normal . x < offset) and the second on the positive side.
struct Plane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();
  double offset = 0.0;
  double signedDistance(const Eigen::Vector3d& x) const { return normal.dot(x) - offset; }
};

/// A separating plane with the two tangent points of Theorem 4.6: P_R^A on A and P_L^B on B,
/// both on the line V2 V3 through the eigenvectors of the two negative roots of f.
struct SeparatingPlane {
  Plane plane;
  Eigen::Vector3d tangent_a = Eigen::Vector3d::Zero();  ///< P_R^A (on the surface of a)
  Eigen::Vector3d tangent_b = Eigen::Vector3d::Zero();  ///< P_L^B (on the surface of b)
  /// true when planeSeparates(plane, a, b) certified the plane. False only within the touching
  /// band, where the plane is the best available (the common tangent plane at the witness).
  bool certified = false;
  /// true when the Theorem 4.6 construction was used; false when the fallback plane with the
  /// certificate's normal grad q_a(x(mu)) was used (see planeWithNormal()).
  bool from_theorem_4_6 = false;
};

/// Separating plane of disjoint ellipsoids a and b (Theorem 4.6): the eigenvectors V2, V3 of the
/// two negative roots of f span a line that meets a in P_R^A and b in P_L^B; the returned plane is
/// the bisector of the tangent plane of a at P_R^A and that of b at P_L^B (both contain the line
/// V0 V1, so every positive combination separates). If the roots are too close to isolate in
/// double (near tangency) or the plane fails certification, planeWithNormal() with the
/// classification's normal is used instead. Returns std::nullopt unless classifyEllipsoids(a, b) is
/// Separated. Never throws for valid Ellipsoid objects.
std::optional<SeparatingPlane> separatingPlane(const Ellipsoid& a, const Ellipsoid& b);

/// The plane with unit normal n (pointing from a to b) placed midway between the two solids:
/// offset = (h_a(n) - h_b(-n)) / 2. It separates iff h_a(n) < -h_b(-n). With n the normal of a
/// SeparationCertificate of a separate pair it always does: for the pencil minimiser x = x(mu),
/// grad q_b(x) = -mu/(1-mu) grad q_a(x), and convexity puts a in {n.(y-x) <= -q_a(x)/|grad q_a|}
/// and b in {n.(y-x) >= (1-mu)/mu q_b(x)/|grad q_a|}; these are disjoint iff
/// mu q_a(x) + (1-mu) q_b(x) = psi(mu) > 0, which is what the certificate proved.
/// \pre n finite and non-zero (it is normalised). A zero n gives the degenerate plane (normal 0,
/// offset 0), which planeSeparates() never certifies; no exception.
Plane planeWithNormal(const Eigen::Vector3d& n, const Ellipsoid& a, const Ellipsoid& b);

/// The plane the coherence caches keep for a Separated certificate of (a, b) (PairCoherence,
/// PairCache; the candidate plane of EECD, Wang et al. 2004 §4, Choi 2008 §4.3):
/// planeWithNormal(cert.normal, a, b), except that a pre-test's certificate
/// (precision_stage -1), whose witness already lies on that mid-plane, gives {n.x = n.witness}
/// without evaluating the supports (equal up to rounding). Not certified here: the caches certify
/// it on every use. \pre cert.status == Separation::Separated (for other certificates the result
/// is meaningless, but finite for finite inputs; no exception).
Plane certificatePlane(const SeparationCertificate& cert, const Ellipsoid& a, const Ellipsoid& b);

/// Certified test that `plane` strictly separates a (negative side) from b (positive side):
/// support(a, n) < offset < -support(b, -n), each with a relative margin covering rounding.
/// A plane that cannot be certified is reported as not separating (the caller then runs the
/// full algebraic test), so a stale plane can never hide a collision. Never throws: a zero or
/// non-finite plane simply fails the certificate (returns false); the normal need not be unit.
/// The same as CachedPlane::fromPlane(plane)->separates(a, b): callers that test one plane
/// frame after frame keep the CachedPlane.
bool planeSeparates(const Plane& plane, const Ellipsoid& a, const Ellipsoid& b);

/// A plane prepared for repeated certified tests: the record the plane caches keep
/// (PairCoherence, PairCache; EECD, Wang et al. 2004 §4, Choi 2008 §4.3). fromPlane() keeps the
/// plane (a normal with max_i |normal_i| outside [2^-64, 2^64] is first scaled into [1, 2) by a
/// power of two, exactly, so that no square of the test underflows), and stores with it
/// the plane-dependent parts of the certificate's rounding margin, tau |n|_1 and tau |offset|;
/// separates() then does only the pose-dependent work of planeSeparates(), which a cached query
/// pays every frame. A default-constructed record is empty: its normal is zero and its offset
/// -1, so separates() is false for every pair without a branch and without a NaN.
class CachedPlane {
 public:
  CachedPlane() = default;
  /// The record of `plane`, or std::nullopt when the plane can never be certified: a normal or
  /// offset that is not finite, a zero normal, or an offset that overflows when the normal is
  /// scaled up. Never throws.
  static std::optional<CachedPlane> fromPlane(const Plane& plane);
  /// True for the default-constructed record.
  bool empty() const { return normal_[0] == 0.0 && normal_[1] == 0.0 && normal_[2] == 0.0; }
  /// The stored plane: the plane given to fromPlane(), unchanged unless its normal was scaled (the
  /// same half-spaces; a unit normal comes back as it was). The empty record gives normal 0,
  /// offset -1.
  Plane plane() const;
  /// Certified: true only if the plane strictly separates a (negative side) from b (positive
  /// side), as planeSeparates(plane(), a, b) (the same margins, docs/algorithms.md section 2,
  /// "Coherence"). False for the empty record. Never throws.
  bool separates(const Ellipsoid& a, const Ellipsoid& b) const;

 private:
  friend struct CachedPlaneAccess;
  double normal_[3] = {0.0, 0.0, 0.0};
  double offset_ = -1.0;
  double tau_normal_l1_ = 0.0;   ///< kCertificateRelativeBoundDouble * |normal|_1
  double tau_abs_offset_ = 0.0;  ///< kCertificateRelativeBoundDouble * |offset|
};

namespace detail {
/// CachedPlane::separates(), the plane test of EECD (Wang et al. 2004 §4; Choi 2008 §4.3),
/// compiled for the baseline instruction set (SSE2 on x86-64). Any record, the empty one included;
/// never throws.
bool cachedPlaneSeparatesGeneric(const CachedPlane& plane, const Ellipsoid& a, const Ellipsoid& b);
/// The same test in AVX registers with fused multiply-adds, reading each ellipsoid's pose by rows
/// (Ellipsoid::pose()). \pre cpuHasFma() (on a CPU without AVX and FMA it would stop on an
/// illegal instruction; off x86-64, or without GCC or Clang, it is cachedPlaneSeparatesGeneric()).
bool cachedPlaneSeparatesFma(const CachedPlane& plane, const Ellipsoid& a, const Ellipsoid& b);
/// True when CachedPlane::separates() (and so planeSeparates()) runs cachedPlaneSeparatesFma():
/// on x86-64 with GCC or Clang, when the CPU has FMA and AVX (checked once, before main(), unless
/// the whole build targets both). The two kernels may differ only for a plane within the
/// certificate's tolerance of touching, where either may decline (neither certifies a plane that
/// does not separate).
bool cpuHasFma();
}  // namespace detail

/// Gap between the plane and the ellipsoid on its positive side: min over x in E of
/// normal.x - offset = -offset - support(-normal). > 0 when E lies strictly on the positive side
/// (the plane does not meet E); for a unit normal it is the Euclidean distance. Negate the plane to
/// measure the negative side. No failure mode; a non-finite plane gives a non-finite gap.
double planeEllipsoidGap(const Plane& plane, const Ellipsoid& e);

}  // namespace fcl_quadric
