#pragma once
/// \file quadric_solver.h
/// fcl_quadric::QuadricSolver<S>: a NarrowPhaseSolver for FCL 0.7 that answers ellipsoid pairs
/// exactly (certified classification, Choi 2008 Theorem 4.1; signed distance with witness points)
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
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <fcl/common/types.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/contact_point.h>
#include <fcl/narrowphase/detail/gjk_solver_libccd.h>
#include <fcl/narrowphase/distance.h>

#include "fcl_quadric/geometry/ellipsoid.h"

namespace fcl_quadric {

namespace detail {

// ---------------------------------------------------------------------------------------------
// Dispatch table: which algorithm QuadricSolver uses for a pair of FCL shape types. This is the
// one place to register a new exact pair (then add its branch in the QuadricSolver member that
// needs it; a static_assert there rejects a kind without a branch).
// ---------------------------------------------------------------------------------------------
enum class QuadricPairKind {
  /// Delegated unchanged to fcl::detail::GJKSolver_libccd<S> (including FCL's own closed forms
  /// such as sphere-sphere, sphere-box, box-box, ellipsoid-plane and ellipsoid-halfspace).
  kLibccd,
  /// fcl::Ellipsoid / fcl::Sphere pairs other than sphere-sphere: both shapes are converted to
  /// fcl_quadric::Ellipsoid (a sphere is an ellipsoid with equal radii) and answered by
  /// classifyEllipsoids / signedDistance.
  kEllipsoidEllipsoid,
  // Extension points (geometry layer functions to come in
  // include/fcl_quadric/geometry/ellipsoid_polytope.h), both orders of each pair:
  //   kEllipsoidPlane      fcl::Ellipsoid x fcl::Plane       (libccd today: FCL's closed form)
  //   kEllipsoidHalfspace  fcl::Ellipsoid x fcl::Halfspace   (libccd today: FCL's closed form)
  //   kEllipsoidBox        fcl::Ellipsoid x fcl::Box         (libccd today: MPR / GJK; OcTree leaves)
  // and for shapeTriangleIntersect / shapeTriangleDistance (BVH meshes) QuadricTriangle below:
  //   kEllipsoidTriangle   fcl::Ellipsoid x triangle         (libccd today)
};

/// Pair table for shapeIntersect / shapeDistance / shapeSignedDistance. `swapped` tells a
/// one-sided kernel (ellipsoid first) to exchange the arguments and flip normals and points.
template <typename Shape1, typename Shape2>
struct QuadricPair {
  static constexpr QuadricPairKind kind = QuadricPairKind::kLibccd;
  static constexpr bool swapped = false;
};
template <typename S>
struct QuadricPair<fcl::Ellipsoid<S>, fcl::Ellipsoid<S>> {
  static constexpr QuadricPairKind kind = QuadricPairKind::kEllipsoidEllipsoid;
  static constexpr bool swapped = false;
};
template <typename S>
struct QuadricPair<fcl::Ellipsoid<S>, fcl::Sphere<S>> {
  static constexpr QuadricPairKind kind = QuadricPairKind::kEllipsoidEllipsoid;
  static constexpr bool swapped = false;
};
template <typename S>
struct QuadricPair<fcl::Sphere<S>, fcl::Ellipsoid<S>> {
  static constexpr QuadricPairKind kind = QuadricPairKind::kEllipsoidEllipsoid;
  static constexpr bool swapped = false;
};

/// Table for the shape-triangle queries (the triangle is always the second operand).
template <typename Shape>
struct QuadricTriangle {
  static constexpr QuadricPairKind kind = QuadricPairKind::kLibccd;
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
Ellipsoid sphereFromFcl(double radius, const Eigen::Vector3d& p_WS, const char* which);

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
  return sphereFromFcl(static_cast<double>(s.radius), tf.translation().template cast<double>(), which);
}

template <typename S>
void writeDistance(const ExactDistance& d, S* dist, fcl::Vector3<S>* p1, fcl::Vector3<S>* p2) {
  if (dist) *dist = static_cast<S>(d.distance);
  if (p1) *p1 = d.p1.template cast<S>();
  if (p2) *p2 = d.p2.template cast<S>();
}

}  // namespace detail

/// NarrowPhaseSolver for FCL 0.7 (the interface of fcl::detail::GJKSolver_libccd<S>).
///
/// Exact pairs (detail::QuadricPair): fcl::Ellipsoid-fcl::Ellipsoid, fcl::Ellipsoid-fcl::Sphere,
/// fcl::Sphere-fcl::Ellipsoid. Results follow FCL's conventions:
///  - shapeIntersect: true iff the solids are not separate (touching counts as collision, certified
///    down to ~1e-27 relative gap, docs/tolerances.md). With `contacts` non-null, one ContactPoint
///    is appended: normal (unit) from o1 to o2, penetration_depth = -signed distance (0 if
///    touching), pos = midpoint of the two witness points of signedDistance.
///  - shapeDistance / shapeSignedDistance: see detail::distanceEllipsoids /
///    detail::signedDistanceEllipsoids; points p1 (on s1) and p2 (on s2) in the world frame, as
///    GJKSolver_libccd returns them in FCL 0.7.
/// Every other pair and every shape-triangle query is delegated to the internal
/// GJKSolver_libccd<S> (`libccd()`), whose tolerances and iteration limits are public.
///
/// Bad input: a non-finite transform (any pair) throws std::invalid_argument naming "tf1"/"tf2";
/// for the exact pairs a non-positive or non-finite radius, or a linear part that is not a
/// rotation within tolerance::kRotationOrthogonality, throws std::invalid_argument naming o1/o2.
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
  /// and OcTreeSolver.
  template <typename Shape1, typename Shape2>
  bool shapeIntersect(const Shape1& s1, const fcl::Transform3<S>& tf1, const Shape2& s2,
                      const fcl::Transform3<S>& tf2,
                      std::vector<fcl::ContactPoint<S>>* contacts = nullptr) const {
    detail::checkTransform(tf1, "tf1");
    detail::checkTransform(tf2, "tf2");
    using Pair = detail::QuadricPair<Shape1, Shape2>;
    if constexpr (Pair::kind == detail::QuadricPairKind::kEllipsoidEllipsoid) {
      return intersectEllipsoidPair(detail::asEllipsoid(s1, tf1, "o1"), detail::asEllipsoid(s2, tf2, "o2"),
                                    contacts);
    } else {
      static_assert(Pair::kind == detail::QuadricPairKind::kLibccd, "QuadricSolver::shapeIntersect: unhandled pair kind");
      return libccd_.shapeIntersect(s1, tf1, s2, tf2, contacts);
    }
  }

