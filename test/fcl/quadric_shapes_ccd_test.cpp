// fcl_quadric::continuousCollide on quadric shapes (the exact region CCD, continuous/region_ccd.h)
// against independent oracles: stock FCL's GJK (libccd) on two fcl::Cylinder sampled densely in
// time for random rational motions of a circular EllipticCylinder; an analytic CSG case (a ball
// down the bore of a ring: passes when it is thinner than the bore, otherwise first touches the
// rim edge at a closed-form time); the transforms overload under CCDM_TRANS; the continuous broad
// phase; and the bad-input contract (motion types without a certified method). Meshes and
// octrees as partners: quadric_shape_mesh_ccd_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/motion/interp_motion.h>
#include <fcl/math/motion/translation_motion.h>

#include "fcl_quadric/fcl/collision.h"
#include "fcl_quadric/fcl/continuous_broadphase.h"
#include "fcl_quadric/fcl/continuous_collision.h"
#include "fcl_quadric/fcl/quadric_shapes.h"
#include "fcl_quadric/fcl/rational_motion.h"
#include "support/fcl_fixtures.h"

namespace fcl_quadric {
namespace quadric_shapes_ccd_test {
namespace {

using Transform = fcl::Transform3<double>;
using Csg = QuadricCSG<double>;
using Op = QuadricRegion::Op;

using test::pose;
Transform at(const Eigen::Vector3d& p) { return pose(Eigen::Matrix3d::Identity(), p); }

Eigen::Matrix3d randomRotation(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
}

Transform poseAt(const RationalMotion<double>& m, double t) {
  m.integrate(t);
  Transform tf;
  m.getCurrentTransform(tf);
  return tf;
}

// Stock FCL (GJK on libccd) on two fcl::Cylinder: the oracle is independent of the region engine.
bool libccdOverlaps(const fcl::Cylinder<double>& a, const Transform& ta, const fcl::Cylinder<double>& b,
                    const Transform& tb, double* depth) {
  fcl::CollisionRequest<double> req(1, true);
  req.gjk_solver_type = fcl::GST_LIBCCD;
  fcl::CollisionResult<double> res;
  fcl_quadric::collide(&a, ta, &b, tb, req, res);
  if (res.numContacts() == 0) return false;
  *depth = res.getContact(0).penetration_depth;
  return true;
}

TEST(QuadricShapeCcd, CircularEllipticCylinderMatchesLibccdSampledAlongRandomRationalMotions) {
  std::mt19937 rng(5150);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  int collisions = 0;
  for (int trial = 0; trial < 24; ++trial) {
    const double r1 = 0.3 + 0.5 * U(rng), l1 = 0.6 + 1.2 * U(rng), r2 = 0.3 + 0.5 * U(rng), l2 = 0.6 + 1.2 * U(rng);
    const EllipticCylinder<double> ours(r1, r1, l1);
    const fcl::Cylinder<double> same(r1, l1), other(r2, l2);
    auto point = [&](double s) { return Eigen::Vector3d(s * (2 * U(rng) - 1), s * (2 * U(rng) - 1), s * (2 * U(rng) - 1)); };
    const RationalMotion<double> m1(pose(randomRotation(rng), point(2.0)), pose(randomRotation(rng), point(2.0)));
    const RationalMotion<double> m2(pose(randomRotation(rng), point(0.6)), pose(randomRotation(rng), point(0.6)));
    fcl::ContinuousCollisionRequest<double> req;
    fcl::ContinuousCollisionResult<double> res;
    fcl_quadric::continuousCollide(&ours, &m1, &other, &m2, req, res);
    const ContinuousCollideStats stats = lastContinuousCollideStats();
    EXPECT_EQ(stats.path, ContinuousCollideStats::Path::Exact);
    // Dense sampling: a clear libccd overlap (depth > 1e-6) must come at or after the reported
    // contact; before it (by more than 1e-6 in time) libccd sees no clear overlap.
    const int n = 800;
    for (int i = 0; i <= n; ++i) {
      const double t = static_cast<double>(i) / n;
      double depth = 0.0;
      if (!libccdOverlaps(same, poseAt(m1, t), other, poseAt(m2, t), &depth) || depth <= 1e-6) continue;
      ASSERT_TRUE(res.is_collide) << "trial " << trial << ": libccd overlap (depth " << depth << ") at t = " << t;
      ASSERT_LE(res.time_of_contact, t) << "trial " << trial;
      break;
    }
    if (!res.is_collide) continue;
    ++collisions;
    const double tc = res.time_of_contact;
    if (tc == 0.0) {  // overlapping at the start: libccd agrees
      double depth = 0.0;
      EXPECT_TRUE(libccdOverlaps(same, poseAt(m1, 0.0), other, poseAt(m2, 0.0), &depth)) << "trial " << trial;
      continue;
    }
    for (int i = 0; i <= n; ++i) {
      const double t = (tc - 1e-6) * i / n;
      if (t < 0.0) break;
      double depth = 0.0;
      if (libccdOverlaps(same, poseAt(m1, t), other, poseAt(m2, t), &depth)) {
        EXPECT_LE(depth, 1e-6) << "trial " << trial << ": overlap at " << t << " before the contact " << tc;
      }
    }
    // At the contact time the pair touches: libccd's distance is ~0 and the contact point lies on
    // both surfaces (within the bodies' tolerance).
    const Transform t1 = poseAt(m1, tc), t2 = poseAt(m2, tc);
    EXPECT_TRUE(res.contact_tf1.isApprox(t1, 1e-12));
    for (const auto& [cyl, tf] : {std::pair(&same, t1), std::pair(&other, t2)}) {
      const Eigen::Vector3d local = tf.inverse() * stats.contact_point;
      const double dr = std::hypot(local[0], local[1]) - cyl->radius, dz = std::fabs(local[2]) - 0.5 * cyl->lz;
      const double dist = (dr <= 0 && dz <= 0) ? std::max(dr, dz) : std::hypot(std::max(dr, 0.0), std::max(dz, 0.0));
      EXPECT_LT(std::fabs(dist), 1e-5) << "trial " << trial;
    }
  }
  EXPECT_GE(collisions, 6);
  EXPECT_LE(collisions, 20);
}

TEST(QuadricShapeCcd, BallDownTheBoreOfARingPassesOrTouchesTheRimAtTheAnalyticTime) {
  // Ring = ellipsoid (1, 1, 0.5) minus the coaxial cylinder of radius 0.4. A ball on the axis
  // falling from z = 3 to z = -3: thinner than the bore it passes; thicker (radius r) it first
  // touches the rim circle (radius 0.4 at height z_rim = 0.5 sqrt(1 - 0.16)) when its centre is at
  // z_rim + sqrt(r^2 - 0.16).
  auto outer = std::make_shared<Quadric<double>>(Quadric<double>::ellipsoid(1.0, 1.0, 0.5));
  auto bore = std::make_shared<Quadric<double>>(Quadric<double>::ellipticCylinder(0.4, 0.4));
  const Csg ring(Op::Difference, {{outer, Transform::Identity()}, {bore, Transform::Identity()}});
  const RationalMotion<double> still(Transform::Identity(), Transform::Identity());
  const fcl::TranslationMotion<double> down(at({0, 0, 3}), at({0, 0, -3}));
  fcl::ContinuousCollisionRequest<double> req;
  {
    const fcl::Sphere<double> thin(0.4 - 1e-3);
    fcl::ContinuousCollisionResult<double> res;
    fcl_quadric::continuousCollide(&ring, &still, &thin, &down, req, res);
    EXPECT_FALSE(res.is_collide);
    EXPECT_EQ(res.time_of_contact, 1.0);
  }
  for (double r : {0.6}) {  // a line contact (the rim circle): ~2 s of certified search
    const fcl::Sphere<double> thick(r);
    fcl::ContinuousCollisionResult<double> res;
    fcl_quadric::continuousCollide(&thick, &down, &ring, &still, req, res);
    const double z = 0.5 * std::sqrt(1.0 - 0.16) + std::sqrt(r * r - 0.16);
    const double expected = (3.0 - z) / 6.0;
    ASSERT_TRUE(res.is_collide);
    EXPECT_LE(res.time_of_contact, expected + 1e-12);
    EXPECT_NEAR(res.time_of_contact, expected, 1e-7);
    const Eigen::Vector3d p = lastContinuousCollideStats().contact_point;
    EXPECT_NEAR(std::hypot(p[0], p[1]), 0.4, 1e-5) << "on the rim circle";
    EXPECT_NEAR(p[2], 0.5 * std::sqrt(1.0 - 0.16), 1e-5);
  }
}

TEST(QuadricShapeCcd, TransformsOverloadTranslatesAndOtherMotionTypesThrow) {
  const EllipticCylinder<double> cyl(1.0, 0.5, 2.0);
  const fcl::Sphere<double> ball(0.25);
  fcl::ContinuousCollisionRequest<double> req;
  req.ccd_motion_type = fcl::CCDM_TRANS;
  fcl::ContinuousCollisionResult<double> res;
  // The ball travels along y towards the flat side (semi-axis 0.5): contact when y = 0.75.
  fcl_quadric::continuousCollide(&cyl, Transform::Identity(), Transform::Identity(), &ball, at({0, 4, 0.2}),
                                 at({0, -4, 0.2}), req, res);
  ASSERT_TRUE(res.is_collide);
  EXPECT_NEAR(res.time_of_contact, (4.0 - 0.75) / 8.0, 1e-7);

  req.ccd_motion_type = fcl::CCDM_LINEAR;
  try {
    fcl_quadric::continuousCollide(&cyl, Transform::Identity(), Transform::Identity(), &ball, at({0, 4, 0}),
                                   at({0, -4, 0}), req, res);
    ADD_FAILURE() << "CCDM_LINEAR accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("CCDM_TRANS"), std::string::npos) << e.what();
  }
  const fcl::InterpMotion<double> interp(at({0, 4, 0}), at({0, -4, 0}));
  const RationalMotion<double> still(Transform::Identity(), Transform::Identity());
  try {
    fcl_quadric::continuousCollide(&cyl, &still, &ball, &interp, req, res);
    ADD_FAILURE() << "InterpMotion accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("motion2 is an fcl::InterpMotion"), std::string::npos) << e.what();
  }
}

TEST(QuadricShapeCcd, ContinuousBroadPhaseAnswersQuadricShapePairsExactly) {
  auto cyl = std::make_shared<EllipticCylinder<double>>(1.0, 0.5, 2.0);
  auto ball = std::make_shared<fcl::Sphere<double>>(0.25);
  SweptCollisionObject a(cyl, PiecewiseMotion(MotionMatrix()));
  SweptCollisionObject b(ball, PiecewiseMotion(MotionMatrix::fromPoses(Eigen::Matrix3d::Identity(), {0, 4, 0.2},
                                                                      Eigen::Matrix3d::Identity(), {0, -4, 0.2})));
  SweptCollisionObject c(ball, PiecewiseMotion(MotionMatrix::fromPoses(Eigen::Matrix3d::Identity(), {5, 4, 0},
                                                                      Eigen::Matrix3d::Identity(), {5, -4, 0})));
  fcl::DynamicAABBTreeCollisionManager<double> manager;
  manager.registerObject(&a);
  manager.registerObject(&b);
  manager.registerObject(&c);
  manager.setup();
  ContinuousBroadPhaseRequest request;
  ContinuousBroadPhaseResult result;
  continuousCollideBroadPhase(&manager, motionMap({&a, &b, &c}), request, result);
  ASSERT_EQ(result.contacts.size(), 1u);
  EXPECT_TRUE(result.contacts[0].exact);
  EXPECT_NEAR(result.contacts[0].time_of_contact, (4.0 - 0.75) / 8.0, 1e-7);
  EXPECT_NEAR(result.contacts[0].contact_point[1], 0.5, 1e-6);
  EXPECT_EQ(result.delegated, 0u);
}

}  // namespace
}  // namespace quadric_shapes_ccd_test
}  // namespace fcl_quadric

