#include "fcl_quadric/geometry/sphere_solid.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <optional>
#include <stdexcept>
#include <string>

#include "fcl_quadric/geometry/point_ellipsoid.h"
#include "fcl_quadric/tolerances.h"

namespace fcl_quadric {

namespace {

/// The sphere's centre and radius, checked.
void checkSphere(const Eigen::Vector3d& c, double r) {
  detail::checkLength(r, "sphere radius");
  detail::checkPosition(c, "sphere centre");
}

/// 2^-e for the exponent e of the largest of `magnitudes` (1 if all are 0): multiplying the
/// problem's lengths by it is exact and brings the largest into [1, 2), so that no square or
/// product below overflows or underflows whatever the inputs' magnitude (solids of 1e-170 and of
/// 1e155 were wrong otherwise: a session 36 audit).
double unitScale(std::initializer_list<double> magnitudes) {
  double m = 0.0;
  for (double v : magnitudes) m = std::max(m, std::fabs(v));
  if (!(m > 0.0) || !std::isfinite(m)) return 1.0;
  return std::ldexp(1.0, -std::ilogb(m));
}

/// The solid's answer for the centre, in its frame and scaled by unitScale(): the boundary point
/// nearest to the centre, the unit direction from the centre toward the solid (nearest - x
/// normalised outside; minus the outward normal of the nearest face inside), the centre's signed
/// distance (> 0 outside, <= 0 inside), and the scale of its rounding (docs/algorithms.md §12d).
struct LocalAnswer {
  Eigen::Vector3d nearest;
  Eigen::Vector3d toward;
  double point_distance;
  double scale;
};

/// The sphere's answer from the solid's (scaled by `unit`, in the frame (R, p)).
SignedDistanceResult finish(const Eigen::Vector3d& c, double r, const Eigen::Matrix3d& R, const Eigen::Vector3d& p,
                            const LocalAnswer& a, double unit) {
  SignedDistanceResult out;
  out.normal = (R * a.toward).normalized();
  out.point_b = p + R * (a.nearest / unit);
  out.point_a = c + r * out.normal;
  const double d = a.point_distance / unit - r;
  const double band = tolerance::kCertificateRelativeBoundDouble * (a.scale / unit + r);
  if (d > band) {
    out.status = Separation::Separated;
    out.distance = d;
  } else if (d < -band) {
    out.status = Separation::Overlapping;
    out.distance = d;
  } else {
    out.status = Separation::Touching;  // within the band: counts as contact
    out.distance = 0.0;
  }
  out.converged = true;
  out.iterations = 0;
  return out;
}

/// The nearest point of the segment [a, b] to q (a == b allowed).
Eigen::Vector3d nearestOnSegment(const Eigen::Vector3d& q, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d e = b - a;
  const double ee = e.squaredNorm();
  if (!(ee > 0.0)) return a;
  const double t = std::clamp((q - a).dot(e) / ee, 0.0, 1.0);
  return a + t * e;
}

/// a * d - b * c to within about one rounding of the result (Kahan's algorithm with a fused
/// multiply-add), where the plain expression loses everything to cancellation.
double differenceOfProducts(double a, double d, double b, double c) {
  const double bc = b * c;
  const double err = std::fma(-b, c, bc);
  return std::fma(a, d, -bc) + err;
}

/// u x v with each coordinate accurate to about one rounding: the normal of a nearly degenerate
/// triangle (its plain cross product's direction is off by ~eps / sin(angle)).
Eigen::Vector3d accurateCross(const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
  return Eigen::Vector3d(differenceOfProducts(u.y(), v.z(), u.z(), v.y()), differenceOfProducts(u.z(), v.x(), u.x(), v.z()),
                         differenceOfProducts(u.x(), v.y(), u.y(), v.x()));
}

/// A solid of revolution about local z seen in the meridian half-plane of the local point x:
/// (rho, z) coordinates, and the lift of a meridian vector (s, t) back to 3D.
struct Meridian {
  Eigen::Vector2d q;      // (rho, z), rho >= 0
  Eigen::Vector2d axis;   // unit radial direction of x in the local xy-plane (e_x on the axis)
  explicit Meridian(const Eigen::Vector3d& x) {
    const double rho = std::hypot(x.x(), x.y());
    q = Eigen::Vector2d(rho, x.z());
    axis = rho > 0.0 ? Eigen::Vector2d(x.x() / rho, x.y() / rho) : Eigen::Vector2d(1.0, 0.0);
  }
  Eigen::Vector3d lift(const Eigen::Vector2d& v) const { return Eigen::Vector3d(v[0] * axis[0], v[0] * axis[1], v[1]); }
};

/// The answer for a centre outside the solid: the direction from the difference nearest - x,
/// except within the touching band of the boundary, where that difference is rounding noise and
/// `fallback` (a unit direction toward the solid in the normal cone of the nearest feature) is
/// used instead. `scale`: the rounding scale other than the distance itself.
LocalAnswer outside(const Eigen::Vector3d& x, const Eigen::Vector3d& nearest, const Eigen::Vector3d& fallback,
                    double scale) {
  const Eigen::Vector3d diff = nearest - x;
  const double dist = diff.norm();
  if (!(dist > tolerance::kCertificateRelativeBoundDouble * scale)) return {nearest, fallback, dist, scale + dist};
  return {nearest, diff / dist, dist, scale + dist};
}

// The solids in their frames, scaled by unitScale(); x the centre there. The rounding scale of
// each answer: |x| (its coordinates' rounding, that of R^T (c - p) included) plus the distance's
// magnitude (of the subtraction that gives it), plus for the cone the terms of its slant-line
// distance.

LocalAnswer boxLocal(const Eigen::Vector3d& half, const Eigen::Vector3d& x) {
  const double scale = x.norm();
  const Eigen::Vector3d excess = x.cwiseAbs() - half;  // > 0 on the outer side of a face
  const int beyond = static_cast<int>((excess.array() > 0.0).count());
  if (beyond == 1) {
    // A face region: the distance and direction exact along the axis (no square root).
    int k = 0;
    excess.maxCoeff(&k);
    Eigen::Vector3d nearest = x;
    nearest[k] = x[k] > 0.0 ? half[k] : -half[k];
    return {nearest, Eigen::Vector3d::Unit(k) * (x[k] > 0.0 ? -1.0 : 1.0), excess[k], scale + excess[k]};
  }
  if (beyond > 1) {
    // An edge or a vertex: the fallback is minus the sum of the outward normals of the faces beyond.
    Eigen::Vector3d fallback = Eigen::Vector3d::Zero();
    for (int i = 0; i < 3; ++i)
      if (excess[i] > 0.0) fallback[i] = x[i] > 0.0 ? -1.0 : 1.0;
    return outside(x, x.cwiseMax(-half).cwiseMin(half), fallback.normalized(), scale);
  }
  // Inside: the nearest face is the one of largest excess (all <= 0).
  int k = 0;
  const double depth = excess.maxCoeff(&k);
  const double side = x[k] >= 0.0 ? 1.0 : -1.0;
  Eigen::Vector3d nearest = x;
  nearest[k] = side * half[k];
  return {nearest, -side * Eigen::Vector3d::Unit(k), depth, scale - depth};
}

LocalAnswer capsuleLocal(double radius, double length, const Eigen::Vector3d& x) {
  const double h = 0.5 * length;
  const Eigen::Vector3d on_axis(0.0, 0.0, std::clamp(x.z(), -h, h));
  const Eigen::Vector3d from_axis = x - on_axis;
  const double rho = from_axis.norm();
  // Unit direction from the axis to the centre (any radial one when the centre is on the axis).
  const Eigen::Vector3d out_dir = rho > 0.0 ? Eigen::Vector3d(from_axis / rho) : Eigen::Vector3d::UnitX();
  const double d = rho - radius;
  return {on_axis + radius * out_dir, -out_dir, d, x.norm() + std::fabs(d)};
}

LocalAnswer cylinderLocal(double radius, double length, const Eigen::Vector3d& x) {
  const Meridian m(x);
  const double scale = x.norm();
  const double h = 0.5 * length;
  const double zside = m.q[1] >= 0.0 ? 1.0 : -1.0;
  const double side_excess = m.q[0] - radius;       // > 0 outside the side
  const double cap_excess = std::fabs(m.q[1]) - h;  // > 0 beyond the cap on the centre's side
  if (side_excess > 0.0 && cap_excess > 0.0) {      // nearest the rim circle
    const Eigen::Vector3d fallback = m.lift(Eigen::Vector2d(-1.0, -zside)).normalized();
    return outside(x, m.lift(Eigen::Vector2d(radius, zside * h)), fallback, scale);
  }
  // A face: the side when outside it, or inside with the side the nearer face; else the cap.
  if (side_excess > 0.0 || (cap_excess <= 0.0 && side_excess >= cap_excess)) {
    return {m.lift(Eigen::Vector2d(radius, m.q[1])), m.lift(Eigen::Vector2d(-1.0, 0.0)), side_excess,
            scale + std::fabs(side_excess)};
  }
  return {m.lift(Eigen::Vector2d(m.q[0], zside * h)), Eigen::Vector3d(0.0, 0.0, -zside), cap_excess,
          scale + std::fabs(cap_excess)};
}

LocalAnswer coneLocal(double radius, double length, const Eigen::Vector3d& x) {
  // A cone of radius 0 is its axis segment, one of length 0 its base disk: no interior.
  if (radius == 0.0) return capsuleLocal(0.0, length, x);
  if (length == 0.0) return cylinderLocal(radius, 0.0, x);
  const Meridian m(x);
  const double h = 0.5 * length;
  // The meridian triangle: apex A, rim corner B, base centre (0, -h); the slant edge's outward
  // unit normal (2h, R) / |(2h, R)|, the base's (0, -1).
  const Eigen::Vector2d A(0.0, h), B(radius, -h);
  const Eigen::Vector2d slant_normal = Eigen::Vector2d(length, radius) / std::hypot(length, radius);
  const double s_slant = (m.q - A).dot(slant_normal);  // signed distance to the slant line
  // The rounding of s_slant is that of its two terms, rho n_0 and (z - h) n_1 (each of its
  // differences exact to one rounding of itself), not of the cone's size: a flat cone (R = 1e155,
  // L = 1) 9.5 above its apex was "touching" with the size in the scale (a session 36 audit).
  const double scale = x.norm() + std::fabs(m.q[0] * slant_normal[0]) + std::fabs((m.q[1] - h) * slant_normal[1]);
  const double s_base = -h - m.q[1];                   // ... and to the base plane
  const Eigen::Vector3d to_base = Eigen::Vector3d::UnitZ();
  auto slant = [&] {
    return LocalAnswer{m.lift(m.q - s_slant * slant_normal), m.lift(-slant_normal), s_slant, scale + std::fabs(s_slant)};
  };
  auto base = [&] { return LocalAnswer{m.lift(Eigen::Vector2d(m.q[0], -h)), to_base, s_base, scale + std::fabs(s_base)}; };
  if (s_slant <= 0.0 && s_base <= 0.0) {
    // Inside: the nearer of the slant side and the base (from inside, the projection onto the
    // nearer edge's line lies on the edge).
    return s_slant >= s_base ? slant() : base();
  }
  // Outside. Facing the base disk: the base is nearest, along the axis.
  if (s_base > 0.0 && m.q[0] <= radius) return base();
  // Facing the slant side (the projection inside the edge): nearest along its normal.
  const Eigen::Vector2d e = B - A;
  const double t = (m.q - A).dot(e) / e.squaredNorm();
  if (s_slant > 0.0 && t > 0.0 && t < 1.0) return slant();
  // Otherwise a vertex of the meridian triangle: the apex or the rim circle. Fallbacks: -e_z is
  // in the apex's normal cone, minus the bisector of the slant and base normals in the rim's.
  if ((m.q - A).squaredNorm() <= (m.q - B).squaredNorm()) return outside(x, m.lift(A), -Eigen::Vector3d::UnitZ(), scale);
  const Eigen::Vector2d rim_cone = (slant_normal + Eigen::Vector2d(0.0, -1.0)).normalized();
  return outside(x, m.lift(B), m.lift(-rim_cone), scale);
}

/// The answer for a capped elliptic cylinder { u^2/a^2 + v^2/b^2 <= 1, |w| <= h } (scaled by
/// unitScale()), with a bracket [lower, upper] of the centre's signed distance. Outside the
/// infinite cylinder the nearest point is (y, clamp(x_z)), y the ellipse's point nearest to
/// (x_x, x_y) (detail::closestPointPrincipal<2>: the 2D problem separates from the caps, since the
/// solid is the product of the filled ellipse and [-h, h]). There the bracket is certified
/// whatever y's accuracy: lower = (m.x - h_K(m)) / |m| along m = x - nearest, with the support
/// function h_K(m) = |(a m_x, b m_y)| + h |m_z| (weak duality: every point of K is at least that
/// far from x along m), and upper = |x - nearest| plus |y| max(0, g(y) - 1), g the ellipse's
/// form (y scaled onto the ellipse is a point of K that much closer). Facing a cap the answer is
/// exact. Inside, the nearer of the side (the ellipse's interior distance, the same solver) and the
/// cap; the bracket is then the value itself (the status is certain there; the depth's accuracy is
/// the solver's, a few eps of the scale, checked against a 50-digit oracle in the tests).
struct CylinderAnswer {
  LocalAnswer answer;
  double lower, upper;
};

/// u^2/a^2 + v^2/b^2: the ellipse's form (<= 1 inside).
double ellipseForm(double a, double b, double u, double v) { return (u / a) * (u / a) + (v / b) * (v / b); }

/// The capped elliptic cylinder's support function h_K(m) = |(a m_x, b m_y)| + h |m_z|.
double ellipticCylinderSupport(double a, double b, double h, const Eigen::Vector3d& m) {
  return std::sqrt((a * m.x()) * (a * m.x()) + (b * m.y()) * (b * m.y())) + h * std::fabs(m.z());
}

CylinderAnswer ellipticCylinderLocal(double a, double b, double length, const Eigen::Vector3d& x) {
  const double h = 0.5 * length;
  const double scale = x.norm();
  const Eigen::Vector2d q(x.x(), x.y());
  const double zside = x.z() >= 0.0 ? 1.0 : -1.0;
  const double cap_excess = std::fabs(x.z()) - h;  // > 0 beyond the cap on the centre's side
  const Eigen::Vector3d cap_normal(0.0, 0.0, zside);
  const double form = ellipseForm(a, b, q.x(), q.y());
  // The side's outward unit normal at a point y of the ellipse: (y_x / a^2, y_y / b^2) normalised.
  auto sideNormal = [&](const Eigen::Vector2d& y) {
    const Eigen::Vector3d n((y.x() / a) / a, (y.y() / b) / b, 0.0);
    const double len = n.norm();
    return len > 0.0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::UnitX();
  };
  if (form <= 1.0 && cap_excess > 0.0) {
    // Facing a cap: its distance along the axis, exactly.
    const LocalAnswer ans{Eigen::Vector3d(q.x(), q.y(), zside * h), -cap_normal, cap_excess, scale + cap_excess};
    return {ans, cap_excess, cap_excess};
  }
  Eigen::Vector2d y;
  const double side = detail::closestPointPrincipal<2>(Eigen::Vector2d(a, b), q, &y);
  if (form <= 1.0) {
    // Inside: the nearer face, the side (depth -side >= 0) or the cap (depth -cap_excess).
    const double side_depth = std::max(0.0, -side);
    if (side_depth <= -cap_excess) {
      const LocalAnswer ans{Eigen::Vector3d(y.x(), y.y(), x.z()), -sideNormal(y), -side_depth, scale + side_depth};
      return {ans, -side_depth, -side_depth};
    }
    const LocalAnswer ans{Eigen::Vector3d(q.x(), q.y(), zside * h), -cap_normal, cap_excess, scale - cap_excess};
    return {ans, cap_excess, cap_excess};
  }
  // Outside the infinite cylinder: the side, or the rim when beyond a cap too.
  const Eigen::Vector3d nearest(y.x(), y.y(), std::clamp(x.z(), -h, h));
  Eigen::Vector3d fallback = sideNormal(y);
  if (cap_excess > 0.0) fallback += cap_normal;
  const LocalAnswer ans = outside(x, nearest, -fallback.normalized(), scale);
  // The bracket. m points from the solid to the centre (the fallback's reverse at distance 0).
  const Eigen::Vector3d m = ans.point_distance > 0.0 ? Eigen::Vector3d(x - nearest) : Eigen::Vector3d(-ans.toward);
  const double lower = (m.dot(x) - ellipticCylinderSupport(a, b, h, m)) / m.norm();
  const double form_y = ellipseForm(a, b, y.x(), y.y());
  const double upper = ans.point_distance + y.norm() * std::max(0.0, form_y - 1.0);
  return {ans, lower, upper};
}

/// The triangle (0, u, v) (scaled) and the centre x relative to its first vertex.
LocalAnswer triangleLocal(const Eigen::Vector3d& u, const Eigen::Vector3d& v, const Eigen::Vector3d& x) {
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  const double scale = x.norm();
  // The normal from an accurate cross product: for a nearly degenerate triangle the plain one's
  // direction is off by ~eps / sin(angle), and the height x.n with it (a session 36 audit: a
  // centre 0.04 deep in a sliver was reported 0.5 away).
  const Eigen::Vector3d n = accurateCross(u, v);
  const double nn = n.squaredNorm();
  if (nn > 0.0) {
    // The projection onto the plane is inside when the three sub-triangles it makes with the
    // edges are oriented as the triangle: (e_i x (x - p_i)) . n >= 0 (the projection drops out of
    // these triple products; each cross product accurate as above).
    const bool inside = accurateCross(u, x).dot(n) >= 0.0 && accurateCross(v - u, x - u).dot(n) >= 0.0 &&
                        accurateCross(-v, x - v).dot(n) >= 0.0;
    if (inside) {
      const Eigen::Vector3d unit_n = n / std::sqrt(nn);
      const double height = x.dot(unit_n);
      // Toward the triangle: against the side the centre is on (+n when on it).
      const Eigen::Vector3d toward = height > 0.0 ? Eigen::Vector3d(-unit_n) : unit_n;
      return {x - height * unit_n, toward, std::fabs(height), scale + std::fabs(height)};
    }
  }
  // The nearest point of the three edges (a degenerate triangle is its edges).
  Eigen::Vector3d best = nearestOnSegment(x, zero, u);
  for (const Eigen::Vector3d& q : {nearestOnSegment(x, u, v), nearestOnSegment(x, v, zero)})
    if ((q - x).squaredNorm() < (best - x).squaredNorm()) best = q;
  // Fallback within the band: across the triangle (its normal, on the centre's side), or across
  // the longest edge of a degenerate one.
  Eigen::Vector3d across;
  if (nn > 0.0) {
    const Eigen::Vector3d unit_n = n / std::sqrt(nn);
    across = x.dot(unit_n) > 0.0 ? Eigen::Vector3d(-unit_n) : unit_n;
  } else {
    Eigen::Vector3d e = u.squaredNorm() >= v.squaredNorm() ? u : v;
    if ((v - u).squaredNorm() > e.squaredNorm()) e = v - u;
    across = e.squaredNorm() > 0.0 ? e.unitOrthogonal() : Eigen::Vector3d::UnitX();
  }
  return outside(x, best, across, scale);
}

}  // namespace

SignedDistanceResult signedDistanceSphereBox(const Eigen::Vector3d& c, double r, const Eigen::Vector3d& half_extents,
                                             const Eigen::Matrix3d& R_WB, const Eigen::Vector3d& p_WB) {
  checkSphere(c, r);
  for (int i = 0; i < 3; ++i) detail::checkLength(half_extents[i], "box half extent", nullptr, i);
  const Eigen::Matrix3d R = detail::storedRotation(R_WB, "box rotation");
  detail::checkPosition(p_WB, "box centre");
  const Eigen::Vector3d x = R.transpose() * (c - p_WB);
  const double unit = unitScale({x.cwiseAbs().maxCoeff(), half_extents.maxCoeff()});
  return finish(c, r, R, p_WB, boxLocal(unit * half_extents, unit * x), unit);
}

namespace {

/// The names a round solid's checks give its values in their messages.
struct RoundSolidNames {
  const char* noun;      ///< "<noun> radius" / "<noun> length"
  const char* rotation;  ///< "<noun> rotation"
  const char* centre;    ///< "<noun> centre"
};

/// A round solid (capsule, cylinder, cone: a radius and a length about local z) checked, the
/// centre brought into its frame and scaled, and `local`'s answer there turned into the sphere's.
template <class Local>
SignedDistanceResult roundSolid(const Eigen::Vector3d& c, double r, double radius, double length,
                                const Eigen::Matrix3d& R_W, const Eigen::Vector3d& p_W, const RoundSolidNames& names,
                                Local local) {
  checkSphere(c, r);
  detail::checkLength(radius, names.noun, "radius");
  detail::checkLength(length, names.noun, "length");
  const Eigen::Matrix3d R = detail::storedRotation(R_W, names.rotation);
  detail::checkPosition(p_W, names.centre);
  const Eigen::Vector3d x = R.transpose() * (c - p_W);
  const double unit = unitScale({x.cwiseAbs().maxCoeff(), radius, length});
  return finish(c, r, R, p_W, local(unit * radius, unit * length, unit * x), unit);
}

}  // namespace

SignedDistanceResult signedDistanceSphereCapsule(const Eigen::Vector3d& c, double r, double radius, double length,
                                                 const Eigen::Matrix3d& R_WC, const Eigen::Vector3d& p_WC) {
  return roundSolid(c, r, radius, length, R_WC, p_WC, {"capsule", "capsule rotation", "capsule centre"}, capsuleLocal);
}

SignedDistanceResult signedDistanceSphereCylinder(const Eigen::Vector3d& c, double r, double radius, double length,
                                                  const Eigen::Matrix3d& R_WC, const Eigen::Vector3d& p_WC) {
  return roundSolid(c, r, radius, length, R_WC, p_WC, {"cylinder", "cylinder rotation", "cylinder centre"},
                    cylinderLocal);
}

SignedDistanceResult signedDistanceSphereCone(const Eigen::Vector3d& c, double r, double radius, double length,
                                              const Eigen::Matrix3d& R_WC, const Eigen::Vector3d& p_WC) {
  return roundSolid(c, r, radius, length, R_WC, p_WC, {"cone", "cone rotation", "cone centre"}, coneLocal);
}

namespace detail {

namespace {

/// sphereEllipticCylinder() with the centre already in the cylinder's frame, x = R^T (c - p).
SignedDistanceResult sphereEllipticCylinderAt(const Eigen::Vector3d& c, double r, double a, double b, double length,
                                              const Eigen::Matrix3d& R, const Eigen::Vector3d& p,
                                              const Eigen::Vector3d& x) {
  const double unit = unitScale({x.cwiseAbs().maxCoeff(), a, b, length});
  const CylinderAnswer local = ellipticCylinderLocal(unit * a, unit * b, unit * length, unit * x);
  SignedDistanceResult out = finish(c, r, R, p, local.answer, unit);
  // The status from the bracket: Separated only when its lower end clears the band, Overlapping
  // only when its upper end does; a bracket wider than the band (the root not converged: not
  // expected) leaves Touching with converged = false, which callers treat as undecided.
  const double band = tolerance::kCertificateRelativeBoundDouble * (local.answer.scale / unit + r);
  const double lower = local.lower / unit - r, upper = local.upper / unit - r;
  if (lower > band) {
    out.status = Separation::Separated;
    out.distance = local.answer.point_distance / unit - r;
  } else if (upper < -band) {
    out.status = Separation::Overlapping;
    out.distance = local.answer.point_distance / unit - r;
  } else {
    out.status = Separation::Touching;
    out.distance = 0.0;
    out.converged = upper - lower <= band;
  }
  return out;
}

}  // namespace

SignedDistanceResult sphereEllipticCylinder(const Eigen::Vector3d& c, double r, double a, double b, double length,
                                            const Eigen::Matrix3d& R, const Eigen::Vector3d& p) {
  return sphereEllipticCylinderAt(c, r, a, b, length, R, p, R.transpose() * (c - p));
}

std::optional<bool> sphereEllipticCylinderContact(const Eigen::Vector3d& c, double r, double a, double b,
                                                  double length, const Eigen::Matrix3d& R, const Eigen::Vector3d& p,
                                                  Eigen::Vector3d* common) {
  const Eigen::Vector3d x = R.transpose() * (c - p);
  const double unit = unitScale({x.cwiseAbs().maxCoeff(), a, b, length, r});
  const Eigen::Vector3d xs = unit * x;
  const double as = unit * a, bs = unit * b, hs = 0.5 * unit * length, rs = unit * r;
  // The band of these two tests: 2^-40 of every length involved (their sums, products and the
  // square root round to a few eps of it).
  const double band = tolerance::kCertificateRelativeBoundDouble * (xs.norm() + as + bs + hs + rs);
  // Apart along the centre's own direction m = x: every point of the solid is at least
  // (|x|^2 - h_K(x)) / |x| from the centre along it (the support function of section 12d).
  const double n2 = xs.squaredNorm();
  if (n2 > 0.0) {
    if ((n2 - ellipticCylinderSupport(as, bs, hs, xs)) / std::sqrt(n2) - rs > band) return false;
  }
  // The centre inside the solid with a margin: a common point.
  const double form = ellipseForm(as, bs, xs.x(), xs.y());
  if (form < 1.0 - tolerance::kCertificateRelativeBoundDouble && std::fabs(xs.z()) < hs - band) {
    *common = c;
    return true;
  }
  const SignedDistanceResult d = sphereEllipticCylinderAt(c, r, a, b, length, R, p, x);
  if (d.status == Separation::Separated) return false;
  if (d.status == Separation::Touching && !d.converged) return std::nullopt;
  // Within r of the centre (up to the band): the cylinder's point nearest to it, or the centre
  // itself when it is inside.
  *common = d.distance + r <= 0.0 ? c : d.point_b;
  return true;
}

}  // namespace detail

SignedDistanceResult signedDistanceSphereEllipticCylinder(const Eigen::Vector3d& c, double r, double a, double b,
                                                          double length, const Eigen::Matrix3d& R_WC,
                                                          const Eigen::Vector3d& p_WC) {
  checkSphere(c, r);
  detail::checkLength(a, "elliptic cylinder", "semi-axis a");
  detail::checkLength(b, "elliptic cylinder", "semi-axis b");
  detail::checkLength(length, "elliptic cylinder", "length");
  if (!(a > 0.0)) throw std::invalid_argument("elliptic cylinder semi-axis a must be > 0, got " + std::to_string(a));
  if (!(b > 0.0)) throw std::invalid_argument("elliptic cylinder semi-axis b must be > 0, got " + std::to_string(b));
  const Eigen::Matrix3d R = detail::storedRotation(R_WC, "elliptic cylinder rotation");
  detail::checkPosition(p_WC, "elliptic cylinder centre");
  return detail::sphereEllipticCylinder(c, r, a, b, length, R, p_WC);
}

SignedDistanceResult signedDistanceSphereTriangle(const Eigen::Vector3d& c, double r, const Eigen::Vector3d& a,
                                                  const Eigen::Vector3d& b, const Eigen::Vector3d& t) {
  checkSphere(c, r);
  detail::checkPosition(a, "triangle vertex a");
  detail::checkPosition(b, "triangle vertex b");
  detail::checkPosition(t, "triangle vertex c");
  // Relative to a (the frame of finish(): identity rotation, origin a).
  const Eigen::Vector3d x = c - a, u = b - a, v = t - a;
  const double unit = unitScale({x.cwiseAbs().maxCoeff(), u.cwiseAbs().maxCoeff(), v.cwiseAbs().maxCoeff()});
  return finish(c, r, Eigen::Matrix3d::Identity(), a, triangleLocal(unit * u, unit * v, unit * x), unit);
}

SignedDistanceResult signedDistanceSphereSphere(const Eigen::Vector3d& c_a, double r_a, const Eigen::Vector3d& c_b,
                                                double r_b) {
  checkSphere(c_a, r_a);
  checkSphere(c_b, r_b);
  const Eigen::Vector3d delta = c_b - c_a;
  const double unit = unitScale({delta.cwiseAbs().maxCoeff()});
  const double dist = (unit * delta).norm() / unit;  // (scaled: no underflow of the squares)
  SignedDistanceResult out;
  out.normal = dist > 0.0 ? Eigen::Vector3d(delta / dist) : Eigen::Vector3d::UnitX();
  out.point_a = c_a + r_a * out.normal;
  out.point_b = c_b - r_b * out.normal;
  const double d = dist - (r_a + r_b);
  const double band = tolerance::kCertificateRelativeBoundDouble * (dist + r_a + r_b);
  out.status = d > band ? Separation::Separated : d < -band ? Separation::Overlapping : Separation::Touching;
  out.distance = out.status == Separation::Touching ? 0.0 : d;
  out.converged = true;
  return out;
}

}  // namespace fcl_quadric
