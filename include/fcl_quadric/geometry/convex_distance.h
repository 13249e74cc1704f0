#pragma once
/// \file convex_distance.h
/// Signed distance between two posed convex solids given by support mappings (convex_support.h):
/// GJK (Gilbert, Johnson and Keerthi 1988, with van den Bergen's stopping rule) for the distance of
/// separated solids and EPA (expanding polytope, van den Bergen 2001) for the penetration depth of
/// overlapping ones, on the Minkowski difference D = A - B. docs/algorithms.md section 12.
///
/// Certificates, not iterates, decide the status:
///  - Separated only if GJK's lower bound v.w / |v| (w the support of D towards -v: no point of D
///    is closer than this along v) exceeds kConvexSeparationRelative * scale;
///  - Overlapping only if the origin lies inside a tetrahedron of support points of D with
///    margin (its distance to every face exceeds the same bound), or, for a sphere or a capsule
///    (ConvexSupport::radius(): GJK and EPA run on the cores and add the radii, docs/algorithms.md
///    section 12), if GJK finds the cores closer than the sum of the radii less that bound;
///  - otherwise Touching, distance 0: near tangency the answer errs toward contact.
/// The support points lie in the solids up to ConvexSupport's feasibility tolerance, so both
/// certificates hold up to that (1e-12 of the size) for Region solids and to rounding otherwise.
/// Distance: on return |distance - true| <= kConvexDistanceRelative * |distance| + 1e-14 scale
/// when converged (GJK's upper bound |v| minus its lower bound; EPA's face distance against the
/// smallest support value seen). Iterations are capped; at the cap the best bounds are returned
/// with converged = false: the distance is then the upper bound |v| (separated) or the
/// smallest support value seen (penetration depth, an overestimate): both err toward contact.
/// Pure geometry (std + Eigen).

#include <cstddef>

#include <Eigen/Core>

#include "fcl_quadric/geometry/convex_support.h"
#include "fcl_quadric/geometry/signed_distance.h"

namespace fcl_quadric {

namespace tolerance_convex {
/// Relative accuracy GJK and EPA stop at (upper minus lower bound over the value).
constexpr double kConvexDistanceRelative = 1e-10;
/// Certificates of separation / overlap: margin relative to the pair's scale (sizes plus the
/// distance between centres).
constexpr double kConvexSeparationRelative = 1e-11;
/// Iteration caps (fallback in the file comment).
constexpr int kMaxGjkIterations = 256;
constexpr int kMaxEpaIterations = 512;
/// Faces of EPA's polytope (removed ones included) before it stops as at the iteration cap.
constexpr std::size_t kMaxEpaFaces = 8192;
}  // namespace tolerance_convex

/// Signed distance of a (local support `a`, posed x -> R_a x + p_a) and b (likewise). Same
/// conventions as signedDistance(Ellipsoid, Ellipsoid): distance > 0 separated, < 0 minus the
/// penetration depth, 0 touching; point_a on a, point_b on b (world frame); normal from a to b
/// (translating b by -distance * normal makes them touch). `iterations` counts GJK plus EPA steps.
/// With want_depth = false an overlap is certified without its depth: by GJK's tetrahedron when
/// the origin lies inside it with margin, otherwise by EPA's polytope as soon as every face of it
/// clears that margin (one or two expansions when GJK left the origin on a face, as it often does
/// for a sphere). Then distance = 0 is returned with status Overlapping, and point_a, point_b are
/// one common point of a and b (equal up to rounding; the caller only needs the sign and a
/// witness). If EPA reaches neither, it runs on as with want_depth = true.
/// If `lower_bound` is non-null it receives, for a Separated result, GJK's lower bound v.w / |v|
/// (converged or not: a stall or the iteration cap leaves |v| an upper and this a lower bound of
/// the distance, exact up to the support points' rounding and tolerance), else 0.
/// \throws std::invalid_argument if a pose is not finite.
SignedDistanceResult convexSignedDistance(const ConvexSupport& a, const Eigen::Matrix3d& R_a, const Eigen::Vector3d& p_a,
                                          const ConvexSupport& b, const Eigen::Matrix3d& R_b, const Eigen::Vector3d& p_b,
                                          bool want_depth = true, double* lower_bound = nullptr);

/// What screenConvexPair() certifies about a pair.
struct ConvexScreening {
  enum class Verdict {
    Far,          ///< the distance exceeds the gap (GJK's lower bound v.w / |v| does)
    Overlapping,  ///< the solids overlap (GJK's tetrahedron holds the origin with margin)
    Undecided,    ///< neither: within the gap or near tangency, a stall, or the iteration cap
  };
  Verdict verdict = Verdict::Undecided;
  /// Overlapping: a common point of a and b (world frame), as convexSignedDistance() gives with
  /// want_depth = false. Otherwise unset (zero).
  Eigen::Vector3d common_point = Eigen::Vector3d::Zero();
  /// GJK's lower bound v.w / |v| when it certified the pair separate (Far, or Undecided within the
  /// gap), else 0. Short of Far, GJK did not stop early, so this is exactly the lower_bound of
  /// convexSignedDistance(..., want_depth = false, &lower_bound).
  double lower_bound = 0.0;
  int iterations = 0;  ///< GJK (and EPA) steps taken
};

/// The screening query of the mesh and OcTree traversals and of the collide of two convex solids
/// (docs/algorithms.md section 12): is the pair certainly farther apart than `gap`, certainly
/// overlapping, or neither? GJK as in convexSignedDistance(), stopped as soon as its lower bound
/// exceeds `gap` (a certificate at any step: it need not converge) or its simplex certifies the
/// overlap; EPA never runs when the tetrahedron has a margin (otherwise it runs as in
/// convexSignedDistance with want_depth = false, and its status counts).
/// Far is as certain as convexSignedDistance's Separated (exact up to the support points'
/// tolerance; pass a gap well above 1e-11 of the pair's scale to cover it).
/// \throws std::invalid_argument if a pose is not finite or gap is not >= 0 (NaN included).
ConvexScreening screenConvexPair(const ConvexSupport& a, const Eigen::Matrix3d& R_a, const Eigen::Vector3d& p_a,
                                 const ConvexSupport& b, const Eigen::Matrix3d& R_b, const Eigen::Vector3d& p_b,
                                 double gap);

}  // namespace fcl_quadric
