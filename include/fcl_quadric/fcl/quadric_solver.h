#pragma once
/// \file quadric_solver.h
/// fcl_quadric::QuadricSolver<S>: a NarrowPhaseSolver for FCL 0.7 that answers ellipsoid pairs
/// exactly (certified classification, Choi 2008 Theorem 4.1; signed distance with witness points),
/// as well as ellipsoid against plane, half-space, box (OcTree leaves) and triangle (BVH meshes),
/// and delegates every other pair, unchanged, to fcl::detail::GJKSolver_libccd<S>.
///
/// It is accepted by FCL's own templated entry points
///   fcl::collide(o1, o2, &solver, request, result)   fcl::distance(o1, o2, &solver, request, result)
/// (and their CollisionGeometry + Transform3 forms), so FCL's shape-shape, BVH-shape and
/// OcTree-shape traversal nodes call it. docs/fcl_integration.md lists what FCL requires of a
/// solver and where FCL reads it.
///
/// Build cost: FCL's collide/distance templates and function matrices for QuadricSolver<double>
/// are instantiated once, in src/fcl/collision.cpp and src/fcl/distance.cpp; the `extern template`
/// declarations at the end of this header keep every other translation unit from re-instantiating
/// them (~30 s each). Only S = double is instantiated.

#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <fcl/common/types.h>
#include <fcl/geometry/collision_geometry.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/halfspace.h>
#include <fcl/geometry/shape/plane.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/contact_point.h>
#include <fcl/narrowphase/detail/gjk_solver_libccd.h>
#include <fcl/narrowphase/distance.h>

#include "fcl_quadric/geometry/ellipsoid.h"
#include "fcl_quadric/geometry/ellipsoid_polytope.h"

