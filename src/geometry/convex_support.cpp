// Support mappings of convex solids (docs/algorithms.md section 12).
#include "fcl_quadric/geometry/convex_support.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <Eigen/Eigenvalues>

#include "geometry/convex_support_region.h"
#include "geometry/region_formula.h"
#include "algebra/dense_decompositions.h"

namespace fcl_quadric {

namespace {

[[noreturn]] __attribute__((cold, noinline)) void throwSize(double v, const char* what, bool allow_zero) {
  std::ostringstream os;
  os << "ConvexSupport: " << what << " = " << v << " must be finite and " << (allow_zero ? ">= 0" : "> 0");
  throw std::invalid_argument(os.str());
}

/// The check stays inline (the front doors make primitives' support mappings per query); the
/// message is built out of line.
inline void requireSize(double v, const char* what, bool allow_zero) {
  if (!(std::isfinite(v) && (allow_zero ? v >= 0.0 : v > 0.0))) throwSize(v, what, allow_zero);  // (no FE_INVALID on NaN)
}

/// The point of {y^T A y + 2 b.y + c <= 0} (K = 2 or 3 dimensions, A given by its
/// eigen-decomposition A = V diag(lam) V^T and bz = V^T b) where m.y is largest, when it is a
/// single smooth point of the surface: the KKT condition m = 2 mu (A y + b), mu > 0, on the
/// surface, solved in the eigenbasis. For A positive semidefinite that is the maximum over the
/// set; for an indefinite A (a cone nappe's or a hyperboloid sheet's section, or a two-sheet
/// hyperboloid) it is the maximum over the convex component it lies on, and the caller's
/// feasibility test decides whether that is the solid's. nullopt when the maximum is not attained
/// at a unique smooth point (unbounded along a null direction, a line of maximisers as on a
/// cylinder's ruling, an apex, or an empty / degenerate set): the other active sets of the
/// enumeration then hold it. `b_tol` decides whether a null direction carries a linear term (a
/// paraboloid); `r_given`, if not NaN, replaces r = b^T A^-1 b - c (a cone's sections, formed
/// without cancellation).
template <int K>
std::optional<Eigen::Matrix<double, K, 1>> smoothMax(const Eigen::Matrix<double, K, 1>& lam,
                                                     const Eigen::Matrix<double, K, K>& V,
                                                     const Eigen::Matrix<double, K, 1>& bz, double c,
                                                     const Eigen::Matrix<double, K, 1>& m, double b_tol,
                                                     double r_given = std::numeric_limits<double>::quiet_NaN()) {
  using Vec = Eigen::Matrix<double, K, 1>;
  const double lmax = lam.cwiseAbs().maxCoeff();
  if (!(lmax > 0.0)) return std::nullopt;
  const double null_tol = tolerance_support::kSupportNullEigenRelative * lmax;
  const bool indefinite = lam.minCoeff() < -null_tol;
  const Vec mz = V.transpose() * m;
  int nulls = 0, i0 = -1;
  for (int i = 0; i < K; ++i)
    if (std::abs(lam[i]) <= null_tol) {
      ++nulls;
      i0 = i;
    }
  Vec z = Vec::Zero();
  if (nulls == 0) {
    double r = -c, s = 0.0;
    for (int i = 0; i < K; ++i) {
      r += bz[i] * bz[i] / lam[i];
      s += mz[i] * mz[i] / lam[i];
    }
    if (!std::isnan(r_given)) r = r_given;
    double k = 0.0;
    if (!indefinite) {
      if (!(r > 0.0)) return std::nullopt;
      k = s > 0.0 ? std::sqrt(r / s) : 0.0;
    } else {
      // An indefinite form (a cone nappe's or a two-sheet hyperboloid's, or a section of one):
      // f(y) = 0 at mu = k / 2 needs r / s > 0; then the point is the only candidate with mu > 0.
      // r = 0 (a cone's apex, where the gradient vanishes) or r / s <= 0 (n outside the
      // asymptotic cone): no smooth maximiser; the apex is a candidate of its own.
      if (!(r * s > 0.0)) return std::nullopt;
      k = std::sqrt(r / s);
    }
    for (int i = 0; i < K; ++i) z[i] = (-bz[i] + mz[i] * k) / lam[i];
  } else {
    // A paraboloid: exactly one null direction, carrying a linear term.
    if (nulls != 1 || !(std::abs(bz[i0]) > b_tol)) return std::nullopt;
    const double two_mu = mz[i0] / bz[i0];
    if (!(two_mu > 0.0)) return std::nullopt;  // unbounded along the opening
    double rest = c;
    for (int i = 0; i < K; ++i) {
      if (i == i0) continue;
      z[i] = (mz[i] / two_mu - bz[i]) / lam[i];
      rest += lam[i] * z[i] * z[i] + 2.0 * bz[i] * z[i];
    }
    z[i0] = -rest / (2.0 * bz[i0]);
  }
  const Vec y = V * z;
  if (!y.allFinite()) return std::nullopt;
  return y;
}

/// Collects the atoms of a conjunction (signed as the region uses them); false if the formula is
/// not a conjunction.
bool collectConjunction(const QuadricRegion& r, bool negate, std::vector<Eigen::Matrix4d>* atoms) {
  using Op = QuadricRegion::Op;
  const auto& ch = r.children();
  switch (r.op()) {
    case Op::Atom:
      atoms->push_back(negate ? Eigen::Matrix4d(-r.matrix()) : r.matrix());
      return true;
    case Op::Intersection:
      if (negate && ch.size() != 1) return false;
      for (const auto& c : ch)
        if (!collectConjunction(c, negate, atoms)) return false;
      return true;
    case Op::Union:
      if (!negate && ch.size() != 1) return false;
      for (const auto& c : ch)  // complement of a union: the conjunction of the complements
        if (!collectConjunction(c, negate, atoms)) return false;
      return true;
    case Op::Difference:
      if (negate) return false;
      if (!collectConjunction(ch[0], false, atoms)) return false;
      for (std::size_t i = 1; i < ch.size(); ++i)
        if (!collectConjunction(ch[i], true, atoms)) return false;
      return true;
  }
  return false;
}

}  // namespace

ConvexSupport ConvexSupport::ellipsoid(const Eigen::Vector3d& radii) {
  for (int i = 0; i < 3; ++i) requireSize(radii[i], "ellipsoid radius", false);
  ConvexSupport s;
  s.kind_ = Kind::Ellipsoid;
  s.dims_ = radii;
  s.size_ = radii.norm();
  if (radii[0] == radii[1] && radii[1] == radii[2]) s.radius_ = radii[0];  // a sphere: its centre grown
  return s;
}

ConvexSupport ConvexSupport::box(const Eigen::Vector3d& half_sides) {
  for (int i = 0; i < 3; ++i) requireSize(half_sides[i], "box half side", false);
  ConvexSupport s;
  s.kind_ = Kind::Box;
  s.dims_ = half_sides;
  s.size_ = half_sides.norm();
  return s;
}

ConvexSupport ConvexSupport::ellipticCylinder(double a, double b, double half_length) {
  requireSize(a, "cylinder semi-axis a", false);
  requireSize(b, "cylinder semi-axis b", false);
  requireSize(half_length, "cylinder half length", true);
  ConvexSupport s;
  s.kind_ = Kind::EllipticCylinder;
  s.dims_ = Eigen::Vector3d(a, b, half_length);
  s.size_ = s.dims_.norm();
  return s;
}

ConvexSupport ConvexSupport::cone(double radius, double half_length) {
  requireSize(radius, "cone radius", false);
  requireSize(half_length, "cone half length", true);
  ConvexSupport s;
  s.kind_ = Kind::Cone;
  s.dims_ = Eigen::Vector3d(radius, radius, half_length);
  s.center_ = Eigen::Vector3d(0, 0, -0.5 * half_length);  // inside: on the axis, below the middle
  s.size_ = s.dims_.norm();
  return s;
}

ConvexSupport ConvexSupport::capsule(double radius, double half_length) {
  requireSize(radius, "capsule radius", false);
  requireSize(half_length, "capsule half length", true);
  ConvexSupport s;
  s.kind_ = Kind::Capsule;
  s.dims_ = Eigen::Vector3d(radius, radius, half_length);
  s.size_ = Eigen::Vector3d(radius, radius, half_length + radius).norm();
  s.radius_ = radius;  // its segment grown
  return s;
}

ConvexSupport ConvexSupport::points(const std::vector<Eigen::Vector3d>& pts) {
  if (pts.empty() || pts.size() > 8)
    throw std::invalid_argument("ConvexSupport::points: expected 1..8 points, got " + std::to_string(pts.size()));
  ConvexSupport s;
  s.kind_ = Kind::Points;
  s.points_ = pts;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (!pts[i].allFinite())
      throw std::invalid_argument("ConvexSupport::points: point " + std::to_string(i) + " is not finite");
    mean += pts[i];
  }
  mean /= static_cast<double>(pts.size());
  s.center_ = mean;
  for (const auto& p : pts) s.size_ = std::max(s.size_, (p - mean).norm());
  return s;
}

