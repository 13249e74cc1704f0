#include "fcl_quadric/geometry/sphere_solid.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "fcl_quadric/tolerances.h"

namespace fcl_quadric {

namespace {

void checkNonNegative(double v, const std::string& what) {
  if (!std::isfinite(v) || !(v >= 0.0)) {
    std::ostringstream os;
    os << what << " must be finite and >= 0, got " << v;
    throw std::invalid_argument(os.str());
  }
}

/// The sphere's centre and radius, checked.
void checkSphere(const Eigen::Vector3d& c, double r) {
  checkNonNegative(r, "sphere radius");
  detail::checkPosition(c, "sphere centre");
}

/// The point's answer in the solid's frame, turned into the sphere's (docs/algorithms.md §12d).
/// nearest: the solid's boundary point nearest to the centre (local); toward: the unit direction
/// from the centre toward the solid (local: nearest - x normalised outside, minus the outward
/// normal of the nearest face inside); point_distance: signed distance of the centre (> 0
/// outside, <= 0 inside).
SignedDistanceResult finish(const Eigen::Vector3d& c, double r, const Eigen::Matrix3d& R, const Eigen::Vector3d& p,
                            const Eigen::Vector3d& nearest, const Eigen::Vector3d& toward, double point_distance,
                            double scale) {
  SignedDistanceResult out;
  out.normal = (R * toward).normalized();
  out.point_b = p + R * nearest;
  out.point_a = c + r * out.normal;
  const double d = point_distance - r;
  const double band = tolerance::kCertificateRelativeBoundDouble * scale;
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
/// `fallback` (a unit direction toward the solid in the normal cone of the nearest feature, local)
/// is used instead.
SignedDistanceResult outside(const Eigen::Vector3d& c, double r, const Eigen::Matrix3d& R, const Eigen::Vector3d& p,
                             const Eigen::Vector3d& x, const Eigen::Vector3d& nearest, const Eigen::Vector3d& fallback,
                             double scale) {
  const Eigen::Vector3d diff = nearest - x;
  const double dist = diff.norm();
  if (!(dist > tolerance::kCertificateRelativeBoundDouble * scale)) return finish(c, r, R, p, nearest, fallback, dist, scale);
  return finish(c, r, R, p, nearest, diff / dist, dist, scale);
}

// The solids in their frames, x the centre there (validated by the callers).

SignedDistanceResult capsuleLocal(const Eigen::Vector3d& c, double r, double radius, double length,
                                  const Eigen::Matrix3d& R, const Eigen::Vector3d& p, const Eigen::Vector3d& x,
                                  double scale) {
  const double h = 0.5 * length;
  const Eigen::Vector3d on_axis(0.0, 0.0, std::clamp(x.z(), -h, h));
  const Eigen::Vector3d from_axis = x - on_axis;
  const double rho = from_axis.norm();
  // Unit direction from the axis to the centre (any radial one when the centre is on the axis).
  const Eigen::Vector3d out_dir = rho > 0.0 ? Eigen::Vector3d(from_axis / rho) : Eigen::Vector3d::UnitX();
  return finish(c, r, R, p, on_axis + radius * out_dir, -out_dir, rho - radius, scale);
}

SignedDistanceResult cylinderLocal(const Eigen::Vector3d& c, double r, double radius, double length,
                                   const Eigen::Matrix3d& R, const Eigen::Vector3d& p, const Eigen::Vector3d& x,
                                   double scale) {
  const Meridian m(x);
  const double h = 0.5 * length;
  const double zside = m.q[1] >= 0.0 ? 1.0 : -1.0;
  const double side_excess = m.q[0] - radius;     // > 0 outside the side
  const double cap_excess = std::fabs(m.q[1]) - h;  // > 0 beyond the cap on the centre's side
  if (side_excess > 0.0 && cap_excess > 0.0) {    // nearest the rim circle
    const Eigen::Vector3d fallback = m.lift(Eigen::Vector2d(-1.0, -zside)).normalized();
    return outside(c, r, R, p, x, m.lift(Eigen::Vector2d(radius, zside * h)), fallback, scale);
  }
  // A face: the side when outside it, or inside with the side the nearer face; else the cap.
  if (side_excess > 0.0 || (cap_excess <= 0.0 && side_excess >= cap_excess)) {
    return finish(c, r, R, p, m.lift(Eigen::Vector2d(radius, m.q[1])), m.lift(Eigen::Vector2d(-1.0, 0.0)), side_excess,
                  scale);
  }
  return finish(c, r, R, p, m.lift(Eigen::Vector2d(m.q[0], zside * h)), Eigen::Vector3d(0.0, 0.0, -zside), cap_excess,
                scale);
}

}  // namespace

SignedDistanceResult signedDistanceSphereBox(const Eigen::Vector3d& c, double r, const Eigen::Vector3d& half_extents,
                                             const Eigen::Matrix3d& R_WB, const Eigen::Vector3d& p_WB) {
  checkSphere(c, r);
  for (int i = 0; i < 3; ++i) checkNonNegative(half_extents[i], "box half extent " + std::to_string(i));
  const Eigen::Matrix3d R = detail::storedRotation(R_WB, "box rotation");
  detail::checkPosition(p_WB, "box centre");
  const Eigen::Vector3d x = R.transpose() * (c - p_WB);
  const double scale = (c - p_WB).norm() + r + half_extents.sum();
  const Eigen::Vector3d excess = x.cwiseAbs() - half_extents;  // > 0 on the outer side of a face
  if ((excess.array() > 0.0).any()) {
    const Eigen::Vector3d nearest = x.cwiseMax(-half_extents).cwiseMin(half_extents);
    const Eigen::Vector3d diff = nearest - x;
    if ((excess.array() > 0.0).count() == 1) {
      // A face region: the distance and direction are exact along the axis (no square root).
      int k = 0;
      excess.maxCoeff(&k);
      return finish(c, r, R, p_WB, nearest, Eigen::Vector3d::Unit(k) * (diff[k] > 0.0 ? 1.0 : -1.0), excess[k], scale);
    }
    // An edge or a vertex: the fallback is the sum of the outward normals of the faces beyond.
    Eigen::Vector3d fallback = Eigen::Vector3d::Zero();
    for (int i = 0; i < 3; ++i)
      if (excess[i] > 0.0) fallback[i] = x[i] > 0.0 ? -1.0 : 1.0;
    return outside(c, r, R, p_WB, x, nearest, fallback.normalized(), scale);
  }
  // Inside: the nearest face is the one of largest excess (all <= 0).
  int k = 0;
  const double depth = excess.maxCoeff(&k);
  const double side = x[k] >= 0.0 ? 1.0 : -1.0;
  Eigen::Vector3d nearest = x;
  nearest[k] = side * half_extents[k];
  return finish(c, r, R, p_WB, nearest, -side * Eigen::Vector3d::Unit(k), depth, scale);
}

SignedDistanceResult signedDistanceSphereCapsule(const Eigen::Vector3d& c, double r, double radius, double length,
                                                 const Eigen::Matrix3d& R_WC, const Eigen::Vector3d& p_WC) {
  checkSphere(c, r);
  checkNonNegative(radius, "capsule radius");
  checkNonNegative(length, "capsule length");
  const Eigen::Matrix3d R = detail::storedRotation(R_WC, "capsule rotation");
  detail::checkPosition(p_WC, "capsule centre");
  const Eigen::Vector3d x = R.transpose() * (c - p_WC);
  const double scale = (c - p_WC).norm() + r + radius + length;
  return capsuleLocal(c, r, radius, length, R, p_WC, x, scale);
}

SignedDistanceResult signedDistanceSphereCylinder(const Eigen::Vector3d& c, double r, double radius, double length,
                                                  const Eigen::Matrix3d& R_WC, const Eigen::Vector3d& p_WC) {
  checkSphere(c, r);
  checkNonNegative(radius, "cylinder radius");
  checkNonNegative(length, "cylinder length");
  const Eigen::Matrix3d R = detail::storedRotation(R_WC, "cylinder rotation");
  detail::checkPosition(p_WC, "cylinder centre");
  const Eigen::Vector3d x = R.transpose() * (c - p_WC);
  const double scale = (c - p_WC).norm() + r + radius + length;
  return cylinderLocal(c, r, radius, length, R, p_WC, x, scale);
}

SignedDistanceResult signedDistanceSphereCone(const Eigen::Vector3d& c, double r, double radius, double length,
                                              const Eigen::Matrix3d& R_WC, const Eigen::Vector3d& p_WC) {
  checkSphere(c, r);
  checkNonNegative(radius, "cone radius");
  checkNonNegative(length, "cone length");
  const Eigen::Matrix3d R = detail::storedRotation(R_WC, "cone rotation");
  detail::checkPosition(p_WC, "cone centre");
  const Eigen::Vector3d x = R.transpose() * (c - p_WC);
  const double scale = (c - p_WC).norm() + r + radius + length;
  // A cone of radius 0 is its axis segment, one of length 0 its base disk: no interior.
  if (radius == 0.0) return capsuleLocal(c, r, 0.0, length, R, p_WC, x, scale);
  if (length == 0.0) return cylinderLocal(c, r, radius, 0.0, R, p_WC, x, scale);
  const Meridian m(x);
  const double h = 0.5 * length;
  // The meridian triangle: apex A, rim corner B, base centre (0, -h); the slant edge's outward
  // unit normal (2h, R) / |(2h, R)|, the base's (0, -1).
  const Eigen::Vector2d A(0.0, h), B(radius, -h);
  const Eigen::Vector2d slant_normal = Eigen::Vector2d(length, radius).normalized();
  const double s_slant = (m.q - A).dot(slant_normal);  // signed distance to the slant line
  const double s_base = -h - m.q[1];                   // ... and to the base plane
  const Eigen::Vector3d to_base = Eigen::Vector3d::UnitZ();
  if (s_slant <= 0.0 && s_base <= 0.0) {
    // Inside: the nearer of the slant side and the base (from inside, the projection onto the
    // nearer edge's line lies on the edge).
    if (s_slant >= s_base)
      return finish(c, r, R, p_WC, m.lift(m.q - s_slant * slant_normal), m.lift(-slant_normal), s_slant, scale);
    return finish(c, r, R, p_WC, m.lift(Eigen::Vector2d(m.q[0], -h)), to_base, s_base, scale);
  }
  // Outside. Facing the base disk: the base is nearest, along the axis.
  if (s_base > 0.0 && m.q[0] <= radius)
    return finish(c, r, R, p_WC, m.lift(Eigen::Vector2d(m.q[0], -h)), to_base, s_base, scale);
  // Facing the slant side (the projection inside the edge): nearest along its normal.
  const Eigen::Vector2d e = B - A;
  const double t = (m.q - A).dot(e) / e.squaredNorm();
  if (s_slant > 0.0 && t > 0.0 && t < 1.0)
    return finish(c, r, R, p_WC, m.lift(m.q - s_slant * slant_normal), m.lift(-slant_normal), s_slant, scale);
  // Otherwise a vertex of the meridian triangle: the apex or the rim circle. Fallbacks: -e_z is
  // in the apex's normal cone, minus the bisector of the slant and base normals in the rim's.
  if ((m.q - A).squaredNorm() <= (m.q - B).squaredNorm())
    return outside(c, r, R, p_WC, x, m.lift(A), -Eigen::Vector3d::UnitZ(), scale);
  const Eigen::Vector2d rim_cone = (slant_normal + Eigen::Vector2d(0.0, -1.0)).normalized();
  return outside(c, r, R, p_WC, x, m.lift(B), m.lift(-rim_cone), scale);
}

SignedDistanceResult signedDistanceSphereTriangle(const Eigen::Vector3d& c, double r, const Eigen::Vector3d& a,
                                                  const Eigen::Vector3d& b, const Eigen::Vector3d& t) {
  checkSphere(c, r);
  detail::checkPosition(a, "triangle vertex a");
  detail::checkPosition(b, "triangle vertex b");
  detail::checkPosition(t, "triangle vertex c");
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  // Work relative to a (the frame of finish(): identity rotation, origin a).
  const Eigen::Vector3d x = c - a, u = b - a, v = t - a;
  const double scale = x.norm() + r + u.norm() + v.norm();
  const Eigen::Vector3d n = u.cross(v);
  const double nn = n.squaredNorm();
  if (nn > 0.0) {
    // The projection onto the plane, if inside the triangle (all three sub-areas non-negative).
    const double s = x.dot(n) / nn;
    const Eigen::Vector3d proj = x - s * n;
    const bool inside = (u.cross(proj)).dot(n) >= 0.0 && ((v - u).cross(proj - u)).dot(n) >= 0.0 &&
                        ((-v).cross(proj - v)).dot(n) >= 0.0;
    if (inside) {
      const Eigen::Vector3d unit_n = n / std::sqrt(nn);
      const double height = x.dot(unit_n);
      // Toward the triangle: against the side the centre is on (+n when on it).
      const Eigen::Vector3d toward = height > 0.0 ? Eigen::Vector3d(-unit_n) : unit_n;
      return finish(c, r, I, a, proj, toward, std::fabs(height), scale);
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
  return outside(c, r, I, a, x, best, across, scale);
}

}  // namespace fcl_quadric
