#pragma once
/// \file bullet_peers.h
/// Bullet 3.24 (Debian libbullet-dev, double-precision build: BulletCollision-float64) as a peer of
/// the benchmarks: the ellipsoid Bullet users build (a btMultiSphereShape of one unit sphere with
/// setLocalScaling(radii)), poses as btTransform, and one-call wrappers of the static query
/// (btGjkPairDetector with btVoronoiSimplexSolver + btGjkEpaPenetrationDepthSolver) and of the
/// continuous one (btContinuousConvexCollision). Shared by the Google Benchmark programs and
/// `fcl_quadric bench`, so that both call Bullet the same way.
///
/// Known behaviour (docs/benchmarks.md): the scaled multisphere's support point in direction v is
/// S v / |v| (S = diag(radii)), not the ellipsoid's S^2 v / |S v|, so Bullet's answer is about a
/// slightly different convex body and misses some overlaps; btContinuousConvexCollision clamps
/// the rotation per step.

#include <limits>
#include <memory>
#include <optional>

#include <BulletCollision/CollisionShapes/btMultiSphereShape.h>
#include <BulletCollision/NarrowPhaseCollision/btContinuousConvexCollision.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h>
#include <BulletCollision/NarrowPhaseCollision/btPointCollector.h>
#include <BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h>
#include <Eigen/Geometry>

#include "fcl_quadric/geometry/ellipsoid.h"

namespace fcl_quadric {
namespace bench {

/// Bullet's ellipsoid: one sphere of radius 1 at the origin, scaled by the radii.
inline std::unique_ptr<btMultiSphereShape> bulletShape(const Eigen::Vector3d& radii) {
  const btVector3 centre(0, 0, 0);
  const btScalar radius = 1;
  auto shape = std::make_unique<btMultiSphereShape>(&centre, &radius, 1);
  shape->setLocalScaling(btVector3(radii[0], radii[1], radii[2]));
  return shape;
}

inline std::unique_ptr<btMultiSphereShape> bulletShape(const Ellipsoid& e) { return bulletShape(e.radii()); }

inline btTransform bulletPose(const Eigen::Matrix3d& R, const Eigen::Vector3d& p) {
  const btMatrix3x3 basis(R(0, 0), R(0, 1), R(0, 2), R(1, 0), R(1, 1), R(1, 2), R(2, 0), R(2, 1), R(2, 2));
  return btTransform(basis, btVector3(p[0], p[1], p[2]));
}

/// X_WE of an ellipsoid as a Bullet transform.
inline btTransform bulletPose(const Ellipsoid& e) { return bulletPose(e.rotation(), e.center()); }

inline btTransform bulletPose(const Eigen::Isometry3d& X) { return bulletPose(X.linear(), X.translation()); }

/// Bullet's signed distance (negative: penetration depth from EPA); +infinity when GJK/EPA
/// report no result (Bullet then reports no contact either).
inline double bulletSignedDistance(const btConvexShape* a, const btTransform& X_WA, const btConvexShape* b,
                                   const btTransform& X_WB) {
  btVoronoiSimplexSolver simplex;
  btGjkEpaPenetrationDepthSolver epa;
  btGjkPairDetector detector(a, b, &simplex, &epa);
  btGjkPairDetector::ClosestPointInput input;
  input.m_transformA = X_WA;
  input.m_transformB = X_WB;
  input.m_maximumDistanceSquared = BT_LARGE_FLOAT;
  btPointCollector result;
  detector.getClosestPoints(input, result, nullptr);
  return result.m_hasResult ? static_cast<double>(result.m_distance) : std::numeric_limits<double>::infinity();
}

/// Bullet's boolean answer: the GJK/EPA distance is <= 0.
inline bool bulletCollide(const btConvexShape* a, const btTransform& X_WA, const btConvexShape* b,
                          const btTransform& X_WB) {
  return bulletSignedDistance(a, X_WA, b, X_WB) <= 0.0;
}

/// btContinuousConvexCollision between the poses at t = 0 and t = 1: the time of impact, or
/// nothing when Bullet finds no contact.
inline std::optional<double> bulletTimeOfImpact(const btConvexShape* a, const btTransform& X_WA0,
                                                const btTransform& X_WA1, const btConvexShape* b,
                                                const btTransform& X_WB0, const btTransform& X_WB1) {
  btVoronoiSimplexSolver simplex;
  btGjkEpaPenetrationDepthSolver epa;
  btContinuousConvexCollision cast(a, b, &simplex, &epa);
  btConvexCast::CastResult result;
  if (!cast.calcTimeOfImpact(X_WA0, X_WA1, X_WB0, X_WB1, result)) return std::nullopt;
  return static_cast<double>(result.m_fraction);
}

}  // namespace bench
}  // namespace fcl_quadric
