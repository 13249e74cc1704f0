// libFuzzer target: fcl_quadric::collide / fcl_quadric::distance with FCL shapes (docs/reliability.md).
// Input: two shapes (a kind byte and raw-double parameters; the first is always an fcl::Ellipsoid
// or fcl::Sphere, so every pair goes through QuadricSolver's exact code or its documented
// fallback), two poses (quaternion, translation) and flags. Properties:
//  - clearly valid input (finite moderate sizes, unit quaternions, finite translations) never
//    throws; any throw is std::invalid_argument (documented for non-finite transforms and bad
//    shape parameters of the exact pairs);
//  - collide(o1, o2) and collide(o2, o1) agree on the collision flag;
//  - distance never returns NaN for valid input, and its sign agrees with collide (exact pairs:
//    FCL's own distance of sphere-plane crashes in stock FCL, see docs/reliability.md);
//  - for two ellipsoids: the front door agrees with classifyEllipsoids on the same poses (two
//    spheres: with their closed form, and that with classifyEllipsoids outside its band), and
//    with the exact oracle where it is clear by a margin.
#include <cmath>
#include <cstdint>
#include <memory>
#include <stdexcept>

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/halfspace.h>
#include <fcl/geometry/shape/plane.h>
#include <fcl/geometry/shape/sphere.h>

#include "fcl_quadric/fcl/collision.h"
#include "fcl_quadric/fcl/distance.h"
#include "fcl_quadric/geometry/sphere_solid.h"
#include "fuzz_common.h"

using namespace fcl_quadric;
using fcl_quadric::fuzz::Reader;

