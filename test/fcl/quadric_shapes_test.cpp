// FCL-facing quadric shapes (quadric_shapes.h): the circular EllipticCylinder against
// fcl::Cylinder (local AABB, volume, inertia, and collisions against ellipsoids agreeing with the
// exact ellipsoid-cylinder kernel on random poses), analytic pairs for Quadric and QuadricCSG,
// bad input, the dispatch (fcl_quadric::collide, broad-phase managers through
// defaultCollisionFunction; a plain fcl::collide / fcl::distance with FCL's stock solver must not
// crash) and the documented unsupported cases.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/broadphase/default_broadphase_callbacks.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/octree/octree.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/plane.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include "fcl_quadric/algebra/quadric_matrix.h"
#include "fcl_quadric/fcl/collision.h"
#include "fcl_quadric/fcl/distance.h"
#include "fcl_quadric/fcl/quadric_shapes.h"
#include "fcl_quadric/geometry/ellipsoid_cylinder.h"
#include "support/fcl_fixtures.h"
#include "support/random_ellipsoids.h"

#include <octomap/OcTree.h>

namespace fcl_quadric {
namespace quadric_shapes_test {
namespace {

using Transform = fcl::Transform3<double>;
using Csg = QuadricCSG<double>;
using Op = QuadricRegion::Op;
constexpr double kPi = 3.14159265358979323846;

using test::pose;

bool collides(const fcl::CollisionGeometry<double>& a, const Transform& ta, const fcl::CollisionGeometry<double>& b,
              const Transform& tb) {
  fcl::CollisionRequest<double> req;
  fcl::CollisionResult<double> res;
  return fcl_quadric::collide(&a, ta, &b, tb, req, res) > 0;
}

TEST(EllipticCylinderShape, CircularCaseAgreesWithFclCylinderOnAabbVolumeAndInertia) {
  for (const auto& [r, L] : {std::pair(0.5, 2.0), std::pair(1.3, 0.4), std::pair(2.0, 2.0)}) {
    EllipticCylinder<double> ours(r, r, L);
    fcl::Cylinder<double> theirs(r, L);
    ours.computeLocalAABB();
    theirs.computeLocalAABB();
    EXPECT_TRUE(ours.aabb_local.min_.isApprox(theirs.aabb_local.min_, 1e-15));
    EXPECT_TRUE(ours.aabb_local.max_.isApprox(theirs.aabb_local.max_, 1e-15));
    EXPECT_NEAR(ours.aabb_radius, theirs.aabb_radius, 1e-14);
    EXPECT_NEAR(ours.computeVolume(), theirs.computeVolume(), 1e-14 * theirs.computeVolume());
    EXPECT_TRUE(ours.computeMomentofInertia().isApprox(theirs.computeMomentofInertia(), 1e-14));
    EXPECT_TRUE(ours.computeCOM().isZero(0.0));
    // The closed forms agree with the generic quadrature of the same region.
    const MassProperties mp = regionMassProperties(ours.region(), ours.localBox());
    EXPECT_NEAR(mp.volume, ours.computeVolume(), 1e-7 * mp.volume);
    EXPECT_TRUE(mp.inertia.isApprox(ours.computeMomentofInertia(), 1e-6));
  }
}

TEST(EllipticCylinderShape, CircularCaseCollidesLikeTheExactEllipsoidCylinderKernelOnRandomPoses) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(-1.8, 1.8), s(0.3, 1.2);
  int decided = 0, hits = 0;
  for (int trial = 0; trial < 150; ++trial) {
    const double r = s(rng), L = 2 * s(rng);
    const Eigen::Vector3d radii = test::randomRadii(rng, 0.8, 3.0);
    const Transform tc = pose(test::randomRotation(rng), Eigen::Vector3d(u(rng), u(rng), u(rng)));
    const Transform te = pose(test::randomRotation(rng), Eigen::Vector3d(u(rng), u(rng), u(rng)));
    const Ellipsoid e(radii, te.linear(), te.translation());
    const SignedDistanceResult ref = signedDistanceEllipsoidCylinder(e, r, L, tc.linear(), tc.translation());
    if (std::fabs(ref.distance) < 1e-6) continue;  // tolerance band
    ++decided;
    EllipticCylinder<double> ours(r, r, L);
    fcl::Cylinder<double> theirs(r, L);
    fcl::Ellipsoid<double> ell(radii);
    const bool expected = ref.distance < 0;
    hits += expected;
    EXPECT_EQ(collides(ours, tc, ell, te), expected) << "trial " << trial << " d = " << ref.distance;
    EXPECT_EQ(collides(ell, te, ours, tc), expected) << "trial " << trial << " (swapped)";
    EXPECT_EQ(collides(theirs, tc, ell, te), expected) << "trial " << trial << " (fcl::Cylinder path)";
  }
  EXPECT_GT(decided, 120);
  EXPECT_GT(hits, 10);  // both answers well represented
  EXPECT_LT(hits, decided - 10);
}

TEST(EllipticCylinderShape, AnalyticSphereContactsAlongEachAxis) {
  const double a = 1.5, b = 0.5, L = 3.0, rs = 0.25;
  EllipticCylinder<double> cyl(a, b, L);
  fcl::Sphere<double> sphere(rs);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Transform tc = pose(R, Eigen::Vector3d(0.3, -1.0, 2.0));
  // Extremes of the solid along its local axes: a, b (side), L/2 (cap).
  for (const Eigen::Vector3d& d : {Eigen::Vector3d(a, 0, 0), Eigen::Vector3d(0, -b, 0), Eigen::Vector3d(0, 0, L / 2)}) {
    const Eigen::Vector3d n = d.normalized();
    for (double gap : {1e-3, 1e-7}) {
      EXPECT_FALSE(collides(cyl, tc, sphere, pose(Eigen::Matrix3d::Identity(), tc * (d + (rs + gap) * n))))
          << d.transpose() << " gap " << gap;
      EXPECT_TRUE(collides(cyl, tc, sphere, pose(Eigen::Matrix3d::Identity(), tc * (d + (rs - gap) * n))))
          << d.transpose() << " penetration " << gap;
    }
  }
}

TEST(EllipticCylinderShape, SphereClosedFormAgreesWithTheGeneralPathOnCollideAndDistance) {
  // The front doors answer an EllipticCylinder against an fcl::Sphere by the closed form of
  // sphere_solid.h; the same solid as a clipped Quadric goes the general way (GJK's screening and
  // the region engine for collide, GJK / EPA for distance). Both argument orders.
  std::mt19937_64 rng(4505);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int colliding = 0;
  for (int k = 0; k < 300; ++k) {
    const double a = 0.2 + std::fabs(unit(rng)), b = 0.2 + std::fabs(unit(rng)), L = 0.3 + 2.0 * std::fabs(unit(rng));
    const EllipticCylinder<double> cyl(a, b, L);
    const Quadric<double> general(quadric::ellipticCylinder(a, b), {{Eigen::Vector3d::UnitZ(), 0.5 * L},
                                                                     {-Eigen::Vector3d::UnitZ(), 0.5 * L}});
    const fcl::Sphere<double> sphere(0.05 + 0.5 * std::fabs(unit(rng)));
    const Eigen::Vector3d axis = Eigen::Vector3d(unit(rng), unit(rng), 1.0).normalized();
    const Transform tc =
        pose(Eigen::AngleAxisd(3.0 * unit(rng), axis).toRotationMatrix(), Eigen::Vector3d(unit(rng), unit(rng), unit(rng)));
    const Eigen::Vector3d local(1.6 * a * unit(rng), 1.6 * b * unit(rng), 0.8 * L * unit(rng));
    const Transform ts = pose(Eigen::Matrix3d::Identity(), tc * local);
    for (const bool sphere_first : {false, true}) {
      auto query = [&](const fcl::CollisionGeometry<double>& shape, fcl::CollisionResult<double>* cres,
                       fcl::DistanceResult<double>* dres) {
        fcl::CollisionRequest<double> creq;
        creq.enable_contact = true;
        fcl::DistanceRequest<double> dreq;
        dreq.enable_signed_distance = true;
        dreq.enable_nearest_points = true;
        if (sphere_first) {
          fcl_quadric::collide(&sphere, ts, &shape, tc, creq, *cres);
          return fcl_quadric::distance(&sphere, ts, &shape, tc, dreq, *dres);
        }
        fcl_quadric::collide(&shape, tc, &sphere, ts, creq, *cres);
        return fcl_quadric::distance(&shape, tc, &sphere, ts, dreq, *dres);
      };
      fcl::CollisionResult<double> c_fast, c_general;
      fcl::DistanceResult<double> d_fast, d_general;
      const double fast = query(cyl, &c_fast, &d_fast), slow = query(general, &c_general, &d_general);
      EXPECT_NEAR(fast, slow, 1e-9) << k;
      if (std::fabs(slow) > 1e-8) {
        EXPECT_EQ(c_fast.isCollision(), c_general.isCollision()) << k;
      }
      EXPECT_EQ(c_fast.isCollision(), fast <= 0.0) << k;
      // The witnesses in FCL's argument order: the sphere's on the sphere, the cylinder's on it.
      const Eigen::Vector3d on_sphere = d_fast.nearest_points[sphere_first ? 0 : 1];
      const Eigen::Vector3d on_cyl = tc.inverse() * d_fast.nearest_points[sphere_first ? 1 : 0];
      EXPECT_NEAR((on_sphere - ts.translation()).norm(), sphere.radius, 1e-12);
      EXPECT_NEAR(std::max((on_cyl.x() / a) * (on_cyl.x() / a) + (on_cyl.y() / b) * (on_cyl.y() / b) - 1.0,
                           std::fabs(on_cyl.z()) - 0.5 * L) < 1e-12,
                  true, 0.0) << k;
      // An fcl::Ellipsoid of three equal radii is the same ball, answered the same way.
      {
        const fcl::Ellipsoid<double> ball(sphere.radius, sphere.radius, sphere.radius);
        fcl::DistanceRequest<double> dreq;
        dreq.enable_signed_distance = true;
        fcl::DistanceResult<double> dres;
        const double via_ellipsoid = sphere_first ? fcl_quadric::distance(&ball, ts, &cyl, tc, dreq, dres)
                                                  : fcl_quadric::distance(&cyl, tc, &ball, ts, dreq, dres);
        EXPECT_EQ(via_ellipsoid, fast) << k;
      }
      if (c_fast.isCollision()) {
        ++colliding;
        // The contact is a point of both solids, its normal unit.
        const fcl::Contact<double>& contact = c_fast.getContact(0);
        const Eigen::Vector3d x = tc.inverse() * contact.pos;
        EXPECT_LE((x.x() / a) * (x.x() / a) + (x.y() / b) * (x.y() / b), 1.0 + 1e-12) << k;
        EXPECT_LE(std::fabs(x.z()), 0.5 * L + 1e-12) << k;
        EXPECT_LE((contact.pos - ts.translation()).norm(), sphere.radius + 1e-12) << k;
        EXPECT_NEAR(contact.normal.norm(), 1.0, 1e-12) << k;
      }
    }
  }
  EXPECT_GT(colliding, 100);
  // A bad sphere radius still gets the general path's error.
  const fcl::Sphere<double> bad(-1.0);
  const EllipticCylinder<double> cyl(1.0, 0.5, 1.0);
  fcl::CollisionRequest<double> req;
  fcl::CollisionResult<double> res;
  EXPECT_THROW(fcl_quadric::collide(&cyl, Transform::Identity(), &bad, Transform::Identity(), req, res),
               std::invalid_argument);
}

/// An operand of the front door with its solid as a quadric region (local frame) and a bounding
/// box: the region engine's view of it, the oracle of the tests below.
struct SolidOperand {
  std::string name;
  std::shared_ptr<fcl::CollisionGeometry<double>> geometry;
  QuadricRegion region;
  Box3 box;
};

QuadricRegion boxSolid(const Eigen::Vector3d& h) {
  std::vector<QuadricRegion> planes;
  for (int i = 0; i < 3; ++i)
    for (double sign : {1.0, -1.0}) planes.push_back(QuadricRegion::halfspace(sign * Eigen::Vector3d::Unit(i), h[i]));
  return QuadricRegion::combine(Op::Intersection, planes);
}

SolidOperand quadricOperand(const std::string& name, std::shared_ptr<QuadricShape<double>> q) {
  return {name, q, q->region(), q->localBox()};
}

std::vector<SolidOperand> convexOperands() {
  using Q = Quadric<double>;
  const Eigen::Vector3d hb(0.5, 0.3, 0.7);
  const double rc = 0.5, hc = 0.6, rs = 0.45;
  return {
      quadricOperand("EllipticCylinder", std::make_shared<EllipticCylinder<double>>(0.6, 0.35, 1.4)),
      quadricOperand("clipped paraboloid",
                     std::make_shared<Q>(Q::ellipticParaboloid(0.8, 0.5, {{Eigen::Vector3d::UnitZ(), 1.5}}))),
      quadricOperand("clipped ellipsoid",
                     std::make_shared<Q>(Q::ellipsoid(0.9, 0.5, 0.7, {{Eigen::Vector3d(1, 1, 0), 0.3}}))),
      {"fcl::Box", std::make_shared<fcl::Box<double>>(2.0 * hb), boxSolid(hb), Box3{-hb, hb}},
      {"fcl::Cylinder", std::make_shared<fcl::Cylinder<double>>(rc, 2.0 * hc),
       QuadricRegion::combine(Op::Intersection, {QuadricRegion::atom(quadric::ellipticCylinder(rc, rc)),
                                                 boxSolid(Eigen::Vector3d(10, 10, hc))}),
       Box3{Eigen::Vector3d(-rc, -rc, -hc), Eigen::Vector3d(rc, rc, hc)}},
      {"fcl::Sphere", std::make_shared<fcl::Sphere<double>>(rs),
       QuadricRegion::atom(quadric::ellipsoid(Eigen::Vector3d::Constant(rs))),
       Box3{Eigen::Vector3d::Constant(-rs), Eigen::Vector3d::Constant(rs)}},
  };
}

/// Operands that are not convex, or not bounded: a union of two balls (an exact convex cover),
/// a ring (an inexact one: the bore is dropped) and a half-space (its oracle box is large enough
/// to hold every partner's reach in the tests below).
std::vector<SolidOperand> otherOperands() {
  using Q = Quadric<double>;
  const Transform I = Transform::Identity();
  Transform up = I, down = I;
  up.translation() = Eigen::Vector3d(0, 0, 0.5);
  down.translation() = Eigen::Vector3d(0.1, 0, -0.5);
  auto ball = std::make_shared<Q>(Q::ellipsoid(0.45, 0.45, 0.45));
  auto ring = std::make_shared<Csg>(Op::Difference, std::vector<Csg::Child>{{std::make_shared<Q>(Q::ellipsoid(1.0, 1.0, 0.5)), I},
                                                                            {std::make_shared<Q>(Q::ellipticCylinder(0.5, 0.5)), I}});
  const Eigen::Vector3d n = Eigen::Vector3d(0.3, -0.2, 1.0).normalized();
  return {
      quadricOperand("two balls", std::make_shared<Csg>(Op::Union, std::vector<Csg::Child>{{ball, up}, {ball, down}})),
      quadricOperand("ring", ring),
      {"fcl::Halfspace", std::make_shared<fcl::Halfspace<double>>(n, 0.1), QuadricRegion::halfspace(n, 0.1),
       Box3{Eigen::Vector3d::Constant(-20), Eigen::Vector3d::Constant(20)}},
  };
}

// A bounded quadric shape goes to GJK's screening before the region engine (session 30), as the
// pieces of its convex cover, against a convex partner or a half-space: far and clearly
// overlapping pairs are decided by certificates, the rest by the engine. Oracle: the region engine
// itself on the same solids (collideRegions, no GJK), on random poses, in both argument orders;
// a reported contact point lies in both solids. Pairs of two non-convex shapes go to the engine
// alone and are checked too.
TEST(QuadricShapeDispatch, ScreenedPairsAgreeWithTheRegionEngine) {
  std::vector<SolidOperand> ops = convexOperands();
  for (SolidOperand& o : otherOperands()) ops.push_back(std::move(o));
  std::mt19937_64 rng(2030);
  std::uniform_real_distribution<double> u(-1.6, 1.6);
  int colliding = 0, separated = 0;
  for (int i = 0; i < 4 * static_cast<int>(ops.size() * ops.size()); ++i) {
    const SolidOperand& a = ops[i % ops.size()];
    const SolidOperand& b = ops[(i / ops.size()) % ops.size()];
    // Only pairs with a quadric shape take this path (FCL answers the others).
    if (!dynamic_cast<const QuadricShape<double>*>(a.geometry.get()) &&
        !dynamic_cast<const QuadricShape<double>*>(b.geometry.get()))
      continue;
    Transform ta = Transform::Identity(), tb = Transform::Identity();
    ta.linear() = test::randomRotation(rng);
    ta.translation() = Eigen::Vector3d(u(rng), u(rng), u(rng)) * 0.2;
    tb.linear() = test::randomRotation(rng);
    tb.translation() = ta.translation() + Eigen::Vector3d(u(rng), u(rng), u(rng));
    const Transform X = ta.inverse() * tb;
    const RegionRelation truth = collideRegions(a.region, a.box, b.region, b.box, X.linear(), X.translation()).relation;
    if (truth == RegionRelation::Touching) continue;
    for (bool swap : {false, true}) {
      fcl::CollisionRequest<double> req(1, true);
      fcl::CollisionResult<double> res;
      const std::size_t n = swap ? fcl_quadric::collide(b.geometry.get(), tb, a.geometry.get(), ta, req, res)
                                 : fcl_quadric::collide(a.geometry.get(), ta, b.geometry.get(), tb, req, res);
      const std::string what = "pair " + std::to_string(i) + ": " + a.name + " and " + b.name + (swap ? " (swapped)" : "");
      ASSERT_EQ(n > 0, truth == RegionRelation::Overlapping) << what;
      if (n == 0) continue;
      const fcl::Contact<double>& c = res.getContact(0);
      EXPECT_GE(a.region.classifyPoint(ta.inverse() * c.pos), 0) << what;
      EXPECT_GE(b.region.classifyPoint(tb.inverse() * c.pos), 0) << what;
      EXPECT_NEAR(c.normal.norm(), 1.0, 1e-12) << what;
    }
    (truth == RegionRelation::Overlapping ? colliding : separated)++;
  }
  EXPECT_GT(colliding, 60);
  EXPECT_GT(separated, 60);
}

// Near tangency, on both sides of the screening's band (2e-8 of the pair's scale, here about 5e-8):
// analytic touching positions of two parallel capped cylinders side by side (a line contact), cap
// to cap (a face contact), and a box face against a cylinder's side. Moved apart by 1e-7 or more
// they must not collide (GJK certifies it); moved together by any gap down to 1e-10 they must.
// Inside the band the region engine decides, and may err toward contact: before GJK screened
// these pairs, the front door reported the side-by-side pair colliding at a gap of 1e-7.
TEST(QuadricShapeDispatch, ConvexPairsNearTangencyAreDecidedOnBothSidesOfTheScreeningBand) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.9, Eigen::Vector3d(1, -2, 2).normalized()).toRotationMatrix();
  const Eigen::Vector3d p0(0.4, -0.7, 1.1);
  const Transform ta = pose(R, p0);
  auto a = std::make_shared<EllipticCylinder<double>>(0.5, 0.5, 2.0);
  auto side = std::make_shared<EllipticCylinder<double>>(0.3, 0.3, 1.0);
  auto box = std::make_shared<fcl::Box<double>>(1.0, 1.0, 1.0);
  struct Case {
    const char* name;
    const fcl::CollisionGeometry<double>* b;
    Eigen::Vector3d direction, lateral;  // in a's frame
    double touching;                     // the centre offset along `direction` at contact
  };
  const std::vector<Case> cases = {
      {"side by side", side.get(), Eigen::Vector3d::UnitX(), Eigen::Vector3d(0, 0, 0.2), 0.8},
      {"cap to cap", side.get(), Eigen::Vector3d::UnitZ(), Eigen::Vector3d(0.1, -0.05, 0), 1.5},
      {"box face on the side", box.get(), Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, 0, 0.3), 1.0},
  };
  for (const Case& c : cases) {
    for (double gap : {1e-3, 1e-6, 1e-7, 1e-8, 1e-10}) {
      for (double sign : {1.0, -1.0}) {
        const Transform tb = pose(R, p0 + R * ((c.touching + sign * gap) * c.direction + c.lateral));
        for (bool swap : {false, true}) {
          fcl::CollisionRequest<double> req;
          fcl::CollisionResult<double> res;
          const bool hit = (swap ? fcl_quadric::collide(c.b, tb, a.get(), ta, req, res)
                                 : fcl_quadric::collide(a.get(), ta, c.b, tb, req, res)) > 0;
          std::ostringstream what;
          what << c.name << ", relative gap " << sign * gap << (swap ? " (swapped)" : "");
          if (sign < 0) {
            EXPECT_TRUE(hit) << what.str();
          } else if (gap >= 1e-7) {
            EXPECT_FALSE(hit) << what.str();
          }
        }
      }
    }
  }
}