namespace fcl_quadric {
namespace quadric_shapes_ccd_test {
namespace {

// A cuboid as a CSG intersection of six half-spaces (a QuadricShape, so its boundary elements
// are cached on the shape).
std::shared_ptr<const QuadricCSG<double>> csgBox(const Eigen::Vector3d& h) {
  std::vector<QuadricCSG<double>::Child> c;
  for (int i = 0; i < 3; ++i)
    for (double s : {1.0, -1.0})
      c.push_back({std::make_shared<const Quadric<double>>(Quadric<double>::halfspace(s * Eigen::Vector3d::Unit(i), h[i]))});
  return std::make_shared<const QuadricCSG<double>>(QuadricRegion::Op::Intersection, c);
}

// CCDC_POLYNOMIAL_SOLVER selects the dimension reduction of thesis §6.2.2 (continuous/
// dimension_reduction_ccd.h): on a box against a capped elliptic cylinder it agrees with the
// certified space-time engine (the default) on every random rational motion.
TEST(QuadricShapeCcd, PolynomialSolverRequestAgreesWithTheCertifiedEngine) {
  std::mt19937 rng(77);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  const auto box = csgBox({0.5, 0.4, 0.3});
  const EllipticCylinder<double> cyl(0.6, 0.4, 1.2);
  int collisions = 0;
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::Vector3d p(U(rng), U(rng), U(rng)), d = Eigen::Vector3d(U(rng), U(rng), U(rng)).normalized();
    const RationalMotion<double> m1(pose(randomRotation(rng), 2.5 * d), pose(randomRotation(rng), -2.5 * d + 0.4 * p));
    const RationalMotion<double> m2(pose(randomRotation(rng), 0.3 * p), pose(randomRotation(rng), -0.3 * p));
    fcl::ContinuousCollisionRequest<double> req;
    fcl::ContinuousCollisionResult<double> engine, reduction;
    fcl_quadric::continuousCollide(box.get(), &m1, &cyl, &m2, req, engine);
    const int engine_boxes = lastContinuousCollideStats().steps;
    req.ccd_solver_type = fcl::CCDC_POLYNOMIAL_SOLVER;
    fcl_quadric::continuousCollide(box.get(), &m1, &cyl, &m2, req, reduction);
    ASSERT_EQ(engine.is_collide, reduction.is_collide) << "trial " << trial;
    if (!engine.is_collide) continue;
    ++collisions;
    EXPECT_LE(engine.time_of_contact, reduction.time_of_contact + 1e-9) << "trial " << trial;
    EXPECT_NEAR(engine.time_of_contact, reduction.time_of_contact, 1e-7) << "trial " << trial;
    // The reduction verified a handful of candidates where the engine visited boxes.
    EXPECT_LT(lastContinuousCollideStats().steps, engine_boxes) << "trial " << trial;
  }
  EXPECT_GE(collisions, 5);
}

// FCL primitives under CCDC_POLYNOMIAL_SOLVER get their boundary elements from a cache keyed by
// type and size: boxes of two sizes and an fcl::Cylinder, interleaved so that a wrong key would
// hand one box the other's elements, against the certified engine on the same motions.
TEST(QuadricShapeCcd, PolynomialSolverOnFclPrimitivesAgreesWithTheEngineForEachSize) {
  std::mt19937 rng(91);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  const fcl::Box<double> small(0.8, 0.6, 0.5), large(1.4, 0.6, 0.9);
  const fcl::Cylinder<double> rod(0.3, 1.5);
  const EllipticCylinder<double> cyl(0.6, 0.4, 1.2);
  const fcl::CollisionGeometry<double>* partners[] = {&small, &large, &rod};
  int collisions = 0, first_times_differ = 0, decided = 0;
  for (int trial = 0; trial < 4; ++trial) {
    const Eigen::Vector3d p(U(rng), U(rng), U(rng)), d = Eigen::Vector3d(U(rng), U(rng), U(rng)).normalized();
    const RationalMotion<double> m1(pose(randomRotation(rng), 2.5 * d), pose(randomRotation(rng), -2.5 * d + 0.3 * p));
    const RationalMotion<double> m2(pose(randomRotation(rng), 0.2 * p), pose(randomRotation(rng), -0.2 * p));
    double first_time = -1.0;
    for (const fcl::CollisionGeometry<double>* g : partners) {
      fcl::ContinuousCollisionRequest<double> req;
      fcl::ContinuousCollisionResult<double> engine, reduction;
      fcl_quadric::continuousCollide(g, &m1, &cyl, &m2, req, engine);
      req.ccd_solver_type = fcl::CCDC_POLYNOMIAL_SOLVER;
      fcl_quadric::continuousCollide(g, &m1, &cyl, &m2, req, reduction);
      decided += lastContinuousCollideStats().dimension_reduction;
      ASSERT_EQ(engine.is_collide, reduction.is_collide) << "trial " << trial << " node type " << g->getNodeType();
      if (!engine.is_collide) continue;
      ++collisions;
      EXPECT_NEAR(engine.time_of_contact, reduction.time_of_contact, 1e-7) << "trial " << trial;
      if (first_time >= 0.0 && std::abs(first_time - reduction.time_of_contact) > 1e-6) ++first_times_differ;
      if (first_time < 0.0) first_time = reduction.time_of_contact;
    }
  }
  EXPECT_GE(collisions, 6);
  EXPECT_GE(first_times_differ, 2);  // the sizes matter on these motions
  EXPECT_GE(decided, 8);             // of 12: the reduction (not its fallback) answered most
}

}  // namespace
}  // namespace quadric_shapes_ccd_test
}  // namespace fcl_quadric
