// Certified lower bounds of the distance for the pairs the OMPL layer advances on and whose
// distance is not exact or not available: quadric shapes of every kind (convex or not) and FCL's
// box / cylinder / cone / capsule, against each other, meshes, octrees and half-spaces.
// docs/algorithms.md section 12 ("Lower bounds"), docs/fcl_integration.md section 9.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/halfspace.h>
#include <fcl/geometry/shape/sphere.h>

#include "fcl/input_checks.h"
#include "fcl/quadric_shape_dispatch.h"
#include "fcl/shape_pieces.h"
#include "fcl_quadric/fcl/distance.h"
#include "fcl_quadric/fcl/quadric_shapes.h"
#include "fcl_quadric/geometry/convex_cover.h"
#include "fcl_quadric/geometry/convex_distance.h"
#include "fcl_quadric/geometry/ellipsoid.h"
#include "fcl_quadric/geometry/region_distance_bound.h"

namespace fcl_quadric {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

bool isEllipsoidal(const fcl::CollisionGeometry<double>* g) {
  return g->getNodeType() == fcl::GEOM_SPHERE || g->getNodeType() == fcl::GEOM_ELLIPSOID;
}

/// FCL's convex primitives without a closed-form distance in this library (their FCL distance
/// is libccd's GJK, whose error the advancement cannot use).
bool isGjkPrimitive(const fcl::CollisionGeometry<double>* g) {
  switch (g->getNodeType()) {
    case fcl::GEOM_BOX:
    case fcl::GEOM_CYLINDER:
    case fcl::GEOM_CONE:
    case fcl::GEOM_CAPSULE: return true;
    default: return false;
  }
}

/// An operand as convex pieces (local frame) posed in the world, with what the region engine
/// needs to refine a bound when the cover is not the solid itself.
struct Covered {
  std::shared_ptr<const ConvexCover> cover;  // a quadric shape's own (made once per shape)
  Eigen::Matrix3d R;
  Eigen::Vector3d p;
  const fcl::CollisionGeometry<double>* g = nullptr;
};

/// The cover of a bounded quadric shape or an FCL convex primitive; none for any other geometry.
/// \throws std::invalid_argument for an unbounded quadric shape.
std::optional<Covered> coverOf(const fcl::CollisionGeometry<double>* g, const fcl::Transform3<double>& tf,
                               const char* which) {
  std::shared_ptr<const ConvexCover> c;
  if (detail::isQuadricShape(g)) {
    const auto& q = static_cast<const QuadricShape<double>&>(*g);
    if (!q.bounded())
      throw std::invalid_argument(std::string("fcl_quadric::distanceLowerBound: ") + which +
                                  " is an unbounded quadric shape (a CSG operand only)");
    c = q.sharedConvexCover();  // (made once per shape, not per query: no copy)
  } else if (std::optional<ConvexSupport> s = detail::convexSupportOf(g, which)) {
    auto own = std::make_shared<ConvexCover>();
    own->pieces.push_back(std::move(*s));
    own->exact = true;
    c = std::move(own);
  } else {
    return std::nullopt;
  }
  return Covered{std::move(c), tf.linear(), tf.translation(), g};
}

/// min over a's pieces of GJK's certified lower bound v.w / |v| against one piece b (stops at 0).
/// Each bound holds whether or not GJK converged (a stall between a large flat face and a near one
/// leaves the relative gap above 1e-10); the support points may lie 1e-12 of the size outside the
/// solids (ConvexSupport's tolerance) and carry rounding, so 1e-11 of the pair's scale is taken
/// off, and a pair GJK does not certify separate gives 0. One GJK run per piece
/// (screenConvexPair): it stops as soon as the piece is certified beyond the best so far plus that
/// 1e-11 (the converged run would repeat those steps and keep a bound at least as large, so the
/// piece could not lower the minimum); otherwise it is the converged run and gives the bound.
double coverBound(const Covered& a, const ConvexSupport& b, const Eigen::Matrix3d& Rb, const Eigen::Vector3d& pb,
                  double cap) {
  double best = cap;
  for (const ConvexSupport& piece : a.cover->pieces) {
    const double scale = piece.size() + b.size() + (a.R * piece.center() + a.p - Rb * b.center() - pb).norm();
    const double skip_above = std::isfinite(best) ? best + 1e-11 * scale : kInf;
    const ConvexScreening s = screenConvexPair(piece, a.R, a.p, b, Rb, pb, skip_above);
    if (s.verdict == ConvexScreening::Verdict::Far) continue;
    best = std::min(best, std::max(0.0, s.lower_bound - 1e-11 * scale));
    if (best <= 0.0) return 0.0;
  }
  return best;
}

/// The box of a's pieces in the frame (Rf, pf) (six support points per piece).
Box3 coverBoxIn(const Covered& a, const Eigen::Matrix3d& Rf, const Eigen::Vector3d& pf) {
  Box3 b{Eigen::Vector3d::Constant(kInf), Eigen::Vector3d::Constant(-kInf)};
  for (const ConvexSupport& piece : a.cover->pieces) {
    const Box3 p = detail::supportBoxIn(piece, a.R, a.p, Rf, pf);
    b.lo = b.lo.cwiseMin(p.lo);
    b.hi = b.hi.cwiseMax(p.hi);
  }
  return b;
}

/// The region engine's bound of a (a quadric shape) against a piece given by its offset
/// supersets in the frame (Rf, pf): used where the cover says 0 but a is not its cover.
double engineBound(const Covered& a, const OffsetSuperset& grown, double reach, const Eigen::Matrix3d& Rf,
                   const Eigen::Vector3d& pf, double cap) {
  const auto& q = static_cast<const QuadricShape<double>&>(*a.g);
  // The piece's frame in a's: x_a = R_a^T (R_f x + p_f - p_a).
  return regionOffsetDistanceLowerBound(q.region(), q.localBox(), grown, reach, a.R.transpose() * Rf,
                                        a.R.transpose() * (pf - a.p), cap);
}

/// Two covered operands (quadric shapes or convex primitives).
double pairBound(const Covered& a, const Covered& b, double cap) {
  double best = cap;
  for (const ConvexSupport& piece : b.cover->pieces) {
    best = std::min(best, coverBound(a, piece, b.R, b.p, best));
    if (best <= 0.0) break;
  }
  if (best > 0.0 || (a.cover->exact && b.cover->exact)) return best;
  // A cover touches the other operand, but it is larger than its solid: the region engine
  // certifies a superset of a delta-neighbourhood separate (region_distance_bound.h): of the
  // convex partner, scaled about an inner ball; else (two non-convex models, or a partner without
  // an inner ball) of one operand with its atoms grown.
  const Covered& model = a.cover->exact ? b : a;
  const Covered& partner = a.cover->exact ? a : b;
  const auto& q = static_cast<const QuadricShape<double>&>(*model.g);
  auto grownBound = [&] {
    const detail::LocalSolid solid = detail::localSolid(partner.g, "partner", "fcl_quadric::distanceLowerBound");
    return regionPairDistanceLowerBound(q.region(), q.localBox(), solid.region, *solid.box,
                                        model.R.transpose() * partner.R, model.R.transpose() * (partner.p - model.p), cap);
  };
  if (!partner.cover->exact) return grownBound();
  if (isEllipsoidal(partner.g)) {
    const Eigen::Vector3d radii = partner.g->getNodeType() == fcl::GEOM_ELLIPSOID
                                      ? static_cast<const fcl::Ellipsoid<double>*>(partner.g)->radii
                                      : Eigen::Vector3d::Constant(static_cast<const fcl::Sphere<double>*>(partner.g)->radius);
    return ellipsoidRegionDistanceLowerBound(Ellipsoid(radii, partner.R, partner.p), q.region(), q.localBox(), model.R,
                                             model.p, cap);
  }
  const std::optional<double> inradius = detail::convexInradius(partner.g);
  if (!inradius) return grownBound();
  const detail::LocalSolid solid = detail::localSolid(partner.g, "partner", "fcl_quadric::distanceLowerBound");
  return regionConvexDistanceLowerBound(q.region(), q.localBox(), solid.region, *solid.box, *inradius,
                                        model.R.transpose() * partner.R, model.R.transpose() * (partner.p - model.p), cap);
}

/// One piece of a mesh or an octree (posed by Rf, pf): the cover's bound, refined by the engine
/// when a is not its cover.
double pieceBound(const Covered& a, const ConvexSupport& piece, const Eigen::Vector3d& piece_origin,
                  const std::optional<OffsetSuperset>& grown, double reach, const Eigen::Matrix3d& Rf,
                  const Eigen::Vector3d& pf, double cap) {
  const double c = coverBound(a, piece, Rf, Rf * piece_origin + pf, cap);
  if (c > 0.0 || a.cover->exact || !grown) return c;
  return engineBound(a, *grown, reach, Rf, pf, cap);
}

}  // namespace

