// QuadricSolver's double-precision kernels and its explicit instantiation for double. This file
// instantiates no FCL traversal or function matrix (those live in collision.cpp / distance.cpp).
#include "fcl_quadric/fcl/quadric_solver.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "fcl_quadric/geometry/ellipsoid_capsule.h"
#include "fcl_quadric/geometry/ellipsoid_cylinder.h"
#include "fcl_quadric/geometry/ellipsoid_plane.h"
#include "fcl_quadric/geometry/ellipsoid_polytope.h"
#include "fcl_quadric/geometry/ellipsoid_separation.h"
#include "fcl_quadric/geometry/signed_distance.h"
#include "fcl_quadric/geometry/sphere_solid.h"
#include "fcl_quadric/tolerances.h"

namespace fcl_quadric {
namespace detail {

namespace {

[[noreturn]] void rethrowNamed(const char* which, const char* shape, const std::invalid_argument& e) {
  std::ostringstream os;
  os << "fcl_quadric::QuadricSolver: " << which << " (" << shape << "): " << e.what();
  throw std::invalid_argument(os.str());
}

bool contactFrom(const SignedDistanceResult& d, ExactContact* contact) {
  if (d.status == Separation::Separated) return false;
  contact->normal = d.normal;  // from the ellipsoid to the polytope
  contact->pos = 0.5 * (d.point_a + d.point_b);
  contact->depth = -d.distance;  // 0 in the touching band
  return true;
}

bool distanceFrom(const EllipsoidPolytopeResult& cert, const SignedDistanceResult* d, ExactDistance* out) {
  if (cert.status == Separation::Overlapping) {
    out->distance = -1.0;  // libccd's ccdGJKDist2 value
    out->p1 = out->p2 = cert.closest;  // a polytope point strictly inside the ellipsoid
    return false;
  }
  out->distance = d->distance;
  out->p1 = d->point_a;
  out->p2 = d->point_b;
  return true;
}

bool signedDistanceFrom(const SignedDistanceResult& d, ExactDistance* out) {
  out->distance = d.distance;
  out->p1 = d.point_a;
  out->p2 = d.point_b;
  return d.distance >= 0.0;
}

/// One certified kernel answering all three queries (a round solid's, or the closed form of a
/// sphere: sphere_solid.h), so that its status decides each.
bool intersectFrom(const SignedDistanceResult& d, ExactContact* contact) {
  if (!contact) return d.status != Separation::Separated;
  return contactFrom(d, contact);
}

/// FCL's shapeDistance convention as distanceEllipsoids() keeps it: separated or touching, the
/// distance (0 when touching) and the witnesses; overlapping, -1 and p1 = p2 = the witnesses'
/// midpoint (in both solids when they are convex and each witness is in the other; not
/// certified in general: a ball deeper than a thin plate is thick has its deepest point beyond
/// it). (Touching pairs got -1 until session 36, an audit.)
bool unsignedDistanceFrom(const SignedDistanceResult& d, ExactDistance* out) {
  if (d.status != Separation::Overlapping) {
    signedDistanceFrom(d, out);
    return true;
  }
  out->distance = -1.0;  // libccd's convention for overlapping pairs
  out->p1 = out->p2 = 0.5 * (d.point_a + d.point_b);
  return false;
}

}  // namespace

Ellipsoid ellipsoidFromFcl(const Eigen::Vector3d& radii, const Eigen::Matrix3d& R_WE, const Eigen::Vector3d& p_WE,
                           const char* which) {
  try {
    return Ellipsoid(radii, R_WE, p_WE);
  } catch (const std::invalid_argument& e) {
    rethrowNamed(which, "fcl::Ellipsoid", e);
  }
}

void checkSphereFromFcl(double radius, const Eigen::Matrix3d& R_WS, const Eigen::Vector3d& p_WS, const char* which) {
  try {
    // (isfinite first: an ordered comparison with NaN raises FE_INVALID, which the tests trap.)
    if (!std::isfinite(radius) || !(radius >= tolerance::kMinRadius && radius <= tolerance::kMaxLength)) {
      std::ostringstream os;
      os << "sphere radius must be finite and in [" << tolerance::kMinRadius << ", " << tolerance::kMaxLength
         << "], got " << radius;
      throw std::invalid_argument(os.str());
    }
    // A sphere's rotation does not move it, but a linear part that is not a rotation (a scaling,
    // a reflection) is refused as for every other solid (session 36, an audit: it was ignored).
    fcl_quadric::detail::checkRotation(R_WS, "sphere rotation");
    fcl_quadric::detail::checkPosition(p_WS, "sphere centre");
  } catch (const std::invalid_argument& e) {
    rethrowNamed(which, "fcl::Sphere", e);
  }
}

Ellipsoid sphereFromFcl(double radius, const Eigen::Matrix3d& R_WS, const Eigen::Vector3d& p_WS, const char* which) {
  checkSphereFromFcl(radius, R_WS, p_WS, which);
  try {
    return Ellipsoid::sphere(radius, p_WS);
  } catch (const std::invalid_argument& e) {
    rethrowNamed(which, "fcl::Sphere", e);
  }
}

void throwNonFiniteTransform(const char* which, const Eigen::Matrix<double, 3, 4>& m) {
  std::ostringstream os;
  os << "fcl_quadric::QuadricSolver: transform " << which << " is not finite, [R | p] =\n" << m;
  throw std::invalid_argument(os.str());
}

namespace {
/// Two spheres (equal radii each): |c_b - c_a| - r_a - r_b in closed form (sphere_solid.h), which
/// then decides all three queries (the general search takes ~1 us and its band differed from the
/// closed form's).
SignedDistanceResult sphereSphere(const Ellipsoid& a, const Ellipsoid& b) {
  return signedDistanceSphereSphere(a.center(), a.radii()[0], b.center(), b.radii()[0]);
}
}  // namespace

bool intersectEllipsoids(const Ellipsoid& a, const Ellipsoid& b, ExactContact* contact) {
  if (isSphere(a) && isSphere(b)) return intersectFrom(sphereSphere(a, b), contact);
  // Without a contact to fill (FCL's boolean collide) the status alone decides: no certificate.
  if (separationStatus(a, b) == Separation::Separated) return false;
  if (!contact) return true;
  // signedDistance re-runs the same (deterministic) classification, so its status is cert.status
  // and its distance is <= 0 here: 0 in the touching band, minus the penetration depth otherwise.
  const SignedDistanceResult d = signedDistance(a, b);
  contact->normal = d.normal;
  contact->pos = 0.5 * (d.point_a + d.point_b);
  contact->depth = -d.distance;
  return true;
}

bool distanceEllipsoids(const Ellipsoid& a, const Ellipsoid& b, ExactDistance* out) {
  if (isSphere(a) && isSphere(b)) return unsignedDistanceFrom(sphereSphere(a, b), out);
  const SeparationCertificate cert = classifyEllipsoids(a, b);
  if (cert.status == Separation::Overlapping) {
    // GJKSolver_libccd's shapeDistance reports -1 for overlapping shapes (ccdGJKDist2); the
    // penetration depth is only computed on request (shapeSignedDistance).
    out->distance = -1.0;
    out->p1 = cert.witness;
    out->p2 = cert.witness;
    return false;
  }
  const SignedDistanceResult d = signedDistance(a, b);
  out->distance = d.distance;  // > 0 separated, 0 touching
  out->p1 = d.point_a;
  out->p2 = d.point_b;
  return true;
}

bool signedDistanceEllipsoids(const Ellipsoid& a, const Ellipsoid& b, ExactDistance* out) {
  const SignedDistanceResult d = isSphere(a) && isSphere(b) ? sphereSphere(a, b) : signedDistance(a, b);
  out->distance = d.distance;
  out->p1 = d.point_a;
  out->p2 = d.point_b;
  return d.distance >= 0.0;
}

// --- Adapters of the existing ellipsoid-ellipsoid kernels -------------------------------------

bool exactIntersect(const Ellipsoid& e, const Ellipsoid& other, ExactContact* contact) {
  return intersectEllipsoids(e, other, contact);
}
bool exactDistance(const Ellipsoid& e, const Ellipsoid& other, ExactDistance* out) {
  return distanceEllipsoids(e, other, out);
}
bool exactSignedDistance(const Ellipsoid& e, const Ellipsoid& other, ExactDistance* out) {
  return signedDistanceEllipsoids(e, other, out);
}

// --- Conversions -------------------------------------------------------------------------------

WorldPlane planeFromFcl(const Eigen::Vector3d& n, double d, bool halfspace, const Eigen::Matrix3d& R,
                        const Eigen::Vector3d& t, const char* which) {
  // fcl::transform(Plane / Halfspace, tf) followed by the constructor's unitNormalTest. The pose
  // must be rigid and within kMaxLength, as every other partner's (R n is the plane's normal only
  // for a rotation R).
  try {
    fcl_quadric::detail::checkRotation(R, "plane rotation");
    fcl_quadric::detail::checkPosition(t, "plane translation");
  } catch (const std::invalid_argument& e) {
    rethrowNamed(which, halfspace ? "fcl::Halfspace" : "fcl::Plane", e);
  }
  WorldPlane P;
  P.halfspace = halfspace;
  P.n = R * n;
  P.d = d + P.n.dot(t);
  const double l = P.n.norm();
  if (!(l > 0.0) || !std::isfinite(l) || !std::isfinite(P.d)) {
    std::ostringstream os;
    os << "fcl_quadric::QuadricSolver: " << which << " (" << (halfspace ? "fcl::Halfspace" : "fcl::Plane")
       << "): the normal must be finite and non-zero and the offset finite, got n = [" << n.transpose()
       << "], d = " << d;
    throw std::invalid_argument(os.str());
  }
  const double inv_l = 1.0 / l;
  P.n *= inv_l;
  P.d *= inv_l;
  return P;
}

WorldBox boxFromFcl(const Eigen::Vector3d& side, const Eigen::Matrix3d& R, const Eigen::Vector3d& p,
                    const char* which) {
  try {
    for (int i = 0; i < 3; ++i) fcl_quadric::detail::checkLength(side[i], "box side", nullptr, i);
    fcl_quadric::detail::checkRotation(R, "box rotation");
    fcl_quadric::detail::checkPosition(p, "box centre");
  } catch (const std::invalid_argument& e) {
    rethrowNamed(which, "fcl::Box", e);
  }
  WorldBox b;
  b.half = 0.5 * side;
  b.R = R;
  b.p = p;
  return b;
}

WorldCapsule capsuleFromFcl(double radius, double length, const Eigen::Matrix3d& R, const Eigen::Vector3d& p,
                            const char* which) {
  try {
    fcl_quadric::detail::checkLength(radius, "capsule radius");
    fcl_quadric::detail::checkLength(length, "capsule length");
    fcl_quadric::detail::checkRotation(R, "capsule rotation");
    fcl_quadric::detail::checkPosition(p, "capsule centre");
  } catch (const std::invalid_argument& e) {
    rethrowNamed(which, "fcl::Capsule", e);
  }
  WorldCapsule c;
  c.radius = radius;
  c.length = length;
  c.R = R;
  c.p = p;
  return c;
}

namespace {

/// The radius / length / rotation checks of a round solid (capsuleFromFcl's, for `shape`).
template <typename World>
World roundSolidFromFcl(double radius, double length, const Eigen::Matrix3d& R, const Eigen::Vector3d& p,
                        const char* which, const char* shape, const char* noun, const char* rotation_name,
                        const char* centre_name) {
  try {
    fcl_quadric::detail::checkLength(radius, noun, "radius");
    fcl_quadric::detail::checkLength(length, noun, "length");
    // (Literal names: building "<noun> rotation" on every call cost an allocation per query.)
    fcl_quadric::detail::checkRotation(R, rotation_name);
    fcl_quadric::detail::checkPosition(p, centre_name);
  } catch (const std::invalid_argument& e) {
    rethrowNamed(which, shape, e);
  }
  World w;
  w.radius = radius;
  w.length = length;
  w.R = R;
  w.p = p;
  return w;
}

}  // namespace

WorldCylinder cylinderFromFcl(double radius, double length, const Eigen::Matrix3d& R, const Eigen::Vector3d& p,
                              const char* which) {
  return roundSolidFromFcl<WorldCylinder>(radius, length, R, p, which, "fcl::Cylinder", "cylinder", "cylinder rotation",
                                          "cylinder centre");
}

WorldCone coneFromFcl(double radius, double length, const Eigen::Matrix3d& R, const Eigen::Vector3d& p,
                      const char* which) {
  return roundSolidFromFcl<WorldCone>(radius, length, R, p, which, "fcl::Cone", "cone", "cone rotation", "cone centre");
}

WorldConvex convexFromFcl(const std::vector<Eigen::Vector3d>& v, const std::vector<int>& faces, int face_count,
                          const Eigen::Matrix3d& R, const Eigen::Vector3d& p, const char* which) {
  WorldConvex out;
  try {
    fcl_quadric::detail::checkRotation(R, "convex rotation");
    fcl_quadric::detail::checkPosition(p, "convex translation");
    if (v.empty()) throw std::invalid_argument("convex has no vertices");
    out.vertices.reserve(v.size());  // one allocation each (the sphere's answer costs ~1 us)
    // (Each face takes at least 4 entries of the list: a bogus face_count cannot ask for more.)
    out.faces.reserve(std::min(static_cast<std::size_t>(std::max(face_count, 0)), faces.size() / 4));
    for (const Eigen::Vector3d& x : v) {
      fcl_quadric::detail::checkPosition(x, "convex vertex");
      out.vertices.push_back(R * x + p);
    }
    // FCL's flat face list: for each face its vertex count n, then n indices.
    std::size_t at = 0;
    for (int k = 0; k < face_count; ++k) {
      if (at >= faces.size() || faces[at] < 0 || at + 1 + static_cast<std::size_t>(faces[at]) > faces.size()) {
        std::ostringstream os;
        os << "convex face list ends before face " << k << " of " << face_count;
        throw std::invalid_argument(os.str());
      }
      const int n = faces[at];
      out.faces.emplace_back(faces.begin() + static_cast<std::ptrdiff_t>(at) + 1,
                             faces.begin() + static_cast<std::ptrdiff_t>(at) + 1 + n);
      at += 1 + static_cast<std::size_t>(n);
      const std::vector<int>& f = out.faces.back();
      const bool indices_ok =
          std::all_of(f.begin(), f.end(), [&](int i) { return i >= 0 && static_cast<std::size_t>(i) < v.size(); });
      if (n < 3 || !indices_ok) {
        std::ostringstream os;
        os << "convex face " << k << " needs at least 3 vertex indices in [0, " << v.size() << "), got " << n
           << " indices" << (indices_ok ? "" : " with one out of range");
        throw std::invalid_argument(os.str());
      }
    }
  } catch (const std::invalid_argument& e) {
    rethrowNamed(which, "fcl::Convex", e);
  }
  return out;
}

WorldTriangle triangleFromFcl(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  if (!a.allFinite() || !b.allFinite() || !c.allFinite()) {
    std::ostringstream os;
    os << "fcl_quadric::QuadricSolver: triangle vertices must be finite, got [" << a.transpose() << "], ["
       << b.transpose() << "], [" << c.transpose() << "]";
    throw std::invalid_argument(os.str());
  }
  return WorldTriangle{a, b, c};
}

// --- Ellipsoid against a plane or a half-space -------------------------------------------------

namespace {

/// Everything the plane and half-space answers need, from one certified classification.
struct PlaneCase {
  Separation status = Separation::Touching;
  /// Signed distance: > 0 separated, 0 in the touching band, -(penetration depth) when they
  /// overlap. Plane: |n.p - d| - h (the nearer side); half-space: (n.p - d) - h.
  double signed_distance = 0.0;
  /// Unit normal pointing from the ellipsoid to the plane / half-space.
  Eigen::Vector3d toward = Eigen::Vector3d::UnitX();
  /// The support point of the ellipsoid in direction `toward` (nearest to, or deepest into, the
  /// other solid) and its projection onto the plane.
  Eigen::Vector3d q = Eigen::Vector3d::Zero();
  Eigen::Vector3d q_on_plane = Eigen::Vector3d::Zero();
  /// FCL's contact position (see exactIntersect below).
  Eigen::Vector3d pos = Eigen::Vector3d::Zero();
};

PlaneCase planeCase(const Ellipsoid& e, const WorldPlane& P) {
  const EllipsoidPlaneResult r = classifyEllipsoidPlane(e, P.n, P.d);
  const double offset = r.centre_offset, h = r.half_width;
  PlaneCase c;
  double raw;
  if (P.halfspace) {
    // { n.x <= d }: collides iff n.p - h <= d (ellipsoidHalfspace). A Touching relation with the
    // centre on the negative side is tangency from inside: the ellipsoid is deep in the solid.
    c.toward = -P.n;
    c.q = r.farthest_negative;
    raw = offset - h;
    if (r.relation == PlaneRelation::PositiveSide) c.status = Separation::Separated;
    else if (r.relation == PlaneRelation::Touching && offset > 0.0) c.status = Separation::Touching;
    else c.status = Separation::Overlapping;
  } else {
    // FCL's ellipsoidPlaneIntersect (plane-inl.h:153-197): the side of the centre; a centre on
    // the plane (signed_dist == 0) takes +n.
    const bool positive = offset > 0.0;
    c.toward = positive ? Eigen::Vector3d(-P.n) : P.n;
    c.q = positive ? r.farthest_negative : r.farthest_positive;
    raw = std::fabs(offset) - h;
    switch (r.relation) {
      case PlaneRelation::PositiveSide:
      case PlaneRelation::NegativeSide: c.status = Separation::Separated; break;
      case PlaneRelation::Touching: c.status = Separation::Touching; break;
      case PlaneRelation::Transversal: c.status = Separation::Overlapping; break;
    }
  }
  c.signed_distance = c.status == Separation::Touching ? 0.0 : raw;
  c.q_on_plane = c.q - (P.n.dot(c.q) - P.d) * P.n;
  const double depth = -c.signed_distance;
  if (P.halfspace) {
    // halfspace-inl.h:200-208: on the segment from the centre to the deepest point, at the middle
    // of the penetrating layer: p + (q - p) (1 - depth / (2h)).
    c.pos = e.center() + (1.0 - 0.5 * depth / h) * (c.q - e.center());
  } else {
    // plane-inl.h:178-184: where the segment from the centre to q crosses the plane:
    // p + (q - p) |n.p - d| / h.
    c.pos = e.center() + (std::fabs(offset) / h) * (c.q - e.center());
  }
  return c;
}

}  // namespace

bool exactIntersect(const Ellipsoid& e, const WorldPlane& other, ExactContact* contact) {
  const PlaneCase c = planeCase(e, other);
  if (c.status == Separation::Separated) return false;
  if (contact) {
    contact->normal = c.toward;
    contact->pos = c.pos;
    contact->depth = -c.signed_distance;
  }
  return true;
}

bool exactDistance(const Ellipsoid& e, const WorldPlane& other, ExactDistance* out) {
  const PlaneCase c = planeCase(e, other);
  if (c.status == Separation::Overlapping) {
    // libccd's convention: -1; both points a point common to both solids (plane: FCL's contact
    // position, on the plane inside the ellipsoid; half-space: the deepest point).
    out->distance = -1.0;
    out->p1 = out->p2 = other.halfspace ? c.q : c.pos;
    return false;
  }
  out->distance = c.signed_distance;
  out->p1 = c.q;
  out->p2 = c.q_on_plane;
  return true;
}

bool exactSignedDistance(const Ellipsoid& e, const WorldPlane& other, ExactDistance* out) {
  const PlaneCase c = planeCase(e, other);
  out->distance = c.signed_distance;
  out->p1 = c.q;           // on the ellipsoid; the deepest point inside the other solid if they overlap
  out->p2 = c.q_on_plane;  // on the plane; p2 - p1 = distance * (normal from the ellipsoid)
  return c.signed_distance >= 0.0;
}

// --- Any convex shape against a plane or a half-space, by support points -------------------------

bool supportPlaneDistance(const SupportExtent& e, const WorldPlane& P, bool signed_distance, ExactDistance* out) {
  const double a = P.n.dot(e.lo) - P.d;  // lowest point's offset
  const double b = P.n.dot(e.hi) - P.d;  // highest point's offset
  auto onPlane = [&](const Eigen::Vector3d& x) -> Eigen::Vector3d { return x - (P.n.dot(x) - P.d) * P.n; };
  if (a > 0.0) {  // entirely on the positive side: separate from the plane and from { n.x <= d }
    out->distance = a;
    out->p1 = e.lo;
    out->p2 = onPlane(e.lo);
    return true;
  }
  if (!P.halfspace && b < 0.0) {  // entirely on the negative side of a two-sided plane
    out->distance = -b;
    out->p1 = e.hi;
    out->p2 = onPlane(e.hi);
    return true;
  }
  // Overlapping. Half-space: the deepest point is lo, depth -a. Plane: pushed out to the side of
  // the centre, as FCL's closed forms choose it (centre on the plane: +n).
  const bool up = P.halfspace || P.n.dot(e.centre) - P.d >= 0.0;
  const Eigen::Vector3d deepest = up ? e.lo : e.hi;
  if (signed_distance) {
    out->distance = up ? a : -b;
    out->p1 = deepest;
    out->p2 = onPlane(deepest);
    return false;
  }
  // libccd's convention: -1 and a point common to both solids.
  out->distance = -1.0;
  if (P.halfspace) {
    out->p1 = out->p2 = e.lo;
  } else {
    // Where the segment from lo to hi (inside the solid) crosses the plane.
    const double w = b - a;
    out->p1 = out->p2 = w > 0.0 ? Eigen::Vector3d(e.lo + (-a / w) * (e.hi - e.lo)) : onPlane(e.lo);
  }
  return false;
}

Eigen::Vector3d supportPoint(const Ellipsoid& sphere, const Eigen::Vector3d& dir) {
  return sphere.center() + sphere.radii()[0] * dir;
}

Eigen::Vector3d supportPoint(const WorldBox& box, const Eigen::Vector3d& dir) {
  const Eigen::Vector3d local = box.R.transpose() * dir;
  Eigen::Vector3d s;
  for (int i = 0; i < 3; ++i) s[i] = local[i] >= 0.0 ? box.half[i] : -box.half[i];
  return box.p + box.R * s;
}

Eigen::Vector3d supportPoint(const WorldCapsule& capsule, const Eigen::Vector3d& dir) {
  const Eigen::Vector3d axis = capsule.R.col(2) * (0.5 * capsule.length);
  return capsule.p + (dir.dot(axis) >= 0.0 ? axis : Eigen::Vector3d(-axis)) + capsule.radius * dir;
}

namespace {
// The unit radial direction of `local` in the local xy-plane (zero when `local` is along z).
Eigen::Vector3d radialUnit(const Eigen::Vector3d& local) {
  const double r = std::hypot(local.x(), local.y());
  return r > 0.0 ? Eigen::Vector3d(local.x() / r, local.y() / r, 0.0) : Eigen::Vector3d::Zero();
}
}  // namespace

Eigen::Vector3d supportPoint(const WorldCylinder& cylinder, const Eigen::Vector3d& dir) {
  const Eigen::Vector3d local = cylinder.R.transpose() * dir;
  const double z = local.z() >= 0.0 ? 0.5 * cylinder.length : -0.5 * cylinder.length;
  return cylinder.p + cylinder.R * (cylinder.radius * radialUnit(local) + Eigen::Vector3d(0, 0, z));
}

Eigen::Vector3d supportPoint(const WorldCone& cone, const Eigen::Vector3d& dir) {
  // Base disk of radius r at local z = -L/2, apex at +L/2 (fcl::Cone).
  const Eigen::Vector3d local = cone.R.transpose() * dir;
  const Eigen::Vector3d apex(0, 0, 0.5 * cone.length);
  const Eigen::Vector3d rim = cone.radius * radialUnit(local) + Eigen::Vector3d(0, 0, -0.5 * cone.length);
  return cone.p + cone.R * (local.dot(apex) >= local.dot(rim) ? apex : rim);
}

// --- Ellipsoid against a box or a triangle -----------------------------------------------------


bool exactIntersect(const Ellipsoid& e, const WorldBox& b, ExactContact* contact) {
  if (isSphere(e)) return intersectFrom(signedDistanceEllipsoidBox(e, b.half, b.R, b.p), contact);
  if (!contact) return ellipsoidBoxStatus(e, b.half, b.R, b.p) != Separation::Separated;
  return contactFrom(signedDistanceEllipsoidBox(e, b.half, b.R, b.p), contact);
}

bool exactDistance(const Ellipsoid& e, const WorldBox& b, ExactDistance* out) {
  if (isSphere(e)) return unsignedDistanceFrom(signedDistanceEllipsoidBox(e, b.half, b.R, b.p), out);
  const EllipsoidPolytopeResult cert = classifyEllipsoidBox(e, b.half, b.R, b.p);
  if (cert.status == Separation::Overlapping) return distanceFrom(cert, nullptr, out);
  const SignedDistanceResult d = signedDistanceEllipsoidBox(e, b.half, b.R, b.p);
  return distanceFrom(cert, &d, out);
}

bool exactSignedDistance(const Ellipsoid& e, const WorldBox& b, ExactDistance* out) {
  return signedDistanceFrom(signedDistanceEllipsoidBox(e, b.half, b.R, b.p), out);
}

bool exactIntersect(const Ellipsoid& e, const WorldCapsule& c, ExactContact* contact) {
  const SignedDistanceResult d = signedDistanceEllipsoidCapsule(e, c.radius, c.length, c.R, c.p);
  if (!contact) return d.status != Separation::Separated;
  return contactFrom(d, contact);
}

bool exactDistance(const Ellipsoid& e, const WorldCapsule& c, ExactDistance* out) {
  const SignedDistanceResult d = signedDistanceEllipsoidCapsule(e, c.radius, c.length, c.R, c.p);
  if (d.status == Separation::Separated) return signedDistanceFrom(d, out);
  out->distance = -1.0;  // libccd's convention for overlapping pairs
  out->p1 = out->p2 = 0.5 * (d.point_a + d.point_b);
  return false;
}

bool exactSignedDistance(const Ellipsoid& e, const WorldCapsule& c, ExactDistance* out) {
  return signedDistanceFrom(signedDistanceEllipsoidCapsule(e, c.radius, c.length, c.R, c.p), out);
}

// Cylinder and cone: one certified kernel answers all three queries (as for the capsule).

bool exactIntersect(const Ellipsoid& e, const WorldCylinder& c, ExactContact* contact) {
  return intersectFrom(signedDistanceEllipsoidCylinder(e, c.radius, c.length, c.R, c.p), contact);
}
bool exactDistance(const Ellipsoid& e, const WorldCylinder& c, ExactDistance* out) {
  return unsignedDistanceFrom(signedDistanceEllipsoidCylinder(e, c.radius, c.length, c.R, c.p), out);
}
bool exactSignedDistance(const Ellipsoid& e, const WorldCylinder& c, ExactDistance* out) {
  return signedDistanceFrom(signedDistanceEllipsoidCylinder(e, c.radius, c.length, c.R, c.p), out);
}

bool exactIntersect(const Ellipsoid& e, const WorldCone& c, ExactContact* contact) {
  return intersectFrom(signedDistanceEllipsoidCone(e, c.radius, c.length, c.R, c.p), contact);
}
bool exactDistance(const Ellipsoid& e, const WorldCone& c, ExactDistance* out) {
  return unsignedDistanceFrom(signedDistanceEllipsoidCone(e, c.radius, c.length, c.R, c.p), out);
}
bool exactSignedDistance(const Ellipsoid& e, const WorldCone& c, ExactDistance* out) {
  return signedDistanceFrom(signedDistanceEllipsoidCone(e, c.radius, c.length, c.R, c.p), out);
}

bool exactIntersect(const Ellipsoid& e, const WorldConvex& P, ExactContact* contact) {
  if (isSphere(e)) return intersectFrom(signedDistanceEllipsoidConvex(e, P), contact);
  if (!contact) return classifyEllipsoidConvex(e, P).status != Separation::Separated;
  return contactFrom(signedDistanceEllipsoidConvex(e, P), contact);
}

bool exactDistance(const Ellipsoid& e, const WorldConvex& P, ExactDistance* out) {
  if (isSphere(e)) return unsignedDistanceFrom(signedDistanceEllipsoidConvex(e, P), out);
  const EllipsoidPolytopeResult cert = classifyEllipsoidConvex(e, P);
  if (cert.status == Separation::Overlapping) return distanceFrom(cert, nullptr, out);
  const SignedDistanceResult d = signedDistanceEllipsoidConvex(e, P);
  return distanceFrom(cert, &d, out);
}

bool exactSignedDistance(const Ellipsoid& e, const WorldConvex& P, ExactDistance* out) {
  return signedDistanceFrom(signedDistanceEllipsoidConvex(e, P), out);
}

bool exactIntersect(const Ellipsoid& e, const WorldTriangle& t, ExactContact* contact) {
  if (isSphere(e)) return intersectFrom(signedDistanceEllipsoidTriangle(e, t.a, t.b, t.c), contact);
  if (!contact) return classifyEllipsoidTriangle(e, t.a, t.b, t.c).status != Separation::Separated;
  return contactFrom(signedDistanceEllipsoidTriangle(e, t.a, t.b, t.c), contact);
}

bool exactDistance(const Ellipsoid& e, const WorldTriangle& t, ExactDistance* out) {
  if (isSphere(e)) return unsignedDistanceFrom(signedDistanceEllipsoidTriangle(e, t.a, t.b, t.c), out);
  const EllipsoidPolytopeResult cert = classifyEllipsoidTriangle(e, t.a, t.b, t.c);
  if (cert.status == Separation::Overlapping) return distanceFrom(cert, nullptr, out);
  const SignedDistanceResult d = signedDistanceEllipsoidTriangle(e, t.a, t.b, t.c);
  return distanceFrom(cert, &d, out);
}

bool exactSignedDistance(const Ellipsoid& e, const WorldTriangle& t, ExactDistance* out) {
  return signedDistanceFrom(signedDistanceEllipsoidTriangle(e, t.a, t.b, t.c), out);
}

}  // namespace detail

template class QuadricSolver<double>;

}  // namespace fcl_quadric