namespace {

enum Kind { kEllipsoid, kSphere, kBox, kCapsule, kCylinder, kCone, kPlane, kHalfspace, kKinds };

struct Shape {
  std::shared_ptr<fcl::CollisionGeometryd> geometry;
  Kind kind;
  bool valid;  // every parameter finite and in [1e-6, 1e6] (plane normals: not tiny)
};

bool moderate(double v) { return std::isfinite(v) && std::fabs(v) >= 1e-6 && std::fabs(v) <= 1e6; }
bool size(double v) { return moderate(v) && v > 0; }

Shape readShape(Reader& in, bool ellipsoidal_only) {
  const int kind = in.byte() % (ellipsoidal_only ? 2 : kKinds);
  const double x = in.value(), y = in.value(), z = in.value(), w = in.value();
  switch (kind) {
    case kEllipsoid: return {std::make_shared<fcl::Ellipsoidd>(x, y, z), kEllipsoid, size(x) && size(y) && size(z)};
    case kSphere: return {std::make_shared<fcl::Sphered>(x), kSphere, size(x)};
    case kBox: return {std::make_shared<fcl::Boxd>(x, y, z), kBox, size(x) && size(y) && size(z)};
    case kCapsule: return {std::make_shared<fcl::Capsuled>(x, y), kCapsule, size(x) && size(y)};
    case kCylinder: return {std::make_shared<fcl::Cylinderd>(x, y), kCylinder, size(x) && size(y)};
    case kCone: return {std::make_shared<fcl::Coned>(x, y), kCone, size(x) && size(y)};
    default: {
      const bool ok = std::isfinite(w) && std::fabs(w) <= 1e6 && std::isfinite(x) && std::isfinite(y) &&
                      std::isfinite(z) && Eigen::Vector3d(x, y, z).norm() >= 1e-3 && Eigen::Vector3d(x, y, z).norm() <= 1e6;
      if (kind == kPlane) return {std::make_shared<fcl::Planed>(x, y, z, w), kPlane, ok};
      return {std::make_shared<fcl::Halfspaced>(x, y, z, w), kHalfspace, ok};
    }
  }
}

/// A pose: normalised quaternion unless the flag byte is odd (then as given); the flag says
/// whether it is a clearly valid rigid transform.
fcl::Transform3d readPose(Reader& in, bool& valid) {
  const bool raw = (in.byte() % 4) == 1;
  const double qw = in.value(), qx = in.value(), qy = in.value(), qz = in.value();  // named: argument order is unspecified
  Eigen::Quaterniond q(qw, qx, qy, qz);
  const double n = q.norm();
  valid = std::isfinite(n) && n > 1e-150 && !raw;
  if (!raw && valid) q.coeffs() /= n;
  fcl::Transform3d X = fcl::Transform3d::Identity();
  X.linear() = q.toRotationMatrix();
  const Eigen::Vector3d t = in.vector3();
  X.translation() = t;
  valid = valid && t.allFinite() && t.cwiseAbs().maxCoeff() <= 1e6;
  return X;
}

/// Pairs answered by fcl_quadric's own code (quadric_solver.h dispatch table); the others go to
/// FCL's libccd solver or closed forms unchanged.
bool isExactPair(Kind a, Kind b) { return a == kEllipsoid || b == kEllipsoid; }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size_in) {
  Reader in(data, size_in);
  const Shape s1 = readShape(in, true);
  const Shape s2 = readShape(in, false);
  bool v1 = false, v2 = false;
  const fcl::Transform3d X1 = readPose(in, v1), X2 = readPose(in, v2);
  const bool valid = s1.valid && s2.valid && v1 && v2;
  const bool exact_pair = isExactPair(s1.kind, s2.kind);
  // FCL's own code is not ours to fuzz with bad shape parameters (its behaviour is kept
  // unchanged); bad transforms still reach our front door's checks.
  if (!exact_pair && !(s1.valid && s2.valid)) return 0;

  fcl::CollisionRequestd request;
  request.num_max_contacts = 1 + in.byte() % 4;
  request.enable_contact = (in.byte() % 2) == 0;
  bool c12 = false, c21 = false;
  try {
    fcl::CollisionResultd r12, r21;
    fcl_quadric::collide(s1.geometry.get(), X1, s2.geometry.get(), X2, request, r12);
    fcl_quadric::collide(s2.geometry.get(), X2, s1.geometry.get(), X1, request, r21);
    c12 = r12.isCollision();
    c21 = r21.isCollision();
    for (std::size_t i = 0; i < r12.numContacts(); ++i) {
      const auto& c = r12.getContact(i);
      // Without enable_contact, FCL's ShapeShapeCollide adds Contact(o1, o2, NONE, NONE), whose
      // pos, normal and penetration_depth are left uninitialised (fcl/narrowphase/contact-inl.h):
      // only o1, o2, b1, b2 mean anything then (docs/fcl_integration.md, section 2).
      if (valid && request.enable_contact)
        FUZZ_CHECK(!c.pos.hasNaN() && !c.normal.hasNaN() && !std::isnan(c.penetration_depth),
                   "NaN in a contact of kinds %d, %d", s1.kind, s2.kind);
    }
  } catch (const std::invalid_argument&) {
    FUZZ_CHECK(!valid, "valid input rejected by collide (kinds %d, %d)", s1.kind, s2.kind);
    return 0;
  }
  if (!valid) return 0;
  if (exact_pair) FUZZ_CHECK(c12 == c21, "asymmetric collide: kinds %d, %d: %d vs %d", s1.kind, s2.kind, c12, c21);

  // FCL's own distance for pairs without an ellipsoid is not ours: stock fcl::distance of a
  // sphere and a plane with libccd dereferences a null support function (SIGSEGV; reproduced
  // without fcl_quadric, docs/reliability.md).
  if (!exact_pair) return 0;
  fcl::DistanceRequestd dreq;
  dreq.enable_signed_distance = true;
  dreq.enable_nearest_points = true;
  fcl::DistanceResultd dres;
  const double d = fcl_quadric::distance(s1.geometry.get(), X1, s2.geometry.get(), X2, dreq, dres);
  FUZZ_CHECK(!std::isnan(d) && !dres.nearest_points[0].hasNaN() && !dres.nearest_points[1].hasNaN(),
             "NaN in distance of kinds %d, %d: %g", s1.kind, s2.kind, d);
  if (exact_pair) {
    // Sign agreement of the two front doors (the touching band counts as contact and distance 0).
    if (c12) FUZZ_CHECK(d <= 0, "kinds %d, %d collide but distance %.17g", s1.kind, s2.kind, d);
    if (!c12) FUZZ_CHECK(d >= 0, "kinds %d, %d separate but distance %.17g", s1.kind, s2.kind, d);
  }

  if (s1.kind == kEllipsoid && s2.kind == kEllipsoid) {
    const auto& e1 = static_cast<const fcl::Ellipsoidd&>(*s1.geometry);
    const auto& e2 = static_cast<const fcl::Ellipsoidd&>(*s2.geometry);
    const Ellipsoid a(e1.radii, X1.linear(), X1.translation()), b(e2.radii, X2.linear(), X2.translation());
    const Separation s = classifyEllipsoids(a, b).status;
    // The front door's own decision procedure: two spheres (three equal radii each) go to the
    // closed form, whose touching band is 2^-40 of |c_b - c_a| + r_a + r_b (sphere_solid.h;
    // docs/fcl_integration.md, "since session 36"); classifyEllipsoids decides on the stored
    // matrices, whose band is ~1e-27 (tolerances.h). Inside the closed form's band the two may
    // differ: two unit spheres exactly 2 apart, one posed by a rounded quaternion, are Separated
    // by ~1e-16 for the stored quadric (its rotation is orthogonal only to rounding) and touching
    // for the closed form (found by fuzz_fcl in CI; corpus file regression_tangent_spheres_rotated).
    // Outside that band they must agree.
    Separation front = s;
    if (isSphere(a) && isSphere(b)) {
      front = signedDistanceSphereSphere(a.center(), a.radii()[0], b.center(), b.radii()[0]).status;
      FUZZ_CHECK(front == Separation::Touching || s == front || s == Separation::Touching,
                 "closed form %d vs classifyEllipsoids %d outside the closed form's band", int(front), int(s));
    }
    FUZZ_CHECK((front != Separation::Separated) == c12, "front door %d vs its decision procedure %d", c12, int(front));
    if (const auto exact = fuzz::clearExactCollision(a, b, fuzz::rigidMargin(a, b))) {
      // Touching (cannot certify: contact) is accepted against a clear separation.
      FUZZ_CHECK(*exact == c12 || (front == Separation::Touching && !*exact), "collide %d disagrees with the oracle",
                 c12);
    }
  }
  return 0;
}
