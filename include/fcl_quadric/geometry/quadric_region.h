#pragma once
/// \file quadric_region.h
/// Pure geometry (std + Eigen) of composite quadric models (CQMs, Choi 2008 ch.6): CSG trees of
/// union / intersection / difference over quadric atoms { X : X^T Q X <= 0 } (X = (x, 1), thesis
/// §4.1 convention; a half-space n.x <= d is the rank-2 atom Q = [0 n/2; n^T/2 -d]).
///
/// Everything that needs the region as a set is answered by one certified engine, box subdivision
/// with a centred-form enclosure of each atom and pencil exclusion (docs/algorithms.md section 9):
///  - findPoint: is a CSG formula satisfiable in a box? Empty / Found (certified interior point) /
///    Undecided (a box of width <= kRegionMinBoxRelative * extent that neither test decides, or
///    the box cap was reached: the conservative "contact" answer of a static collide);
///  - maxLinear: a certified upper bound of max d.x over the region (local AABB), starting from
///    a bound by weak duality (dualLinearBound);
///  - cell volume / centroid / inertia with a certified error bound.
/// Only rounding-padded signs are trusted (tolerance::kRegionSignRelative).

#include <string>
#include <optional>
#include <vector>

#include <Eigen/Core>

namespace fcl_quadric {

namespace tolerance_region {
/// A computed value v of X^T Q X is trusted to have the exact sign when |v| > this times
/// |X|^T |Q| |X| (the same expression on absolute values): the a-priori rounding bound of the
/// 16 products and sums is ~gamma_20 ~ 2.2e-15; 2^-40 leaves a factor > 400. Dimensionless.
constexpr double kRegionSignRelative = 9.094947017729282e-13;  // 2^-40
/// Boxes narrower than this fraction of the search box's largest edge are not split: such a box
/// that is neither excluded nor certified inside makes findPoint answer Undecided (contact).
/// 2^-30 ~ 9.3e-10: a pair reported Touching has boundaries within ~1e-9 * extent of contact
/// (for non-degenerate gradients).
constexpr double kRegionMinBoxRelative = 9.313225746154785e-10;  // 2^-30
/// Work cap of one findPoint (boxes visited); on reaching it the answer is Undecided (contact).
constexpr int kRegionMaxBoxes = 200000;
/// Golden-section steps of the pencil weight mu in [0,1] (0.618^40 ~ 4e-9 of the interval).
constexpr int kRegionPencilSteps = 40;
/// maxLinear stops when the certified upper bound is within this fraction of the search extent of
/// the best certified interior point; the upper bound is returned (outward-rounded AABB). 1e-7:
/// where the maximum is attained along a curve and the duality bound (dualLinearBound) is not
/// tight there, each search costs ~1/sqrt(tol) boxes, so tighter AABBs get expensive; FCL's broad
/// phase needs only a conservative box.
constexpr double kRegionAabbRelative = 1e-7;
/// Bisection steps of maxLinear on the level (2^-60 of the search box); at the cap the current
/// certified upper bound is returned.
constexpr int kRegionMaxAabbBisections = 60;
/// After the first undecided box, findPoint keeps looking for an interior point for this many
/// more boxes before answering Undecided.
constexpr int kRegionExtraBoxesAfterUndecided = 2000;
/// findPoint splits the axis that contributes most to the undecided atoms' enclosures, unless the
/// box would get more elongated than this (its centre must be able to land in a thin lens).
/// maxLinear, which only needs certified exclusions, lets boxes stay long along a line of contact.
constexpr double kRegionMaxAspect = 16.0;
/// Local AABBs are searched inside |x_i| <= this (in the shape's length unit): a region reaching
/// it is rejected as unbounded.
constexpr double kRegionMaxExtent = 1e6;
/// boundaryElements keeps an element unless the region restricted to its surfaces is certified
/// empty with boxes down to this fraction of the search box (2^-20 ~ 9.5e-7): elements within
/// about that distance of the boundary are kept (a superset; contacts are verified downstream).
constexpr double kBoundaryElementBoxRelative = 9.5367431640625e-07;  // 2^-20
/// Cell volume: subdivision stops when the undecided cells hold at most this fraction of the
/// bounding-box volume, or at kRegionMaxVolumeCells cells (the bound is then reported as is).
constexpr double kRegionVolumeRelative = 1e-6;
constexpr int kRegionMaxVolumeCells = 400000;
}  // namespace tolerance_region

/// Kind of an atom's surface for Definition 6.1 (Choi 2008 §6.2.1), as the atom is used (a
/// difference negates the subtracted atoms: the closure of the complement of {f<=0} is {-f<=0}).
enum class FaceShape {
  Planar,   ///< 3x3 part zero, or a pair of planes (rank-2 indefinite)
  Convex,   ///< both principal curvatures >= 0 w.r.t. the outward normal (ellipsoid, cylinder, ...)
  Concave,  ///< both principal curvatures <= 0, one negative (complements: a cavity, a bore)
  /// Principal curvatures of opposite signs everywhere (det Q > 0: a hyperboloid of one sheet, a
  /// hyperbolic paraboloid, or their complements). Concave by Definition 6.1 (a negative
  /// principal curvature everywhere), but two saddles can touch externally at an isolated point
  /// (docs/reliability.md finding 53), so it is a class of its own.
  Saddle,
};
const char* toString(FaceShape s);

/// Definition 6.1 for the face of the atom {X^T Q X <= 0}: from the inertia of the 3x3 part A and
/// the sign of det Q (Gaussian curvature has the sign of -det Q for a non-degenerate quadric).
FaceShape classifyFace(const Eigen::Matrix4d& Q);

/// An axis-aligned box [lo, hi].
struct Box3 {
  Eigen::Vector3d lo = Eigen::Vector3d::Zero();
  Eigen::Vector3d hi = Eigen::Vector3d::Zero();
  bool empty() const { return (lo.array() > hi.array()).any(); }
  Eigen::Vector3d center() const { return 0.5 * (lo + hi); }
  Eigen::Vector3d halfWidth() const { return 0.5 * (hi - lo); }
  /// The longest edge.
  double maxEdge() const { return (hi - lo).maxCoeff(); }
};

/// A CSG tree over quadric atoms, in its own (local) frame.
class QuadricRegion {
 public:
  enum class Op { Atom, Union, Intersection, Difference };