// A union of two balls is screened piece by piece: a sphere just touching one ball (overlapping it
// by 1e-13: GJK certifies neither overlap nor separation there, so the engine decides, and errs
// toward contact) while far from the other must collide, whichever ball it touches; moved off by
// 1e-6 it must not. (A screening that let the far ball's verdict stand for the union fails here.)
TEST(QuadricShapeDispatch, UnionNearContactWithOnePieceIsLeftToTheEngine) {
  using Q = Quadric<double>;
  const Transform I = Transform::Identity();
  Transform up = I, down = I;
  up.translation() = Eigen::Vector3d(0, 0, 0.5);
  down.translation() = Eigen::Vector3d(0, 0, -0.5);
  const double rb = 0.45, rs = 0.2;
  auto ball = std::make_shared<Q>(Q::ellipsoid(rb, rb, rb));
  const Csg balls(Op::Union, std::vector<Csg::Child>{{ball, up}, {ball, down}});
  const fcl::Sphere<double> sphere(rs);
  std::mt19937_64 rng(3);
  const Transform tu = pose(test::randomRotation(rng), Eigen::Vector3d(0.2, -0.1, 0.3));
  for (const double side : {1.0, -1.0}) {  // above the upper ball, below the lower one
    const Eigen::Vector3d centre(0, 0, side * 0.5);
    const Eigen::Vector3d dir = Eigen::Vector3d(0.3, 0.4, side).normalized();
    for (const double gap : {-1e-13, 1e-6}) {
      const Transform ts = pose(Eigen::Matrix3d::Identity(), tu * (centre + (rb + rs + gap) * dir));
      for (bool swap : {false, true}) {
        fcl::CollisionRequest<double> req;
        fcl::CollisionResult<double> res;
        const bool hit = (swap ? fcl_quadric::collide(&sphere, ts, &balls, tu, req, res)
                               : fcl_quadric::collide(&balls, tu, &sphere, ts, req, res)) > 0;
        EXPECT_EQ(hit, gap < 0) << (side > 0 ? "upper" : "lower") << " ball, gap " << gap << (swap ? " (swapped)" : "");
      }
    }
  }
}