  /// Shape vs a triangle given in the world frame (FCL's BVH traversal with AABB-family BVs).
  template <typename Shape>
  bool shapeTriangleIntersect(const Shape& s, const fcl::Transform3<S>& tf, const fcl::Vector3<S>& P1,
                              const fcl::Vector3<S>& P2, const fcl::Vector3<S>& P3,
                              fcl::Vector3<S>* contact_points = nullptr, S* penetration_depth = nullptr,
                              fcl::Vector3<S>* normal = nullptr) const {
    detail::checkTransform(tf, "tf");
    static_assert(detail::QuadricTriangle<Shape>::kind == detail::QuadricPairKind::kLibccd,
                  "QuadricSolver::shapeTriangleIntersect: unhandled kind");
    return libccd_.shapeTriangleIntersect(s, tf, P1, P2, P3, contact_points, penetration_depth, normal);
  }

  /// Shape (pose tf1) vs a triangle whose vertices are in the frame tf2 (oriented BVH nodes:
  /// OBB, RSS, kIOS, OBBRSS; OcTree-mesh).
  template <typename Shape>
  bool shapeTriangleIntersect(const Shape& s, const fcl::Transform3<S>& tf1, const fcl::Vector3<S>& P1,
                              const fcl::Vector3<S>& P2, const fcl::Vector3<S>& P3,
                              const fcl::Transform3<S>& tf2, fcl::Vector3<S>* contact_points = nullptr,
                              S* penetration_depth = nullptr, fcl::Vector3<S>* normal = nullptr) const {
    detail::checkTransform(tf1, "tf1");
    detail::checkTransform(tf2, "tf2");
    static_assert(detail::QuadricTriangle<Shape>::kind == detail::QuadricPairKind::kLibccd,
                  "QuadricSolver::shapeTriangleIntersect: unhandled kind");
    return libccd_.shapeTriangleIntersect(s, tf1, P1, P2, P3, tf2, contact_points, penetration_depth, normal);
  }

  /// Unsigned distance (FCL's ShapeDistanceTraversalNode when !request.enable_signed_distance,
  /// OcTreeSolver, conservative advancement). Exact pairs: detail::distanceEllipsoids.
  template <typename Shape1, typename Shape2>
  bool shapeDistance(const Shape1& s1, const fcl::Transform3<S>& tf1, const Shape2& s2,
                     const fcl::Transform3<S>& tf2, S* dist = nullptr, fcl::Vector3<S>* p1 = nullptr,
                     fcl::Vector3<S>* p2 = nullptr) const {
    detail::checkTransform(tf1, "tf1");
    detail::checkTransform(tf2, "tf2");
    using Pair = detail::QuadricPair<Shape1, Shape2>;
    if constexpr (Pair::kind == detail::QuadricPairKind::kEllipsoidEllipsoid) {
      detail::ExactDistance d;
      const bool separated = detail::distanceEllipsoids(detail::asEllipsoid(s1, tf1, "o1"),
                                                        detail::asEllipsoid(s2, tf2, "o2"), &d);
      detail::writeDistance(d, dist, p1, p2);
      return separated;
    } else {
      static_assert(Pair::kind == detail::QuadricPairKind::kLibccd, "QuadricSolver::shapeDistance: unhandled pair kind");
      return libccd_.shapeDistance(s1, tf1, s2, tf2, dist, p1, p2);
    }
  }

