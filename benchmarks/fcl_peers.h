#pragma once
/// \file fcl_peers.h
/// FCL 0.7 as the peer of the benchmarks: conversion of fcl_quadric ellipsoids to FCL shapes and
/// one-call wrappers of fcl::collide / fcl::distance on (geometry, transform) pairs, so that each
/// benchmark program instantiates FCL's entry points once.

#include <cstddef>
#include <memory>
#include <vector>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/detail/gjk_solver_indep.h>
#include <fcl/narrowphase/distance.h>

#include "fcl_quadric/geometry/ellipsoid.h"
#include "sqrt3_tessellation.h"

namespace fcl_quadric {
namespace bench {

/// X_WE of an ellipsoid as an FCL transform (rotation and translation set explicitly).
inline fcl::Transform3d fclPose(const Ellipsoid& e) {
  fcl::Transform3d X_WE = fcl::Transform3d::Identity();
  X_WE.linear() = e.rotation();
  X_WE.translation() = e.center();
  return X_WE;
}

inline fcl::Ellipsoidd fclShape(const Ellipsoid& e) {
  return fcl::Ellipsoidd(e.radii()[0], e.radii()[1], e.radii()[2]);
}

/// A triangle mesh (sqrt3_tessellation.h) as an fcl::Convex.
inline std::shared_ptr<fcl::Convexd> fclConvex(const TriangleMesh& m) {
  auto vertices = std::make_shared<std::vector<fcl::Vector3d>>(m.vertices.begin(), m.vertices.end());
  auto faces = std::make_shared<std::vector<int>>();
  faces->reserve(4 * m.faces.size());
  for (const auto& f : m.faces) faces->insert(faces->end(), {3, f[0], f[1], f[2]});
  return std::make_shared<fcl::Convexd>(vertices, static_cast<int>(m.faces.size()), faces);
}

/// A triangle mesh (sqrt3_tessellation.h) as an fcl::BVHModel<OBBRSS> (FCL's usual mesh type;
/// collide tests triangle against triangle, so it sees surfaces, not volumes).
inline std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> fclBvh(const TriangleMesh& m) {
  std::vector<fcl::Triangle> triangles;
  triangles.reserve(m.faces.size());
  for (const auto& f : m.faces) triangles.emplace_back(f[0], f[1], f[2]);
  std::vector<fcl::Vector3d> vertices(m.vertices.begin(), m.vertices.end());
  auto bvh = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  bvh->beginModel(static_cast<int>(triangles.size()), static_cast<int>(vertices.size()));
  bvh->addSubModel(vertices, triangles);
  bvh->endModel();
  return bvh;
}

/// Boolean fcl::collide (no contacts) with the given GJK implementation.
inline bool fclCollide(const fcl::CollisionGeometryd* g1, const fcl::Transform3d& X_W1,
                       const fcl::CollisionGeometryd* g2, const fcl::Transform3d& X_W2,
                       fcl::GJKSolverType solver) {
  fcl::CollisionRequestd request;
  request.num_max_contacts = 1;
  request.enable_contact = false;
  request.gjk_solver_type = solver;
  fcl::CollisionResultd result;
  return fcl::collide(g1, X_W1, g2, X_W2, request, result) > 0;
}

/// Signed fcl::distance with nearest points (negative = penetration as estimated by FCL).
inline double fclSignedDistance(const fcl::CollisionGeometryd* g1, const fcl::Transform3d& X_W1,
                                const fcl::CollisionGeometryd* g2, const fcl::Transform3d& X_W2,
                                fcl::GJKSolverType solver) {
  fcl::DistanceRequestd request;
  request.enable_signed_distance = true;
  request.enable_nearest_points = true;
  request.gjk_solver_type = solver;
  fcl::DistanceResultd result;
  return fcl::distance(g1, X_W1, g2, X_W2, request, result);
}

/// Penetration depth of the first contact of fcl::collide with contacts (0 when no collision).
inline double fclPenetrationDepth(const fcl::CollisionGeometryd* g1, const fcl::Transform3d& X_W1,
                                  const fcl::CollisionGeometryd* g2, const fcl::Transform3d& X_W2,
                                  fcl::GJKSolverType solver) {
  fcl::CollisionRequestd request;
  request.num_max_contacts = 1;
  request.enable_contact = true;
  request.gjk_solver_type = solver;
  fcl::CollisionResultd result;
  if (fcl::collide(g1, X_W1, g2, X_W2, request, result) == 0) return 0.0;
  return result.getContact(0).penetration_depth;
}

/// The signed distance GJKSolver_indep computes for two ellipsoids, with the solver set up as
/// fcl::distance sets it up. fcl::distance(GST_INDEP, enable_signed_distance) continues to a
/// contact query when this is negative; in FCL 0.7.0 that query reports negative penetration
/// depths, which trips `assert(index != -1)` (distance-inl.h) in an assert-enabled libfcl (the
/// Debian package). Benchmarks therefore run that peer only on pairs where this is >= 0.
inline double fclIndepSolverSignedDistance(const fcl::Ellipsoidd& e1, const fcl::Transform3d& X_W1,
                                           const fcl::Ellipsoidd& e2, const fcl::Transform3d& X_W2) {
  fcl::detail::GJKSolver_indep<double> solver;
  solver.gjk_tolerance = fcl::DistanceRequestd().distance_tolerance;
  double d = 0.0;
  fcl::Vector3d p1, p2;
  solver.shapeSignedDistance(e1, X_W1, e2, X_W2, &d, &p1, &p2);
  return d;
}

inline const char* solverName(fcl::GJKSolverType solver) {
  return solver == fcl::GST_LIBCCD ? "fcl_libccd" : "fcl_indep";
}

}  // namespace bench
}  // namespace fcl_quadric