// The support mapping each shape makes at construction, and the cover it makes once: the closed
// form for an EllipticCylinder, fromRegion's for another convex region (the same support points
// as one made afresh), none for a non-convex shape; the cover exact for a union of convex solids
// and not for a ring, made once and shared by copies.
TEST(QuadricShapeTypes, ConvexSupportAndCoverAreMadeOnceFromTheRegion) {
  using Q = Quadric<double>;
  const Transform I = Transform::Identity();
  const EllipticCylinder<double> cylinder(0.6, 0.35, 1.4);
  ASSERT_TRUE(cylinder.convexSupport());
  EXPECT_EQ(cylinder.convexSupport()->kind(), ConvexSupport::Kind::EllipticCylinder);
  const Q paraboloid = Q::ellipticParaboloid(0.8, 0.5, {{Eigen::Vector3d::UnitZ(), 1.5}});
  ASSERT_TRUE(paraboloid.convexSupport());
  const std::optional<ConvexSupport> fresh = ConvexSupport::fromRegion(paraboloid.region(), paraboloid.localBox());
  ASSERT_TRUE(fresh);
  std::mt19937_64 rng(8);
  std::normal_distribution<double> g(0.0, 1.0);
  for (int i = 0; i < 50; ++i) {
    const Eigen::Vector3d n(g(rng), g(rng), g(rng));
    EXPECT_EQ(paraboloid.convexSupport()->support(n), fresh->support(n)) << n.transpose();
    // The cylinder's support is its closed form: the rim point of the end facing n.
    const Eigen::Vector3d x = cylinder.convexSupport()->support(n);
    EXPECT_NEAR(x.x() * x.x() / (0.6 * 0.6) + x.y() * x.y() / (0.35 * 0.35), 1.0, 1e-12);
    EXPECT_EQ(x.z(), n.z() >= 0 ? 0.7 : -0.7);
  }
  auto ball = std::make_shared<Q>(Q::ellipsoid(0.5, 0.5, 0.5));
  Transform up = I;
  up.translation() = Eigen::Vector3d(0, 0, 0.6);
  const Csg balls(Op::Union, std::vector<Csg::Child>{{ball, I}, {ball, up}});
  const Csg ring(Op::Difference, std::vector<Csg::Child>{{std::make_shared<Q>(Q::ellipsoid(1.0, 1.0, 0.5)), I},
                                                         {std::make_shared<Q>(Q::ellipticCylinder(0.5, 0.5)), I}});
  EXPECT_FALSE(balls.convexSupport());
  EXPECT_FALSE(ring.convexSupport());
  EXPECT_TRUE(balls.sharedConvexCover()->exact);
  EXPECT_EQ(balls.sharedConvexCover()->pieces.size(), 2u);
  EXPECT_FALSE(ring.sharedConvexCover()->exact);
  EXPECT_EQ(cylinder.sharedConvexCover()->pieces.size(), 1u);
  EXPECT_TRUE(cylinder.sharedConvexCover()->exact);
  EXPECT_EQ(balls.sharedConvexCover(), balls.sharedConvexCover());  // made once
  const Csg copy = balls;
  EXPECT_EQ(copy.sharedConvexCover(), balls.sharedConvexCover());  // and shared by copies
}