std::optional<double> distanceLowerBound(const fcl::CollisionGeometry<double>* o1, const fcl::Transform3<double>& tf1,
                                         const fcl::CollisionGeometry<double>* o2, const fcl::Transform3<double>& tf2,
                                         double cap) {
  const char* where = "fcl_quadric::distanceLowerBound";
  if (o1 == nullptr || o2 == nullptr) throw std::invalid_argument("fcl_quadric::distanceLowerBound: null geometry");
  if (std::isnan(cap) || cap < 0.0)  // isnan first: an ordered comparison with NaN raises FE_INVALID
    throw std::invalid_argument("fcl_quadric::distanceLowerBound: cap must be >= 0, got " + std::to_string(cap));
  const bool q1 = detail::isQuadricShape(o1), q2 = detail::isQuadricShape(o2);
  auto handledPartner = [](const fcl::CollisionGeometry<double>* g) {
    return isGjkPrimitive(g) || detail::isMeshOrOcTree(g) || g->getNodeType() == fcl::GEOM_HALFSPACE;
  };
  if (!q1 && !q2 && !(isGjkPrimitive(o1) && handledPartner(o2)) && !(isGjkPrimitive(o2) && handledPartner(o1)))
    return std::nullopt;
  detail::checkPose(tf1, where, "tf1");
  detail::checkPose(tf2, where, "tf2");
  detail::checkRotation(tf1.linear(), "fcl_quadric::distanceLowerBound: rotation of tf1");
  detail::checkRotation(tf2.linear(), "fcl_quadric::distanceLowerBound: rotation of tf2");

  // The covered operand first: a quadric shape if there is one, else the GJK primitive.
  const bool swap = q1 ? false : (q2 || !isGjkPrimitive(o1));
  const fcl::CollisionGeometry<double>* ga = swap ? o2 : o1;
  const fcl::CollisionGeometry<double>* gb = swap ? o1 : o2;
  const fcl::Transform3<double>& tfa = swap ? tf2 : tf1;
  const fcl::Transform3<double>& tfb = swap ? tf1 : tf2;
  const Covered a = *coverOf(ga, tfa, swap ? "o2" : "o1");
  const Eigen::Matrix3d Rb = tfb.linear();
  const Eigen::Vector3d pb = tfb.translation();

  if (std::optional<Covered> b = coverOf(gb, tfb, swap ? "o1" : "o2")) return pairBound(a, *b, cap);

  if (gb->getNodeType() == fcl::GEOM_HALFSPACE) {
    // min over a piece of n.x - d is its support value towards -n: exact up to the support's
    // tolerance (1e-12 of the size; 1e-11 of the scale covers it).
    const auto* hs = static_cast<const fcl::Halfspace<double>*>(gb);
    const Eigen::Vector3d n = Rb * hs->n.normalized();
    const double off = hs->d / hs->n.norm() + n.dot(pb);
    double best = cap;
    for (const ConvexSupport& piece : a.cover->pieces) {
      const Eigen::Vector3d x = a.R * piece.support(-(a.R.transpose() * n)) + a.p;
      const double scale = piece.size() + (a.R * piece.center() + a.p).norm() + std::abs(off);
      best = std::min(best, std::max(0.0, n.dot(x) - off - 1e-11 * scale));
    }
    if (best > 0.0 || a.cover->exact) return best;
    // The engine against the half-space pushed out by delta, searched in a's box.
    const Box3 a_box = coverBoxIn(a, Rb, pb);
    const Eigen::Vector3d hn = hs->n.normalized();
    const double hd = hs->d / hs->n.norm();
    const OffsetSuperset grown = [hn, hd, a_box](double delta) {
      const Eigen::Vector3d pad = Eigen::Vector3d::Constant(delta + 1e-9 * (a_box.hi - a_box.lo).norm());
      return std::make_pair(QuadricRegion::halfspace(hn, hd + delta), Box3{a_box.lo - pad, a_box.hi + pad});
    };
    return engineBound(a, grown, 0.0, Rb, pb, cap);
  }

  const Box3 query = coverBoxIn(a, Rb, pb);  // a's box in the partner's frame
  // The cover's local box (its own frame) posed in the partner's frame: the six-axis node gaps.
  const Box3 local = coverBoxIn(a, a.R, a.p);
  const detail::PosedBox posed{Rb.transpose() * a.R, Rb.transpose() * (a.R * local.center() + a.p - pb),
                               local.halfWidth()};
  double best = cap;
  const bool is_mesh = detail::withMesh(gb, [&](const auto& m) {
    detail::nearestMeshTriangles(
        m, query, &posed,
        [&](int, const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2) {
          const double reach = std::max({p0.norm(), p1.norm(), p2.norm()});
          best = std::min(best, pieceBound(a, ConvexSupport::points({p0, p1, p2}), Eigen::Vector3d::Zero(),
                                           triangleOffsetSuperset(p0, p1, p2), reach, Rb, pb, best));
          return best;
        },
        [](double d) { return d <= 0.0; }, cap);
  });
  if (is_mesh) return best;
  if (gb->getObjectType() == fcl::OT_OCTREE) {
    detail::nearestOcTreeLeaves(
        *static_cast<const fcl::OcTree<double>*>(gb), query, &posed,
        [&](const Eigen::Vector3d& c, const Eigen::Vector3d& h) {
          best = std::min(best, pieceBound(a, ConvexSupport::box(h), c, boxOffsetSuperset(c, h),
                                           (c.cwiseAbs() + h).norm(), Rb, pb, best));
          return best;
        },
        [](double d) { return d <= 0.0; }, cap);
    return best;
  }
  // A quadric shape against anything else: the front door's own message.
  detail::localSolid(gb, swap ? "o1" : "o2", where);
  return std::nullopt;
}

}  // namespace fcl_quadric