namespace fcl_quadric {

template <typename S>
class QuadricShape;  // fcl_quadric/fcl/quadric_shapes.h

namespace detail {

/// True for fcl_quadric's quadric shapes (EllipticCylinder, Quadric, QuadricCSG, or QuadricShape
/// itself), which exist for S = double only.
template <typename Shape>
inline constexpr bool kIsQuadricShape = std::is_base_of_v<QuadricShape<double>, Shape>;

// ---------------------------------------------------------------------------------------------
// Dispatch table: which algorithm QuadricSolver uses for a pair of FCL shape types. This is the
// one place to register a new exact pair (then add its branch in the QuadricSolver member that
// needs it; a static_assert there rejects a kind without a branch).
// ---------------------------------------------------------------------------------------------
enum class QuadricPairKind {
  /// Delegated unchanged to fcl::detail::GJKSolver_libccd<S> (including FCL's own closed forms
  /// such as sphere-sphere, sphere-box and box-box).
  kLibccd,
  /// fcl::Ellipsoid / fcl::Sphere pairs other than sphere-sphere: both shapes are converted to
  /// fcl_quadric::Ellipsoid (a sphere is an ellipsoid with equal radii) and answered by
  /// classifyEllipsoids / signedDistance.
  kEllipsoidEllipsoid,
  /// fcl::Sphere x fcl::Sphere / Box / Capsule / Cylinder (both orders): collision and unsigned
  /// distance are FCL's closed forms (sphere_*-inl.h: exact up to rounding, ~50-120 ns); the
  /// signed distance is fcl_quadric's closed forms (sphere_solid.h, reached through the ellipsoid
  /// kernels, which hand them an ellipsoid of equal radii: 0.17-0.25 us). libccd's EPA, which FCL
  /// 0.7 runs for it, was off by up to 6e-5 of the scale, gave +1e-6 for two spheres overlapping by
  /// 1e-9, and aborted inside libccd with distance_tolerance = 1e-12 (session 35, an audit).
  kSphereClosedForm,
  /// fcl::Ellipsoid x fcl::Plane (both orders): classifyEllipsoidPlane (seed Theorem 13 /
  /// Corollary 14) and the support function; contacts as FCL's ellipsoidPlaneIntersect.
  kEllipsoidPlane,
  /// fcl::Ellipsoid x fcl::Halfspace (both orders): ellipsoidHalfspace; contacts as FCL's
  /// ellipsoidHalfspaceIntersect.
  kEllipsoidHalfspace,
  /// fcl::Ellipsoid x fcl::Box (both orders; OcTree leaves are (Box, Ellipsoid)):
  /// classifyEllipsoidBox / signedDistanceEllipsoidBox.
  kEllipsoidBox,
  /// fcl::Ellipsoid x fcl::Capsule (both orders): signedDistanceEllipsoidCapsule (the segment's
  /// exact classification and signed distance, minus the radius).
  kEllipsoidCapsule,
  /// fcl::Ellipsoid x fcl::Cylinder / fcl::Cone (both orders): signedDistanceEllipsoidCylinder /
  /// signedDistanceEllipsoidCone (ellipsoid_cylinder.h: certified status, exact signed distance).
  kEllipsoidCylinder,
  /// ... and fcl::Sphere x fcl::Cone too: FCL 0.7 has no closed form for it, and libccd's GJK
  /// missed overlaps of 1e-9-1e-6 of the size (session 35, an audit). The kernel hands a sphere to
  /// signedDistanceSphereCone (sphere_solid.h): ~0.24 us, as fast as libccd's boolean GJK.
  kEllipsoidCone,
  /// fcl::Ellipsoid or fcl::Sphere x fcl::Convex (both orders): classifyEllipsoidConvex (the
  /// centre inside every face plane, or a face's fan triangle met: classifyEllipsoidTriangle) /
  /// signedDistanceEllipsoidConvex. libccd missed overlaps of 1e-9-1e-6 of the size on about a
  /// quarter of an audit's random pairs (session 35).
  kEllipsoidConvex,
  /// fcl::Ellipsoid or fcl::Sphere x triangle (QuadricTriangle, BVH meshes):
  /// classifyEllipsoidTriangle / signedDistanceEllipsoidTriangle.
  kEllipsoidTriangle,
  /// fcl::Sphere / Box / Capsule / Cylinder / Cone / Convex x fcl::Plane / fcl::Halfspace (both
  /// orders), distance and signed distance only: FCL 0.7 has no closed form for them and its GJK
  /// has no support function for a plane, so stock fcl::distance segfaults (docs/reliability.md,
  /// finding 5). Answered from the shape's two extreme points along the plane normal
  /// (detail::supportPlaneDistance, closed-form support functions). Collision stays FCL's own
  /// closed forms (plane-inl.h, halfspace-inl.h) for the sphere, box and capsule.
  kSupportPlane,
  /// fcl::Cylinder / fcl::Cone / fcl::Convex x fcl::Plane / fcl::Halfspace: as kSupportPlane, and
  /// collision too (signed distance <= 0; one contact: normal toward the plane solid, depth,
  /// position midway between the deepest point and its projection). FCL 0.7's cylinder-plane and
  /// cone-half-space closed forms report contact at clear gaps (measured up to 0.5 on shapes of
  /// size ~1), and its convex-plane collision segfaults like the distance
  /// (test/fcl/support_plane_test.cpp).
  kSupportPlaneExact,
  /// fcl::Plane / fcl::Halfspace x fcl::Plane / fcl::Halfspace: collision is FCL's closed form;
  /// distance throws std::invalid_argument (FCL 0.7 has no closed form and its GJK segfaults; two
  /// unbounded solids have no penetration depth).
  kPlanePlane,
  /// An fcl_quadric quadric shape (EllipticCylinder, Quadric, QuadricCSG) against anything the
  /// front doors accept (another quadric shape, an FCL primitive, a triangle): the front doors'
  /// certified region engine (collideQuadricShapes, distanceQuadricShapes). This is what FCL's
  /// traversal node templates instantiated with a quadric shape reach (MeshShape*, ShapeMesh*,
  /// OcTreeShape*, ShapeOcTree*, Shape* nodes; docs/fcl_integration.md section 9).
  kQuadricShape,
};

/// An entry of the pair tables: the algorithm and whether the shapes come in the reverse order.
template <QuadricPairKind Kind, bool Swapped>
struct PairEntry {
  static constexpr QuadricPairKind kind = Kind;
  static constexpr bool swapped = Swapped;
};

/// Pair table for shapeIntersect / shapeDistance / shapeSignedDistance. `swapped` tells a
/// one-sided kernel (ellipsoid first) to exchange the arguments and flip normals and points.
template <typename Shape1, typename Shape2>
struct QuadricPair : PairEntry<kIsQuadricShape<Shape1> || kIsQuadricShape<Shape2> ? QuadricPairKind::kQuadricShape
                                                                                : QuadricPairKind::kLibccd,
                               false> {};

/// (A, B) answered by `Kind` with A first; (B, A) by the same kernel with the arguments swapped.
#define FCL_QUADRIC_PAIR_BOTH_ORDERS(A, B, Kind)                                                   \
  template <typename S>                                                                          \
  struct QuadricPair<fcl::A<S>, fcl::B<S>> : PairEntry<QuadricPairKind::Kind, false> {};        \
  template <typename S>                                                                          \
  struct QuadricPair<fcl::B<S>, fcl::A<S>> : PairEntry<QuadricPairKind::Kind, true> {};
/// Symmetric entries: no swap in either order (both shapes convert to the same kind of solid).
#define FCL_QUADRIC_PAIR_SYMMETRIC(A, B, Kind) \
  template <typename S>                        \
  struct QuadricPair<fcl::A<S>, fcl::B<S>> : PairEntry<QuadricPairKind::Kind, false> {};

FCL_QUADRIC_PAIR_SYMMETRIC(Ellipsoid, Ellipsoid, kEllipsoidEllipsoid)
FCL_QUADRIC_PAIR_SYMMETRIC(Ellipsoid, Sphere, kEllipsoidEllipsoid)
FCL_QUADRIC_PAIR_SYMMETRIC(Sphere, Ellipsoid, kEllipsoidEllipsoid)
FCL_QUADRIC_PAIR_BOTH_ORDERS(Ellipsoid, Plane, kEllipsoidPlane)
FCL_QUADRIC_PAIR_BOTH_ORDERS(Ellipsoid, Halfspace, kEllipsoidHalfspace)
FCL_QUADRIC_PAIR_BOTH_ORDERS(Ellipsoid, Box, kEllipsoidBox)
FCL_QUADRIC_PAIR_BOTH_ORDERS(Ellipsoid, Capsule, kEllipsoidCapsule)
FCL_QUADRIC_PAIR_BOTH_ORDERS(Ellipsoid, Cylinder, kEllipsoidCylinder)
FCL_QUADRIC_PAIR_BOTH_ORDERS(Ellipsoid, Cone, kEllipsoidCone)
FCL_QUADRIC_PAIR_BOTH_ORDERS(Ellipsoid, Convex, kEllipsoidConvex)
FCL_QUADRIC_PAIR_BOTH_ORDERS(Sphere, Convex, kEllipsoidConvex)
FCL_QUADRIC_PAIR_SYMMETRIC(Sphere, Sphere, kSphereClosedForm)
FCL_QUADRIC_PAIR_BOTH_ORDERS(Sphere, Box, kSphereClosedForm)
FCL_QUADRIC_PAIR_BOTH_ORDERS(Sphere, Capsule, kSphereClosedForm)
FCL_QUADRIC_PAIR_BOTH_ORDERS(Sphere, Cylinder, kSphereClosedForm)
FCL_QUADRIC_PAIR_BOTH_ORDERS(Sphere, Cone, kEllipsoidCone)
// Shapes answered against planes and half-spaces by their support functions.
FCL_QUADRIC_PAIR_BOTH_ORDERS(Sphere, Plane, kSupportPlane)
FCL_QUADRIC_PAIR_BOTH_ORDERS(Sphere, Halfspace, kSupportPlane)
FCL_QUADRIC_PAIR_BOTH_ORDERS(Box, Plane, kSupportPlane)
FCL_QUADRIC_PAIR_BOTH_ORDERS(Box, Halfspace, kSupportPlane)
FCL_QUADRIC_PAIR_BOTH_ORDERS(Capsule, Plane, kSupportPlane)
FCL_QUADRIC_PAIR_BOTH_ORDERS(Capsule, Halfspace, kSupportPlane)
FCL_QUADRIC_PAIR_BOTH_ORDERS(Convex, Plane, kSupportPlaneExact)
FCL_QUADRIC_PAIR_BOTH_ORDERS(Convex, Halfspace, kSupportPlaneExact)
FCL_QUADRIC_PAIR_BOTH_ORDERS(Cylinder, Plane, kSupportPlaneExact)
FCL_QUADRIC_PAIR_BOTH_ORDERS(Cylinder, Halfspace, kSupportPlaneExact)
FCL_QUADRIC_PAIR_BOTH_ORDERS(Cone, Plane, kSupportPlaneExact)
FCL_QUADRIC_PAIR_BOTH_ORDERS(Cone, Halfspace, kSupportPlaneExact)
FCL_QUADRIC_PAIR_SYMMETRIC(Plane, Plane, kPlanePlane)
FCL_QUADRIC_PAIR_SYMMETRIC(Plane, Halfspace, kPlanePlane)
FCL_QUADRIC_PAIR_SYMMETRIC(Halfspace, Plane, kPlanePlane)
FCL_QUADRIC_PAIR_SYMMETRIC(Halfspace, Halfspace, kPlanePlane)
#undef FCL_QUADRIC_PAIR_BOTH_ORDERS
#undef FCL_QUADRIC_PAIR_SYMMETRIC

/// Table for the shape-triangle queries (the triangle is always the second operand).
template <typename Shape>
struct QuadricTriangle {
  static constexpr QuadricPairKind kind =
      kIsQuadricShape<Shape> ? QuadricPairKind::kQuadricShape : QuadricPairKind::kLibccd;
};
template <typename S>
struct QuadricTriangle<fcl::Ellipsoid<S>> {
  static constexpr QuadricPairKind kind = QuadricPairKind::kEllipsoidTriangle;
};
/// A sphere is the ellipsoid of equal radii (asExact). FCL's own sphere-triangle distance
/// (sphere_triangle-inl.h, which libccd's solver calls) leaves the distance unwritten when they
/// overlap, so FCL's mesh distance nodes read an uninitialised value, and returns its points in the
/// sphere's and the mesh's local frames (docs/fcl_integration.md §3.3).
template <typename S>
struct QuadricTriangle<fcl::Sphere<S>> {
  static constexpr QuadricPairKind kind = QuadricPairKind::kEllipsoidTriangle;
};

// ---------------------------------------------------------------------------------------------
// Double-precision kernels (src/fcl/quadric_solver.cpp). Frames: everything in the world frame W.
// ---------------------------------------------------------------------------------------------

/// One contact in FCL's convention: `normal` unit, pointing from the first shape to the second;
/// `depth` = -signedDistance >= 0 (0 when touching); `pos` the midpoint of the two witness points.
struct ExactContact {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();
  Eigen::Vector3d pos = Eigen::Vector3d::Zero();
  double depth = 0.0;
};

/// Distance output: `distance` and the points p1 on the first shape, p2 on the second (world).
struct ExactDistance {
  double distance = 0.0;
  Eigen::Vector3d p1 = Eigen::Vector3d::Zero();
  Eigen::Vector3d p2 = Eigen::Vector3d::Zero();
};

/// The posed fcl::Ellipsoid / fcl::Sphere as an fcl_quadric::Ellipsoid. `which` ("o1"/"o2") and
/// `shape` name the operand in the message of the std::invalid_argument thrown for a bad radius
/// or a linear part that is not a rotation (|R^T R - I| > tolerance::kRotationOrthogonality).
Ellipsoid ellipsoidFromFcl(const Eigen::Vector3d& radii, const Eigen::Matrix3d& R_WE,
                           const Eigen::Vector3d& p_WE, const char* which);
/// A sphere's R_WS must be a rotation too (it does not move the sphere). checkSphereFromFcl: the
/// same checks without the construction (std::invalid_argument naming `which`).
Ellipsoid sphereFromFcl(double radius, const Eigen::Matrix3d& R_WS, const Eigen::Vector3d& p_WS, const char* which);
void checkSphereFromFcl(double radius, const Eigen::Matrix3d& R_WS, const Eigen::Vector3d& p_WS, const char* which);

/// Collision of a and b (touching counts, as everywhere in fcl_quadric): classifyEllipsoids.
/// If colliding and `contact` is non-null, fills it from signedDistance(a, b).
bool intersectEllipsoids(const Ellipsoid& a, const Ellipsoid& b, ExactContact* contact);

/// FCL's shapeDistance convention (the one of GJKSolver_libccd): separated or touching -> the
/// distance (>= 0) and the nearest points, returns true; overlapping -> distance -1 and
/// p1 = p2 = a point common to both solids (the classification witness), returns false.
bool distanceEllipsoids(const Ellipsoid& a, const Ellipsoid& b, ExactDistance* out);

/// FCL's shapeSignedDistance convention: signedDistance(a, b) (negative = minus the penetration
/// depth), p1 = point_a, p2 = point_b (for overlap: the deepest point of each inside the other,
/// as libccd's EPA); returns false iff the distance is negative.
/// Two spheres (equal radii each): all three answer from the closed form of sphere_solid.h, with
/// its 2^-40 touching band.
bool signedDistanceEllipsoids(const Ellipsoid& a, const Ellipsoid& b, ExactDistance* out);

/// Throws std::invalid_argument naming `which` and the offending transform.
[[noreturn]] void throwNonFiniteTransform(const char* which, const Eigen::Matrix<double, 3, 4>& m);

template <typename S>
void checkTransform(const fcl::Transform3<S>& tf, const char* which) {
  // std::isfinite raises no floating-point exception (the tests trap FE_INVALID).
  const auto& m = tf.matrix();
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 3; ++r)
      if (!std::isfinite(m(r, c))) throwNonFiniteTransform(which, m.template topRows<3>().template cast<double>());
}

template <typename S>
Ellipsoid asEllipsoid(const fcl::Ellipsoid<S>& s, const fcl::Transform3<S>& tf, const char* which) {
  return ellipsoidFromFcl(s.radii.template cast<double>(), tf.linear().template cast<double>(),
                          tf.translation().template cast<double>(), which);
}
template <typename S>
Ellipsoid asEllipsoid(const fcl::Sphere<S>& s, const fcl::Transform3<S>& tf, const char* which) {
  return sphereFromFcl(static_cast<double>(s.radius), tf.linear().template cast<double>(),
                       tf.translation().template cast<double>(), which);
}

template <typename S>
void writeDistance(const ExactDistance& d, S* dist, fcl::Vector3<S>* p1, fcl::Vector3<S>* p2) {
  if (dist) *dist = static_cast<S>(d.distance);
  if (p1) *p1 = d.p1.template cast<S>();
  if (p2) *p2 = d.p2.template cast<S>();
}

// --- Ellipsoid against a plane, a half-space, a box, a triangle (world frame) ------------------

/// An fcl::Plane or fcl::Halfspace posed in the world: unit normal n and offset d (the plane
/// n.x = d; the half-space n.x <= d). `halfspace` selects the solid.
struct WorldPlane {
  Eigen::Vector3d n = Eigen::Vector3d::UnitX();
  double d = 0.0;
  bool halfspace = false;
};

/// An fcl::Box posed in the world: { p + R s : |s_i| <= half_i }.
struct WorldBox {
  Eigen::Vector3d half = Eigen::Vector3d::Zero();
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
};

/// An fcl::Capsule posed in the world: the segment p +- R e_z L/2 swept by a ball of radius r.
struct WorldCapsule {
  double radius = 0.0;
  double length = 0.0;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
};

/// An fcl::Cylinder posed in the world: { p + R (x, y, z) : |(x, y)| <= r, |z| <= L/2 }.
struct WorldCylinder {
  double radius = 0.0;
  double length = 0.0;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
};

/// An fcl::Cone posed in the world: base disk of radius r at local z = -L/2, apex at +L/2.
struct WorldCone {
  double radius = 0.0;
  double length = 0.0;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
};

/// A triangle in the world frame.
struct WorldTriangle {
  Eigen::Vector3d a, b, c;
};

/// FCL's transform(Plane/Halfspace, tf) (geometry/shape/plane-inl.h:153-165): n' = R n,
/// d' = d + n'.t, then normalised as FCL's constructors do (unitNormalTest). Throws
/// std::invalid_argument naming `which` for a zero or non-finite normal or offset.
WorldPlane planeFromFcl(const Eigen::Vector3d& n, double d, bool halfspace, const Eigen::Matrix3d& R,
                        const Eigen::Vector3d& t, const char* which);
/// half = side / 2 (fcl::Box stores full side lengths). Throws std::invalid_argument naming
/// `which` for a negative or non-finite side or a linear part that is not a rotation.
WorldBox boxFromFcl(const Eigen::Vector3d& side, const Eigen::Matrix3d& R, const Eigen::Vector3d& p,
                    const char* which);
/// Throws std::invalid_argument naming `which` for a bad radius or length or a non-rotation.
WorldCapsule capsuleFromFcl(double radius, double length, const Eigen::Matrix3d& R, const Eigen::Vector3d& p,
                            const char* which);
/// Throw std::invalid_argument naming `which` for a bad radius or length or a non-rotation.
WorldCylinder cylinderFromFcl(double radius, double length, const Eigen::Matrix3d& R, const Eigen::Vector3d& p,
                              const char* which);
WorldCone coneFromFcl(double radius, double length, const Eigen::Matrix3d& R, const Eigen::Vector3d& p,
                      const char* which);
/// An fcl::Convex posed in the world: its vertices transformed, its faces as index lists.
using WorldConvex = ConvexPolytope;
/// The fcl::Convex (vertices `v` in its frame, faces in FCL's flat format [n, i_1..i_n, n, ...]
/// for `face_count` faces) posed by (R, p). Throws std::invalid_argument naming `which` for a
/// non-rotation R, a translation or vertex out of range, or a malformed face list.
WorldConvex convexFromFcl(const std::vector<Eigen::Vector3d>& v, const std::vector<int>& faces, int face_count,
                          const Eigen::Matrix3d& R, const Eigen::Vector3d& p, const char* which);
/// Throws std::invalid_argument for a non-finite vertex.
WorldTriangle triangleFromFcl(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c);

/// The exact kernels, one overload per second operand; the first operand is always the
/// ellipsoid. Same contracts as intersectEllipsoids / distanceEllipsoids /
/// signedDistanceEllipsoids (normal from the ellipsoid to the other solid; p1 on the ellipsoid,
/// p2 on the other solid), with the conventions of FCL's closed forms for planes and half-spaces
/// (docs/fcl_integration.md section 3).
bool exactIntersect(const Ellipsoid& e, const Ellipsoid& other, ExactContact* contact);
bool exactIntersect(const Ellipsoid& e, const WorldPlane& other, ExactContact* contact);
bool exactIntersect(const Ellipsoid& e, const WorldBox& other, ExactContact* contact);
bool exactIntersect(const Ellipsoid& e, const WorldTriangle& other, ExactContact* contact);
bool exactIntersect(const Ellipsoid& e, const WorldCapsule& other, ExactContact* contact);
bool exactIntersect(const Ellipsoid& e, const WorldCylinder& other, ExactContact* contact);
bool exactIntersect(const Ellipsoid& e, const WorldCone& other, ExactContact* contact);
bool exactIntersect(const Ellipsoid& e, const WorldConvex& other, ExactContact* contact);
bool exactDistance(const Ellipsoid& e, const Ellipsoid& other, ExactDistance* out);
bool exactDistance(const Ellipsoid& e, const WorldPlane& other, ExactDistance* out);
bool exactDistance(const Ellipsoid& e, const WorldBox& other, ExactDistance* out);
bool exactDistance(const Ellipsoid& e, const WorldTriangle& other, ExactDistance* out);
bool exactDistance(const Ellipsoid& e, const WorldCapsule& other, ExactDistance* out);
bool exactDistance(const Ellipsoid& e, const WorldCylinder& other, ExactDistance* out);
bool exactDistance(const Ellipsoid& e, const WorldCone& other, ExactDistance* out);
bool exactDistance(const Ellipsoid& e, const WorldConvex& other, ExactDistance* out);
bool exactSignedDistance(const Ellipsoid& e, const Ellipsoid& other, ExactDistance* out);
bool exactSignedDistance(const Ellipsoid& e, const WorldPlane& other, ExactDistance* out);
bool exactSignedDistance(const Ellipsoid& e, const WorldBox& other, ExactDistance* out);
bool exactSignedDistance(const Ellipsoid& e, const WorldTriangle& other, ExactDistance* out);
bool exactSignedDistance(const Ellipsoid& e, const WorldCapsule& other, ExactDistance* out);
bool exactSignedDistance(const Ellipsoid& e, const WorldCylinder& other, ExactDistance* out);
bool exactSignedDistance(const Ellipsoid& e, const WorldCone& other, ExactDistance* out);
bool exactSignedDistance(const Ellipsoid& e, const WorldConvex& other, ExactDistance* out);

/// The posed FCL shape as the operand type of the exact kernels.
template <typename S>
Ellipsoid asExact(const fcl::Ellipsoid<S>& s, const fcl::Transform3<S>& tf, const char* which) {
  return asEllipsoid(s, tf, which);
}
template <typename S>
Ellipsoid asExact(const fcl::Sphere<S>& s, const fcl::Transform3<S>& tf, const char* which) {
  return asEllipsoid(s, tf, which);
}
template <typename S>
WorldPlane asExact(const fcl::Plane<S>& s, const fcl::Transform3<S>& tf, const char* which) {
  return planeFromFcl(s.n.template cast<double>(), static_cast<double>(s.d), false, tf.linear().template cast<double>(),
                      tf.translation().template cast<double>(), which);
}
template <typename S>
WorldPlane asExact(const fcl::Halfspace<S>& s, const fcl::Transform3<S>& tf, const char* which) {
  return planeFromFcl(s.n.template cast<double>(), static_cast<double>(s.d), true, tf.linear().template cast<double>(),
                      tf.translation().template cast<double>(), which);
}
template <typename S>
WorldBox asExact(const fcl::Box<S>& s, const fcl::Transform3<S>& tf, const char* which) {
  return boxFromFcl(s.side.template cast<double>(), tf.linear().template cast<double>(),
                    tf.translation().template cast<double>(), which);
}
template <typename S>
WorldCapsule asExact(const fcl::Capsule<S>& s, const fcl::Transform3<S>& tf, const char* which) {
  return capsuleFromFcl(static_cast<double>(s.radius), static_cast<double>(s.lz), tf.linear().template cast<double>(),
                        tf.translation().template cast<double>(), which);
}
template <typename S>
WorldCylinder asExact(const fcl::Cylinder<S>& s, const fcl::Transform3<S>& tf, const char* which) {
  return cylinderFromFcl(static_cast<double>(s.radius), static_cast<double>(s.lz),
                         tf.linear().template cast<double>(), tf.translation().template cast<double>(), which);
}
template <typename S>
WorldCone asExact(const fcl::Cone<S>& s, const fcl::Transform3<S>& tf, const char* which) {
  return coneFromFcl(static_cast<double>(s.radius), static_cast<double>(s.lz), tf.linear().template cast<double>(),
                     tf.translation().template cast<double>(), which);
}
template <typename S>
WorldConvex asExact(const fcl::Convex<S>& s, const fcl::Transform3<S>& tf, const char* which) {
  std::vector<Eigen::Vector3d> v;
  v.reserve(s.getVertices().size());
  for (const fcl::Vector3<S>& x : s.getVertices()) v.push_back(x.template cast<double>());
  return convexFromFcl(v, s.getFaces(), s.getFaceCount(), tf.linear().template cast<double>(),
                       tf.translation().template cast<double>(), which);
}
template <typename S>
WorldTriangle asExactTriangle(const fcl::Vector3<S>& P1, const fcl::Vector3<S>& P2, const fcl::Vector3<S>& P3) {
  return triangleFromFcl(P1.template cast<double>(), P2.template cast<double>(), P3.template cast<double>());
}
template <typename S>
WorldTriangle asExactTriangle(const fcl::Vector3<S>& P1, const fcl::Vector3<S>& P2, const fcl::Vector3<S>& P3,
                              const fcl::Transform3<S>& tf) {
  return triangleFromFcl((tf * P1).template cast<double>(), (tf * P2).template cast<double>(),
                         (tf * P3).template cast<double>());
}

/// A convex solid seen along a unit direction n: its extreme points lo = argmin n.x and
/// hi = argmax n.x (world frame) and its centre (the origin of its local frame, which decides the
/// side of a two-sided plane as FCL's closed forms do).
struct SupportExtent {
  Eigen::Vector3d lo = Eigen::Vector3d::Zero();
  Eigen::Vector3d hi = Eigen::Vector3d::Zero();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
};

/// Distance (signed_distance = false: libccd's convention, -1 and p1 = p2 = a common point when
/// they overlap) or signed distance (negative = minus the penetration depth along the plane
/// normal) between a convex solid known by its SupportExtent along other.n and a plane or
/// half-space. p1 on the solid, p2 on the plane. Returns true iff separated. Exact up to the
/// rounding of the support points (closed forms); no tolerance band.
bool supportPlaneDistance(const SupportExtent& e, const WorldPlane& other, bool signed_distance, ExactDistance* out);

/// argmax of dir . x over the validated operand (dir unit, world frame): closed-form support
/// points. A sphere operand is the Ellipsoid of asExact(fcl::Sphere) (equal radii). No failure
/// mode (the operands were validated by their *FromFcl constructors).
Eigen::Vector3d supportPoint(const Ellipsoid& sphere, const Eigen::Vector3d& dir);
Eigen::Vector3d supportPoint(const WorldBox& box, const Eigen::Vector3d& dir);
Eigen::Vector3d supportPoint(const WorldCapsule& capsule, const Eigen::Vector3d& dir);
Eigen::Vector3d supportPoint(const WorldCylinder& cylinder, const Eigen::Vector3d& dir);
Eigen::Vector3d supportPoint(const WorldCone& cone, const Eigen::Vector3d& dir);

/// The posed shape's support point along dir, after the same validation as the exact kernels'
/// operands (asExact; `which` names the operand in the std::invalid_argument thrown for bad
/// parameters).
template <typename S, typename Shape>
Eigen::Vector3d supportOf(const Shape& s, const fcl::Transform3<S>& tf, const Eigen::Vector3d& dir, const char* which) {
  return supportPoint(asExact(s, tf, which), dir);
}
template <typename S>
Eigen::Vector3d supportOf(const fcl::Convex<S>& s, const fcl::Transform3<S>& tf, const Eigen::Vector3d& dir,
                          const char* which) {
  const std::vector<fcl::Vector3<S>>& v = s.getVertices();
  if (v.empty()) throw std::invalid_argument(std::string("fcl_quadric::QuadricSolver: ") + which + " (fcl::Convex) has no vertices");
  Eigen::Vector3d best = (tf * v.front()).template cast<double>();
  for (const fcl::Vector3<S>& x : v) {
    const Eigen::Vector3d w = (tf * x).template cast<double>();
    if (!w.array().isFinite().all())
      throw std::invalid_argument(std::string("fcl_quadric::QuadricSolver: ") + which + " (fcl::Convex) has a non-finite vertex");
    if (w.dot(dir) > best.dot(dir)) best = w;
  }
  return best;
}

/// The kSupportPlane pair: the shape's extent along the plane normal, then supportPlaneDistance.
template <typename S, typename Shape>
bool supportPairDistance(const Shape& shape, const fcl::Transform3<S>& tf_shape, const char* which,
                         const WorldPlane& plane, bool signed_distance, ExactDistance* out) {
  SupportExtent e;
  e.lo = supportOf(shape, tf_shape, -plane.n, which);
  e.hi = supportOf(shape, tf_shape, plane.n, which);
  e.centre = tf_shape.translation().template cast<double>();
  return supportPlaneDistance(e, plane, signed_distance, out);
}

/// Runs the exact kernel of a non-libccd pair: Shape1/Shape2 in FCL's order; a `swapped` pair
/// (ellipsoid second) calls the kernel with the ellipsoid first and turns its answer around
/// (normal negated, p1 and p2 exchanged; the contact position and depth do not change, as FCL's
/// own FCL_GJK_LIBCCD_SHAPE_SHAPE_INTERSECT_INV and flipNormal do, gjk_solver_libccd-inl.h:220-235).
template <bool swapped, typename S, typename Shape1, typename Shape2>
bool exactPairIntersect(const Shape1& s1, const fcl::Transform3<S>& tf1, const Shape2& s2,
                        const fcl::Transform3<S>& tf2, ExactContact* contact) {
  if constexpr (swapped) {
    const bool hit = exactIntersect(asExact(s2, tf2, "o2"), asExact(s1, tf1, "o1"), contact);
    if (hit && contact) contact->normal = -contact->normal;
    return hit;
  } else {
    return exactIntersect(asExact(s1, tf1, "o1"), asExact(s2, tf2, "o2"), contact);
  }
}
template <bool swapped, bool signed_distance, typename S, typename Shape1, typename Shape2>
bool exactPairDistance(const Shape1& s1, const fcl::Transform3<S>& tf1, const Shape2& s2,
                       const fcl::Transform3<S>& tf2, ExactDistance* out) {
  if constexpr (swapped) {
    const bool separated = signed_distance ? exactSignedDistance(asExact(s2, tf2, "o2"), asExact(s1, tf1, "o1"), out)
                                           : exactDistance(asExact(s2, tf2, "o2"), asExact(s1, tf1, "o1"), out);
    out->p1.swap(out->p2);
    return separated;
  } else {
    return signed_distance ? exactSignedDistance(asExact(s1, tf1, "o1"), asExact(s2, tf2, "o2"), out)
                           : exactDistance(asExact(s1, tf1, "o1"), asExact(s2, tf2, "o2"), out);
  }
}

// --- Quadric shapes (kQuadricShape; src/fcl/quadric_shape_dispatch.cpp) ------------------------

/// s1 (pose tf1) against s2 (pose tf2), at least one a QuadricShape: fcl_quadric::collide's
/// certified answer (touching counts). On contact, if `contact` is non-null: pos = the witness
/// point, normal = unit outward normal of s1's nearest surface there (from s1 towards s2),
/// depth = 0 (not computed for quadric shapes). \throws std::invalid_argument as
/// fcl_quadric::collide does for an unsupported partner or two unbounded operands.
bool quadricShapeIntersect(const fcl::CollisionGeometry<double>& s1, const fcl::Transform3<double>& tf1,
                           const fcl::CollisionGeometry<double>& s2, const fcl::Transform3<double>& tf2,
                           ExactContact* contact);
/// The quadric shape s (pose tf) against the triangle P1 P2 P3 given in the frame tf_triangle
/// (the identity for world-frame vertices), as fcl_quadric::collide answers a one-triangle mesh:
/// a zero-area triangle never collides (skipped, as in the front doors' mesh traversal). Normal
/// from the shape towards the triangle.
bool quadricShapeTriangleIntersect(const fcl::CollisionGeometry<double>& s, const fcl::Transform3<double>& tf,
                                   const Eigen::Vector3d& P1, const Eigen::Vector3d& P2, const Eigen::Vector3d& P3,
                                   const fcl::Transform3<double>& tf_triangle, ExactContact* contact);
/// fcl_quadric::distance of s1 and s2 (at least one a convex QuadricShape, or a union of convex
/// ones): `signed_distance` false is FCL's shapeDistance convention (-1 and a common point when
/// they overlap), true its shapeSignedDistance (minus the penetration depth). p1 on s1, p2 on s2,
/// world frame. Returns true iff the distance is >= 0. \throws std::invalid_argument as
/// fcl_quadric::distance does (another non-convex quadric shape, an unsupported partner).
bool quadricShapeDistance(const fcl::CollisionGeometry<double>& s1, const fcl::Transform3<double>& tf1,
                          const fcl::CollisionGeometry<double>& s2, const fcl::Transform3<double>& tf2,
                          bool signed_distance, ExactDistance* out);
/// The same against the triangle P1 P2 P3 in the frame tf_triangle (p2 on the triangle).
bool quadricShapeTriangleDistance(const fcl::CollisionGeometry<double>& s, const fcl::Transform3<double>& tf,
                                  const Eigen::Vector3d& P1, const Eigen::Vector3d& P2, const Eigen::Vector3d& P3,
                                  const fcl::Transform3<double>& tf_triangle, bool signed_distance,
                                  ExactDistance* out);

template <typename S>
void appendContact(const ExactContact& c, std::vector<fcl::ContactPoint<S>>* contacts) {
  contacts->emplace_back(c.normal.template cast<S>(), c.pos.template cast<S>(), static_cast<S>(c.depth));
}

}  // namespace detail