TEST(QuadricShapeTypes, NamedQuadricsHaveAnalyticExtentsAndContacts) {
  using Clip = HalfspaceClip<double>;
  const double h = 2.0;
  // Paraboloid cap x^2 + y^2 <= z <= h: a sphere on the axis below the apex, above the cap.
  const Quadric<double> par = Quadric<double>::ellipticParaboloid(1.0, 1.0, {Clip{{0, 0, 1}, h}});
  EXPECT_TRUE(par.bounded());
  // Certified outward, tight to ~1e-6 of the extent (tolerance_region::kRegionAabbRelative per stage).
  EXPECT_GE(par.localBox().hi[0], std::sqrt(h));
  EXPECT_NEAR(par.localBox().hi[0], std::sqrt(h), 4e-6);
  EXPECT_NEAR(par.computeVolume(), kPi * h * h / 2, 1e-6);
  EXPECT_NEAR(par.computeCOM()[2], 2 * h / 3, 1e-6);
  fcl::Sphere<double> s(0.2);
  const Transform I = Transform::Identity();
  EXPECT_FALSE(collides(par, I, s, pose(Eigen::Matrix3d::Identity(), {0, 0, -0.2 - 1e-4})));
  EXPECT_TRUE(collides(par, I, s, pose(Eigen::Matrix3d::Identity(), {0, 0, -0.2 + 1e-4})));
  EXPECT_FALSE(collides(par, I, s, pose(Eigen::Matrix3d::Identity(), {0, 0, h + 0.2 + 1e-4})));
  // Beside the wall: the nearest point of x^2 = z (y = 0) to (x0, 0, z0) is at distance 0.2.
  // Take the foot point (t, 0, t^2) and move along the outward normal (2t, 0, -1)/|.|.
  const double t = 1.0;
  const Eigen::Vector3d foot(t, 0, t * t), nrm = Eigen::Vector3d(2 * t, 0, -1).normalized();
  EXPECT_FALSE(collides(par, I, s, pose(Eigen::Matrix3d::Identity(), foot + (0.2 + 1e-5) * nrm)));
  EXPECT_TRUE(collides(par, I, s, pose(Eigen::Matrix3d::Identity(), foot + (0.2 - 1e-5) * nrm)));

  // Hyperboloid of one sheet (waist radius 1) clipped |z| <= 1: a sphere of radius 0.5 at the
  // waist's centre is inside; a ring-shaped gap: a sphere at (1 + 0.5 + gap, 0, 0) is outside.
  const Quadric<double> hyp =
      Quadric<double>::hyperboloidOneSheet(1.0, 1.0, 1.0, {Clip{{0, 0, 1}, 1.0}, Clip{{0, 0, -1}, 1.0}});
  fcl::Sphere<double> s5(0.5);
  EXPECT_TRUE(collides(hyp, I, s5, I));
  EXPECT_FALSE(collides(hyp, I, s5, pose(Eigen::Matrix3d::Identity(), {1.5 + 1e-4, 0, 0})));
  EXPECT_TRUE(collides(hyp, I, s5, pose(Eigen::Matrix3d::Identity(), {1.5 - 1e-4, 0, 0})));
  // Two-sheet hyperboloid, upper cap 1 <= z <= 3 (vertex at z = 1).
  const Quadric<double> two = Quadric<double>::hyperboloidTwoSheets(1.0, 1.0, 1.0, {Clip{{0, 0, -1}, 0.0}, Clip{{0, 0, 1}, 3.0}});
  EXPECT_LE(two.localBox().lo[2], 1.0);
  EXPECT_NEAR(two.localBox().lo[2], 1.0, 4e-6);
  EXPECT_FALSE(collides(two, I, s5, pose(Eigen::Matrix3d::Identity(), {0, 0, 0.5 - 1e-4})));
  EXPECT_TRUE(collides(two, I, s5, pose(Eigen::Matrix3d::Identity(), {0, 0, 0.5 + 1e-4})));
}

