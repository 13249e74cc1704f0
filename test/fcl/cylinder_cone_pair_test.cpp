// Ellipsoid-cylinder and ellipsoid-cone through QuadricSolver (fcl::collide / fcl::distance with
// &solver) and the front doors equal the geometry layer's signedDistanceEllipsoidCylinder / Cone,
// in both argument orders; near-tangent poses, with stock FCL's disagreements counted (printed,
// not asserted).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <string>

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>

#include "fcl/fcl_test_support.h"
#include "fcl_quadric/fcl/collision.h"
#include "fcl_quadric/fcl/distance.h"
#include "fcl_quadric/fcl/quadric_solver.h"
#include "fcl_quadric/geometry/ellipsoid_cylinder.h"
#include "support/random_ellipsoids.h"

namespace fcl_quadric {
namespace {

struct Case {
  bool cone = false;
  Ellipsoid e{Eigen::Vector3d::Ones(), Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()};
  double r = 1.0, L = 1.0;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p = Eigen::Vector3d::Zero();

  SignedDistanceResult kernel() const {
    return cone ? signedDistanceEllipsoidCone(e, r, L, R, p) : signedDistanceEllipsoidCylinder(e, r, L, R, p);
  }
  std::shared_ptr<fcl::CollisionGeometryd> solid() const {
    if (cone) return std::make_shared<fcl::Coned>(r, L);
    return std::make_shared<fcl::Cylinderd>(r, L);
  }
  fcl::Transform3d solidPose() const {
    fcl::Transform3d t = fcl::Transform3d::Identity();
    t.linear() = R;
    t.translation() = p;
    return t;
  }
  fcl::Transform3d ellipsoidPose() const {
    fcl::Transform3d t = fcl::Transform3d::Identity();
    t.linear() = e.rotation();
    t.translation() = e.center();
    return t;
  }
};

Case randomCase(std::mt19937_64& rng, bool cone) {
  std::uniform_real_distribution<double> u(-2.5, 2.5), ur(0.1, 1.2), ul(0.1, 2.5);
  Case c;
  c.cone = cone;
  c.e = test::anchorEllipsoid(rng);
  c.r = ur(rng);
  c.L = ul(rng);
  c.R = test::randomRotation(rng);
  c.p = Eigen::Vector3d(u(rng), u(rng), u(rng));
  return c;
}

/// Moves the solid along the kernel's normal so that the distance becomes side * gap * d0 (side
/// +1 outward, -1 inward), for an initially separated pair (d0 its distance).
bool makeNearTangent(Case* c, double gap, int side) {
  const SignedDistanceResult d0 = c->kernel();
  if (d0.status != Separation::Separated) return false;
  c->p -= d0.distance * (1.0 - side * gap) * d0.normal;
  return true;
}

TEST(CylinderConePair, SolverAndFrontDoorsAgreeWithTheGeometryLayerInBothOrders) {
  std::mt19937_64 rng(4242);
  const QuadricSolverd solver;
  for (bool cone : {false, true}) {
    int collisions = 0, near = 0;
    for (int i = 0; i < 1200; ++i) {
      Case c = randomCase(rng, cone);
      if (i % 3 == 1 && makeNearTangent(&c, 1e-8, (i % 2) ? 1 : -1)) ++near;
      const SignedDistanceResult d = c.kernel();
      auto eg = std::make_shared<fcl::Ellipsoidd>(c.e.radii());
      auto sg = c.solid();
      const fcl::Transform3d te = c.ellipsoidPose(), ts = c.solidPose();
      const bool expect = d.status != Separation::Separated;
      fcl::CollisionRequestd req;
      req.enable_contact = true;
      fcl::CollisionResultd r1, r2, r3, r4;
      fcl::collide(eg.get(), te, sg.get(), ts, &solver, req, r1);
      fcl::collide(sg.get(), ts, eg.get(), te, &solver, req, r2);
      fcl_quadric::collide(eg.get(), te, sg.get(), ts, req, r3);
      fcl_quadric::collide(sg.get(), ts, eg.get(), te, req, r4);
      for (const fcl::CollisionResultd* r : {&r1, &r2, &r3, &r4}) ASSERT_EQ(r->isCollision(), expect) << i;
      if (expect) {
        ++collisions;
        for (const fcl::CollisionResultd* r : {&r1, &r3}) {
          ASSERT_EQ(r->numContacts(), 1u);
          ASSERT_LE((r->getContact(0).normal - d.normal).norm(), 1e-12) << i;  // o1 -> o2
          ASSERT_NEAR(r->getContact(0).penetration_depth, -d.distance, 1e-12) << i;
          ASSERT_LE((r->getContact(0).pos - 0.5 * (d.point_a + d.point_b)).norm(), 1e-12) << i;
        }
        for (const fcl::CollisionResultd* r : {&r2, &r4}) {
          ASSERT_LE((r->getContact(0).normal + d.normal).norm(), 1e-12) << i;  // reversed order
          ASSERT_NEAR(r->getContact(0).penetration_depth, -d.distance, 1e-12) << i;
        }
      }
      // Signed distance with nearest points, both orders (points swap with the operands).
      fcl::DistanceRequestd dreq;
      dreq.enable_signed_distance = true;
      dreq.enable_nearest_points = true;
      fcl::DistanceResultd s1, s2;
      fcl_quadric::distance(eg.get(), te, sg.get(), ts, dreq, s1);
      fcl::distance(sg.get(), ts, eg.get(), te, &solver, dreq, s2);
      ASSERT_NEAR(s1.min_distance, d.distance, 1e-12 * (1 + std::fabs(d.distance))) << i;
      ASSERT_NEAR(s2.min_distance, d.distance, 1e-12 * (1 + std::fabs(d.distance))) << i;
      ASSERT_LE((s1.nearest_points[0] - d.point_a).norm(), 1e-12) << i;
      ASSERT_LE((s1.nearest_points[1] - d.point_b).norm(), 1e-12) << i;
      ASSERT_LE((s2.nearest_points[0] - d.point_b).norm(), 1e-12) << i;
      ASSERT_LE((s2.nearest_points[1] - d.point_a).norm(), 1e-12) << i;
      // Unsigned distance: -1 when they overlap (libccd's convention).
      fcl::DistanceRequestd ureq;
      ureq.enable_nearest_points = true;
      fcl::DistanceResultd u1;
      fcl_quadric::distance(sg.get(), ts, eg.get(), te, ureq, u1);
      if (d.status == Separation::Overlapping) {
        ASSERT_EQ(u1.min_distance, -1.0) << i;
      } else {
        ASSERT_NEAR(u1.min_distance, d.distance, 1e-12 * (1 + d.distance)) << i;
      }
    }
    std::printf("[ info     ] ellipsoid-%s: 1200 pairs (%d near-tangent at 1e-8), %d colliding, 0 disagreements\n",
                cone ? "cone" : "cylinder", near, collisions);
    EXPECT_GT(collisions, 200);
    EXPECT_GT(near, 200);
  }
}

TEST(CylinderConePair, NearTangentPairsAreCertifiedAndStockFclIsCounted) {
  std::mt19937_64 rng(777);
  for (bool cone : {false, true}) {
    int cases = 0, stock_wrong_in = 0, stock_wrong_out = 0, overlapping_in = 0;
    for (double gap : {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8}) {
      for (int i = 0; i < 100; ++i) {
        for (int side : {1, -1}) {
          Case c = randomCase(rng, cone);
          if (!makeNearTangent(&c, gap, side)) continue;
          ++cases;
          const SignedDistanceResult d = c.kernel();
          if (side > 0) {
            ASSERT_EQ(d.status, Separation::Separated) << gap << " " << i;
          } else {
            ASSERT_NE(d.status, Separation::Separated) << gap << " " << i;
            overlapping_in += d.status == Separation::Overlapping;
          }
          fcl::CollisionObjectd o1(std::make_shared<fcl::Ellipsoidd>(c.e.radii()), c.ellipsoidPose());
          fcl::CollisionObjectd o2(c.solid(), c.solidPose());
          fcl::CollisionRequestd req;
          fcl::CollisionResultd ours, stock;
          fcl_quadric::collide(&o1, &o2, req, ours);
          ASSERT_EQ(ours.isCollision(), side < 0) << gap << " " << i;
          {
            test::ScopedNoFpTraps no_traps;
            fcl::collide(&o1, &o2, req, stock);
          }
          if (stock.isCollision() != (side < 0)) ++(side < 0 ? stock_wrong_in : stock_wrong_out);
        }
      }
    }
    std::printf("[ info     ] ellipsoid-%s near-tangent (gaps 1e-3..1e-8, relative to the initial distance): %d "
                "cases; ours wrong 0 (%d inward certified Overlapping, rest Touching); stock FCL wrong %d inward, "
                "%d outward\n",
                cone ? "cone" : "cylinder", cases, overlapping_in, stock_wrong_in, stock_wrong_out);
    EXPECT_GT(cases, 500);
  }
}

TEST(CylinderConePair, SpherePairsRouteAndBadInputNamesTheOperand) {
  // (Sphere, Cylinder): FCL's closed forms for collision and distance, the ellipsoid kernel for
  // the signed distance, as (Sphere, Sphere / Box / Capsule); (Sphere, Cone) the ellipsoid kernel
  // throughout (session 35).
  static_assert(detail::QuadricPair<fcl::Sphered, fcl::Cylinderd>::kind == detail::QuadricPairKind::kSphereClosedForm, "");
  static_assert(detail::QuadricPair<fcl::Cylinderd, fcl::Sphered>::swapped, "");
  static_assert(detail::QuadricPair<fcl::Sphered, fcl::Sphered>::kind == detail::QuadricPairKind::kSphereClosedForm, "");
  static_assert(detail::QuadricPair<fcl::Sphered, fcl::Coned>::kind == detail::QuadricPairKind::kEllipsoidCone, "");
  static_assert(detail::QuadricPair<fcl::Coned, fcl::Ellipsoidd>::kind == detail::QuadricPairKind::kEllipsoidCone, "");
  static_assert(detail::QuadricPair<fcl::Coned, fcl::Ellipsoidd>::swapped, "");
  const QuadricSolverd solver;
  const fcl::Ellipsoidd e(1, 2, 3);
  fcl::Cylinderd cyl(1, 1);
  cyl.radius = -1.0;  // FCL's constructor does not check
  fcl::Transform3d t1 = fcl::Transform3d::Identity(), t2 = fcl::Transform3d::Identity();
  t2.translation() = Eigen::Vector3d(3, 0, 0);
  try {
    solver.shapeIntersect(cyl, t2, e, t1, nullptr);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& ex) {
    EXPECT_NE(std::string(ex.what()).find("o1 (fcl::Cylinder): cylinder radius"), std::string::npos) << ex.what();
  }
  fcl::Coned cone(1, 1);
  fcl::Transform3d sheared = t2;
  sheared.linear()(0, 1) = 0.5;
  try {
    solver.shapeDistance(e, t1, cone, sheared, static_cast<double*>(nullptr));
    FAIL() << "no exception";
  } catch (const std::invalid_argument& ex) {
    EXPECT_NE(std::string(ex.what()).find("o2 (fcl::Cone): cone rotation"), std::string::npos) << ex.what();
  }
}

// Sphere pairs against closed forms, through the front doors in both argument orders. A sphere of
// radius r is placed at a known gap g (negative: overlap) along the outward normal of a point of
// the partner's face (sphere, box face, capsule, cylinder side, cone side), so the signed distance
// is g exactly (up to the placement's rounding). Until session 35 these pairs went to libccd: an
// audit measured signed distances off by up to 6e-5 of the scale, a positive one for spheres
// overlapping by 1e-9, and sphere-cone collisions that missed overlaps of 1e-9-1e-6.
TEST(CylinderConePair, SpherePairsMatchClosedFormsInBothOrders) {
  std::mt19937_64 rng(35);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  const fcl::CollisionRequestd creq(1, true);
  fcl::DistanceRequestd dreq(true);
  dreq.enable_signed_distance = true;
  int cases = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const double r = 0.1 + U(rng);
    const Eigen::Matrix3d R = test::randomRotation(rng);
    const Eigen::Vector3d p = 2.0 * test::randomUnitVector(rng);
    const double th = 2 * M_PI * U(rng);
    const Eigen::Vector3d radial(std::cos(th), std::sin(th), 0.0);
    // The partner, its local point P with local outward unit normal n.
    std::shared_ptr<fcl::CollisionGeometryd> partner;
    Eigen::Vector3d P, n;
    switch (trial % 5) {
      case 0: {  // a sphere
        const double rs = 0.2 + U(rng);
        partner = std::make_shared<fcl::Sphered>(rs);
        n = test::randomUnitVector(rng);
        P = rs * n;
        break;
      }
      case 1: {  // a box face, away from its edges
        const Eigen::Vector3d h(0.3 + U(rng), 0.3 + U(rng), 0.3 + U(rng));
        partner = std::make_shared<fcl::Boxd>(2.0 * h);
        P = Eigen::Vector3d((U(rng) - 0.5) * h[0], (U(rng) - 0.5) * h[1], h[2]);
        n = Eigen::Vector3d::UnitZ();
        break;
      }
      case 2: {  // a capsule's side
        const double rc = 0.2 + U(rng), L = 0.5 + U(rng);
        partner = std::make_shared<fcl::Capsuled>(rc, L);
        P = rc * radial + (U(rng) - 0.5) * L * Eigen::Vector3d::UnitZ();
        n = radial;
        break;
      }
      case 3: {  // a cylinder's side, away from its rims
        const double rc = 0.3 + U(rng), L = 1.0 + U(rng);
        partner = std::make_shared<fcl::Cylinderd>(rc, L);
        P = rc * radial + (U(rng) - 0.5) * 0.5 * L * Eigen::Vector3d::UnitZ();
        n = radial;
        break;
      }
      default: {  // a cone's side (base at z = -h, apex at z = h), away from apex and rim
        const double rc = 0.5 + U(rng), h = 0.5 + 0.5 * U(rng);
        partner = std::make_shared<fcl::Coned>(rc, 2.0 * h);
        const double z = h * (U(rng) - 0.5);
        P = rc * (h - z) / (2.0 * h) * radial + z * Eigen::Vector3d::UnitZ();
        n = (radial + rc / (2.0 * h) * Eigen::Vector3d::UnitZ()).normalized();
        break;
      }
    }
    // Small spheres only where the partner's side curves (so the face point stays the nearest).
    const double rs = std::min(r, 0.25);
    const auto sphere = std::make_shared<fcl::Sphered>(rs);
    for (double g : {1e-2, 1e-6, 1e-9, -1e-9, -1e-6, -1e-2}) {
      fcl::Transform3d tp = fcl::Transform3d::Identity(), ts = fcl::Transform3d::Identity();
      tp.linear() = R;
      tp.translation() = p;
      ts.translation() = p + R * (P + (rs + g) * n);
      for (const bool sphere_first : {true, false}) {
        const fcl::CollisionGeometryd* a = sphere_first ? static_cast<const fcl::CollisionGeometryd*>(sphere.get()) : partner.get();
        const fcl::CollisionGeometryd* b = sphere_first ? static_cast<const fcl::CollisionGeometryd*>(partner.get()) : sphere.get();
        const fcl::Transform3d& ta = sphere_first ? ts : tp;
        const fcl::Transform3d& tb = sphere_first ? tp : ts;
        fcl::CollisionResultd cres;
        fcl_quadric::collide(a, ta, b, tb, creq, cres);
        EXPECT_EQ(cres.isCollision(), g < 0) << "partner " << trial % 5 << ", gap " << g << ", sphere first " << sphere_first;
        fcl::DistanceResultd dres;
        const double d = fcl_quadric::distance(a, ta, b, tb, dreq, dres);
        // Exact up to the placement's rounding (coordinates ~3: a few 1e-16).
        EXPECT_NEAR(d, g, 4e-15) << "partner " << trial % 5 << ", gap " << g << ", sphere first " << sphere_first;
        ++cases;
      }
    }
  }
  EXPECT_EQ(cases, 40 * 6 * 2);
}

}  // namespace
}  // namespace fcl_quadric