namespace {

/// The vertices of the polytope {h_k.x <= d_k} (every vertex where three planes meet, kept when
/// it satisfies the others to kSupportFeasibilityRelative of the size). The planes include the
/// region's bounding box, so the polytope is bounded.
std::vector<Eigen::Vector3d> polytopeVertices(const std::vector<Eigen::Vector3d>& h, const std::vector<double>& d,
                                              double length) {
  std::vector<Eigen::Vector3d> out;
  const std::size_t np = h.size();
  for (std::size_t i = 0; i < np; ++i)
    for (std::size_t j = i + 1; j < np; ++j)
      for (std::size_t k = j + 1; k < np; ++k) {
        Eigen::Matrix3d M;
        M << h[i].transpose(), h[j].transpose(), h[k].transpose();
        const double det = M.determinant();
        if (!(std::abs(det) > 1e-12)) continue;  // unit normals: nearly dependent planes
        const Eigen::Vector3d x = M.inverse() * Eigen::Vector3d(d[i], d[j], d[k]);
        bool inside = x.allFinite();
        for (std::size_t m = 0; m < np && inside; ++m)
          inside = h[m].dot(x) - d[m] <= tolerance_support::kSupportFeasibilityRelative * (x.norm() + std::abs(d[m]) + length);
        if (inside) out.push_back(x);
      }
  return out;
}

}  // namespace