/// NarrowPhaseSolver for FCL 0.7 (the interface of fcl::detail::GJKSolver_libccd<S>).
///
/// Exact pairs (detail::QuadricPair, both argument orders unless noted):
///  - fcl::Ellipsoid-fcl::Ellipsoid, fcl::Ellipsoid-fcl::Sphere: classifyEllipsoids, signedDistance;
///  - fcl::Ellipsoid-fcl::Plane, fcl::Ellipsoid-fcl::Halfspace: classifyEllipsoidPlane /
///    ellipsoidHalfspace (seed Theorem 13 / Corollary 14) and the support function;
///  - fcl::Ellipsoid-fcl::Box (OcTree leaves): classifyEllipsoidBox, signedDistanceEllipsoidBox;
///  - fcl::Ellipsoid-fcl::Capsule / fcl::Cylinder / fcl::Cone: signedDistanceEllipsoidCapsule /
///    signedDistanceEllipsoidCylinder / signedDistanceEllipsoidCone;
///  - fcl::Ellipsoid-triangle and fcl::Sphere-triangle (shapeTriangleIntersect /
///    shapeTriangleDistance, BVH meshes): classifyEllipsoidTriangle, signedDistanceEllipsoidTriangle;
///  - an fcl_quadric quadric shape (EllipticCylinder, Quadric, QuadricCSG; S = double) against
///    anything, triangles included: the front doors' certified region engine
///    (detail::quadricShapeIntersect / quadricShapeDistance). So FCL's traversal node templates
///    instantiated with a quadric shape and this solver (MeshShapeCollisionTraversalNode*,
///    OcTreeShapeCollisionTraversalNode, MeshShapeDistanceTraversalNode*, ...) answer exactly;
///    contact depth is 0 for these shapes (not computed).
/// Results follow FCL's conventions (docs/fcl_integration.md section 3):
///  - shapeIntersect: true iff the solids are not separate (touching counts as collision, certified
///    down to ~1e-27 relative gap for ellipsoid pairs and 2^-40 for the others,
///    docs/tolerances.md). With `contacts` non-null, one ContactPoint is appended with the normal
///    (unit) from o1 to o2. Plane and half-space contacts are those of FCL's closed forms
///    (ellipsoidPlaneIntersect / ellipsoidHalfspaceIntersect: depth, side, position); otherwise
///    penetration_depth = -signed distance (0 if touching) and pos = the midpoint of the two
///    witness points of the signed distance.
///  - shapeDistance / shapeSignedDistance / shapeTriangleDistance: see detail::distanceEllipsoids
///    / detail::signedDistanceEllipsoids; points p1 (on s1) and p2 (on s2) in the world frame, as
///    GJKSolver_libccd returns them in FCL 0.7.
/// Every other pair and every non-ellipsoid shape-triangle query is delegated to the internal
/// GJKSolver_libccd<S> (`libccd()`), whose tolerances and iteration limits are public.
///
/// Bad input: a non-finite transform (any pair) throws std::invalid_argument naming "tf1"/"tf2";
/// for the exact pairs and the sphere pairs answered by FCL's closed forms (kSphereClosedForm) a
/// non-positive or non-finite radius, a negative box side, a length beyond 1e100, a centre beyond
/// 1e100, a zero plane normal, a non-finite triangle vertex, or a linear part that is not a
/// rotation within tolerance::kRotationOrthogonality (a sphere's too), throws
/// std::invalid_argument naming o1/o2.
///
/// Stateless: the const members may be called concurrently from several threads.
template <typename S_>
class QuadricSolver {
 public:
  using S = S_;

