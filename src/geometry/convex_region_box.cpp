// The certified bounding box of a convex region from its support mapping (convex_support.h,
// ConvexSupport::regionBox; docs/algorithms.md section 12, "Bounding boxes of convex regions").
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Dense>

#include "fcl_quadric/geometry/convex_support.h"
#include "algebra/input_checks.h"
#include "geometry/convex_support_region.h"
#include "geometry/nonnegative_multipliers.h"

namespace fcl_quadric {

namespace {

/// Stages of the support box: each stage's box bounds the next stage's enumeration, so that the
/// feasibility tolerance (relative to the box) ends up relative to the region's own size. From
/// the +-kRegionMaxExtent cube a region of size 1e-6 needs three.
constexpr int kBoxStages = 8;
/// A face the region engine cannot certify at kRegionAabbRelative of the box (a cone's apex on
/// it: the atom's gradient vanishes there, and no pencil excludes a plane from a cone) moves out
/// by doubling steps up to this fraction of the box, then the caller falls back to regionAabb.
constexpr double kMaxFacePadRelative = 1e-3;
/// The rounding unit of the duality bound's terms: a generous multiple of the double's epsilon
/// (each term is a short sum of products; docs/algorithms.md section 12).
constexpr double kDualRounding = 64.0 * std::numeric_limits<double>::epsilon();
/// At most this many constraints enter the multiplier search (those with the smallest slack);
/// subsets of up to three of them are tried (three normals span the space: Caratheodory).
constexpr int kDualMaxConstraints = 6;

}  // namespace

// dualSupportBound: weak duality (docs/algorithms.md section 12, "Bounding boxes of convex
// regions"). With multipliers lambda >= 0 (the curved atom f) and mu_k >= 0 (the planes
// h_k.y <= d_k), write e = lambda grad f(x) + sum mu_k h_k + r. For y in the region and in
// `outer`:
//   grad f(x).(y - x) = f(y) - f(x) - (y - x)^T A (y - x) <= rho_f - f(x) + nu |y - x|^2,
//   h_k.(y - x) <= d_k - h_k.x + rho_k + q_k X^2 (q_k: a dropped quadratic part, plane_quad),
// with rho the rounding of the stored (normalised) constraints against the region's own, and nu
// A's most negative eigenvalue (0 up to rounding: A is positive semidefinite). Hence
//   e.y <= e.x + lambda (rho_f - f(x) + nu D^2) + sum mu_k (d_k - h_k.x + rho_k) + |r| D,
// D the diameter of `outer`. Any non-negative multipliers give a valid bound; those of the
// support point's KKT system make it tight.
std::optional<double> ConvexSupport::dualSupportBound(const Eigen::Vector3d& e, const Eigen::Vector3d& x,
                                                      const Box3& outer) const {
  constexpr double u = kDualRounding;
  if (kind_ != Kind::Region || !detail::allFinite(e)) return std::nullopt;
  const RegionData& g = *region_;
  const double e_norm = e.norm();
  // The tangent-plane inequality of f needs f convex: not for a cone nappe or a hyperboloid
  // sheet (convex only on one component), which the engine certifies instead.
  // (fromRegion accepts a curved atom otherwise only as positive semidefinite, its smallest
  // eigenvalue >= -kSupportIndefiniteRelative of the largest: `nu` below.)
  if (g.has_curved && (g.cone || std::isfinite(g.r))) return std::nullopt;
  if (!detail::allFinite(x) || !detail::allFinite(outer.lo) || !detail::allFinite(outer.hi) ||
      (x.array() < outer.lo.array()).any() || (x.array() > outer.hi.array()).any())
    return std::nullopt;
  const double D = (outer.hi - outer.lo).norm();
  const double X = outer.lo.cwiseAbs().cwiseMax(outer.hi.cwiseAbs()).norm();  // |y| <= X in outer
  const Eigen::Vector3d xa = x.cwiseAbs();
  struct Constraint {
    Eigen::Vector3d grad;  // computed gradient
    double grad_err;       // bound of its rounding
    double slack;          // upper bound of grad_exact.(y - x) over the region in outer
  };
  std::array<Constraint, kDualMaxConstraints> all;
  int n = 0;
  auto add = [&](const Constraint& c) {
    // A vanishing gradient (the centre of a slab or a ball) cannot carry a multiplier.
    if (!(c.slack >= 0.0) || !std::isfinite(c.slack) || !detail::allFinite(c.grad) || !(c.grad.norm() > 0.0)) return;
    if (n < kDualMaxConstraints) {
      all[n++] = c;
      return;
    }
    // Keep the kDualMaxConstraints of smallest slack.
    int worst = 0;
    for (int i = 1; i < n; ++i)
      if (all[i].slack > all[worst].slack) worst = i;
    if (c.slack < all[worst].slack) all[worst] = c;
  };
  if (g.has_curved) {
    const Eigen::Matrix3d absA = g.A.cwiseAbs();
    const Eigen::Vector3d absb = g.b.cwiseAbs();
    const double mag_x = xa.dot(absA * xa) + 2.0 * absb.dot(xa) + std::abs(g.c);
    const double mag_outer = X * X * absA.norm() + 2.0 * absb.norm() * X + std::abs(g.c);
    const double fx = x.dot(g.A * x) + 2.0 * g.b.dot(x) + g.c;
    const double nu = std::max(0.0, -g.curved.lam[0]) + u;  // A normalised: largest |eigenvalue| 1
    Constraint c;
    c.grad = 2.0 * (g.A * x + g.b);
    c.grad_err = 2.0 * u * (absA * xa + absb).norm();
    c.slack = (u * mag_outer) + (-fx + u * mag_x) + nu * D * D;
    add(c);
  }
  for (std::size_t k = 0; k < g.own_planes; ++k) {
    const Eigen::Vector3d& h = g.plane_h[k];
    const double d = g.plane_d[k];
    Constraint c;
    c.grad = h;
    c.grad_err = 0.0;
    c.slack = (d - h.dot(x)) + u * (x.norm() + std::abs(d)) + u * (X + std::abs(d)) + g.plane_quad[k] * X * X;
    add(c);
  }
  std::optional<double> best;
  // Every subset of one to three constraints: least-squares multipliers, kept when non-negative.
  detail::forEachNonNegativeCombination(
      n, [&](int i) { return all[i].grad; }, e,
      [&](const int idx[3], int k, const Eigen::Matrix<double, 3, Eigen::Dynamic>& G, const Eigen::VectorXd& mu) {
        const Eigen::Vector3d r = e - G * mu;
        double r_bound = r.norm() + u * e_norm;
        double gain = 0.0;
        for (int j = 0; j < k; ++j) {
          const Constraint& c = all[idx[j]];
          r_bound += mu[j] * (c.grad_err + u * c.grad.norm());
          gain += mu[j] * c.slack;
        }
        const double rest = gain + r_bound * D;
        const double ex = e.dot(x);
        const double bound = ex + rest + u * (e_norm * x.norm() + rest);
        if (std::isfinite(bound) && (!best || bound < *best)) best = bound;
      });
  return best;
}

std::optional<Box3> ConvexSupport::regionBox(const QuadricRegion& region, const Box3* hint) {
  using namespace tolerance_region;
  // An atom alone is bounded only as an ellipsoid, which regionAabb boxes in closed form.
  if (region.op() == QuadricRegion::Op::Atom) return std::nullopt;
  const bool have_hint =
      hint != nullptr && detail::allFinite(hint->lo) && detail::allFinite(hint->hi) && !hint->empty();
  Box3 search = have_hint
                    ? *hint
                    : Box3{Eigen::Vector3d::Constant(-kRegionMaxExtent), Eigen::Vector3d::Constant(kRegionMaxExtent)};
  // The last stage's support mapping and its support points towards +e_i (row 0) and -e_i (row 1).
  std::optional<ConvexSupport> last;
  std::array<std::array<Eigen::Vector3d, 3>, 2> points;
  for (int stage = 0; stage < kBoxStages; ++stage) {
    last = fromRegion(region, search);
    if (!last || last->kind() != Kind::Region) return std::nullopt;  // not convex in fromRegion's sense
    Box3 next;
    for (int i = 0; i < 3; ++i) {
      for (int side = 0; side < 2; ++side) {
        Eigen::Vector3d e = Eigen::Vector3d::Zero();
        e[i] = side == 0 ? 1.0 : -1.0;
        bool found = false;
        points[side][i] = last->regionSupport(e, &found);
        if (!found || !detail::allFinite(points[side][i])) return std::nullopt;
      }
      next.hi[i] = std::min(points[0][i][i], search.hi[i]);
      next.lo[i] = std::max(points[1][i][i], search.lo[i]);
    }
    if (next.empty()) return std::nullopt;
    if (!have_hint && stage == 0) {
      // Reaching the search cube's faces: unbounded, which regionAabb reports (and names).
      const double reach = kRegionMaxExtent * (1.0 - 1e-3);
      if ((next.hi.array() >= reach).any() || (next.lo.array() <= -reach).any()) return std::nullopt;
    }
    const bool shrunk = next.maxEdge() < 0.5 * search.maxEdge();
    // Outward by kRegionAabbRelative of the box, plus the rounding of its coordinates.
    const double magnitude = std::max(next.lo.cwiseAbs().maxCoeff(), next.hi.cwiseAbs().maxCoeff());
    const Eigen::Vector3d pad = Eigen::Vector3d::Constant(kRegionAabbRelative * next.maxEdge() +
                                                          16.0 * std::numeric_limits<double>::epsilon() * magnitude);
    search = Box3{next.lo - pad, next.hi + pad};
    if (!shrunk) break;
  }

  // The certificate, independent of the enumeration above: a point of the region inside the box
  // (the engine's findPoint), and none in the shell between the box and the box grown by its own
  // half-widths (`outer`). The region is convex, hence connected, so it lies in the box. Each
  // face is certified by weak duality at its support point where the curved atom is convex
  // (dualSupportBound), else by weak duality over pairs of inequalities (dualLinearBound), else
  // by the engine: region AND {e.x >= face} has no point in `outer`. A face
  // the engine leaves undecided moves out by doubling steps; a point found beyond a face means
  // the support was wrong: either way regionAabb decides instead.
  if (search.maxEdge() <= 0.0) return std::nullopt;
  if (findPoint(region, search, 0).status != PointSearch::Found) return std::nullopt;
  const Eigen::Vector3d c = search.center(), h = search.halfWidth();
  const Box3 outer{c - 2.0 * h, c + 2.0 * h};
  const double edge = search.maxEdge();
  Box3 out = search;
  for (int i = 0; i < 3; ++i) {
    for (int side = 0; side < 2; ++side) {
      const double sign = side == 0 ? 1.0 : -1.0;
      Eigen::Vector3d e = Eigen::Vector3d::Zero();
      e[i] = sign;
      const double face = sign > 0.0 ? search.hi[i] : -search.lo[i];  // e.x <= face on the box
      const std::optional<double> dual = last->dualSupportBound(e, points[side][i], outer);
      if (dual && *dual <= face) continue;
      // A cone's or a sheet's face along its caps: the duality bound over pairs of inequalities
      // (the atom with its caps' product, quadric_region.h).
      if (dualLinearBound(region, e, outer) <= face) continue;
      bool certified = false;
      for (double p = 0.0; p <= kMaxFacePadRelative * edge; p = p == 0.0 ? kRegionAabbRelative * edge : 2.0 * p) {
        // The slab e.x >= face + p, i.e. -e.x <= -(face + p), within the outer box.
        const QuadricRegion beyond = QuadricRegion::combine(QuadricRegion::Op::Intersection,
                                                            {region, QuadricRegion::halfspace(-e, -(face + p))});
        // Searched in the part of `outer` beyond the face only (the rest is excluded anyway).
        Box3 shell = outer;
        (sign > 0.0 ? shell.lo[i] : shell.hi[i]) = sign * (face + p);
        const PointSearch status = findPoint(beyond, shell, 0).status;
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

std::optional<Box3> ConvexSupport::treeBox(const QuadricRegion& region, const Box3* hint) {
  switch (region.op()) {
    case QuadricRegion::Op::Union: {
      std::optional<Box3> out;
      for (const QuadricRegion& child : region.children()) {
        const std::optional<Box3> b = treeBox(child);
        if (!b) return std::nullopt;
        if (!out) {
          out = b;
        } else {
          out->lo = out->lo.cwiseMin(b->lo);
          out->hi = out->hi.cwiseMax(b->hi);
        }
      }
      return out;
    }
    case QuadricRegion::Op::Atom: {
      // An ellipsoid (3x3 part positive definite): regionAabb's closed form, which is immediate.
      // Any other atom alone is unbounded or empty, which regionAabb names for the whole region.
      if (Eigen::LLT<Eigen::Matrix3d>(region.matrix().topLeftCorner<3, 3>()).info() != Eigen::Success)
        return std::nullopt;
      try {
        return regionAabb(region);
      } catch (const std::invalid_argument&) {
        return std::nullopt;
      }
    }
    case QuadricRegion::Op::Intersection:
    case QuadricRegion::Op::Difference: return regionBox(region, hint);
  }
  return std::nullopt;
}

}  // namespace fcl_quadric