TEST(QuadricShapeTypes, RingLetsASmallBallThroughItsBore) {
  // Ring = ball of radius 1 minus a coaxial cylinder of radius 0.6 (thesis Example 6.1 (a)).
  auto ballShape = std::make_shared<Quadric<double>>(Quadric<double>::ellipsoid(1.0, 1.0, 1.0));
  auto bore = std::make_shared<Quadric<double>>(Quadric<double>::ellipticCylinder(0.6, 0.6));
  EXPECT_FALSE(bore->bounded());
  const Csg ring(Op::Difference, {{ballShape, Transform::Identity()}, {bore, Transform::Identity()}});
  EXPECT_NEAR(ring.computeVolume(), 4.0 / 3.0 * kPi * std::pow(1 - 0.36, 1.5), 1e-6);
  const Transform I = Transform::Identity();
  fcl::Sphere<double> small(0.6 - 1e-4), big(0.6 + 1e-4);
  EXPECT_FALSE(collides(ring, I, small, I));
  EXPECT_TRUE(collides(ring, I, big, I));
  // Poses on CSG children: the same ring built from a cylinder posed along x and rotated back.
  const Eigen::Matrix3d Ry = Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Csg ring_x(Op::Difference, {{ballShape, I}, {bore, pose(Ry, Eigen::Vector3d::Zero())}});
  EXPECT_FALSE(collides(ring_x, pose(Ry.transpose(), Eigen::Vector3d::Zero()), small, I));
  EXPECT_FALSE(collides(ring_x, I, fcl::Sphere<double>(0.3), pose(Eigen::Matrix3d::Identity(), {0.5, 0, 0})));
  EXPECT_TRUE(collides(ring_x, I, fcl::Sphere<double>(0.3), pose(Eigen::Matrix3d::Identity(), {0, 0.5, 0})));
}

