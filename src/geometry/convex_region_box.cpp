// The certified bounding box of a convex region from its support mapping (convex_support.h,
// ConvexSupport::regionBox; docs/algorithms.md section 12, "Bounding boxes of convex regions").
#include <algorithm>
#include <cmath>
#include <limits>

#include "fcl_quadric/geometry/convex_support.h"

namespace fcl_quadric {

namespace {

double maxEdge(const Box3& b) { return (b.hi - b.lo).maxCoeff(); }

/// Stages of the support box: each stage's box bounds the next stage's enumeration, so that the
/// feasibility tolerance (relative to the box) ends up relative to the region's own size. From
/// the +-kRegionMaxExtent cube a region of size 1e-6 needs three.
constexpr int kBoxStages = 8;
/// A face the region engine cannot certify at kRegionAabbRelative of the box (a cone's apex on
/// it: the atom's gradient vanishes there, and no pencil excludes a plane from a cone) moves out
/// by doubling steps up to this fraction of the box, then the caller falls back to regionAabb.
constexpr double kMaxFacePadRelative = 1e-3;

}  // namespace

std::optional<Box3> ConvexSupport::regionBox(const QuadricRegion& region, const Box3* hint) {
  using namespace tolerance_region;
  // An atom alone is bounded only as an ellipsoid, which regionAabb boxes in closed form.
  if (region.op() == QuadricRegion::Op::Atom) return std::nullopt;
  const bool have_hint = hint != nullptr && !hint->empty() && hint->lo.allFinite() && hint->hi.allFinite();
  Box3 search = have_hint ? *hint
                          : Box3{Eigen::Vector3d::Constant(-kRegionMaxExtent), Eigen::Vector3d::Constant(kRegionMaxExtent)};
  // The support value towards sign * e_axis: the support point's coordinate, or nullopt when no
  // candidate was feasible.
  auto extent = [](const ConvexSupport& s, int axis, double sign) -> std::optional<double> {
    Eigen::Vector3d e = Eigen::Vector3d::Zero();
    e[axis] = sign;
    bool found = false;
    const Eigen::Vector3d x = s.regionSupport(e, &found);
    if (!found || !std::isfinite(x[axis])) return std::nullopt;
    return x[axis];
  };
  for (int stage = 0; stage < kBoxStages; ++stage) {
    const std::optional<ConvexSupport> s = fromRegion(region, search);
    if (!s || s->kind() != Kind::Region) return std::nullopt;  // not convex in fromRegion's sense
    Box3 next;
    for (int i = 0; i < 3; ++i) {
      const std::optional<double> up = extent(*s, i, 1.0);
      const std::optional<double> down = extent(*s, i, -1.0);
      if (!up || !down) return std::nullopt;
      next.hi[i] = std::min(*up, search.hi[i]);
      next.lo[i] = std::max(*down, search.lo[i]);
    }
    if (next.empty()) return std::nullopt;
    if (!have_hint && stage == 0) {
      // Reaching the search cube's faces: unbounded, which regionAabb reports (and names).
      const double reach = kRegionMaxExtent * (1.0 - 1e-3);
      if ((next.hi.array() >= reach).any() || (next.lo.array() <= -reach).any()) return std::nullopt;
    }
    const bool shrunk = maxEdge(next) < 0.5 * maxEdge(search);
    // Outward by kRegionAabbRelative of the box, plus the rounding of its coordinates.
    const double magnitude = std::max(next.lo.cwiseAbs().maxCoeff(), next.hi.cwiseAbs().maxCoeff());
    const Eigen::Vector3d pad = Eigen::Vector3d::Constant(
        kRegionAabbRelative * maxEdge(next) + 16.0 * std::numeric_limits<double>::epsilon() * magnitude);
    search = Box3{next.lo - pad, next.hi + pad};
    if (!shrunk) break;
  }

  // The certificate, by the region engine (independent of the enumeration above): a point of the
  // region inside the box, and none in the shell between the box and the box grown by its own
  // half-widths. The region is convex, hence connected, so it lies in the box. A face the engine
  // leaves undecided moves out by doubling steps; a point found beyond a face means the support
  // was wrong: either way regionAabb decides instead.
  if (maxEdge(search) <= 0.0) return std::nullopt;
  if (findPoint(region, search, 0).status != PointSearch::Found) return std::nullopt;
  const Eigen::Vector3d c = search.center(), h = search.halfWidth();
  const Box3 outer{c - 2.0 * h, c + 2.0 * h};
  const double edge = maxEdge(search);
  Box3 out = search;
  for (int i = 0; i < 3; ++i) {
    for (const double sign : {1.0, -1.0}) {
      Eigen::Vector3d e = Eigen::Vector3d::Zero();
      e[i] = sign;
      const double face = sign > 0.0 ? search.hi[i] : -search.lo[i];  // e.x <= face on the box
      bool certified = false;
      for (double p = 0.0; p <= kMaxFacePadRelative * edge; p = p == 0.0 ? kRegionAabbRelative * edge : 2.0 * p) {
        // The slab e.x >= face + p, i.e. -e.x <= -(face + p), within the outer box.
        const QuadricRegion beyond =
            QuadricRegion::combine(QuadricRegion::Op::Intersection, {region, QuadricRegion::halfspace(-e, -(face + p))});
        const PointSearch status = findPoint(beyond, outer, 0).status;
        if (status == PointSearch::Found) return std::nullopt;
        if (status == PointSearch::Empty) {
          (sign > 0.0 ? out.hi[i] : out.lo[i]) = sign * (face + p);
          certified = true;
          break;
        }
      }
      if (!certified) return std::nullopt;
    }
  }
  return out;
}

}  // namespace fcl_quadric
