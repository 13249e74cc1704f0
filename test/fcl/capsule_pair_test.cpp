// Ellipsoid-capsule through QuadricSolver and the front doors equals the geometry layer's
// signedDistanceEllipsoidCapsule, in both argument orders, including near-tangent poses.
#include <gtest/gtest.h>

#include <memory>
#include <random>

#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/ellipsoid.h>

#include "fcl_quadric/fcl/collision.h"
#include "fcl_quadric/fcl/distance.h"
#include "fcl_quadric/geometry/ellipsoid_capsule.h"
#include "support/random_ellipsoids.h"

namespace fcl_quadric {
namespace {

TEST(CapsulePair, FrontDoorsAgreeWithTheGeometryLayerInBothOrders) {
  std::mt19937_64 rng(141);
  std::uniform_real_distribution<double> u(-2.5, 2.5), ur(0.1, 1.0), ul(0.0, 2.0);
  int collisions = 0, near = 0;
  for (int i = 0; i < 2000; ++i) {
    const Ellipsoid e = test::anchorEllipsoid(rng);
    const double r = ur(rng), L = ul(rng);
    const Eigen::Matrix3d R = test::randomRotation(rng);
    Eigen::Vector3d p(u(rng), u(rng), u(rng));
    if (i % 2 == 1) {
      // Near-tangent: slide the capsule along the direction of its witness to a relative gap 1e-8.
      const SignedDistanceResult d0 = signedDistanceEllipsoidCapsule(e, r, L, R, p);
      p -= d0.distance * d0.normal * (1.0 - ((i % 4 == 1) ? 1e-8 : -1e-8));
      ++near;
    }
    const SignedDistanceResult d = signedDistanceEllipsoidCapsule(e, r, L, R, p);
    auto eg = std::make_shared<fcl::Ellipsoidd>(e.radii());
    auto cg = std::make_shared<fcl::Capsuled>(r, L);
    fcl::Transform3d te = fcl::Transform3d::Identity(), tc = fcl::Transform3d::Identity();
    te.linear() = e.rotation();
    te.translation() = e.center();
    tc.linear() = R;
    tc.translation() = p;
    fcl::CollisionRequestd req;
    req.enable_contact = true;
    fcl::CollisionResultd r1, r2;
    fcl_quadric::collide(eg.get(), te, cg.get(), tc, req, r1);
    fcl_quadric::collide(cg.get(), tc, eg.get(), te, req, r2);
    const bool expect = d.status != Separation::Separated;
    ASSERT_EQ(r1.isCollision(), expect) << i;
    ASSERT_EQ(r2.isCollision(), expect) << i;
    if (expect) {
      ++collisions;
      ASSERT_NEAR((r1.getContact(0).normal - d.normal).norm(), 0.0, 1e-12);
      ASSERT_NEAR((r2.getContact(0).normal + d.normal).norm(), 0.0, 1e-12);  // o1 -> o2
      ASSERT_NEAR(r1.getContact(0).penetration_depth, -d.distance, 1e-12);
    }
    fcl::DistanceRequestd dreq;
    dreq.enable_signed_distance = true;
    dreq.enable_nearest_points = true;
    fcl::DistanceResultd dr;
    fcl_quadric::distance(eg.get(), te, cg.get(), tc, dreq, dr);
    if (d.status == Separation::Separated) {
      ASSERT_NEAR(dr.min_distance, d.distance, 1e-12 * (1 + d.distance));
    }
  }
  EXPECT_GT(collisions, 300);
  EXPECT_EQ(near, 1000);
}

}  // namespace
}  // namespace fcl_quadric