TEST(QuadricShapeTypes, BadInputThrowsNamingTheValue) {
  auto expectThrow = [](auto fn, const char* word) {
    try {
      fn();
      ADD_FAILURE() << "no exception, expected one mentioning '" << word << "'";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
    }
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  expectThrow([] { EllipticCylinder<double>(0.0, 1.0, 1.0); }, "semi-axis a");
  expectThrow([] { EllipticCylinder<double>(1.0, -1.0, 1.0); }, "semi-axis b");
  expectThrow([&] { EllipticCylinder<double>(1.0, 1.0, nan); }, "length lz");
  Eigen::Matrix4d Q = Eigen::Vector4d(1, 1, 1, -1).asDiagonal();
  Q(0, 3) = 0.3;
  expectThrow([&] { Quadric<double>{Q}; }, "symmetric");
  expectThrow([] { Quadric<double>::ellipsoid(1.0, 1.0, 1.0, {HalfspaceClip<double>{{1, 0, 0}, -1.5}}); }, "empty");
  expectThrow([] { Quadric<double>::ellipsoid(1.0, 1.0, 1.0, {HalfspaceClip<double>{{0, 0, 0}, 1.0}}); }, "non-zero");
  expectThrow([] { Quadric<double>::ellipticCone(1.0, 0.0, 1.0); }, "b");
  auto ballShape = std::make_shared<Quadric<double>>(Quadric<double>::ellipsoid(1.0, 1.0, 1.0));
  auto par = std::make_shared<Quadric<double>>(Quadric<double>::ellipticParaboloid(1.0, 1.0));
  expectThrow([&] { par->localBox(); }, "unbounded");
  expectThrow([&] { par->sharedConvexCover(); }, "unbounded");
  EXPECT_FALSE(par->convexSupport());  // (no failure mode: none for an unbounded shape)
  expectThrow([&] { fcl::CollisionObject<double> obj(par); }, "unbounded");
  expectThrow([&] { Csg(Op::Union, {}); }, "at least one child");
  expectThrow([&] { Csg(Op::Union, {{nullptr, Transform::Identity()}}); }, "child 0 is null");
  expectThrow([&] { Csg(Op::Union, {{ballShape, Transform::Identity()}, {par, Transform::Identity()}}); }, "unbounded");
  Transform skew = Transform::Identity();
  skew.linear()(0, 1) = 0.5;
  expectThrow([&] { Csg(Op::Union, {{ballShape, skew}}); }, "child 0 pose");
  expectThrow([&] { Csg(Op::Intersection, {{ballShape, pose(Eigen::Matrix3d::Identity(), {5, 0, 0})}, {ballShape, Transform::Identity()}}); },
              "empty");
}

// fcl_quadric::collide tries the seed paper's small-ellipsoid filter (ellipsoid_quadric.h, zones
// split by the clip planes) before the region engine. Its answers, and its contact points, against
// the region engine alone on the same pairs: ellipsoids placed near clipped quadric surfaces, in
// both argument orders.
TEST(QuadricShapeDispatch, SmallEllipsoidFilterAgreesWithTheRegionEngineAndItsPointsAreInterior) {
  using Q = Quadric<double>;
  const Transform I = Transform::Identity();
  auto ring_ball = std::make_shared<Q>(Q::ellipsoid(1.2, 1.2, 0.6));
  auto ring_bore = std::make_shared<Q>(Q::ellipticCylinder(0.6, 0.6));
  auto ring = std::make_shared<Csg>(Op::Difference, std::vector<Csg::Child>{{ring_ball, I}, {ring_bore, I}});
  auto wedge_body = std::make_shared<Q>(Q::ellipticCylinder(1.0, 0.7, {{Eigen::Vector3d::UnitZ(), 0.4}, {-Eigen::Vector3d::UnitZ(), 0.4}}));
  auto wedge_cut = std::make_shared<Q>(Q::halfspace(-Eigen::Vector3d::UnitY(), 0.0));
  auto wedge_bore = std::make_shared<Q>(Q::ellipticCylinder(0.3, 0.3));
  auto wedge =
      std::make_shared<Csg>(Op::Difference, std::vector<Csg::Child>{{wedge_body, I}, {wedge_cut, I}, {wedge_bore, I}});
  // Each shape with a quadric near whose surface the ellipsoids are placed.
  const std::vector<std::pair<std::shared_ptr<const QuadricShape<double>>, Eigen::Matrix4d>> shapes = {
      {std::make_shared<Q>(Q::ellipticParaboloid(1.0, 1.0, {{Eigen::Vector3d::UnitZ(), 3.0}})),
       quadric::ellipticParaboloid(1.0, 1.0)},
      {std::make_shared<Q>(Q::hyperboloidOneSheet(1.0, 0.8, 1.0, {{Eigen::Vector3d::UnitZ(), 2.0}, {-Eigen::Vector3d::UnitZ(), 2.0}})),
       quadric::hyperboloidOneSheet(1.0, 0.8, 1.0)},
      {std::make_shared<Q>(Q::hyperboloidTwoSheets(1.0, 1.0, 0.7, {{-Eigen::Vector3d::UnitZ(), -0.5}, {Eigen::Vector3d::UnitZ(), 3.0}})),
       quadric::hyperboloidTwoSheets(1.0, 1.0, 0.7)},
      {std::make_shared<Q>(Q::ellipticCylinder(1.2, 0.9, {{Eigen::Vector3d::UnitZ(), 1.5}, {-Eigen::Vector3d::UnitZ(), 1.5}})),
       quadric::ellipticCylinder(1.2, 0.9)},
      {std::make_shared<Q>(Q::planePair(Eigen::Vector3d(1, 1, 0), 0.2, 0.6,
                                        {{Eigen::Vector3d::UnitZ(), 1.0}, {-Eigen::Vector3d::UnitZ(), 1.0},
                                         {Eigen::Vector3d(1, -1, 0), 2.0}, {Eigen::Vector3d(-1, 1, 0), 2.0}})),
       quadric::planePair(Eigen::Vector3d(1, 1, 0).normalized(), 0.2 / std::sqrt(2.0), 0.6)},
      {ring, quadric::ellipsoid({1.2, 1.2, 0.6})},
      {ring, quadric::ellipticCylinder(0.6, 0.6)},
      {wedge, quadric::ellipticCylinder(1.0, 0.7)},
      {wedge, quadric::ellipticCylinder(0.3, 0.3)},
  };
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> u(0.0, 1.0), r(0.05, 0.4);
  int colliding = 0, separated = 0;
  for (int i = 0; i < 1800; ++i) {
    const QuadricShape<double>& shape = *shapes[i % shapes.size()].first;
    const Eigen::Matrix4d& near = shapes[i % shapes.size()].second;
    const Box3& box = shape.localBox();
    Eigen::Vector4d X(0, 0, 0, 1);
    do {
      for (int k = 0; k < 3; ++k) X[k] = box.lo[k] - 0.5 + u(rng) * (box.hi[k] - box.lo[k] + 1.0);
    } while (std::fabs(X.dot(near * X)) > 0.6 * 2.0 * (near * X).head<3>().norm());
    const Eigen::Vector3d radii(r(rng), r(rng), r(rng));
    Transform pose = Transform::Identity();
    pose.linear() = test::randomRotation(rng);
    pose.translation() = X.head<3>();
    const Box3 eb{-radii, radii};
    const RegionRelation truth =
        collideRegions(shape.region(), box, QuadricRegion::atom(quadric::ellipsoid(radii)), eb, pose.linear(),
                       pose.translation())
            .relation;
    if (truth == RegionRelation::Touching) continue;
    const fcl::Ellipsoid<double> e(radii);
    for (bool swap : {false, true}) {
      fcl::CollisionRequest<double> req;
      fcl::CollisionResult<double> res;
      const std::size_t n = swap ? fcl_quadric::collide<double>(&shape, I, &e, pose, req, res)
                                 : fcl_quadric::collide<double>(&e, pose, &shape, I, req, res);
      ASSERT_EQ(n > 0, truth == RegionRelation::Overlapping) << "pair " << i << (swap ? " (swapped)" : "");
      if (n == 0) continue;
      // The reported point is interior to both solids (certified point classification).
      const Eigen::Vector3d x = res.getContact(0).pos;
      EXPECT_GE(shape.region().classifyPoint(x), 0) << "pair " << i;
      EXPECT_LE(Ellipsoid(radii, pose.linear(), pose.translation()).implicit(x), 1e-12) << "pair " << i;
    }
    (truth == RegionRelation::Overlapping ? colliding : separated)++;
  }
  EXPECT_GT(colliding, 250);
  EXPECT_GT(separated, 250);
}

TEST(QuadricShapeDispatch, PlainFclCollideWithStockSolverDoesNotCrashAndReportsNothing) {
  // Documented: FCL's own tables have no entry for BV_UNKNOWN; FCL prints a warning and returns
  // 0. Only fcl_quadric::collide answers these shapes.
  auto cyl = std::make_shared<EllipticCylinder<double>>(1.0, 0.5, 2.0);
  auto sph = std::make_shared<fcl::Sphere<double>>(0.5);
  fcl::CollisionObject<double> a(cyl), b(sph);
  fcl::CollisionRequest<double> req;
  fcl::CollisionResult<double> res;
  EXPECT_EQ(fcl::collide(&a, &b, req, res), 0u);
  req.gjk_solver_type = fcl::GST_INDEP;
  EXPECT_EQ(fcl::collide(&a, &b, req, res), 0u);
  fcl::DistanceRequest<double> dreq;
  fcl::DistanceResult<double> dres;
  fcl::distance(&a, &b, dreq, dres);  // must return (value unspecified by FCL)
  // The front door answers: the sphere's centre is inside the cylinder.
  fcl::CollisionResult<double> ours;
  EXPECT_EQ(fcl_quadric::collide(&a, &b, fcl::CollisionRequest<double>(), ours), 1u);
  ASSERT_EQ(ours.numContacts(), 1u);
  EXPECT_NEAR(ours.getContact(0).normal.norm(), 1.0, 1e-12);
  // The front door's distance answers too: overlapping, FCL's -1 without signed distance.
  fcl::DistanceResult<double> our_d;
  EXPECT_EQ(fcl_quadric::distance(&a, &b, dreq, our_d), -1.0);
}

TEST(QuadricShapeDispatch, UnsupportedPartnersThrowNamingTheNodeType) {
  EllipticCylinder<double> cyl(1.0, 0.5, 2.0);
  fcl::Plane<double> plane(Eigen::Vector3d(0, 0, 1), 0.0);
  fcl::CollisionRequest<double> req;
  fcl::CollisionResult<double> res;
  try {
    fcl_quadric::collide(&cyl, Transform::Identity(), &plane, Transform::Identity(), req, res);
    FAIL() << "plane accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("node type"), std::string::npos) << e.what();
  }
}

TEST(QuadricShapeDispatch, MeshTrianglesAgainstAnEllipticCylinderAtAnalyticPositions) {
  // A square plate (two triangles) of side 4 in the plane z = h above a capped elliptic cylinder
  // (top cap at z = 1), and the same plate standing vertically at x = c beside its side (x <= 1.5).
  fcl::BVHModel<fcl::OBBRSS<double>> plate;
  plate.beginModel();
  plate.addTriangle(Eigen::Vector3d(-2, -2, 0), Eigen::Vector3d(2, -2, 0), Eigen::Vector3d(2, 2, 0));
  plate.addTriangle(Eigen::Vector3d(-2, -2, 0), Eigen::Vector3d(2, 2, 0), Eigen::Vector3d(-2, 2, 0));
  plate.endModel();
  EllipticCylinder<double> cyl(1.5, 0.5, 2.0);
  const Transform I = Transform::Identity();
  for (double gap : {1e-3, 1e-6}) {
    EXPECT_FALSE(collides(plate, pose(Eigen::Matrix3d::Identity(), {0.3, 0.1, 1.0 + gap}), cyl, I)) << gap;
    EXPECT_TRUE(collides(plate, pose(Eigen::Matrix3d::Identity(), {0.3, 0.1, 1.0 - gap}), cyl, I)) << gap;
    const Eigen::Matrix3d Ry = Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
    EXPECT_FALSE(collides(cyl, I, plate, pose(Ry, {1.5 + gap, 0, 0}))) << gap;
    EXPECT_TRUE(collides(cyl, I, plate, pose(Ry, {1.5 - gap, 0, 0}))) << gap;
  }
}

TEST(QuadricShapeDispatch, OcTreeLeavesAgainstAQuadricShapeAtAnalyticPositions) {
  // One occupied leaf of side 0.1 near (1, 0, 0), and a ball Quadric of radius 0.2 whose centre
  // is 0.2 -+ gap beyond the middle of the leaf's +x face.
  auto tree = std::make_shared<octomap::OcTree>(0.1);
  tree->updateNode(octomap::point3d(1.02f, 0.02f, 0.02f), true);
  auto fcl_tree = std::make_shared<fcl::OcTree<double>>(tree);
  const std::vector<std::array<double, 6>> leaves = fcl_tree->toBoxes();
  ASSERT_EQ(leaves.size(), 1u);
  const Eigen::Vector3d c(leaves[0][0], leaves[0][1], leaves[0][2]);
  const double h = 0.5 * leaves[0][3];
  const Quadric<double> probe = Quadric<double>::ellipsoid(0.2, 0.2, 0.2);
  for (double gap : {1e-3, 1e-6}) {
    EXPECT_FALSE(collides(*fcl_tree, Transform::Identity(), probe,
                          pose(Eigen::Matrix3d::Identity(), c + Eigen::Vector3d(h + 0.2 + gap, 0, 0))))
        << gap;
    EXPECT_TRUE(collides(*fcl_tree, Transform::Identity(), probe,
                         pose(Eigen::Matrix3d::Identity(), c + Eigen::Vector3d(h + 0.2 - gap, 0, 0))))
        << gap;
  }
}

TEST(QuadricShapeDispatch, BroadPhaseManagerFindsExactlyThePairwiseContacts) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  std::vector<std::shared_ptr<fcl::CollisionGeometry<double>>> geoms;
  auto ballShape = std::make_shared<Quadric<double>>(Quadric<double>::ellipsoid(0.8, 0.8, 0.8));
  auto bore = std::make_shared<Quadric<double>>(Quadric<double>::ellipticCylinder(0.4, 0.4));
  geoms.push_back(std::make_shared<Csg>(Op::Difference, std::vector<Csg::Child>{{ballShape, Transform::Identity()},
                                                                                 {bore, Transform::Identity()}}));
  geoms.push_back(std::make_shared<EllipticCylinder<double>>(0.9, 0.4, 1.5));
  geoms.push_back(std::make_shared<Quadric<double>>(
      Quadric<double>::ellipticParaboloid(0.7, 0.7, {HalfspaceClip<double>{{0, 0, 1}, 1.0}})));
  geoms.push_back(std::make_shared<fcl::Sphere<double>>(0.6));
  geoms.push_back(std::make_shared<fcl::Ellipsoid<double>>(Eigen::Vector3d(0.9, 0.5, 0.3)));
  std::vector<std::unique_ptr<fcl::CollisionObject<double>>> objects;
  for (int i = 0; i < 12; ++i) {
    objects.push_back(std::make_unique<fcl::CollisionObject<double>>(
        geoms[i % geoms.size()], pose(test::randomRotation(rng), Eigen::Vector3d(u(rng), u(rng), u(rng)))));
  }
  std::set<std::pair<const void*, const void*>> expected;
  for (std::size_t i = 0; i < objects.size(); ++i)
    for (std::size_t j = i + 1; j < objects.size(); ++j) {
      fcl::CollisionResult<double> res;
      if (fcl_quadric::collide(objects[i].get(), objects[j].get(), fcl::CollisionRequest<double>(), res) > 0)
        expected.insert(std::minmax<const void*>(objects[i].get(), objects[j].get()));
    }
  EXPECT_GE(expected.size(), 2u);
  fcl::DynamicAABBTreeCollisionManager<double> manager;
  for (auto& o : objects) manager.registerObject(o.get());
  manager.setup();
  std::set<std::pair<const void*, const void*>> found;
  struct Data {
    std::set<std::pair<const void*, const void*>>* found;
  } data{&found};
  manager.collide(&data, [](fcl::CollisionObject<double>* o1, fcl::CollisionObject<double>* o2, void* d) {
    fcl::DefaultCollisionData<double> cd;
    fcl_quadric::defaultCollisionFunction<double>(o1, o2, &cd);
    if (cd.result.isCollision())
      static_cast<Data*>(d)->found->insert(std::minmax<const void*>(o1, o2));
    return false;
  });
  EXPECT_EQ(found, expected);
}

