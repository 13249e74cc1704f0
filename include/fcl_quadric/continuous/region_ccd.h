#pragma once
/// \file region_ccd.h
/// Continuous collision of two composite quadric models (CQMs: elliptic cylinders, clipped
/// quadrics, CSG solids; geometry/quadric_region.h) under rational motions (motion_matrix.h):
/// the first time in [0, 1] at which the two solids touch, by certified space-time subdivision
/// (docs/algorithms.md section 10).
///
/// Method. Points are written in the frame F of one body (the one with the smaller local AABB, or
/// the bounded one); the other body O's atoms Q are carried into that frame by the relative motion
/// P(t) = c(t) M_O(t)^{-1} M_F(t), as X^T S(t) X with S = P^T Q P a polynomial matrix (thesis §5.1:
/// the moving quadric up to the positive factor c(t)^2). The search space is that body's
/// local AABB times [0, 1]. On a box c ± r times [t0, t1] each atom is enclosed by its centred form
/// in space, f(c + h, t) = v(t) + g(t).h + h^T A(t) h, with the ranges of v, g and A over
/// [t0, t1] taken from their Bernstein coefficients (convex hull property). A box is dropped when
/// the CSG formula is certified empty on it (an atom positive on the box, or a positive pencil of
/// two or three conjoined atoms: the separating pencil of thesis §4.2 made local in space and
/// time). The time axis is covered by an advancing front of slabs: [0, L) is certified free (every
/// box of the slab excluded), and a certified interior point at some instant U (a witness) bounds
/// the first contact from above; each slab [L, L + dt] is searched depth-first in space with a box
/// budget, dt doubling after a certified slab and halving after a witness or an inconclusive slab.
///
/// Contact is reported at the certified front L (never later than the true first contact):
///  - when the witness time U comes within kRegionCcdTimeTolerance of it;
///  - when, in a slab of width kRegionCcdTimeTolerance, a box of kRegionCcdMinBoxRelative of the
///    search box is neither excluded nor certified inside (the boundaries are within the tolerance
///    band of contact there: near_tangent);
///  - when kRegionCcdMaxBoxes boxes have been visited or kRegionCcdMaxPencilEvaluations pencil
///    bounds evaluated on one piece of the motion (capped: a conservative contact; RegionCcdLimits).
/// So a reported "no collision" is certified, and a reported contact time is a lower bound of the
/// true one, within kRegionCcdTimeTolerance of it unless the pair only comes within the band
/// (then it is early by about the band over the approach speed) or the cap is reached.
///
/// This is not the dimension reduction of thesis §6.2.2 (subproblems per pair of boundary
/// elements with subresultant sequences); it answers the same question for every pair of element
/// types at once, as the static engine does (docs/algorithms.md section 9).

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "fcl_quadric/continuous/motion_matrix.h"
#include "fcl_quadric/geometry/quadric_region.h"

namespace fcl_quadric {

namespace tolerance_region {
/// Time resolution of the region CCD (fraction of the motion's [0, 1]): 2^-27 ~ 7.5e-9.
constexpr double kRegionCcdTimeTolerance = 7.450580596923828e-09;
/// Spatial resolution of the region CCD (fraction of the search box's largest edge): 2^-36 ~
/// 1.5e-11. Finer than the static engine's kRegionMinBoxRelative because a contact time is
/// ill-conditioned where the gap closes slowly (a grazing approach): the time error of a
/// near-tangent answer is about this band divided by the approach speed.
constexpr double kRegionCcdMinBoxRelative = 1.4551915228366852e-11;  // 2^-36
/// Work cap of one region CCD query on each piece of the motion (space-time boxes visited); on
/// reaching it the answer is a contact at the certified lower end of the first contact time
/// (conservative). Per piece, so that a keyframed motion is answered as its pieces would be one
/// by one; a query takes at most the number of pieces times a capped piece's time.
constexpr int kRegionCcdMaxBoxes = 400000;
/// Work cap of one region CCD query on each piece in pencil bound evaluations (reaching it caps
/// the query as kRegionCcdMaxBoxes does). The pencil exclusion of a box tries pairs and
/// triples of the atoms undecided on it, O(m^3) bounds for m of them: up to 16,417 on one box of
/// a box-against-box pair (measured), so the box cap alone left a query's time unbounded in
/// practice. 2^25; one evaluation costs 0.07-0.14 us for motions from poses (measured, session
/// 52: 2-5 s at the cap), and the tests' largest query used 19.4 million.
constexpr long long kRegionCcdMaxPencilEvaluations = 33554432;
/// Largest degree in t of a moving atom X^T S(t) X (the relative motion's degree twice). Two
/// motions from poses give 10; a chain of three such joints about 30.
constexpr int kRegionCcdMaxDegree = 60;
/// When the frame body starts farther from the world origin than this many times its box's
/// largest edge, the search runs on both motions shifted so that it starts at the origin (the
/// same relative motion; the contact point is shifted back). Far out, the magnitudes of the
/// relative motion's translations (|p| ~ 10^3 of the size, cancelling to the size) widened every
/// sign pad by about |p|^2 / size^2, and half of the audit's pairs at 10^3 sizes away reached the
/// box cap (docs/reliability.md finding 48).
constexpr double kRegionCcdShiftRelative = 8.0;
}  // namespace tolerance_region

/// A CQM in its local frame moving by `motion` (local -> world).
struct MovingRegion {
  MovingRegion() = default;
  /// Members as named (no validation here: continuousCollideRegions checks what it needs).
  MovingRegion(QuadricRegion region_, std::optional<Box3> box_, PiecewiseMotion motion_,
               std::shared_ptr<const BoundaryElements> elements_ = nullptr)
      : region(std::move(region_)), box(std::move(box_)), motion(std::move(motion_)), elements(std::move(elements_)) {}