  /// The libccd fallback with FCL's defaults (max_collision_iterations 500,
  /// max_distance_iterations 1000, collision_tolerance = constants<S>::gjk_default_tolerance(),
  /// distance_tolerance 1e-6).
  QuadricSolver() = default;
  explicit QuadricSolver(const fcl::detail::GJKSolver_libccd<S>& fallback) : libccd_(fallback) {}

  /// The solver non-exact pairs are delegated to. fcl_quadric::collide / distance set
  /// collision_tolerance = request.gjk_tolerance and distance_tolerance =
  /// request.distance_tolerance on it, as fcl::collide / fcl::distance do for GST_LIBCCD.
  fcl::detail::GJKSolver_libccd<S>& libccd() { return libccd_; }
  const fcl::detail::GJKSolver_libccd<S>& libccd() const { return libccd_; }

  /// Collision of two shapes; see the class comment. Called by FCL's ShapeCollisionTraversalNode
  /// and OcTreeSolver (leaf Box first, shape second).
  template <typename Shape1, typename Shape2>
  bool shapeIntersect(const Shape1& s1, const fcl::Transform3<S>& tf1, const Shape2& s2,
                      const fcl::Transform3<S>& tf2,
                      std::vector<fcl::ContactPoint<S>>* contacts = nullptr) const {
    detail::checkTransform(tf1, "tf1");
    detail::checkTransform(tf2, "tf2");
    using Pair = detail::QuadricPair<Shape1, Shape2>;
    if constexpr (Pair::kind == detail::QuadricPairKind::kSphereClosedForm) {
      validateOperands(s1, tf1, s2, tf2);
      const std::size_t before = contacts ? contacts->size() : 0;
      const bool hit = libccd_.shapeIntersect(s1, tf1, s2, tf2, contacts);  // FCL's closed forms
      // FCL's sphere-sphere and sphere-capsule forms give a zero normal to a centre on the other
      // centre or on the capsule's axis (session 36, an audit): the closed form's normal there.
      if (hit && contacts) {
        for (std::size_t i = before; i < contacts->size(); ++i) {
          fcl::ContactPoint<S>& c = (*contacts)[i];
          if (c.normal.norm() > 0.5) continue;
          detail::ExactDistance d;
          detail::exactPairDistance<Pair::swapped, true>(s1, tf1, s2, tf2, &d);
          const Eigen::Vector3d n = d.p2 - d.p1;  // from s1's deepest point to s2's: along -normal
          const double len = n.norm();
          // p2 - p1 = distance * normal (distance < 0 here), so the normal is -(p2 - p1) / |.|.
          if (len > 0.0) c.normal = (-n / len).template cast<S>();
          else c.normal = fcl::Vector3<S>::UnitX();
        }
      }
      return hit;
    } else if constexpr (Pair::kind == detail::QuadricPairKind::kLibccd ||
                         Pair::kind == detail::QuadricPairKind::kSupportPlane ||
                         Pair::kind == detail::QuadricPairKind::kPlanePlane) {
      return libccd_.shapeIntersect(s1, tf1, s2, tf2, contacts);  // FCL's closed forms
    } else if constexpr (Pair::kind == detail::QuadricPairKind::kSupportPlaneExact) {
      S dist = 0;
      fcl::Vector3<S> p1, p2;
      if (supportPlanePair<Pair::swapped>(s1, tf1, s2, tf2, true, &dist, &p1, &p2)) return false;
      if (contacts) {
        // p1 on s1, p2 on s2: when they overlap, p2 - p1 = dist * (unit normal from s1 to s2).
        const fcl::Vector3<S> d = p2 - p1;
        const S len = d.norm();
        fcl::Vector3<S> normal = len > 0 ? fcl::Vector3<S>(-d / len) : fcl::Vector3<S>(supportNormal<Pair::swapped>(s1, tf1, s2, tf2));
        contacts->emplace_back(normal, (0.5 * (p1 + p2)).eval(), -dist);
      }
      return true;
    } else if constexpr (Pair::kind == detail::QuadricPairKind::kQuadricShape) {
      static_assert(std::is_same_v<S, double>, "fcl_quadric's quadric shapes exist for S = double only");
      detail::ExactContact c;
      const bool hit = detail::quadricShapeIntersect(s1, tf1, s2, tf2, contacts ? &c : nullptr);
      if (hit && contacts) detail::appendContact(c, contacts);
      return hit;
    } else {
      static_assert(isShapePairKind(Pair::kind), "QuadricSolver::shapeIntersect: unhandled pair kind");
      detail::ExactContact c;
      const bool hit = detail::exactPairIntersect<Pair::swapped>(s1, tf1, s2, tf2, contacts ? &c : nullptr);
      if (hit && contacts) detail::appendContact(c, contacts);
      return hit;
    }
  }

