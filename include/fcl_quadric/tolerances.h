#pragma once
/// \file tolerances.h
/// The one place where fcl_quadric's numerical tolerances live (docs/tolerances.md explains the
/// policy). Every constant says what it is measured against. Sign decisions are *certified*:
/// a value is trusted only when it exceeds an a-priori error bound; otherwise the computation is
/// repeated in double-double arithmetic, and if it is still within that (much smaller) bound the
/// configuration is reported as touching, i.e. as contact: near tangency we err toward contact.

#include <cstddef>

namespace fcl_quadric {
namespace tolerance {

/// Unit roundoff of IEEE double (2^-53).
constexpr double kUnitRoundoff = 1.1102230246251565e-16;

/// Relative rounding bound used by the certificates of the static classification
/// (ellipsoid_separation.cpp): a computed value v is trusted to have the sign of the exact one
/// when |v| > kCertificate... * scale(v), scale(v) being the same expression evaluated on absolute
/// values (plus the magnitude of the rounding of the transform into A's unit frame). The a-priori
/// bound for the <= 30 rounded operations on the longest path is gamma_30 ~ 3.3e-15; 2^-40 ~ 9.1e-13
/// leaves a safety factor > 250. Dimensionless.
constexpr double kCertificateRelativeBoundDouble = 9.094947017729282e-13;  // 2^-40

/// The same for the double-double stage (unit roundoff <= 2^-104): 2^-92 ~ 2.0e-28. A pair whose
/// certificates fail at this level is within ~1e-27 (relative) of tangency and is reported as
/// Touching: contact.
constexpr double kCertificateRelativeBoundDoubleDouble = 2.0194839173657902e-28;  // 2^-92

/// A rotation matrix R is accepted as rigid when ||R^T R - I||_max <= this and det R > 0.
/// Quaternion-derived rotations are orthogonal to ~1e-16; composed transforms drift slowly.
/// The library interprets body coordinates as S^-1 R^T (x - p): an accepted R with defect e
/// describes the intended ellipsoid to relative accuracy ~e.
constexpr double kRotationOrthogonality = 1e-9;

/// An Ellipsoid stores a rotation with max|R^T R - I| <= this (2^-48 ~ 3.6e-15): an accepted
/// rotation that is less orthogonal is replaced by its nearest rotation (Ellipsoid's constructor),
/// so that every test of the static classification decides on one and the same solid. The
/// support function |S R^-1 n| of the stored solid then differs from the computed |S R^T n| by at
/// most (gamma_3 + 3.2 * 2^-48) (r_0 + r_1 + r_2) |n|_1 < 1.3e-14 (r_0 + r_1 + r_2) |n|_1, rounding
/// included, far inside the margin kCertificateRelativeBoundDouble * (r_0 + r_1 + r_2) |n|_1 that
/// the certificates use (docs/tolerances.md, "Supports"). Dimensionless.
constexpr double kStoredRotationDefect = 3.552713678800501e-15;  // 2^-48

/// Absolute rounding of a world point x mapped into an ellipsoid's unit frame S^-1 R^T (x - c):
/// at most this times |x - c|_1 (1/r_0 + 1/r_1 + 1/r_2) per coordinate (the subtraction is
/// rounded relative to x - c itself; the rotation's dot products by gamma_3 |x - c|_1, the
/// division by 1/r_j by 2 more units: <= 6u, and 2^-47 = 64u leaves a factor > 10). Unlike the
/// relative bound above this is absolute: a thin ellipsoid's unit frame magnifies |x - c|_1 by
/// its largest 1/r_j, so a point far along the long axis carries an error of ~eps L / r_min,
/// which the result's own magnitude does not bound. Used through detail::unitFrameRounding() by
/// the ellipsoid-box, -triangle, -capsule and -cylinder / -cone certificates. Dimensionless.
constexpr double kUnitFrameRoundingBound = 7.105427357601002e-15;  // 2^-47

/// Accepted range of radii and of centre coordinates (absolute, in the user's length unit): keeps
/// squares and the products formed by the pencil finite. Outside it the constructor throws.
/// Pairs whose sizes differ by more than ~1e25 can overflow the pencil's determinants: pairs the
/// pre-tests leave undecided whose radii (both ellipsoids together) span more than
/// kPencilMaxSizeRatio are not given to the pencil and are reported Touching (conservative).
constexpr double kMinRadius = 1e-100;
constexpr double kMaxLength = 1e100;
/// 2^64 ~ 1.8e19: below the ~1e25 where the pencil's products overflow, with margin; no
/// floating-point exception is raised on the way (the tests run with FE_INVALID trapped).
constexpr double kPencilMaxSizeRatio = 18446744073709551616.0;  // 2^64

/// Padding of the pruning tests of fcl_quadric::collide's own OcTree and mesh traversals
/// (src/fcl/octree_collision.cpp, mesh_collision.cpp), relative to the pose's scale (|p_env|_inf
/// + |p_shape|_inf + |c|_inf + r_max, c the shape's centre in the environment's frame; the mesh
/// test adds the node's |centre|_inf and largest half width). A rotation defect up to
/// kRotationOrthogonality moves a point by at most ~4e-9 of that scale, 25 times less; the exact
/// leaf tests' touching band (kCertificateRelativeBoundDouble of their scale) is ~10^5 times less.
/// So a cell or node pruned with it holds only leaves the exact test finds separate. Dimensionless.
constexpr double kTraversalPruningPadding = 1e-7;

/// Scene input: |q| of a pose quaternion must be within this of 1 (relative). Dimensionless.
constexpr double kQuaternionNorm = 1e-6;

/// Iteration caps (every loop in the library is bounded; the fallback on reaching a cap is
/// documented at the loop).
constexpr int kMaxPencilNewtonIterations = 60;   ///< safeguarded Newton for max of psi(mu)
constexpr int kMaxRootBracketIterations = 200;   ///< safeguarded Newton/bisection for a root
constexpr int kMaxDistanceNewtonIterations = 100;  ///< Riemannian Newton on the unit sphere
constexpr int kMaxPointEllipsoidIterations = 200;  ///< point-ellipsoid root (bisection-safeguarded)

/// The pencil maximiser's Newton iteration stops after a step of at most this size (mu in [0,1]):
/// quadratic convergence makes the remaining error ~1e-20, and only psi(mu), flat at the maximum,
/// matters to the certificates.
constexpr double kPencilNewtonStep = 1e-10;

/// Convergence of the signed-distance Newton iteration: stop when the Riemannian gradient norm
/// is <= this times the scale (sum of the largest radii and the centre distance).
constexpr double kDistanceGradientTolerance = 1e-14;
/// ... or after this many accepted steps in a row that each raise the support gap by at most its
/// rounding (16 u times the scale): phi no longer resolves the gradient there, and near-tangent
/// thin pairs otherwise ran to kMaxDistanceNewtonIterations (docs/reliability.md finding 33).
/// 3 steps left the witnesses of a needle 2e-9 of the scale apart beyond the distance; 6 keep
/// them as close as the 100 iterations did (1.6e-11 of the scale).
constexpr int kDistanceStallSteps = 6;


// --- Continuous collision of ellipsoids (thesis ch.5; docs/algorithms.md section 8) ----------

/// Touching band of the CCD state function (thesis §5.3.1): at time t the pair is "touching" when
/// |max_u F(u, t)| <= this times max_i |c_i(t)|, c_i(t) the Bernstein coefficients in u of F(., t)
/// (their extremes are det A(t) and det B(t)). A state within the band counts as contact: the
/// solver errs toward reporting a collision. Near an external contact max_u F behaves like the
/// relative gap, so gaps down to roughly this size are told apart from contact.
constexpr double kCcdTouchingRelative = 1.0 / 1099511627776.0;  // 2^-40 ~ 9.1e-13

/// Width to which Bezier-shoot roots (firstRoot) are refined: contact times are reported as the
/// lower end of a certified bracket of this width (never later than the root).
constexpr double kCcdTimeTolerance = 1.0 / 1099511627776.0;  // 2^-40 ~ 9.1e-13

/// Rounding margin of the one-sided Bezier clipping of a shoot, in units of (n + 1) ulps of the
/// largest coefficient (n the degree): covers the backward error of the de Casteljau
/// restrictions of kCcdMaxClipSteps steps.
constexpr double kCcdClipMarginUlps = 64.0;

/// Clipping / halving steps of one shoot. The left end of the current sub-interval is always a
/// valid lower bound of the first root, so reaching the cap just ends the shoot early (the chain
/// shoots again from there).
constexpr int kCcdMaxClipSteps = 96;

/// Candidate intervals narrower than this are not subdivided further; when such an interval
/// cannot be certified separate it is reported as colliding (thesis Remark 5.4: conservative).
constexpr double kCcdMinIntervalWidth = 1.0 / 1073741824.0;  // 2^-30 ~ 9.3e-10

/// Work cap of the ellipsoid CCD per piece of the motions (all balance segments of the piece
/// together): state evaluations plus Bezier shoots plus the u-slabs of the overlap certificates
/// (kCcdMaxSlabVisits). When it is reached every interval of the piece not yet certified separate
/// is reported as colliding and the result is flagged unresolved (conservative fallback). Per
/// piece since session 53, as the region and dimension-reduction engines' caps: a keyframed
/// motion is answered as its pieces would be one by one, in at most their number times a capped
/// piece's time.
constexpr int kCcdMaxWork = 20000;

/// Balance breaks of the CCD (docs/algorithms.md section 8, "Nearly vanishing w"): a segment is
/// bisected while, over 9 samples, the ratio |w_a(t)| / |w_b(t)| of the two motions' homogeneous
/// weights, or (|det L_a(t)| / |det L_b(t)|)^(1/3), varies by more than this factor. A common
/// scalar factor of a motion matrix that nearly vanishes near [0, 1] (finding 9: w(t) with roots
/// at -1e-8 and 1 + 1e-8) drives the balance of the pencil det(lambda A(t) - B(t)) away from
/// lambda = -1 over the segment, and the Bezier shoots of the solver then stall. Motions from two
/// poses (ratio at most 2) are never split; the breaks only change how [0, 1] is cut into
/// exactly solved segments, never an answer.
constexpr double kCcdBalanceRatio = 4.0;

/// Bisection depth and segment count caps of the balance breaks, per piece of the motions (a
/// segment at the cap is solved as it is: at worst the work cap's conservative answer).
constexpr int kCcdMaxBalanceDepth = 48;
constexpr int kCcdMaxBalanceSegments = 256;

/// Largest degree in t of the CCD function F(u, t) of an ellipsoid pair under exact (rigid or
/// polynomial) motions: the Bernstein conversions of F use rows of Pascal's triangle up to this
/// one (ccd_function.cpp). Two motions from poses give 18, the thesis' degree-6 arm links 96, a
/// general affine motion of degree k against a fixed body 24 k; ccdFunctionDegree() gives the
/// degree of a pair, and a pair above this limit is rejected up front (CcdDegreeError, a
/// std::invalid_argument), before any cull or root search runs on it.
constexpr int kCcdMaxDegree = 400;

/// Ill-conditioned CCD pairs (docs/algorithms.md section 8): a condition estimate (aspect ratio x
/// condition of the motion's linear part)^2 of either moving quadric above this sets
/// EllipsoidCcdResult::precision_checked, whose answers the extended-precision error estimate
/// moves further toward contact. Until session 18 the precision check itself ran only above it;
/// it now runs for every rigid pair (finding 16: F's rounding is not bounded by this estimate at
/// grazing instants).
constexpr double kCcdCheckedCondition = 1e4;

/// Beyond this condition estimate even the extended-precision F (64-bit significand) is mostly
/// rounding noise: the CCD does not decide, it reports the pair colliding throughout [0, t_max]
/// and flags the result unresolved (conservative fallback; e.g. a shear of condition 1e7 applied
/// to an ellipsoid of aspect ratio 4, fuzz finding 8).
constexpr double kCcdMaxCondition = 1e14;

/// Depth limit of the u-slab subdivision of the overlap certificate (F <= 0 or F_t of one sign on
/// each slab; docs/algorithms.md section 8). Until session 26 this was 6, a full tree of at most
/// 127 slabs; the certificate of two thin bodies' overlap (F ~1e-8 of its coefficients) needs
/// slabs of width ~1e-4 where F is largest, and failed (docs/reliability.md, finding 21).
constexpr int kCcdMaxSlabDepth = 20;
/// Slabs one overlap certificate may examine (depth first) before it gives up, uncertified: the
/// old full tree's 127, so that the deeper limit above does not raise the cost of a certificate.
/// Every slab examined also counts toward kCcdMaxWork (since session 51).
constexpr int kCcdMaxSlabVisits = 127;

}  // namespace tolerance
}  // namespace fcl_quadric
