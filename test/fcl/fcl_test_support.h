#pragma once
// Shared helpers of the FCL-layer tests: posed FCL shapes built from fcl_quadric ellipsoids, and
// seeded pair generators (random, and near-tangent at a relative gap).
#include <cfenv>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include <Eigen/Geometry>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision_object.h>

#include "fcl_quadric/geometry/ellipsoid.h"
#include "fcl_quadric/geometry/ellipsoid_separation.h"
#include "support/random_ellipsoids.h"

namespace fcl_quadric {
namespace test {

/// Turns the test main's floating-point traps (FE_INVALID, FE_DIVBYZERO) off for a scope. Stock
/// libccd raises them internally and recovers (e.g. ccdVec3PointTriDist2 in the GJK distance of
/// box-box), and QuadricSolver delegates such pairs to it unchanged; use this only around calls
/// that reach libccd, never around the exact paths.
class ScopedNoFpTraps {
 public:
  ScopedNoFpTraps() {
#if defined(__GLIBC__) && (defined(__x86_64__) || defined(__i386__))
    saved_ = fegetexcept();
    fedisableexcept(FE_ALL_EXCEPT);
#endif
  }
  ~ScopedNoFpTraps() {
#if defined(__GLIBC__) && (defined(__x86_64__) || defined(__i386__))
    std::feclearexcept(FE_ALL_EXCEPT);
    feenableexcept(saved_);
#endif
  }
  ScopedNoFpTraps(const ScopedNoFpTraps&) = delete;
  ScopedNoFpTraps& operator=(const ScopedNoFpTraps&) = delete;

 private:
  int saved_ = 0;
};

/// An fcl_quadric ellipsoid and the same solid as an FCL shape (fcl::Sphere when `sphere`). For a
/// sphere, `e` is Ellipsoid::sphere (identity rotation, as QuadricSolver converts it) while the
/// FCL pose carries the rotation `sphere_rotation`, which does not change the solid.
struct PosedShape {
  Ellipsoid e;
  bool sphere = false;
  Eigen::Matrix3d sphere_rotation = Eigen::Matrix3d::Identity();

  fcl::Transform3d pose() const {
    fcl::Transform3d tf = fcl::Transform3d::Identity();
    tf.linear() = sphere ? sphere_rotation : e.rotation();
    tf.translation() = e.center();
    return tf;
  }
  std::shared_ptr<fcl::CollisionGeometryd> geometry() const {
    if (sphere) return std::make_shared<fcl::Sphered>(e.radii()[0]);
    return std::make_shared<fcl::Ellipsoidd>(e.radii());
  }
  fcl::CollisionObjectd object() const { return fcl::CollisionObjectd(geometry(), pose()); }
};

struct ShapePair {
  PosedShape a, b;
  const char* kind = "";
};

/// A sphere whose FCL pose has a random (irrelevant) rotation.
inline PosedShape randomSphere(std::mt19937_64& rng, double r, const Eigen::Vector3d& c) {
  return PosedShape{Ellipsoid::sphere(r, c), true, randomRotation(rng)};
}

/// ANCHORS.md distribution; `b_sphere` makes b a sphere of radius U(0.5, 3), `a_sphere` likewise.
inline ShapePair anchorPair(std::mt19937_64& rng, bool a_sphere, bool b_sphere) {
  std::uniform_real_distribution<double> ur(0.5, 3.0), uc(-3.0, 3.0);
  auto make = [&](bool sphere) {
    if (sphere) {
      const double r = ur(rng);
      return randomSphere(rng, r, Eigen::Vector3d(uc(rng), uc(rng), uc(rng)));
    }
    return PosedShape{anchorEllipsoid(rng), false, Eigen::Matrix3d::Identity()};
  };
  PosedShape a = make(a_sphere);
  PosedShape b = make(b_sphere);
  return ShapePair{a, b, "random"};
}

/// Near-tangent pairs: b's centre at c_a + s d; bisection with classifyEllipsoids finds adjacent
/// doubles lo (not separate) < hi (separate); returns b moved to lo (1 - gap) (overlapping) and
/// hi (1 + gap) (separate): the two pairs of ANCHORS.md's near-tangent experiment.
inline std::vector<ShapePair> nearTangentPairs(std::mt19937_64& rng, bool b_sphere, double gap) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Eigen::Vector3d ra = randomRadii(rng, std::pow(10.0, u(rng) - 0.5), 10.0);
  const Eigen::Vector3d rb =
      b_sphere ? Eigen::Vector3d::Constant(std::pow(10.0, u(rng) - 0.5)) : randomRadii(rng, std::pow(10.0, u(rng) - 0.5), 10.0);
  const Eigen::Matrix3d Ra = randomRotation(rng), Rb = randomRotation(rng);
  const Eigen::Vector3d ca = 10.0 * u(rng) * randomUnitVector(rng);
  const Eigen::Vector3d d = randomUnitVector(rng);
  const Ellipsoid a(ra, Ra, ca);
  auto make_b = [&](double s) { return b_sphere ? Ellipsoid::sphere(rb[0], ca + s * d) : Ellipsoid(rb, Rb, ca + s * d); };
  double lo = 0.0, hi = 2.0 * (ra.maxCoeff() + rb.maxCoeff());
  for (int it = 0; it < 200 && std::nextafter(lo, hi) < hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    if (classifyEllipsoids(a, make_b(mid)).status == Separation::Separated) hi = mid; else lo = mid;
  }
  std::vector<ShapePair> out;
  for (double s : {lo * (1.0 - gap), hi * (1.0 + gap)}) {
    out.push_back(ShapePair{PosedShape{a, false, Eigen::Matrix3d::Identity()}, PosedShape{make_b(s), b_sphere, Rb},
                            "near-tangent"});
  }
  return out;
}

inline bool classifyCollide(const ShapePair& p) {
  return classifyEllipsoids(p.a.e, p.b.e).status != Separation::Separated;
}

}  // namespace test
}  // namespace fcl_quadric