  /// Shape vs a triangle given in the world frame (FCL's BVH traversal with AABB-family BVs).
  /// `normal` points from the shape to the triangle (MeshShapeCollisionTraversalNode negates it,
  /// mesh_shape_collision_traversal_node-inl.h:102); outputs are written only on collision.
  template <typename Shape>
  bool shapeTriangleIntersect(const Shape& s, const fcl::Transform3<S>& tf, const fcl::Vector3<S>& P1,
                              const fcl::Vector3<S>& P2, const fcl::Vector3<S>& P3,
                              fcl::Vector3<S>* contact_points = nullptr, S* penetration_depth = nullptr,
                              fcl::Vector3<S>* normal = nullptr) const {
    detail::checkTransform(tf, "tf");
    constexpr detail::QuadricPairKind kind = detail::QuadricTriangle<Shape>::kind;
    if constexpr (kind == detail::QuadricPairKind::kLibccd) {
      return libccd_.shapeTriangleIntersect(s, tf, P1, P2, P3, contact_points, penetration_depth, normal);
    } else if constexpr (kind == detail::QuadricPairKind::kQuadricShape) {
      return quadricTriangleIntersect(s, tf, P1, P2, P3, fcl::Transform3<S>::Identity(), contact_points,
                                      penetration_depth, normal);
    } else {
      static_assert(kind == detail::QuadricPairKind::kEllipsoidTriangle,
                    "QuadricSolver::shapeTriangleIntersect: unhandled kind");
      return triangleIntersect(detail::asExact(s, tf, "shape"), detail::asExactTriangle(P1, P2, P3), contact_points,
                               penetration_depth, normal);
    }
  }

