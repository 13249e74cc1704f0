#pragma once
/// \file dimension_reduction_ccd.h
/// Continuous collision of two composite quadric models by dimension reduction (Choi 2008 thesis
/// §6.1-6.2, docs/algorithms.md section 10b): the first contact time is the earliest verified
/// candidate over the CCD subproblems of ccd_subproblems.h.
///
/// Method. Body a's local frame is the working frame: a's elements are constant there; b's are
/// carried by the relative motion, as polynomials in the piece's time u (points and directions
/// by N_a(u) M_b(u), planes and quadrics by its inverse P = N_b(u) M_a(u): π^T P and P^T Q P;
/// homogeneous, up to factors without roots on the piece). Each subproblem becomes a condition
/// on u whose solutions are the moments the two extended elements touch (§6.2.2):
///  - face-vertex:  g = X^T S X (direct substitution of the vertex);
///  - quadric-line: g = b^2 - a c for (U + s D)^T S (U + s D) = a s^2 + 2 b s + c (discriminant).
///    When g vanishes identically (a line parallel to a cylinder's axis, an edge sliding tangent
///    to a sphere) the contact lasts over an interval and begins at t = 0 or on the elements
///    that bound it (a vertex of the line, an edge of the face): no candidate of its own;
///  - quadric-plane: g = -det [[S, π], [π^T, 0]] = π^T adj(S) π (the dual quadric; the
///    characteristic polynomial det(λS - π π^T) = λ^3 (λ det S - π^T adj(S) π) by the matrix
///    determinant lemma, so its multiple root appears exactly when π^T adj(S) π = 0). Skipped for
///    a cylinder: it touches a plane only along a line, found on the face's bounding edges;
///  - plane-conic:  g = det [[S, π1, π2], [π1^T, 0, 0], [π2^T, 0, 0]] (the line π1 ∩ π2 is tangent
///    to the conic S ∩ π2 iff the quadric restricted to it is degenerate: the bordered form);
///  - conic-line:   g = X^T S X with X = (π.D) U - (π.U) D the line's point in the conic's plane
///    (a line parallel to the plane: its crossings with the conic when it lies in the plane);
///  - line-line:    g = det [U1, D1, U2, D2] (coplanar lines);
///  - a cone's apex (the finite null vector of a singular face quadric; not an element of §6.1):
///    a face-vertex condition against every face of the other body (a convex tip may first touch
///    a concave face, so no exclusion). A cone touches a plane along a generator, which ends at
///    the apex or on a rim, so cone-plane contacts are found there as for cylinders;
///  - quadric-quadric, quadric-conic (in the conic's plane: 3x3 conics), conic-conic (on the
///    line of the two planes: the bordered pencil, whose binary forms share a root): a negative
///    multiple root λ of the characteristic polynomial f(λ; u) = det(λ M1 - M2(u)) (external
///    tangency, §6.2.2). Instead of the roots of its discriminant in λ expanded in u (degree up
///    to 120 for two moving bodies: cancellation moved its roots by up to 1e-3 in the tests), the
///    common zeros of F(x, u) = x^m f((x-1)/x; u) and dF/dx over (x, u) in [0, 1]^2 (λ < 0 <->
///    x in (0, 1), as the CCD function of thesis §5.3) are enclosed by Bernstein subdivision,
///    earliest u first, to boxes of 1e-7. A singular pencil (f identically zero: parallel
///    cylinders) has no isolated tangency: its contacts are lines, found on the bounding edges.
/// Every polynomial in u (the relative motion, the posed elements, the conditions g, the pencils'
/// coefficients and F) is kept in the Bernstein basis of the piece, whose products have positive
/// weights: in the power basis the degree-48 pencils of two rotating bodies lost up to 12 digits
/// to cancellation near u = 1 and missed contacts (docs/reliability.md finding 45).
/// Every candidate (a root of g isolated on the Bernstein form, a local extremum of g within
/// kReductionNearRootRelative of zero -- a graze that rounding could lift off zero --) is refined
/// on the same condition evaluated at u from the elements at u (no expansion in u) to
/// kReductionRootWidth; a pencil box is tried at its Newton solution of (F, F_x) = 0, then
/// refined on the numeric discriminant (which alone fails for spheres: their permanent positive
/// double root keeps it at zero). Its contact point (the vertex, the tangency point or the null
/// vector of the pencil at its negative multiple root, the line's point in the plane, the lines'
/// closest points) is verified with the interior / boundary predicates of Figure 29 through both
/// CSG trees, with a band of kReductionVerifyRelative times the pair's size (within it, a point
/// counts as on the boundary: err toward contact). The earliest verified candidate is the first
/// contact; the pencil searches run last, pruned to times before the best contact so far.
/// Proximity windows: before the subproblems of a piece, the squared distance of the bodies'
/// bounding-sphere centres less the squared (padded) sum of their radii, a polynomial in u in the
/// Bernstein basis (b's centre posed as a vertex), is subdivided to kReductionWindowResolution;
/// intervals where all its coefficients are positive (beyond rounding) are certified apart and
/// skipped, and the subproblems are solved on each remaining window as a piece of its own (a
/// pair that passes close only briefly, a small body past a large one, costs a short window).
///
/// Scope. Answered here: CQMs whose edges are lines and conics (thesis ch.6's class): boxes,
/// capped elliptic cylinders, clipped quadrics, wedges, and CSG solids of quadrics and planes
/// whose curved faces meet only planes. A line edge is the meet of two planes or a plane's
/// section of a quadric (a cut through a cylinder's axis: two parallel lines, the second one an
/// edge of its own reported under the same index; a tangent plane: one line); an edge of two
/// parallel planes (coincident faces of a union's children) has no points of its own and no
/// subproblems. Plane-line and plane-plane contacts are found on the
/// elements that bound them (an edge lying on a face touches it first at a vertex or where it
/// crosses the face's edges). Undecided, with the reason (the caller then uses the certified
/// space-time engine of region_ccd.h):
///  - a quartic edge (two curved faces meeting: thesis §6.5), a curved face of rank 2 or less,
///    a pair of planes as one atom;
///  - a degenerate candidate: g identically zero within kReductionZeroRelative (other than
///    quadric-line, above), or a contact
///    point that is undefined (coincident planes: a cap landing flat on a face);
///  - a pencil search reaching kPencilMaxBoxes (a curve of multiple roots), or the pencil
///    searches of one piece reaching kReductionMaxPencilBoxes together;
///  - an unbounded body (no local AABB), a non-rigid pose at t = 0 for the start test.
/// Completeness rests on generic position of the first contact (thesis §6.1): a first contact
/// at a point where each body's lowest-dimensional element is one of the pairs above is a root
/// of that pair's condition. The tests cross-check every answer against the certified engine.