  /// The solid X^T Q X <= 0.
  /// \throws std::invalid_argument if Q is not finite, not symmetric (relative 1e-12), or zero.
  static QuadricRegion atom(const Eigen::Matrix4d& Q);
  /// The half-space n.x <= d (n need not be unit; it is normalised).
  /// \throws std::invalid_argument if n is zero or not finite or d is not finite.
  static QuadricRegion halfspace(const Eigen::Vector3d& n, double d);
  /// Union / intersection of >= 1 children; difference: the first child minus all the others
  /// (regularised: closure of the complement). \throws std::invalid_argument if `children` is
  /// empty, or op is Atom.
  static QuadricRegion combine(Op op, std::vector<QuadricRegion> children);
  /// Region mapped by x -> R x + p (R a rotation, checked; or any invertible affine map via
  /// transformedAffine).
  QuadricRegion transformed(const Eigen::Matrix3d& R, const Eigen::Vector3d& p) const;
  QuadricRegion transformedAffine(const Eigen::Matrix3d& M, const Eigen::Vector3d& p) const;

  Op op() const { return op_; }
  const Eigen::Matrix4d& matrix() const { return Q_; }
  const std::vector<QuadricRegion>& children() const { return children_; }

  /// Exact-sign membership of x (Figure 29 predicates): +1 interior (certified), -1 exterior
  /// (certified), 0 within the rounding band of some deciding atom (on or near the boundary).
  int classifyPoint(const Eigen::Vector3d& x) const;