  /// Shape (pose tf1) vs a triangle whose vertices are in the frame tf2 (oriented BVH nodes:
  /// OBB, RSS, kIOS, OBBRSS; OcTree-mesh). Outputs in the world frame, as above.
  template <typename Shape>
  bool shapeTriangleIntersect(const Shape& s, const fcl::Transform3<S>& tf1, const fcl::Vector3<S>& P1,
                              const fcl::Vector3<S>& P2, const fcl::Vector3<S>& P3,
                              const fcl::Transform3<S>& tf2, fcl::Vector3<S>* contact_points = nullptr,
                              S* penetration_depth = nullptr, fcl::Vector3<S>* normal = nullptr) const {
    detail::checkTransform(tf1, "tf1");
    detail::checkTransform(tf2, "tf2");
    constexpr detail::QuadricPairKind kind = detail::QuadricTriangle<Shape>::kind;
    if constexpr (kind == detail::QuadricPairKind::kLibccd) {
      return libccd_.shapeTriangleIntersect(s, tf1, P1, P2, P3, tf2, contact_points, penetration_depth, normal);
    } else if constexpr (kind == detail::QuadricPairKind::kQuadricShape) {
      return quadricTriangleIntersect(s, tf1, P1, P2, P3, tf2, contact_points, penetration_depth, normal);
    } else {
      static_assert(kind == detail::QuadricPairKind::kEllipsoidTriangle,
                    "QuadricSolver::shapeTriangleIntersect: unhandled kind");
      return triangleIntersect(detail::asExact(s, tf1, "shape"), detail::asExactTriangle(P1, P2, P3, tf2),
                               contact_points, penetration_depth, normal);
    }
  }