/// An indefinite curved atom (lam[0] < 0 < lam[1] <= lam[2], A normalised) is convex on the
/// region's side only as one nappe of the cone r = 0 or one sheet of the two-sheet hyperboloid
/// r < 0, where f(x) = (x - x0)^T A (x - x0) - r, x0 = -A^-1 b, r = b^T A^-1 b - c: {f <= 0} is
/// then two convex components, one on each side of the plane v.(x - x0) = 0 (v the negative
/// eigenvector). The region is convex when its planes (the box included) keep it on one side:
/// every vertex of their polytope has v.(x - x0) of one sign, up to kSupportFeasibilityRelative
/// of the size plus that product's rounding (a cone clipped through its apex). r > 0 (a one-sheet
/// hyperboloid, connected and not convex) or vertices on both sides: false. Sets `cone` and
/// `apex` for r = 0 to 16 eps of f's terms (the apex is a candidate of its own: the gradient
/// vanishes there), else `r` for the sheet's smooth point.
bool ConvexSupport::acceptIndefinite(RegionData* g, double length) {
  const RegionData::Curved& cv = g->curved;
  // The centre x0 = -A^-1 b in the eigenbasis, refined by one Newton step; then r = -f(x0).
  // f is stationary at x0, so x0's error enters r only to second order, and r carries just the
  // rounding of f's evaluation, ~eps times its terms (`mag`). Formed as b^T A^-1 b - c instead,
  // r would carry A's conditioning times eps |x0|^2: a cone whose apex sits off the frame's
  // origin could pass for a hyperboloid, and a waist or a sheet's gap of 1e-6 |x0| for a cone
  // (an audit of session 37: support values 6.7e-7 of the size off).
  auto centreStep = [&](const Eigen::Vector3d& residual) {
    const Eigen::Vector3d z = cv.V.transpose() * residual;
    return Eigen::Vector3d(cv.V * Eigen::Vector3d(z[0] / cv.lam[0], z[1] / cv.lam[1], z[2] / cv.lam[2]));
  };
  Eigen::Vector3d x0 = centreStep(-g->b);
  x0 += centreStep(-(g->A * x0 + g->b));
  const Eigen::Vector3d x_abs = x0.cwiseAbs();
  const double mag = x_abs.dot(g->A.cwiseAbs() * x_abs) + 2.0 * g->b.cwiseAbs().dot(x_abs) + std::abs(g->c);
  const double r = -(x0.dot(g->A * x0) + 2.0 * g->b.dot(x0) + g->c);
  // A cone when r is within 16 eps of its terms (the input's own resolution: a waist below
  // ~1e-7 |x0| cannot be told from an apex in double); above, a one-sheet hyperboloid (not convex).
  const double r_tol = 16.0 * std::numeric_limits<double>::epsilon() * mag;
  if (!std::isfinite(r) || !x0.allFinite() || r > r_tol) return false;
  const Eigen::Vector3d v = cv.V.col(0);
  // The side test's band: 1e-12 of the size (a sliver of the other nappe no larger is
  // accepted), plus the rounding of v.(x - x0), a few eps of |x| + |x0|.
  const double tol = tolerance_support::kSupportFeasibilityRelative * length + 1e-15 * x0.norm();
  bool below = false, above = false;
  for (const Eigen::Vector3d& x : polytopeVertices(g->plane_h, g->plane_d, length)) {
    const double side = v.dot(x - x0);
    const double band = tol + 1e-15 * x.norm();
    below = below || side < -band;
    above = above || side > band;
  }
  if (below && above) return false;  // both components: not convex
  g->cone = r >= -r_tol;
  g->apex = x0;
  g->r = g->cone ? 0.0 : r;
  return true;
}