  /// Signed distance (ShapeDistanceTraversalNode when request.enable_signed_distance). Exact
  /// pairs: detail::signedDistanceEllipsoids.
  template <typename Shape1, typename Shape2>
  bool shapeSignedDistance(const Shape1& s1, const fcl::Transform3<S>& tf1, const Shape2& s2,
                           const fcl::Transform3<S>& tf2, S* dist = nullptr, fcl::Vector3<S>* p1 = nullptr,
                           fcl::Vector3<S>* p2 = nullptr) const {
    detail::checkTransform(tf1, "tf1");
    detail::checkTransform(tf2, "tf2");
    using Pair = detail::QuadricPair<Shape1, Shape2>;
    if constexpr (Pair::kind == detail::QuadricPairKind::kEllipsoidEllipsoid) {
      detail::ExactDistance d;
      const bool separated = detail::signedDistanceEllipsoids(detail::asEllipsoid(s1, tf1, "o1"),
                                                              detail::asEllipsoid(s2, tf2, "o2"), &d);
      detail::writeDistance(d, dist, p1, p2);
      return separated;
    } else {
      static_assert(Pair::kind == detail::QuadricPairKind::kLibccd,
                    "QuadricSolver::shapeSignedDistance: unhandled pair kind");
      return libccd_.shapeSignedDistance(s1, tf1, s2, tf2, dist, p1, p2);
    }
  }

  /// Shape vs a world-frame triangle (mesh-shape distance with AABB-family BVs).
  template <typename Shape>
  bool shapeTriangleDistance(const Shape& s, const fcl::Transform3<S>& tf, const fcl::Vector3<S>& P1,
                             const fcl::Vector3<S>& P2, const fcl::Vector3<S>& P3, S* dist = nullptr,
                             fcl::Vector3<S>* p1 = nullptr, fcl::Vector3<S>* p2 = nullptr) const {
    detail::checkTransform(tf, "tf");
    static_assert(detail::QuadricTriangle<Shape>::kind == detail::QuadricPairKind::kLibccd,
                  "QuadricSolver::shapeTriangleDistance: unhandled kind");
    return libccd_.shapeTriangleDistance(s, tf, P1, P2, P3, dist, p1, p2);
  }

  /// Shape (pose tf1) vs a triangle in the frame tf2 (oriented BVH nodes, OcTree-mesh).
  template <typename Shape>
  bool shapeTriangleDistance(const Shape& s, const fcl::Transform3<S>& tf1, const fcl::Vector3<S>& P1,
                             const fcl::Vector3<S>& P2, const fcl::Vector3<S>& P3,
                             const fcl::Transform3<S>& tf2, S* dist = nullptr, fcl::Vector3<S>* p1 = nullptr,
                             fcl::Vector3<S>* p2 = nullptr) const {
    detail::checkTransform(tf1, "tf1");
    detail::checkTransform(tf2, "tf2");
    static_assert(detail::QuadricTriangle<Shape>::kind == detail::QuadricPairKind::kLibccd,
                  "QuadricSolver::shapeTriangleDistance: unhandled kind");
    return libccd_.shapeTriangleDistance(s, tf1, P1, P2, P3, tf2, dist, p1, p2);
  }

  /// GJK warm-start hooks called by FCL's ShapeShapeCollide (collision_func_matrix-inl.h).
  /// Delegated; libccd ignores them in FCL 0.7 (getCachedGuess returns (-1, 0, 0)).
  void enableCachedGuess(bool if_enable) const { libccd_.enableCachedGuess(if_enable); }
  void setCachedGuess(const fcl::Vector3<S>& guess) const { libccd_.setCachedGuess(guess); }
  fcl::Vector3<S> getCachedGuess() const { return libccd_.getCachedGuess(); }

 private:
  static bool intersectEllipsoidPair(const Ellipsoid& a, const Ellipsoid& b,
                                     std::vector<fcl::ContactPoint<S>>* contacts) {
    if (!contacts) return detail::intersectEllipsoids(a, b, nullptr);
    detail::ExactContact c;
    if (!detail::intersectEllipsoids(a, b, &c)) return false;
    contacts->emplace_back(c.normal.template cast<S>(), c.pos.template cast<S>(), static_cast<S>(c.depth));
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
