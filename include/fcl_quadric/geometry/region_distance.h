#pragma once
/// \file region_distance.h
/// Distance between composite quadric models that are not convex (rings, wedges, hyperboloids,
/// double cones: quadric_region.h) and convex solids or other such models, with witness points
/// on both: branch and bound over boxes of each model with convex relaxations and certified GJK
/// lower bounds (docs/algorithms.md section 12b). Pure geometry (std + Eigen).
///
/// Method. Each operand is a region (a CSG formula over signed atoms, in its own frame, with a
/// bounding box) or a convex support mapping (convex_support.h). A node is a pair of boxes, one
/// per region operand (a convex operand is never split).
///  - Relaxation. On a box X the formula is simplified by the atoms' certified enclosures
///    (centred form, as the static engine: an atom certified negative on X is dropped, one
///    certified positive removes its conjunction) and expanded into conjunctions of the undecided
///    atoms. Each conjunction becomes one convex piece: X's six faces, its planar atoms and its
///    first positive-semidefinite curved atom exactly, every other atom g <= 0 by the half-space
///    g(c) + grad g(c).(x - c) + q_lo <= 0 about X's centre c, where q_lo <= (x-c)^T A (x-c) on X
///    (0 for a convex atom, whose tangent plane bounds it; the centred-form bound otherwise). The
///    union of the pieces contains the model's part in X; the slack is O(|X|^2) where a
///    non-convex atom (a ring's bore) is relaxed.
///  - Lower bound of a node: the smallest GJK lower bound (convex_distance.h) over its pairs of
///    pieces, less 1e-11 of the pair's scale (the support points' tolerance and rounding, as
///    distanceLowerBound takes it): certified.
///  - Upper bound: each pair's GJK witnesses are moved onto their model (Gauss-Newton onto the
///    undecided atoms they violate) and kept only if the model's exact-sign membership does not
///    certify them outside (QuadricRegion::classifyPoint); a witness on a convex operand is
///    replaced by the nearest point of that operand to the other witness. The best such pair is
///    the answer's witnesses, and |point_a - point_b| its distance.
///  - Polish: from the best witnesses, nearest points alternate between the surfaces through them
///    (one or two atoms of a region: a face or an edge) and a convex operand, each round kept
///    only if it brings them closer; it takes an edge's witness, left O(|X|^2) off by the
///    relaxations, to rounding. The certificate is untouched.
///  - Search: best first on the lower bound; a node is dropped once its lower bound is within the
///    tolerance of the best upper bound; the larger box of a node is halved on its longest edge.
///    Where the nearest points are isolated, O(1) nodes survive per level and the gap shrinks four
///    times per level (quadratic slack); where they form a curve (a ball centred in a bore) the
///    survivors grow like 1 / |X|, and the node cap may stop the search first.
/// Every loop is capped (kRegionDistanceMaxNodes); at the cap the best bounds are returned with
/// converged = false: `lower_bound` stays certified, `distance` is the upper bound (the distance of
/// the witnesses).

#include <Eigen/Core>

#include "fcl_quadric/geometry/convex_support.h"
#include "fcl_quadric/geometry/quadric_region.h"

namespace fcl_quadric {

namespace tolerance_region_distance {
/// Default stopping gap (distance minus certified lower bound) relative to the pair's scale (the
/// operands' bounding-box half diagonals plus the distance between their centres). The distance
/// itself is that of real witness points and is usually exact to rounding long before the
/// certificate closes: where the nearest points form a curve or a segment (a ball centred in a
/// bore, a rod parallel to it) the surviving boxes grow like 1 / sqrt(gap): around a ring 4 wide
/// (scale ~2.5) a ball on its axis and a rod in its bore took 1,800-9,200 nodes (31-229 ms,
/// Release) for an absolute gap of 1e-5, 6,300 to the node cap for 1e-6.
constexpr double kRegionDistanceRelative = 1e-6;
/// Smallest gap a caller may ask for, relative to the scale: ten times the margin taken off GJK's
/// lower bounds (tolerance_convex::kConvexSeparationRelative, 1e-11: support tolerance and
/// rounding).
constexpr double kRegionDistanceFloorRelative = 1e-10;
/// Nodes expanded (each splits one box in two) before the search stops with converged = false.
constexpr int kRegionDistanceMaxNodes = 20000;
/// Boxes narrower than this fraction of their operand's bounding box are not split (2^-34 ~ 6e-11:
/// below the stopping gap): a node whose boxes are both that small keeps its lower bound.
constexpr double kRegionDistanceMinBoxRelative = 5.820766091346741e-11;
/// Conjunctions per box after expanding the simplified formula; beyond, the box itself is the one
/// piece of that operand there (a superset).
constexpr int kRegionDistanceMaxBranches = 16;
/// Gauss-Newton steps moving a witness onto its model (and onto its surfaces in the polish).
constexpr int kRegionDistanceProjectionSteps = 8;
/// The polish: alternating nearest points between the witnesses' surfaces, at most this many
/// rounds (each kept only if it brings the witnesses closer).
constexpr int kRegionDistancePolishSteps = 64;
/// A region witness lies on an atom's surface when |g| / |grad g| is below this fraction of its
/// operand's half diagonal.
constexpr double kRegionDistanceActiveRelative = 1e-6;
}  // namespace tolerance_region_distance

/// One operand of regionDistance, posed in the common frame by x -> R x + p: a region (with a
/// bounding box in its own frame, which must contain it) or a convex support mapping. The
/// referenced objects must outlive the call.
struct DistanceOperand {
  const QuadricRegion* region = nullptr;
  Box3 box;
  const ConvexSupport* convex = nullptr;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p = Eigen::Vector3d::Zero();

  static DistanceOperand ofRegion(const QuadricRegion& region, const Box3& box, const Eigen::Matrix3d& R,
                                  const Eigen::Vector3d& p);
  static DistanceOperand ofConvex(const ConvexSupport& convex, const Eigen::Matrix3d& R, const Eigen::Vector3d& p);
};

struct RegionDistanceResult {
  /// Separated: distance > 0 is the witnesses' distance, within `tolerance` of the true distance
  /// when converged. Contact: the witnesses are within the tolerance of each other (touching or
  /// overlapping: the static collide decides which); distance is then that gap.
  enum class Status { Separated, Contact };
  Status status = Status::Contact;
  double distance = 0.0;     ///< |point_a - point_b|: an upper bound of the true distance
  double lower_bound = 0.0;  ///< certified: the true distance is at least this
  Eigen::Vector3d point_a = Eigen::Vector3d::Zero();  ///< on a (common frame)
  Eigen::Vector3d point_b = Eigen::Vector3d::Zero();  ///< on b (common frame)
  bool converged = false;    ///< distance - lower_bound <= the tolerance
  int nodes = 0;             ///< nodes expanded
};

/// Distance between a and b (file comment). `tolerance` is the absolute stopping gap: 0 means
/// kRegionDistanceRelative times the pair's scale; a positive value is used as given, but not
/// below kRegionDistanceFloorRelative times the scale.
/// \throws std::invalid_argument if an operand is neither or both a region and a convex support, a
/// region's box is empty or not finite, a pose is not finite and rigid, or the tolerance is NaN
/// or negative.
RegionDistanceResult regionDistance(const DistanceOperand& a, const DistanceOperand& b, double tolerance = 0.0);

}  // namespace fcl_quadric