// distanceLowerBound: a sphere beside a capped cylinder (closed-form distance) in either argument
// order; a cube and a second (convex) composite model beside it; nothing for a pair without a
// composite model; bad input.
TEST(QuadricShapes, DistanceLowerBoundIsBelowTheClosedFormAndNamesItsPairs) {
  const EllipticCylinder<double> cyl(0.5, 0.5, 2.0);
  const fcl::Sphere<double> ball(0.2);
  const fcl::Box<double> cube(0.4, 0.4, 0.4);
  fcl::Transform3d I = fcl::Transform3d::Identity(), beside = fcl::Transform3d::Identity();
  beside.translation() = Eigen::Vector3d(1.5, 0, 0);  // 1.0 from the axis: 0.5 - 0.2 = 0.3 apart
  for (const bool swap : {false, true}) {
    const std::optional<double> d = swap ? distanceLowerBound(&ball, beside, &cyl, I, 2.0)
                                         : distanceLowerBound(&cyl, I, &ball, beside, 2.0);
    ASSERT_TRUE(d.has_value());
    // Both convex: GJK's distance less its certified error.
    EXPECT_LE(*d, 0.8);
    EXPECT_GE(*d, 0.8 - 1e-9);
  }
  const std::optional<double> c = distanceLowerBound(&cyl, I, &cube, beside, 2.0);  // face-on: 1.5 - 0.5 - 0.2
  ASSERT_TRUE(c.has_value());
  EXPECT_LE(*c, 0.8);
  EXPECT_GE(*c, 0.8 - 1e-9);
  const EllipticCylinder<double> rod(0.2, 0.1, 0.5);  // facing side at 1.5 - 0.2
  const std::optional<double> r = distanceLowerBound(&cyl, I, &rod, beside, 2.0);
  ASSERT_TRUE(r.has_value());
  EXPECT_LE(*r, 0.8);
  EXPECT_GE(*r, 0.8 - 1e-9);
  EXPECT_EQ(*distanceLowerBound(&cyl, I, &rod, I, 2.0), 0.0);  // overlapping
  EXPECT_EQ(*distanceLowerBound(&cyl, I, &ball, beside, 0.5), 0.5);  // capped
  // A non-convex model (a ring: ellipsoid minus bore) and the ball beside it: the scaled-partner
  // bound (region_distance_bound.h). The ball's centre is 2.0 from the axis, the ring's outer
  // equator at 1.0: distance 0.8; the bound is below it and within the bisection's resolution.
  auto outer = std::make_shared<Quadric<double>>(Quadric<double>::ellipsoid(1.0, 1.0, 0.4));
  auto bore = std::make_shared<Quadric<double>>(Quadric<double>::ellipticCylinder(0.5, 0.5));
  const QuadricCSG<double> ring(Op::Difference, {{outer, I}, {bore, I}});
  fcl::Transform3d far = fcl::Transform3d::Identity();
  far.translation() = Eigen::Vector3d(2.0, 0, 0);
  const std::optional<double> g = distanceLowerBound(&ring, I, &ball, far, 2.0);
  ASSERT_TRUE(g.has_value());
  EXPECT_LE(*g, 0.8 + 1e-9);
  EXPECT_GE(*g, 0.8 - 2.0 / 1000.0 - 1e-6);
  EXPECT_FALSE(distanceLowerBound(&ball, I, &cube, beside, 2.0).has_value());  // no composite model
  EXPECT_THROW(distanceLowerBound(nullptr, I, &ball, beside, 2.0), std::invalid_argument);
  EXPECT_THROW(distanceLowerBound(&cyl, I, &ball, beside, -1.0), std::invalid_argument);
}

}  // namespace
}  // namespace quadric_shapes_test
}  // namespace fcl_quadric