  /// The atoms in depth-first order, each negated when it sits under an odd number of
  /// subtracted operands (the face it contributes as used by the solid).
  std::vector<Eigen::Matrix4d> signedAtoms() const;

 private:
  QuadricRegion transformedHomogeneous(const Eigen::Matrix4d& T) const;
  QuadricRegion transformedByInverse(const Eigen::Matrix4d& Tinv) const;

  Op op_ = Op::Atom;
  Eigen::Matrix4d Q_ = Eigen::Matrix4d::Zero();
  std::vector<QuadricRegion> children_;
};

/// Outcome of findPoint.
enum class PointSearch { Empty, Found, Undecided };

struct PointSearchResult {
  PointSearch status = PointSearch::Undecided;
  /// Found: a certified interior point. Undecided: the centre of the undecided box.
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  int boxes = 0;        ///< boxes visited
  bool capped = false;  ///< Undecided because kRegionMaxBoxes was reached
};

/// Is `region` non-empty inside `box`? Depth-first subdivision; a box is dropped when an atom is
/// certified positive on it or when, for two atoms f, g conjoined in the simplified formula, some
/// pencil mu f + (1 - mu) g (mu in [0,1]) is certified positive on it (then f <= 0 and g <= 0
/// have no common point there: the static analogue of the separating pencil, thesis §4.2).
/// After the first undecided box the search goes on for `extra_after_undecided` boxes looking
/// for an interior point (0: answer Undecided at once, as maxLinear does).
PointSearchResult findPoint(const QuadricRegion& region, const Box3& box,
                            int extra_after_undecided = tolerance_region::kRegionExtraBoxesAfterUndecided);

/// A candidate common interior point of the solids X^T A X < 0 and X^T B X < 0 (homogeneous 4x4
/// matrices, one frame) from their pencil, the static analogue of Theorem 4.1's separating
/// pencil (thesis §4.2): over the mu in [0, 1] where the upper-left 3x3 block of
/// C(mu) = mu A + (1 - mu) B is positive definite, g(mu) = min_x X^T C(mu) X is concave, and at
/// its maximiser the minimiser x(mu) has a(x) = b(x) = g (the derivative a - b vanishes): inside
/// both when g < 0. Found by bisection on the sign of a(x(mu)) - b(x(mu)) (60 steps). Empty when
/// no such mu exists (neither block positive definite). Not certified: a caller certifies the
/// candidate (QuadricRegion::classifyPoint). No failure mode.
std::optional<Eigen::Vector3d> pencilInteriorCandidate(const Eigen::Matrix4d& A, const Eigen::Matrix4d& B);

/// Intersection of two regions as a region (in a's frame, b posed by X_AB = (R, p)).
QuadricRegion intersectionInFrame(const QuadricRegion& a, const QuadricRegion& b, const Eigen::Matrix3d& R_AB,
                                  const Eigen::Vector3d& p_AB);

/// Certified upper bound of max d.x over region within `box` (tight to kRegionAabbRelative).
/// \return false if the region is empty in `box`.
bool maxLinear(const QuadricRegion& region, const Eigen::Vector3d& d, const Box3& box, double* upper);

/// A certified upper bound of d.x over the region within `box` by weak duality (docs/algorithms.md
/// section 9, "Faces by duality"): over pairs of its atoms (the S-procedure; two opposite planes
/// also as their product), its planes' linear program, and each convex atom with all its planes;
/// +infinity when none gives one. maxLinear starts from it. Tight (to rounding) where the best
/// one's duality gap is zero: two convex atoms (a lens), an ellipsoid of revolution minus a
/// coaxial bore (a ring), a polytope, an ellipsoid cut by planes; not at a cone's apex. The model
/// is thesis ch.6's CQM (§6.1); the bound is weak Lagrangian duality, not from the papers. Bad
/// input (d or the box not finite) gives +infinity, no bound, rather than an exception: callers
/// keep their own certified bound.
double dualLinearBound(const QuadricRegion& region, const Eigen::Vector3d& d, const Box3& box);

/// Local AABB of a bounded region: searched in [-kRegionMaxExtent, kRegionMaxExtent]^3 (or in
/// `hint` when given and non-empty: the caller guarantees the region lies inside it).
/// \throws std::invalid_argument if the region is empty or reaches the search limit (unbounded).
Box3 regionAabb(const QuadricRegion& region, const Box3* hint = nullptr);

/// Mass properties of the region (unit density) by certified cell classification inside `box`:
/// cells certified inside count fully, undecided cells by half; `volume_error` bounds the error
/// of `volume` (half the undecided volume). Centroid and second moments from the same cells.
struct MassProperties {
  double volume = 0.0;
  double volume_error = 0.0;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  /// Inertia tensor about the local origin: integral of (|x|^2 I - x x^T).
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
};
MassProperties regionMassProperties(const QuadricRegion& region, const Box3& box);

/// Boundary elements of a CQM (thesis §6.1-6.2): faces (one per atom that may touch the
/// boundary), edges (pairs of faces whose surfaces may meet on it: conic = plane x quadric,
/// line = plane x plane, curve = quadric x quadric) and vertices (three planes, or a quadric and
/// two planes, meeting on it). Elements certified absent (findPoint Empty at the resolution
/// kBoundaryElementBoxRelative) are dropped; the lists are a superset only by elements within
/// that band of the boundary. A planar face, and an edge or vertex on the line of two of its
/// planes, is kept at once when a point on a line of its planes is certified in the region with
/// the element's surfaces through it (a witness: the search could not drop it), which spares the
/// search's descent to its resolution: 1.5 ms instead of 74 for a box, 13 instead of 377 for a
/// plus-shaped union of two boxes (docs/benchmarks.md, session 58).
struct BoundaryFace {
  int atom = 0;  ///< index into signedAtoms()
  FaceShape shape = FaceShape::Convex;
  bool concave() const { return shape == FaceShape::Concave; }
  bool saddle() const { return shape == FaceShape::Saddle; }
  bool planar() const { return shape == FaceShape::Planar; }
};
enum class EdgeKind { Line, Conic, Curve };
struct BoundaryEdge {
  int face0 = 0, face1 = 0;  ///< indices into faces
  EdgeKind kind = EdgeKind::Conic;
  bool concave = false;  ///< Definition 6.1 (conic edges on a planar face bending away from it)
};
struct BoundaryVertex {
  int face0 = 0, face1 = 0, face2 = 0;
};
struct BoundaryElements {
  std::vector<BoundaryFace> faces;
  std::vector<BoundaryEdge> edges;
  std::vector<BoundaryVertex> vertices;
};
/// `max_order` 1 stops after the faces, 2 after the edges (the lists computed are the same
/// prefixes as for 3: indices do not depend on it).
BoundaryElements boundaryElements(const QuadricRegion& region, const Box3& box, int max_order = 3);

/// Static classification of two regions posed in a common frame (a in its frame, b posed by
/// X_AB). Separated: certified (every box excluded). Overlapping: a certified common interior
/// point. Touching: neither could be certified down to the tolerance band or the cap (contact).
enum class RegionRelation { Separated, Touching, Overlapping };
const char* toString(RegionRelation r);
struct RegionCollision {
  RegionRelation relation = RegionRelation::Touching;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< in a's frame (witness or undecided box)
  int boxes = 0;
  bool capped = false;
};
RegionCollision collideRegions(const QuadricRegion& a, const Box3& aabb_a, const QuadricRegion& b,
                               const Box3& aabb_b, const Eigen::Matrix3d& R_AB, const Eigen::Vector3d& p_AB);

/// The AABB (in the parent frame) of a box posed by (R, p).
Box3 transformBox(const Box3& box, const Eigen::Matrix3d& R, const Eigen::Vector3d& p);

}  // namespace fcl_quadric
