// QuadricSolver's double-precision kernels and its explicit instantiation for double. This file
// instantiates no FCL traversal or function matrix (those live in collision.cpp / distance.cpp).
#include "fcl_quadric/fcl/quadric_solver.h"

#include <sstream>
#include <stdexcept>
#include <string>

#include "fcl_quadric/geometry/ellipsoid_separation.h"
#include "fcl_quadric/geometry/signed_distance.h"

namespace fcl_quadric {
namespace detail {

namespace {

[[noreturn]] void rethrowNamed(const char* which, const char* shape, const std::invalid_argument& e) {
  std::ostringstream os;
  os << "fcl_quadric::QuadricSolver: " << which << " (" << shape << "): " << e.what();
  throw std::invalid_argument(os.str());
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

Ellipsoid sphereFromFcl(double radius, const Eigen::Vector3d& p_WS, const char* which) {
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

bool intersectEllipsoids(const Ellipsoid& a, const Ellipsoid& b, ExactContact* contact) {
  const SeparationCertificate cert = classifyEllipsoids(a, b);
  if (cert.status == Separation::Separated) return false;
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
  const SignedDistanceResult d = signedDistance(a, b);
  out->distance = d.distance;
  out->p1 = d.point_a;
  out->p2 = d.point_b;
  return d.distance >= 0.0;
}

}  // namespace detail

template class QuadricSolver<double>;

}  // namespace fcl_quadric