  /// Unsigned distance (FCL's ShapeDistanceTraversalNode when !request.enable_signed_distance,
  /// OcTreeSolver, conservative advancement). Exact pairs: detail::exactDistance (separated or
  /// touching: distance >= 0 and nearest points, true; overlapping: -1 and p1 = p2 = a common
  /// point, false).
  template <typename Shape1, typename Shape2>
  bool shapeDistance(const Shape1& s1, const fcl::Transform3<S>& tf1, const Shape2& s2,
                     const fcl::Transform3<S>& tf2, S* dist = nullptr, fcl::Vector3<S>* p1 = nullptr,
                     fcl::Vector3<S>* p2 = nullptr) const {
    detail::checkTransform(tf1, "tf1");
    detail::checkTransform(tf2, "tf2");
    using Pair = detail::QuadricPair<Shape1, Shape2>;
    if constexpr (Pair::kind == detail::QuadricPairKind::kSphereClosedForm) {
      validateOperands(s1, tf1, s2, tf2);
      return libccd_.shapeDistance(s1, tf1, s2, tf2, dist, p1, p2);
    } else if constexpr (Pair::kind == detail::QuadricPairKind::kLibccd) {
      return libccd_.shapeDistance(s1, tf1, s2, tf2, dist, p1, p2);
    } else if constexpr (Pair::kind == detail::QuadricPairKind::kSupportPlane ||
                         Pair::kind == detail::QuadricPairKind::kSupportPlaneExact) {
      return supportPlanePair<Pair::swapped>(s1, tf1, s2, tf2, false, dist, p1, p2);
    } else if constexpr (Pair::kind == detail::QuadricPairKind::kPlanePlane) {
      throw std::invalid_argument(
          "fcl_quadric::QuadricSolver: no distance between two planes / half-spaces (FCL 0.7 has no closed form "
          "and its GJK segfaults on them)");
    } else {
      static_assert(isShapePairKind(Pair::kind) || Pair::kind == detail::QuadricPairKind::kQuadricShape,
                    "QuadricSolver::shapeDistance: unhandled pair kind");
      detail::ExactDistance d;
      bool separated;
      if constexpr (Pair::kind == detail::QuadricPairKind::kQuadricShape) {
        static_assert(std::is_same_v<S, double>, "fcl_quadric's quadric shapes exist for S = double only");
        separated = detail::quadricShapeDistance(s1, tf1, s2, tf2, false, &d);
      } else {
        separated = detail::exactPairDistance<Pair::swapped, false>(s1, tf1, s2, tf2, &d);
      }
      detail::writeDistance(d, dist, p1, p2);
      return separated;
    }
  }

  /// Signed distance (ShapeDistanceTraversalNode when request.enable_signed_distance). Exact
  /// pairs: detail::exactSignedDistance (negative = minus the penetration depth; p1 on s1 and p2
  /// on s2, each the deepest point inside the other when overlapping; false iff negative).
  template <typename Shape1, typename Shape2>
  bool shapeSignedDistance(const Shape1& s1, const fcl::Transform3<S>& tf1, const Shape2& s2,
                           const fcl::Transform3<S>& tf2, S* dist = nullptr, fcl::Vector3<S>* p1 = nullptr,
                           fcl::Vector3<S>* p2 = nullptr) const {
    detail::checkTransform(tf1, "tf1");
    detail::checkTransform(tf2, "tf2");
    using Pair = detail::QuadricPair<Shape1, Shape2>;
    if constexpr (Pair::kind == detail::QuadricPairKind::kLibccd) {
      return libccd_.shapeSignedDistance(s1, tf1, s2, tf2, dist, p1, p2);
    } else if constexpr (Pair::kind == detail::QuadricPairKind::kSupportPlane ||
                         Pair::kind == detail::QuadricPairKind::kSupportPlaneExact) {
      return supportPlanePair<Pair::swapped>(s1, tf1, s2, tf2, true, dist, p1, p2);
    } else if constexpr (Pair::kind == detail::QuadricPairKind::kPlanePlane) {
      throw std::invalid_argument(
          "fcl_quadric::QuadricSolver: no distance between two planes / half-spaces (FCL 0.7 has no closed form "
          "and its GJK segfaults on them)");
    } else {
      static_assert(isShapePairKind(Pair::kind) || Pair::kind == detail::QuadricPairKind::kQuadricShape ||
                        Pair::kind == detail::QuadricPairKind::kSphereClosedForm,
                    "QuadricSolver::shapeSignedDistance: unhandled pair kind");
      detail::ExactDistance d;
      bool separated;
      if constexpr (Pair::kind == detail::QuadricPairKind::kQuadricShape) {
        static_assert(std::is_same_v<S, double>, "fcl_quadric's quadric shapes exist for S = double only");
        separated = detail::quadricShapeDistance(s1, tf1, s2, tf2, true, &d);
      } else {
        separated = detail::exactPairDistance<Pair::swapped, true>(s1, tf1, s2, tf2, &d);
      }
      detail::writeDistance(d, dist, p1, p2);
      return separated;
    }
  }

  /// Shape vs a world-frame triangle (mesh-shape distance with AABB-family BVs). Ellipsoids:
  /// detail::exactDistance (libccd's GJKDistance convention: >= 0 when separate, -1 when they
  /// overlap); p1 on the shape, p2 on the triangle, world frame.
  template <typename Shape>
  bool shapeTriangleDistance(const Shape& s, const fcl::Transform3<S>& tf, const fcl::Vector3<S>& P1,
                             const fcl::Vector3<S>& P2, const fcl::Vector3<S>& P3, S* dist = nullptr,
                             fcl::Vector3<S>* p1 = nullptr, fcl::Vector3<S>* p2 = nullptr) const {
    detail::checkTransform(tf, "tf");
    constexpr detail::QuadricPairKind kind = detail::QuadricTriangle<Shape>::kind;
    if constexpr (kind == detail::QuadricPairKind::kLibccd) {
      return libccd_.shapeTriangleDistance(s, tf, P1, P2, P3, dist, p1, p2);
    } else if constexpr (kind == detail::QuadricPairKind::kQuadricShape) {
      return quadricTriangleDistance(s, tf, P1, P2, P3, fcl::Transform3<S>::Identity(), dist, p1, p2);
    } else {
      static_assert(kind == detail::QuadricPairKind::kEllipsoidTriangle,
                    "QuadricSolver::shapeTriangleDistance: unhandled kind");
      detail::ExactDistance d;
      const bool separated = detail::exactDistance(detail::asExact(s, tf, "shape"), detail::asExactTriangle(P1, P2, P3), &d);
      detail::writeDistance(d, dist, p1, p2);
      return separated;
    }
  }

  /// Shape (pose tf1) vs a triangle in the frame tf2 (oriented BVH nodes, OcTree-mesh). Points in
  /// the world frame.
  template <typename Shape>
  bool shapeTriangleDistance(const Shape& s, const fcl::Transform3<S>& tf1, const fcl::Vector3<S>& P1,
                             const fcl::Vector3<S>& P2, const fcl::Vector3<S>& P3,
                             const fcl::Transform3<S>& tf2, S* dist = nullptr, fcl::Vector3<S>* p1 = nullptr,
                             fcl::Vector3<S>* p2 = nullptr) const {
    detail::checkTransform(tf1, "tf1");
    detail::checkTransform(tf2, "tf2");
    constexpr detail::QuadricPairKind kind = detail::QuadricTriangle<Shape>::kind;
    if constexpr (kind == detail::QuadricPairKind::kLibccd) {
      return libccd_.shapeTriangleDistance(s, tf1, P1, P2, P3, tf2, dist, p1, p2);
    } else if constexpr (kind == detail::QuadricPairKind::kQuadricShape) {
      return quadricTriangleDistance(s, tf1, P1, P2, P3, tf2, dist, p1, p2);
    } else {
      static_assert(kind == detail::QuadricPairKind::kEllipsoidTriangle,
                    "QuadricSolver::shapeTriangleDistance: unhandled kind");
      detail::ExactDistance d;
      const bool separated =
          detail::exactDistance(detail::asExact(s, tf1, "shape"), detail::asExactTriangle(P1, P2, P3, tf2), &d);
      detail::writeDistance(d, dist, p1, p2);
      return separated;
    }
  }

  /// GJK warm-start hooks called by FCL's ShapeShapeCollide (collision_func_matrix-inl.h).
  /// Delegated; libccd ignores them in FCL 0.7 (getCachedGuess returns (-1, 0, 0)).
  void enableCachedGuess(bool if_enable) const { libccd_.enableCachedGuess(if_enable); }
  void setCachedGuess(const fcl::Vector3<S>& guess) const { libccd_.setCachedGuess(guess); }
  fcl::Vector3<S> getCachedGuess() const { return libccd_.getCachedGuess(); }

 private:
  // The exact kernels' validation of both operands, for the pairs answered by FCL's own closed
  // forms, which take a NaN radius, a centre at 1e200 or a scaled pose without a word (NaN or
  // DBL_MAX answers with unwritten points: session 36, an audit). ~40 ns measured.
  template <typename Shape1, typename Shape2>
  static void validateOperands(const Shape1& s1, const fcl::Transform3<S>& tf1, const Shape2& s2,
                               const fcl::Transform3<S>& tf2) {
    validateOperand(s1, tf1, "o1");
    validateOperand(s2, tf2, "o2");
  }
  template <typename Shape>
  static void validateOperand(const Shape& s, const fcl::Transform3<S>& tf, const char* which) {
    (void)detail::asExact(s, tf, which);
  }
  static void validateOperand(const fcl::Sphere<S>& s, const fcl::Transform3<S>& tf, const char* which) {
    detail::checkSphereFromFcl(static_cast<double>(s.radius), tf.linear().template cast<double>(),
                               tf.translation().template cast<double>(), which);
  }

