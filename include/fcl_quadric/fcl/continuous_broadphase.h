#pragma once
/// \file continuous_broadphase.h
/// Continuous collision over a broad-phase manager (issue 4; Choi 2008 thesis §5.4.1).
///
/// The manager must hold collision objects whose AABBs are their SWEPT AABBs over [0, 1], so that
/// every pair that may touch at some t in [0, 1] is a candidate. SweptCollisionObject sets such an
/// AABB (sweptAABB below); a plain fcl::CollisionObject keeps its static AABB and is treated as
/// static unless it has a motion in the map.
///
/// continuousCollideBroadPhase runs manager->collide(data, callback) once. For each candidate pair
/// the callback runs:
///  - ellipsoid / sphere pairs: the exact CCD (continuousCollideEllipsoids, first contact only);
///  - pairs with a quadric shape (quadric_shapes.h): fcl_quadric::continuousCollide's exact
///    region CCD (continuous/region_ccd.h; counted in exact_solves, contact point exact);
///  - any other pair: fcl_quadric::continuousCollide with RationalMotion objects (delegated to
///    fcl::continuousCollide with request.delegated_request; not certified).
/// Two modes:
///  - every pair (default): each pair that touches in [0, 1] is reported with its first contact
///    time;
///  - earliest only: the running minimum contact time t-bar (thesis §5.4.1) is kept, and every
///    later ellipsoid pair is solved only on [0, t-bar] (CcdOptions::t_max = t-bar): a pair that
///    cannot touch before t-bar is discarded by the culls of the exact solver. The traversal stops
///    when t-bar reaches 0. The one reported pair has the global minimum contact time.
///
/// Only double. Implementation in src/fcl/continuous_collision.cpp.

#include <cstddef>
#include <memory>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include <fcl/broadphase/broadphase_collision_manager.h>
#include <fcl/math/bv/AABB.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/continuous_collision_request.h>

#include "fcl_quadric/continuous/motion_matrix.h"
#include "fcl_quadric/geometry/ellipsoid.h"

namespace fcl_quadric {

/// Conservative AABB of the solid swept by `body` (in body coordinates) under `motion` over
/// [0, 1]. Per piece and axis i: the centre coordinate c_i(t) = (M(t) (c, 1))_i / w(t) is bounded
/// by the rational Bezier hull (min and max of the ratios of the Bernstein coefficients of
/// numerator and w, valid when w's coefficients have one strict sign; the piece is halved until
/// they do), and the half-extent h_i(t) = |row_i(L(t)) R diag(radii)| / |w| by
/// sqrt(max Bernstein coefficient of its squared numerator) / min |w| (and by the largest radius for
/// rigid motions). Widened by a relative 1e-12 for rounding.
/// \throws std::invalid_argument if w cannot be certified sign-definite on a piece.
fcl::AABB<double> sweptAABB(const Ellipsoid& body, const PiecewiseMotion& motion);

/// The same for a ball (centre, radius) in body coordinates (any geometry's bounding sphere).
/// \throws std::invalid_argument for a negative or non-finite radius or a non-finite centre, and
/// as above.
fcl::AABB<double> sweptAABB(const Eigen::Vector3d& centre, double radius, const PiecewiseMotion& motion);

/// A collision object whose AABB is the swept AABB of its geometry under `motion` over [0, 1]
/// (ellipsoids and spheres: sweptAABB(Ellipsoid, motion); any other geometry: its local bounding
/// sphere, aabb_center / aabb_radius), and whose transform is the pose at t = 0. Register it in
/// any broad-phase manager. Call refreshSweptAABB() after changing the motion or calling
/// computeAABB() (which would restore the static AABB).
/// \throws std::invalid_argument for a null geometry or a non-rigid pose at t = 0 of a geometry
///         that is not an ellipsoid or sphere.
class SweptCollisionObject : public fcl::CollisionObject<double> {
 public:
  SweptCollisionObject(const std::shared_ptr<fcl::CollisionGeometry<double>>& geometry, PiecewiseMotion motion);
  const PiecewiseMotion& motion() const { return motion_; }
  /// Replaces the motion: the transform becomes the pose at t = 0 and the AABB the swept one.
  /// \throws std::invalid_argument as the constructor.
  void setMotion(PiecewiseMotion motion);
  /// Recomputes the swept AABB (after the geometry changed in place). \throws as the constructor.
  void refreshSweptAABB();

 private:
  PiecewiseMotion motion_;
};

/// Objects -> motions (body -> world over [0, 1]). Objects without an entry are static at their
/// current transform.
using MotionMap = std::unordered_map<const fcl::CollisionObject<double>*, PiecewiseMotion>;

/// The motions of a set of SweptCollisionObjects (null entries are skipped).
MotionMap motionMap(const std::vector<SweptCollisionObject*>& objects);

struct ContinuousBroadPhaseRequest {
  /// Report only the earliest contact, pruning with the running minimum t-bar.
  bool earliest_only = false;
  /// For pairs that are not ellipsoid/sphere pairs (passed to fcl::continuousCollide).
  fcl::ContinuousCollisionRequest<double> delegated_request{};
};

struct ContinuousContactPair {
  const fcl::CollisionObject<double>* o1 = nullptr;
  const fcl::CollisionObject<double>* o2 = nullptr;
  /// First contact time in [0, 1].
  double time_of_contact = 1.0;
  /// World contact point (exact pairs; the midpoint of the two posed centres for delegated pairs).
  Eigen::Vector3d contact_point = Eigen::Vector3d::Zero();
  /// Answered by the exact CCD (false: delegated to FCL, not certified).
  bool exact = true;
  /// The exact solver flagged near-tangent or unresolved decisions (contact reported early).
  bool near_tangent = false;
};

struct ContinuousBroadPhaseResult {
  /// Colliding pairs sorted by time (earliest_only: at most one, the global earliest).
  std::vector<ContinuousContactPair> contacts;
  /// Candidate pairs handed over by the manager (overlapping swept AABBs).
  std::size_t candidate_pairs = 0;
  /// Exact CCD solves run, and how many of them a cull (bounding spheres, separating plane) ended.
  std::size_t exact_solves = 0;
  std::size_t culled = 0;
  std::size_t delegated = 0;

  bool collide() const { return !contacts.empty(); }
  /// Earliest contact time (1 when there is none).
  double earliestTime() const { return contacts.empty() ? 1.0 : contacts.front().time_of_contact; }
};

/// Continuous collision of all objects of `manager` (already set up) over [0, 1].
/// \throws std::invalid_argument if manager is null, and from the exact solver on bad motions.
void continuousCollideBroadPhase(const fcl::BroadPhaseCollisionManager<double>* manager, const MotionMap& motions,
                                 const ContinuousBroadPhaseRequest& request, ContinuousBroadPhaseResult& result);

}  // namespace fcl_quadric