#include <optional>
#include <string>

#include <Eigen/Core>

#include "fcl_quadric/continuous/ccd_subproblems.h"
#include "fcl_quadric/continuous/region_ccd.h"
#include "fcl_quadric/geometry/quadric_contact_configuration.h"

namespace fcl_quadric {

namespace tolerance_reduction {
/// A candidate contact point is accepted on a body's boundary when every deciding atom's
/// first-order distance estimate |f| / |grad f| is within this fraction of the pair's size
/// (the larger local AABB extent). Dimensionless.
constexpr double kReductionVerifyRelative = 1e-9;
/// Root isolation width in the piece's time (then refined to this accuracy).
constexpr double kReductionRootWidth = 1e-13;
/// A local extremum u of g with |g(u)| <= this times the evaluation's absolute magnitude
/// (sum |c_k| u^k) is a grazing candidate (rounding could have lifted a double root off zero).
constexpr double kReductionNearRootRelative = 1e-10;
/// g is degenerate (identically zero) when max |c_k| <= this times the magnitude of its
/// formula on absolute values.
constexpr double kReductionZeroRelative = 1e-11;
/// A candidate point is also on an atom's surface when |f| is within this fraction of the form's
/// absolute magnitude sum |X_i| |Q_ij| |X_j| (X = (x, 1)): the rounding of evaluating f from the
/// posed polynomial matrices. This decides points at a singular point of a surface (a cone's
/// apex), where the gradient vanishes and kReductionVerifyRelative's first-order band is empty;
/// elsewhere it is far below that band. Near an apex it accepts points within about 1e-7 of the
/// size (f is second order there). Dimensionless.
constexpr double kReductionEvalRelative = 1e-14;
/// A candidate whose contact point is degenerate (a conic lying in a face's plane within the
/// band) leaves the answer Undecided unless another candidate verifies at most this much later
/// in the piece's time; that contact is then the answer (its time may be late by up to this
/// much). About 10 sqrt(eps): a graze's double root is located to about sqrt(eps) only.
constexpr double kReductionDegenerateWindow = 1e-7;
/// Proximity windows: the bounding spheres' radii (each local AABB's half diagonal) are summed
/// and padded by this fraction before the windows where the spheres may overlap are found.
constexpr double kReductionWindowPadRelative = 1e-6;
/// Proximity windows: subdivision of the piece stops at intervals of this width (in the piece's
/// time), which are kept whole.
constexpr double kReductionWindowResolution = 1.0 / 1024;
/// Pencil subproblems: boxes of (x, u) narrower than this in both are candidates.
constexpr double kPencilSeedWidth = 1e-7;
/// Pencil subproblems: the first pass's budget of each search (boxes). A search that needs more
/// is paused and goes on after every other search of the piece has had its first pass, pruned by
/// the contacts those found (a long search no longer delays a short one that finds an earlier
/// contact).
constexpr int kPencilFirstPassBoxes = 4096;
/// Pencil subproblems: work cap of one search (boxes); reaching it makes the answer Undecided.
constexpr int kPencilMaxBoxes = 40000;
/// Pencil subproblems (thesis §6.2.2): work cap of one piece of the motion (boxes of all its
/// pencil searches, every pair of elements together); reaching it makes the answer Undecided. Before it, a piece
/// could run every one of its searches (up to 49 for two clipped ellipsoids) nearly to
/// kPencilMaxBoxes. A query costs about 11 us per pencil box for motions from poses (measured,
/// session 52), about 1 s at the cap; the tests' largest single-piece query used 46,952 (one of
/// its searches stopped at kPencilMaxBoxes). Per piece, as region_ccd.h's caps, so that a
/// keyframed motion is answered as its pieces would be one by one.
constexpr int kReductionMaxPencilBoxes = 100000;
}  // namespace tolerance_reduction

enum class ReductionStatus { Decided, Undecided };

struct ReductionCcdResult {
  ReductionStatus status = ReductionStatus::Undecided;
  bool collide = false;
  double time = 1.0;                                 ///< first contact time (global), 1 when none
  Eigen::Vector3d point = Eigen::Vector3d::Zero();   ///< contact point, world frame
  CcdSubproblem subproblem;                          ///< the pair that gave the first contact
  std::string label_a, label_b;                      ///< its elements ("F1", "E0", "V2"; "" at t = 0)
  std::string reason;                                ///< why Undecided
  /// A face-face (quadric-quadric) first contact: the contact configuration of the two extended
  /// surfaces there (Lemma 6.2, and the genuine-contact test of §6.3.2 with Tables 7-10,
  /// geometry/quadric_contact_configuration.h). Reported, not used as a filter: a tangency on a
  /// real intersection curve is never the first contact of two solids that were disjoint
  /// before, so the earliest verified candidate is genuine whenever the search is complete.
  std::optional<ContactConfiguration> configuration;
  int subproblems = 0;                               ///< subproblems examined (all pieces)
  int candidates = 0;                                ///< candidate moments verified
  /// Boxes of the pencil searches (all pieces and pairs of elements; kReductionMaxPencilBoxes
  /// caps those of each piece, one more counted when that cap stopped the query).
  long long pencil_boxes = 0;
};

/// First contact of a and b over [0, 1] by dimension reduction (file comment). Never throws for
/// unsupported or degenerate configurations: they come back Undecided with a reason.
/// \throws std::invalid_argument as continuousCollideRegions for invalid motions (degree).
ReductionCcdResult continuousCollideRegionsByReduction(const MovingRegion& a, const MovingRegion& b);

}  // namespace fcl_quadric
