#pragma once
/// \file convex_cover.h
/// Convex pieces whose union contains a composite quadric model (quadric_region.h): the input
/// of distance and distance lower bounds for models that are not convex themselves (unions,
/// rings, wedges; docs/algorithms.md section 12). Pure geometry (std + Eigen).
///
/// Method, on the model's and/or formula over signed atoms (the CQM's CSG tree of thesis §6.1
/// with differences pushed to the atoms, as the certified engines use it): a conjunction keeps its convex atoms (planes and curved atoms
/// whose quadratic part is positive semidefinite: ConvexSupport::fromRegion's class) and drops
/// the others (a superset); a disjunction is the union of its children's pieces; a conjunction
/// with disjunctive children is distributed over them (at most kMaxCoverPieces pieces; beyond,
/// the disjunction is dropped: a superset). A conjunction that keeps two curved atoms keeps the
/// first only. Every piece is cut by the model's bounding box, so it is bounded; a piece with no
/// atom left is the box itself. The cover is `exact` when nothing was dropped: then the union of
/// the pieces is the model (a union of convex solids, e.g. two ellipsoids, or a box with a
/// cylinder), and the distance to the model is the smallest distance to a piece.

#include <vector>

#include "fcl_quadric/geometry/convex_support.h"
#include "fcl_quadric/geometry/quadric_region.h"

namespace fcl_quadric {

namespace tolerance_support {
/// Most pieces a cover may have (distribution of conjunctions over disjunctions).
constexpr int kMaxCoverPieces = 64;
}  // namespace tolerance_support

struct ConvexCover {
  /// Convex supersets of parts of the model; their union contains it. Never empty.
  std::vector<ConvexSupport> pieces;
  /// True when the union of the pieces is the model itself (no atom or branch dropped).
  bool exact = false;
};

/// The cover of `region` (file comment); `box` is a bounding box of it (QuadricShape::localBox).
/// \throws std::invalid_argument if the box is empty or not finite.
ConvexCover convexCover(const QuadricRegion& region, const Box3& box);

}  // namespace fcl_quadric