std::optional<ConvexSupport> ConvexSupport::fromRegion(const QuadricRegion& region, const Box3& box, BoxRole role) {
  if (box.empty() || !box.lo.allFinite() || !box.hi.allFinite())
    throw std::invalid_argument("ConvexSupport::fromRegion: the bounding box is empty or not finite");
  std::vector<Eigen::Matrix4d> atoms;
  if (!collectConjunction(region, false, &atoms)) return std::nullopt;
  ConvexSupport s;
  s.kind_ = Kind::Region;
  const auto g = std::make_shared<RegionData>();
  s.center_ = box.center();
  s.size_ = box.halfWidth().norm();
  auto addPlane = [&s, &g](Eigen::Vector3d h, double d, double quad) {
    const double n = h.norm();
    h /= n;
    d /= n;
    for (std::size_t k = 0; k < g->plane_h.size(); ++k)  // drop exact repeats (the box's own faces)
      if ((g->plane_h[k] - h).cwiseAbs().maxCoeff() <= 1e-14 &&
          std::abs(g->plane_d[k] - d) <= 1e-14 * (std::abs(d) + s.size_ + s.center_.norm()))
        return;
    g->plane_h.push_back(h);
    g->plane_d.push_back(d);
    g->plane_quad.push_back(quad / n);
  };
  const double reach = box.lo.cwiseAbs().cwiseMax(box.hi.cwiseAbs()).norm();  // |x| over the box
  for (const Eigen::Matrix4d& M : atoms) {
    const Eigen::Matrix3d A = M.topLeftCorner<3, 3>();
    const Eigen::Vector3d b = M.topRightCorner<3, 1>();
    const double c = M(3, 3);
    // isPlanarAtom drops a quadratic part up to 1e-14 |b|, relative to b alone: over the box it
    // moves the surface by up to 3 max|A_ij| |x|^2 / |2 b|. Where that exceeds the feasibility
    // tolerance the atom stays curved (a paraboloid of radius 2e7 clipped 1e5 from the origin,
    // planar by the relative test, reached 4e-5 beyond its plane: an audit of session 42).
    const double amax = A.cwiseAbs().maxCoeff();
    if (detail::isPlanarAtom(M) &&
        (amax == 0.0 || 3.0 * amax * reach * reach <= tolerance_support::kSupportFeasibilityRelative *
                                                          (s.size_ + s.center_.norm()) * 2.0 * b.norm())) {
      if (b.norm() == 0.0) {
        if (c <= 0.0) continue;  // the whole space
        return std::nullopt;     // empty (the shapes' constructors reject empty regions)
      }
      addPlane(2.0 * b, -c, 3.0 * amax);  // 2 b.x + c <= 0, up to the dropped x^T A x
      continue;
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(A, Eigen::EigenvaluesOnly);
    const double lmax = es.eigenvalues().cwiseAbs().maxCoeff();
    if (g->has_curved) return std::nullopt;  // two curved atoms: no closed-form support here
    // Positive semidefinite up to rounding, or clearly indefinite with two clearly positive
    // eigenvalues: one nappe of a cone or one sheet of a two-sheet hyperboloid, checked below once
    // the planes are known (acceptIndefinite()). Anything between (a negative eigenvalue within
    // kSupportNullEigenRelative of the largest but beyond rounding: a cone of aspect >= 1e6, which
    // passed as a slab and got a support outside the solid, an audit of session 37) is refused.
    const double null_tol = tolerance_support::kSupportNullEigenRelative * lmax;
    const double lmin = es.eigenvalues()[0];
    if (lmin < -tolerance_support::kSupportIndefiniteRelative * lmax &&
        !(lmin < -null_tol && es.eigenvalues()[1] > null_tol))
      return std::nullopt;
    g->has_curved = true;
    g->A = A / lmax;
    g->b = b / lmax;
    g->c = c / lmax;
  }
  g->own_planes = g->plane_h.size();
  for (int i = 0; i < 3; ++i) {
    Eigen::Vector3d e = Eigen::Vector3d::Zero();
    e[i] = 1.0;
    addPlane(e, box.hi[i], 0.0);
    addPlane(-e, -box.lo[i], 0.0);
  }
  g->support_planes = g->plane_h.size();
  if (g->has_curved) {
    // Everything about the curved atom and its planar sections that does not depend on n.
    const double length = s.size_ + s.center_.norm();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(g->A);
    g->curved.lam = es.eigenvalues();
    g->curved.V = es.eigenvectors();
    g->curved.bz = es.eigenvectors().transpose() * g->b;
    g->curved.b_tol = 1e-12 * (g->b.norm() + g->curved.lam.cwiseAbs().maxCoeff() * length);
    if (g->curved.lam[0] < -tolerance_support::kSupportNullEigenRelative * g->curved.lam.cwiseAbs().maxCoeff() &&
        !acceptIndefinite(g.get(), length))
      return std::nullopt;
    for (std::size_t i = 0; i < g->plane_h.size(); ++i) {
      // The plane h.x = d as x0 + U y (U orthonormal, h unit).
      const Eigen::Vector3d& h = g->plane_h[i];
      RegionData::Section sec;
      sec.x0 = g->plane_d[i] * h;
      const Eigen::Vector3d t = std::abs(h.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
      const Eigen::Vector3d u1 = (t - t.dot(h) * h).normalized();
      sec.U << u1, h.cross(u1);
      const Eigen::Matrix2d A2 = sec.U.transpose() * g->A * sec.U;
      const Eigen::Vector2d b2 = sec.U.transpose() * (g->A * sec.x0 + g->b);
      const detail::SymmetricEigen2 es2 = detail::selfAdjointEigen(A2);
      sec.lam = es2.values;
      sec.V = es2.vectors;
      sec.bz = es2.vectors.transpose() * b2;
      sec.c = sec.x0.dot(g->A * sec.x0) + 2.0 * g->b.dot(sec.x0) + g->c;
      sec.b_tol = 1e-12 * (b2.norm() + sec.lam.cwiseAbs().maxCoeff() * length);
      if (g->cone && sec.lam.cwiseAbs().minCoeff() > tolerance_support::kSupportNullEigenRelative * sec.lam.cwiseAbs().maxCoeff()) {
        // With the apex a = x0 + U y_a + delta h, the cone f(x) = (x - a)^T A (x - a) restricted to
        // the plane is (y - y_a)^T A2 (y - y_a) - 2 delta (y - y_a)^T g + delta^2 h^T A h, g = U^T A h,
        // whose r is delta^2 (g^T A2^-1 g - h^T A h): no cancellation, and exactly 0 for a plane
        // through the apex. Formed from b2 and c, r would carry the rounding of c (~eps |x0|^2 |A|),
        // and near a plane through the apex (the clip that selects a nappe) k = sqrt(r / s) would
        // turn it into a spurious section point ~sqrt(eps) of the size away from the apex.
        const double delta = h.dot(g->apex) - g->plane_d[i];
        const Eigen::Vector2d gz = sec.V.transpose() * (sec.U.transpose() * (g->A * h));
        const double sigma = gz[0] * gz[0] / sec.lam[0] + gz[1] * gz[1] / sec.lam[1] - h.dot(g->A * h);
        sec.r = delta * delta * sigma;
      }
      g->sections.push_back(sec);
    }
  }
  s.region_ = g;
  if (role == BoxRole::Contains && g->own_planes < g->plane_h.size()) {
    // The box contains the region, so the region's own constraints bound it and the box's faces
    // are redundant: max n.x over the region is attained at a candidate of its own constraints.
    // They were 6 of a clipped cone's 8 planes, and the enumeration is cubic in the planes
    // (pairs, each clipped by the rest): skipping them made its support 5-7 times faster.
    // The precondition is checked: the region cut by the box grown by its largest half-width on
    // every side must reach no farther than the box towards +-x, +-y, +-z. The region is convex,
    // so a point of it outside the box would put one of it between the two boxes, beyond a face
    // along some axis; and a region its own constraints leave unbounded reaches the grown box.
    // If not (or if the grown box makes the region non-convex here), the faces stay.
    const double grow = box.halfWidth().maxCoeff();
    const Box3 grown{box.lo - Eigen::Vector3d::Constant(grow), box.hi + Eigen::Vector3d::Constant(grow)};
    const std::optional<ConvexSupport> wide =
        grow > 0.0 ? fromRegion(region, grown, BoxRole::Clips) : std::optional<ConvexSupport>();
    const double slack = 1e-9 * (s.size_ + s.center_.norm());
    bool contained = grow > 0.0 && wide.has_value();
    for (int i = 0; i < 6 && contained; ++i) {
      Eigen::Vector3d e = Eigen::Vector3d::Zero();
      e[i / 2] = i % 2 == 0 ? 1.0 : -1.0;
      bool found = false;
      const Eigen::Vector3d x = wide->regionSupport(e, &found);
      contained = found && (x - box.hi).maxCoeff() <= slack && (box.lo - x).maxCoeff() <= slack;
    }
    if (contained) g->support_planes = g->own_planes;
  }
  // A probe: every direction of the 3 x 3 x 3 stencil must find a feasible candidate. None is
  // found when the atom is beyond the enumeration's resolution (a cone of aspect ratio 1e7, whose
  // eigenvalues +-1e-14 of the largest pass for a positive semidefinite slab: the support was
  // the box centre, outside the solid, and a sphere inside it was reported apart; an audit of
  // session 37); such a region is refused, and answered as a non-convex shape. Only for a
  // curved atom with two near-null eigenvalues (a slab's, or beyond resolution) or an indefinite
  // one: the branch and bound makes the other kinds per node.
  int near_null = 0;
  for (int i = 0; i < 3 && g->has_curved; ++i)
    near_null += std::abs(g->curved.lam[i]) <= tolerance_support::kSupportNullEigenRelative * g->curved.lam.cwiseAbs().maxCoeff();
  const bool probe = g->has_curved && (near_null >= 2 || g->curved.lam[0] < 0.0);
  for (int i = 0; i < 27 && probe; ++i) {
    if (i == 13) continue;  // the stencil's centre, (0, 0, 0)
    bool found = false;
    s.regionSupport(Eigen::Vector3d(i % 3 - 1, (i / 3) % 3 - 1, i / 9 - 1), &found);
    if (!found) return std::nullopt;
  }
  return s;
}

namespace {
/// sqrt(x^2 + y^2), with std::hypot's protection only where the squares leave the normal range
/// (GJK calls the supports in its inner loop, and hypot costs several times the square root).
inline double planarLength(double x, double y) {
  const double q = x * x + y * y;
  if (q > 1e-300 && q < 1e300) return std::sqrt(q);
  return std::hypot(x, y);
}
}  // namespace

std::optional<Eigen::Vector3d> ConvexSupport::apex() const {
  if (kind_ == Kind::Cone) return Eigen::Vector3d(0, 0, dims_.z());
  if (kind_ == Kind::Region && region_->cone) return region_->apex;
  return std::nullopt;
}

Eigen::Vector3d ConvexSupport::support(const Eigen::Vector3d& n) const {
  switch (kind_) {
    case Kind::Ellipsoid: {
      const Eigen::Vector3d rn = dims_.cwiseProduct(n);
      const double len = rn.norm();
      if (!(len > 0.0)) return Eigen::Vector3d::Zero();
      return dims_.cwiseProduct(rn) / len;
    }
    case Kind::Box:
      return Eigen::Vector3d(n.x() >= 0 ? dims_.x() : -dims_.x(), n.y() >= 0 ? dims_.y() : -dims_.y(),
                             n.z() >= 0 ? dims_.z() : -dims_.z());
    case Kind::EllipticCylinder: {
      const double ax = dims_.x() * n.x(), by = dims_.y() * n.y();
      const double len = planarLength(ax, by);
      Eigen::Vector3d p(0, 0, n.z() >= 0 ? dims_.z() : -dims_.z());
      if (len > 0.0) {
        p.x() = dims_.x() * ax / len;
        p.y() = dims_.y() * by / len;
      }
      return p;
    }
    case Kind::Cone: {
      const double r = dims_.x(), h = dims_.z();
      const double nxy = planarLength(n.x(), n.y());
      const Eigen::Vector3d apex(0, 0, h);
      Eigen::Vector3d rim(0, 0, -h);
      if (nxy > 0.0) {
        rim.x() = r * n.x() / nxy;
        rim.y() = r * n.y() / nxy;
      }
      return n.dot(apex) >= n.dot(rim) ? apex : rim;
    }
    case Kind::Capsule: {
      const double len = n.norm();
      Eigen::Vector3d p(0, 0, n.z() >= 0 ? dims_.z() : -dims_.z());
      if (len > 0.0) p += (dims_.x() / len) * n;
      return p;
    }
    case Kind::Points: {
      std::size_t best = 0;
      double v = n.dot(points_[0]);
      for (std::size_t i = 1; i < points_.size(); ++i) {
        const double w = n.dot(points_[i]);
        if (w > v) {
          v = w;
          best = i;
        }
      }
      return points_[best];
    }
    case Kind::Region: return regionSupport(n);
  }
  return center_;
}

Eigen::Vector3d ConvexSupport::coreSupport(const Eigen::Vector3d& n) const {
  if (radius_ == 0.0) return support(n);
  if (kind_ == Kind::Capsule) return Eigen::Vector3d(0, 0, n.z() >= 0 ? dims_.z() : -dims_.z());
  return Eigen::Vector3d::Zero();  // a sphere's centre
}

// KKT enumeration (file comment): every extreme point of the region is the unique smooth maximum
// of the curved atom, of one of its planar sections, or an end of a line where two planes meet,
// clipped by all other constraints; the best feasible candidate is the support.
Eigen::Vector3d ConvexSupport::regionSupport(const Eigen::Vector3d& n, bool* found) const {
  if (found) *found = true;
  constexpr double kFeas = tolerance_support::kSupportFeasibilityRelative;
  const RegionData& g = *region_;
  const double length = size_ + center_.norm();
  const std::size_t np = g.support_planes;  // the box's faces only when it clips (BoxRole)
  auto curvedValue = [&](const Eigen::Vector3d& x, double* mag) {
    *mag = x.cwiseAbs().dot(g.A.cwiseAbs() * x.cwiseAbs()) + 2.0 * g.b.cwiseAbs().dot(x.cwiseAbs()) + std::abs(g.c);
    return x.dot(g.A * x) + 2.0 * g.b.dot(x) + g.c;
  };
  auto feasible = [&](const Eigen::Vector3d& x) {
    if (!x.allFinite()) return false;
    const double xn = x.norm();
    for (std::size_t k = 0; k < np; ++k)
      if (g.plane_h[k].dot(x) - g.plane_d[k] > kFeas * (xn + std::abs(g.plane_d[k]) + length)) return false;
    if (g.has_curved) {
      double mag = 0.0;
      if (curvedValue(x, &mag) > kFeas * mag) return false;
    }
    return true;
  };
  double best = -std::numeric_limits<double>::infinity();
  Eigen::Vector3d best_x = center_;
  auto consider = [&](const Eigen::Vector3d& x) {
    const double v = n.dot(x);
    if (v > best && feasible(x)) {
      best = v;
      best_x = x;
    }
  };
  if (g.has_curved) {
    if (g.cone) {
      consider(g.apex);  // a vertex of the solid when the planes keep it
    } else if (auto x = smoothMax<3>(g.curved.lam, g.curved.V, g.curved.bz, g.c, n, g.curved.b_tol, g.r)) {
      // The maximum over the curved atom alone (over its convex component, for a two-sheet
      // hyperboloid: the point with outward normal n): if the planes keep it, it is the maximum
      // over the whole solid (which it bounds), and no other candidate can beat it.
      if (feasible(*x)) return *x;
    }
    for (std::size_t i = 0; i < np; ++i) {
      const RegionData::Section& sec = g.sections[i];
      if (auto y = smoothMax<2>(sec.lam, sec.V, sec.bz, sec.c, Eigen::Vector2d(sec.U.transpose() * n), sec.b_tol, sec.r))
        consider(sec.x0 + sec.U * *y);
    }
  }
  for (std::size_t i = 0; i < np; ++i) {
    for (std::size_t j = i + 1; j < np; ++j) {
      const Eigen::Vector3d& hi = g.plane_h[i];
      const Eigen::Vector3d& hj = g.plane_h[j];
      const Eigen::Vector3d u = hi.cross(hj);
      const double un2 = u.squaredNorm();
      if (!(un2 > 1e-24)) continue;  // parallel planes (unit normals)
      // The point of both planes nearest the origin: x0 = (d_i (hj x u) + d_j (u x hi)) / |u|^2.
      const Eigen::Vector3d x0 = (g.plane_d[i] * hj.cross(u) + g.plane_d[j] * u.cross(hi)) / un2;
      double lo = -std::numeric_limits<double>::infinity(), hiT = std::numeric_limits<double>::infinity();
      bool empty = false;
      for (std::size_t k = 0; k < np && !empty; ++k) {
        if (k == i || k == j) continue;
        const double a = g.plane_h[k].dot(u);
        const double r = g.plane_d[k] - g.plane_h[k].dot(x0);
        if (std::abs(a) <= 1e-14 * std::sqrt(un2)) {
          if (r < -kFeas * (x0.norm() + std::abs(g.plane_d[k]) + length)) empty = true;
        } else if (a > 0) {
          hiT = std::min(hiT, r / a);
        } else {
          lo = std::max(lo, r / a);
        }
      }
      if (empty) continue;
      if (g.has_curved) {
        // q(t) = qa t^2 + 2 qb t + qc <= 0 along x0 + t u.
        const double qa = u.dot(g.A * u), qb = u.dot(g.A * x0 + g.b);
        double mag = 0.0;
        const double qc = curvedValue(x0, &mag);
        const double qa_tol = tolerance_support::kSupportNullEigenRelative * un2;
        if (qa > qa_tol) {
          const double disc = qb * qb - qa * qc;
          if (disc < 0.0) continue;
          const double sq = std::sqrt(disc);
          // Stable roots: t1 = (-qb - sign(qb) sq) / qa, t2 = qc / (qa t1).
          const double q = -(qb + std::copysign(sq, qb));
          double t1 = q / qa, t2 = q != 0.0 ? qc / q : t1;
          if (t1 > t2) std::swap(t1, t2);
          lo = std::max(lo, t1);
          hiT = std::min(hiT, t2);
        } else if (qa < -qa_tol) {
          // An indefinite atom (a cone nappe, a hyperboloid sheet): f <= 0 outside the roots,
          // (-inf, t1] and [t2, inf). The planes keep the solid in one of them (acceptIndefinite),
          // but which one depends on the line: the ends of both pieces within [lo, hiT] are
          // candidates, and feasibility rejects those of the other component.
          const double disc = qb * qb - qa * qc;
          if (disc > 0.0 && lo <= hiT) {
            const double sq = std::sqrt(disc);
            const double q = -(qb + std::copysign(sq, qb));
            double t1 = q / qa, t2 = q != 0.0 ? qc / q : t1;
            if (t1 > t2) std::swap(t1, t2);
            const double s = n.dot(u);
            auto piece = [&](double a, double b) {  // the piece [a, b] of the line, if not empty
              if (!(a <= b)) return;
              if (s >= 0.0 && std::isfinite(b)) consider(x0 + b * u);
              if (s <= 0.0 && std::isfinite(a)) consider(x0 + a * u);
            };
            piece(lo, std::min(hiT, t1));
            piece(std::max(lo, t2), hiT);
            continue;
          }
          // disc <= 0: f <= 0 along the whole line; [lo, hiT] stands.
        } else if (std::abs(qb) > 1e-14 * (std::sqrt(un2) * (x0.norm() + length) + std::abs(qc))) {
          const double t0 = -qc / (2.0 * qb);
          if (qb > 0) hiT = std::min(hiT, t0);
          else lo = std::max(lo, t0);
        } else if (qc > kFeas * mag) {
          continue;
        }
      }
      if (lo > hiT) {
        // Allow a rounding-size inversion (a vertex met by several planes).
        if (lo - hiT > kFeas * (x0.norm() + length) / std::sqrt(un2)) continue;
        hiT = lo = 0.5 * (lo + hiT);
      }
      const double s = n.dot(u);
      const double t = s >= 0.0 ? hiT : lo;
      if (!std::isfinite(t)) continue;
      consider(x0 + t * u);
      if (s == 0.0 && std::isfinite(lo)) consider(x0 + lo * u);
    }
  }
  if (found) *found = best > -std::numeric_limits<double>::infinity();
  return best_x;
}

}  // namespace fcl_quadric