  QuadricRegion region;
  /// Local AABB; none for an unbounded region (a half-space): at least one of a pair needs one.
  std::optional<Box3> box;
  PiecewiseMotion motion;
  /// The region's boundary elements (boundaryElements(region, *box)) when the caller keeps them
  /// (they depend on the shape only, and cost tens of ms for a box of six planes); computed on
  /// demand by the dimension-reduction solver when absent. Must match `region` and `box`.
  std::shared_ptr<const BoundaryElements> elements;
};

struct RegionCcdResult {
  bool collide = false;
  /// First contact time (global, in [0, 1]); 1 when there is none.
  double time = 1.0;
  /// The contact point in world coordinates at `time` (the witness or the undecided box centre).
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  /// Indices into a.region.signedAtoms() / b.region.signedAtoms() of the atoms whose surfaces
  /// pass near the point (|f| / |grad f| within 1e-6 of the search box, or within the undecided
  /// box's size for a near-tangent answer): the boundary elements of each body involved in the
  /// contact (see boundaryElementLabel). Empty for a deep overlap at t = 0.
  std::vector<int> active_a, active_b;
  bool near_tangent = false;  ///< the contact is an undecided box within the tolerance band
  bool capped = false;        ///< a work cap reached (RegionCcdLimits): conservative contact
  int boxes = 0;              ///< space-time boxes visited (all pieces; saturates at INT_MAX)
  long long pencil_evaluations = 0;  ///< pencil bound evaluations (all pieces)
};

/// Work caps of one query of the space-time search (file comment; docs/algorithms.md section 10),
/// on each piece of the motions (the union of both motions' breaks). Reaching one gives a
/// conservative contact at the certified front (`capped`). Lower limits bound a query's time more
/// tightly at the price of more capped answers; a limit below 1 is refused (continuousCollideRegions).
struct RegionCcdLimits {
  int max_boxes = tolerance_region::kRegionCcdMaxBoxes;
  long long max_pencil_evaluations = tolerance_region::kRegionCcdMaxPencilEvaluations;
};

/// First contact of a and b over t in [0, 1] (file comment).
/// \throws std::invalid_argument if neither region has a box, or if a limit is below 1 (naming
/// it); CcdDegreeError (a std::invalid_argument) if a motion pair's relative degree exceeds
/// kRegionCcdMaxDegree.
RegionCcdResult continuousCollideRegions(const MovingRegion& a, const MovingRegion& b,
                                         const RegionCcdLimits& limits = RegionCcdLimits());

/// The label of the boundary element (thesis §6.1-6.2) formed by the given atoms of a CQM:
/// "F<i>" for one atom (faces[i]), "E<i>" for two (edges[i]), "V<i>" for three (vertices[i]),
/// indices from 0 into `elements`; for more atoms, or a combination that is not an element, the
/// labels of the faces joined by "+" (e.g. "F0+F2"); "" for none. No failure mode: atoms that
/// are not faces of `elements` are ignored.
std::string boundaryElementLabel(const BoundaryElements& elements, const std::vector<int>& atoms);

}  // namespace fcl_quadric