  static constexpr bool isShapePairKind(detail::QuadricPairKind k) {
    return k == detail::QuadricPairKind::kEllipsoidEllipsoid || k == detail::QuadricPairKind::kEllipsoidPlane ||
           k == detail::QuadricPairKind::kEllipsoidHalfspace || k == detail::QuadricPairKind::kEllipsoidBox ||
           k == detail::QuadricPairKind::kEllipsoidCapsule || k == detail::QuadricPairKind::kEllipsoidCylinder ||
           k == detail::QuadricPairKind::kEllipsoidCone || k == detail::QuadricPairKind::kEllipsoidConvex;
  }

  // kSupportPlane: the shape in FCL's order s1, s2 (swapped: the plane first).
  template <bool swapped, typename Shape1, typename Shape2>
  static bool supportPlanePair(const Shape1& s1, const fcl::Transform3<S>& tf1, const Shape2& s2,
                               const fcl::Transform3<S>& tf2, bool signed_distance, S* dist, fcl::Vector3<S>* p1,
                               fcl::Vector3<S>* p2) {
    detail::ExactDistance d;
    bool separated;
    if constexpr (swapped) {
      separated = detail::supportPairDistance(s2, tf2, "o2", detail::asExact(s1, tf1, "o1"), signed_distance, &d);
      d.p1.swap(d.p2);
    } else {
      separated = detail::supportPairDistance(s1, tf1, "o1", detail::asExact(s2, tf2, "o2"), signed_distance, &d);
    }
    detail::writeDistance(d, dist, p1, p2);
    return separated;
  }

  // The unit normal from s1 to s2 when the deepest point lies on the plane (zero depth): the
  // plane normal toward the plane solid's side.
  template <bool swapped, typename Shape1, typename Shape2>
  static Eigen::Vector3d supportNormal(const Shape1& s1, const fcl::Transform3<S>& tf1, const Shape2& s2,
                                       const fcl::Transform3<S>& tf2) {
    if constexpr (swapped) {
      const detail::WorldPlane P = detail::asExact(s1, tf1, "o1");
      const bool up = P.halfspace || P.n.dot(tf2.translation().template cast<double>()) - P.d >= 0.0;
      return up ? Eigen::Vector3d(P.n) : Eigen::Vector3d(-P.n);  // from the plane toward the shape
    } else {
      const detail::WorldPlane P = detail::asExact(s2, tf2, "o2");
      const bool up = P.halfspace || P.n.dot(tf1.translation().template cast<double>()) - P.d >= 0.0;
      return up ? Eigen::Vector3d(-P.n) : Eigen::Vector3d(P.n);  // from the shape toward the plane
    }
  }

  // kQuadricShape against a triangle in the frame tf2 (tf1 = the identity: world-frame vertices);
  // the distance is FCL's unsigned shapeTriangleDistance convention.
  template <typename Shape>
  static bool quadricTriangleIntersect(const Shape& s, const fcl::Transform3<S>& tf1, const fcl::Vector3<S>& P1,
                                       const fcl::Vector3<S>& P2, const fcl::Vector3<S>& P3,
                                       const fcl::Transform3<S>& tf2, fcl::Vector3<S>* contact_points,
                                       S* penetration_depth, fcl::Vector3<S>* normal) {
    static_assert(std::is_same_v<S, double>, "fcl_quadric's quadric shapes exist for S = double only");
    const bool want = contact_points || penetration_depth || normal;
    detail::ExactContact c;
    if (!detail::quadricShapeTriangleIntersect(s, tf1, P1, P2, P3, tf2, want ? &c : nullptr)) return false;
    if (contact_points) *contact_points = c.pos;
    if (penetration_depth) *penetration_depth = c.depth;
    if (normal) *normal = c.normal;
    return true;
  }
  template <typename Shape>
  static bool quadricTriangleDistance(const Shape& s, const fcl::Transform3<S>& tf1, const fcl::Vector3<S>& P1,
                                      const fcl::Vector3<S>& P2, const fcl::Vector3<S>& P3,
                                      const fcl::Transform3<S>& tf2, S* dist, fcl::Vector3<S>* p1,
                                      fcl::Vector3<S>* p2) {
    static_assert(std::is_same_v<S, double>, "fcl_quadric's quadric shapes exist for S = double only");
    detail::ExactDistance d;
    const bool separated = detail::quadricShapeTriangleDistance(s, tf1, P1, P2, P3, tf2, false, &d);
    detail::writeDistance(d, dist, p1, p2);
    return separated;
  }

  static bool triangleIntersect(const Ellipsoid& e, const detail::WorldTriangle& t, fcl::Vector3<S>* contact_points,
                                S* penetration_depth, fcl::Vector3<S>* normal) {
    const bool want = contact_points || penetration_depth || normal;
    detail::ExactContact c;
    if (!detail::exactIntersect(e, t, want ? &c : nullptr)) return false;
    if (contact_points) *contact_points = c.pos.template cast<S>();
    if (penetration_depth) *penetration_depth = static_cast<S>(c.depth);
    if (normal) *normal = c.normal.template cast<S>();
    return true;
  }

  fcl::detail::GJKSolver_libccd<S> libccd_;
};

using QuadricSolverd = QuadricSolver<double>;

extern template class QuadricSolver<double>;

}  // namespace fcl_quadric

// -----------------------------------------------------------------------------------------------
// FCL's templates for QuadricSolver<double>: instantiated once in src/fcl/collision.cpp and
// src/fcl/distance.cpp; declared here so that no other translation unit instantiates them.
// -----------------------------------------------------------------------------------------------
namespace fcl {

namespace detail {
extern template struct CollisionFunctionMatrix<fcl_quadric::QuadricSolver<double>>;
extern template struct DistanceFunctionMatrix<fcl_quadric::QuadricSolver<double>>;
}  // namespace detail

extern template detail::CollisionFunctionMatrix<fcl_quadric::QuadricSolver<double>>&
getCollisionFunctionLookTable<fcl_quadric::QuadricSolver<double>>();
extern template detail::DistanceFunctionMatrix<fcl_quadric::QuadricSolver<double>>&
getDistanceFunctionLookTable<fcl_quadric::QuadricSolver<double>>();

extern template std::size_t collide(const CollisionObject<double>* o1, const CollisionObject<double>* o2,
                                    const fcl_quadric::QuadricSolver<double>* nsolver,
                                    const CollisionRequest<double>& request, CollisionResult<double>& result);
extern template std::size_t collide(const CollisionGeometry<double>* o1, const Transform3<double>& tf1,
                                    const CollisionGeometry<double>* o2, const Transform3<double>& tf2,
                                    const fcl_quadric::QuadricSolver<double>* nsolver,
                                    const CollisionRequest<double>& request, CollisionResult<double>& result);

/// Explicit specialization (src/fcl/distance.cpp): FCL's own body of distance() with one change.
/// FCL 0.7 (distance-inl.h) keeps the solver's signed distance and nearest points for
/// primitive-primitive pairs only when the solver is GJKSolver_libccd; for any other solver type
/// it re-runs collide() and replaces min_distance by -(max penetration depth) and both nearest
/// points by the contact position. QuadricSolver is treated like GJKSolver_libccd, so delegated
/// pairs (box-box, ...) give exactly stock FCL's answers and exact pairs keep their witness points.
template <>
double distance<fcl_quadric::QuadricSolver<double>>(const CollisionGeometry<double>* o1, const Transform3<double>& tf1,
                                                    const CollisionGeometry<double>* o2, const Transform3<double>& tf2,
                                                    const fcl_quadric::QuadricSolver<double>* nsolver,
                                                    const DistanceRequest<double>& request,
                                                    DistanceResult<double>& result);

extern template double distance<fcl_quadric::QuadricSolver<double>>(const CollisionObject<double>* o1,
                                                                    const CollisionObject<double>* o2,
                                                                    const fcl_quadric::QuadricSolver<double>* nsolver,
                                                                    const DistanceRequest<double>& request,
                                                                    DistanceResult<double>& result);

}  // namespace fcl
