// fcl_quadric::collide / distance: pairs QuadricSolver delegates give exactly stock FCL's answers
// (shape pairs, a capsule against a BVH mesh and an OcTree); bad input throws
// std::invalid_argument, never crashes.
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <fcl/config.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/geometry/shape/triangle_p.h>
#include <fcl/math/bv/AABB.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>
#if FCL_HAVE_OCTOMAP
#include <fcl/geometry/octree/octree.h>
#include <octomap/OcTree.h>
#endif

#include "fcl_quadric/fcl/collision.h"
#include "fcl_quadric/fcl/distance.h"
#include "fcl_quadric/fcl/quadric_solver.h"
#include "fcl/fcl_test_support.h"
#include "support/expect_invalid.h"
#include "support/random_ellipsoids.h"

namespace fcl_quadric {
namespace front_doors_test {
namespace {

using GeometryPtr = std::shared_ptr<fcl::CollisionGeometryd>;

fcl::Transform3d randomPose(std::mt19937_64& rng, double spread) {
  std::uniform_real_distribution<double> u(-spread, spread);
  fcl::Transform3d tf = fcl::Transform3d::Identity();
  tf.linear() = test::randomRotation(rng);
  tf.translation() = Eigen::Vector3d(u(rng), u(rng), u(rng));
  return tf;
}

/// Same contacts; the geometric fields only with `with_contacts` (for boolean requests FCL's
/// Contact(o1, o2, b1, b2) leaves pos, normal and depth uninitialised).
void expectSameCollision(const fcl::CollisionResultd& a, const fcl::CollisionResultd& b, bool with_contacts,
                         const std::string& what) {
  ASSERT_EQ(a.numContacts(), b.numContacts()) << what;
  for (std::size_t k = 0; k < a.numContacts(); ++k) {
    EXPECT_EQ(a.getContact(k).b1, b.getContact(k).b1) << what;
    EXPECT_EQ(a.getContact(k).b2, b.getContact(k).b2) << what;
    if (!with_contacts) continue;
    EXPECT_EQ(a.getContact(k).pos, b.getContact(k).pos) << what;
    EXPECT_EQ(a.getContact(k).normal, b.getContact(k).normal) << what;
    EXPECT_EQ(a.getContact(k).penetration_depth, b.getContact(k).penetration_depth) << what;
  }
}

/// Runs collide (boolean and with contacts) and distance (unsigned and signed, with nearest points)
/// through fcl_quadric and through stock FCL (GST_LIBCCD) and expects identical results.
void expectSameAsStock(const fcl::CollisionObjectd& o1, const fcl::CollisionObjectd& o2, const std::string& what) {
  for (bool contact : {false, true}) {
    fcl::CollisionRequestd request(contact ? 8 : 1, contact);
    fcl::CollisionResultd ours, stock;
    const std::size_t n_ours = fcl_quadric::collide(&o1, &o2, request, ours);
    const std::size_t n_stock = fcl::collide(&o1, &o2, request, stock);
    EXPECT_EQ(n_ours, n_stock) << what;
    expectSameCollision(ours, stock, contact, what + (contact ? " (contacts)" : " (boolean)"));
  }
  for (bool signed_distance : {false, true}) {
    fcl::DistanceRequestd request(true, signed_distance);
    fcl::DistanceResultd ours, stock;
    const double d_ours = fcl_quadric::distance(&o1, &o2, request, ours);
    const double d_stock = fcl::distance(&o1, &o2, request, stock);
    // Same algorithm, but stock's code was compiled into libfcl.so and ours here: on curved
    // shapes the GJK/EPA iterates can differ in the last bits, and EPA amplifies that (its points
    // are only determined to about its tolerance). Polyhedral pairs agree bitwise in practice.
    const bool epa = signed_distance && stock.min_distance < 0;
    const double value_tol = epa ? 1e-6 : 1e-12, point_tol = epa ? 1e-2 : 1e-9;
    EXPECT_NEAR(d_ours, d_stock, value_tol) << what;
    EXPECT_NEAR(ours.min_distance, stock.min_distance, value_tol) << what;
    EXPECT_LE((ours.nearest_points[0] - stock.nearest_points[0]).norm(), point_tol) << what;
    EXPECT_LE((ours.nearest_points[1] - stock.nearest_points[1]).norm(), point_tol) << what;
  }
}

TEST(FrontDoors, DelegatedShapePairsGiveStockFclAnswers) {
  const test::ScopedNoFpTraps no_traps;  // every pair here runs stock libccd code
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> size(0.3, 2.0);
  int colliding = 0;
  for (int i = 0; i < 150; ++i) {
    std::vector<std::pair<std::string, std::pair<GeometryPtr, GeometryPtr>>> cases = {
        {"box-box", {std::make_shared<fcl::Boxd>(size(rng), size(rng), size(rng)),
                     std::make_shared<fcl::Boxd>(size(rng), size(rng), size(rng))}},
        // (Sphere pairs with a box, capsule, cylinder or cone are exact since session 35,
        // test/fcl/cylinder_cone_pair_test.cpp; sphere-sphere keeps only FCL's collision.)
        {"capsule-box", {std::make_shared<fcl::Capsuled>(size(rng), size(rng)), std::make_shared<fcl::Boxd>(size(rng), size(rng), size(rng))}},
        {"box-capsule", {std::make_shared<fcl::Boxd>(size(rng), size(rng), size(rng)), std::make_shared<fcl::Capsuled>(size(rng), size(rng))}},
        {"capsule-cylinder", {std::make_shared<fcl::Capsuled>(size(rng), size(rng)), std::make_shared<fcl::Cylinderd>(size(rng), size(rng))}},
        {"cylinder-box", {std::make_shared<fcl::Cylinderd>(size(rng), size(rng)), std::make_shared<fcl::Boxd>(size(rng), size(rng), size(rng))}},
        {"capsule-capsule", {std::make_shared<fcl::Capsuled>(size(rng), size(rng)), std::make_shared<fcl::Capsuled>(size(rng), size(rng))}},
    };
    for (const auto& c : cases) {
      const fcl::CollisionObjectd o1(c.second.first, randomPose(rng, 1.5));
      const fcl::CollisionObjectd o2(c.second.second, randomPose(rng, 1.5));
      fcl::CollisionResultd r;
      colliding += fcl::collide(&o1, &o2, fcl::CollisionRequestd(), r) > 0;
      expectSameAsStock(o1, o2, c.first + " #" + std::to_string(i));
    }
  }
  EXPECT_GT(colliding, 150);  // both outcomes are exercised
}

/// A closed triangle mesh of the box [-h, h]^3 (12 triangles).
std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> boxMesh(double h) {
  std::vector<Eigen::Vector3d> v;
  for (int i = 0; i < 8; ++i) v.emplace_back(i & 1 ? h : -h, i & 2 ? h : -h, i & 4 ? h : -h);
  const std::vector<fcl::Triangle> t = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                                        {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  auto mesh = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  mesh->beginModel();
  mesh->addSubModel(v, t);
  mesh->endModel();
  return mesh;
}

TEST(FrontDoors, DelegatedShapeAgainstBvhMeshGivesStockFclAnswers) {
  // Mesh-shape traversal (OBBRSS) with a shape whose triangle tests are delegated to libccd (a
  // capsule; ellipsoid-triangle is exact, test/fcl/octree_mesh_test.cpp).
  const test::ScopedNoFpTraps no_traps;
  std::mt19937_64 rng(6);
  const auto mesh = boxMesh(1.0);
  for (int i = 0; i < 40; ++i) {
    const fcl::CollisionObjectd m(mesh, randomPose(rng, 1.0));
    const fcl::CollisionObjectd e(std::make_shared<fcl::Capsuled>(0.4, 1.2), randomPose(rng, 2.0));
    for (bool contact : {false, true}) {
      fcl::CollisionRequestd request(contact ? 100 : 1, contact);
      fcl::CollisionResultd ours, stock;
      fcl_quadric::collide(&m, &e, request, ours);
      fcl::collide(&m, &e, request, stock);
      expectSameCollision(ours, stock, contact, "mesh-capsule #" + std::to_string(i));
      fcl::CollisionResultd ours_swapped, stock_swapped;
      fcl_quadric::collide(&e, &m, request, ours_swapped);
      fcl::collide(&e, &m, request, stock_swapped);
      expectSameCollision(ours_swapped, stock_swapped, contact, "capsule-mesh #" + std::to_string(i));
    }
    fcl::DistanceRequestd request(true);
    fcl::DistanceResultd ours, stock;
    fcl_quadric::distance(&m, &e, request, ours);
    fcl::distance(&m, &e, request, stock);
    EXPECT_EQ(ours.min_distance, stock.min_distance);
    EXPECT_EQ(ours.nearest_points[0], stock.nearest_points[0]);
  }
}

#if FCL_HAVE_OCTOMAP
TEST(FrontDoors, DelegatedShapeAgainstOcTreeGivesStockFclAnswers) {
  // OcTree-shape traversal with a shape whose leaf tests are delegated to libccd (a capsule;
  // ellipsoid leaves are exact, test/fcl/octree_mesh_test.cpp).
  const test::ScopedNoFpTraps no_traps;
  auto tree = std::make_shared<octomap::OcTree>(0.1);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 400; ++i) tree->updateNode(octomap::point3d(u(rng), u(rng), u(rng)), true);
  const fcl::CollisionObjectd octree(std::make_shared<fcl::OcTreed>(tree), fcl::Transform3d::Identity());
  for (int i = 0; i < 20; ++i) {
    const fcl::CollisionObjectd e(std::make_shared<fcl::Capsuled>(0.2, 0.5), randomPose(rng, 1.0));
    fcl::CollisionRequestd request(1000, false);
    fcl::CollisionResultd ours, stock;
    fcl_quadric::collide(&octree, &e, request, ours);
    fcl::collide(&octree, &e, request, stock);
    expectSameCollision(ours, stock, false, "octree-capsule #" + std::to_string(i));
  }
}
#endif

// ---------------------------------------------------------------------------------------------
// Bad input
// ---------------------------------------------------------------------------------------------

template <typename F>
std::string invalidArgumentMessage(F&& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no std::invalid_argument";
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

TEST(FrontDoorsBadInput, NullGeometryOrObjectThrowsInvalidArgument) {
  const GeometryPtr sphere = std::make_shared<fcl::Sphered>(1.0);
  const fcl::Transform3d I = fcl::Transform3d::Identity();
  const fcl::CollisionObjectd good(sphere, I);
  const fcl::CollisionObjectd empty(nullptr);  // FCL allows an object without geometry
  fcl::CollisionRequestd crequest;
  fcl::CollisionResultd cresult;
  fcl::DistanceRequestd drequest;
  fcl::DistanceResultd dresult;
  EXPECT_TRUE(contains(invalidArgumentMessage([&] { fcl_quadric::collide(&good, &empty, crequest, cresult); }),
                       "o2 has no collision geometry"));
  EXPECT_TRUE(contains(invalidArgumentMessage([&] { fcl_quadric::collide(&empty, &good, crequest, cresult); }),
                       "o1 has no collision geometry"));
  EXPECT_TRUE(contains(invalidArgumentMessage([&] {
                         fcl_quadric::collide(static_cast<const fcl::CollisionObjectd*>(nullptr), &good, crequest, cresult);
                       }),
                       "o1 is a null collision object"));
  EXPECT_TRUE(contains(invalidArgumentMessage([&] {
                         fcl_quadric::collide(sphere.get(), I, static_cast<const fcl::CollisionGeometryd*>(nullptr), I,
                                              crequest, cresult);
                       }),
                       "o2 is a null collision geometry"));
  EXPECT_TRUE(contains(invalidArgumentMessage([&] { fcl_quadric::distance(&good, &empty, drequest, dresult); }),
                       "fcl_quadric::distance: o2 has no collision geometry"));
  EXPECT_TRUE(contains(invalidArgumentMessage([&] {
                         fcl_quadric::distance(static_cast<const fcl::CollisionGeometryd*>(nullptr), I, sphere.get(), I,
                                               drequest, dresult);
                       }),
                       "o1 is a null collision geometry"));
  EXPECT_EQ(cresult.numContacts(), 0u);
}

/// Empty, unfinished (no endModel()) and point-cloud BVH models: FCL's traversals read their
/// missing BV tree and crashed with SIGSEGV, as stock fcl::collide / fcl::distance do
/// (docs/reliability.md finding 34). They throw, naming the operand; a finished mesh still works.
template <typename BV>
void expectUnfinishedMeshesRejected() {
  auto make = [](int kind) {
    auto m = std::make_shared<fcl::BVHModel<BV>>();
    m->beginModel();
    if (kind == 1) m->addTriangle(fcl::Vector3d(0, 0, 0), fcl::Vector3d(1, 0, 0), fcl::Vector3d(0, 1, 0));
    if (kind == 2) {
      m->addVertex(fcl::Vector3d(0, 0, 0));
      m->addVertex(fcl::Vector3d(0.1, 0, 0));
    }
    if (kind != 1) m->endModel();  // kind 0: no triangles; kind 1: never finished
    return m;
  };
  const fcl::Transform3d I = fcl::Transform3d::Identity();
  const GeometryPtr partners[] = {std::make_shared<fcl::Ellipsoidd>(0.3, 0.2, 0.1), std::make_shared<fcl::Sphered>(0.2),
                                  std::make_shared<fcl::Boxd>(0.2, 0.2, 0.2)};
  for (int kind = 0; kind < 3; ++kind)
    for (const GeometryPtr& partner : partners) {
      const GeometryPtr mesh = make(kind);
      fcl::CollisionRequestd crequest;
      fcl::CollisionResultd cresult;
      fcl::DistanceRequestd drequest;
      fcl::DistanceResultd dresult;
      const std::string expected = "is a BVH model that is not a finished triangle mesh";
      EXPECT_TRUE(contains(
          invalidArgumentMessage([&] { fcl_quadric::collide(mesh.get(), I, partner.get(), I, crequest, cresult); }),
          "fcl_quadric::collide: o1 " + expected))
          << kind;
      EXPECT_TRUE(contains(
          invalidArgumentMessage([&] { fcl_quadric::distance(partner.get(), I, mesh.get(), I, drequest, dresult); }),
          "fcl_quadric::distance: o2 " + expected))
          << kind;
      const fcl::CollisionObjectd a(mesh, I), b(partner, I);
      EXPECT_TRUE(contains(invalidArgumentMessage([&] { fcl_quadric::collide(&b, &a, crequest, cresult); }), expected));
    }
  auto finished = std::make_shared<fcl::BVHModel<BV>>();
  finished->beginModel();
  finished->addTriangle(fcl::Vector3d(-1, -1, 0), fcl::Vector3d(1, -1, 0), fcl::Vector3d(0, 1, 0));
  finished->endModel();
  fcl::CollisionRequestd crequest;
  fcl::CollisionResultd cresult;
  EXPECT_EQ(fcl_quadric::collide(finished.get(), I, partners[0].get(), I, crequest, cresult), 1u);
}

TEST(FrontDoorsBadInput, EmptyUnfinishedOrPointCloudMeshesThrowInsteadOfCrashing) {
  expectUnfinishedMeshesRejected<fcl::OBBRSSd>();
  expectUnfinishedMeshesRejected<fcl::AABBd>();
}

/// A mesh or an OcTree posed beyond kMaxLength (1e100) against an ellipsoid or a sphere: collide
/// returned 0 (no triangle or leaf was reached) while distance threw for its first triangle
/// (docs/reliability.md finding 34 (4)). Both now throw, naming the translation, as the quadric
/// shapes' front doors do; and within the limit both answer.
TEST(FrontDoorsBadInput, MeshesAndOcTreesPosedBeyondTheLengthLimitThrowInBothFrontDoors) {
  auto mesh = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  mesh->beginModel();
  mesh->addTriangle(fcl::Vector3d(0, 0, 0), fcl::Vector3d(1, 0, 0), fcl::Vector3d(0, 1, 0));
  mesh->endModel();
  auto octo = std::make_shared<octomap::OcTree>(0.5);
  octo->updateNode(octomap::point3d(0.1f, 0.1f, 0.1f), true);
  const GeometryPtr tree = std::make_shared<fcl::OcTreed>(octo);
  const GeometryPtr ellipsoid = std::make_shared<fcl::Ellipsoidd>(1.0, 2.0, 0.5);
  const GeometryPtr sphere = std::make_shared<fcl::Sphered>(1.0);
  const fcl::Transform3d I = fcl::Transform3d::Identity();
  for (const double x : {1e200, 1e100 * 1.0000001, 1e99}) {
    fcl::Transform3d far = fcl::Transform3d::Identity();
    far.translation() = Eigen::Vector3d(x, 0.0, 0.0);
    for (const GeometryPtr& pieces : {GeometryPtr(mesh), tree}) {
      for (const GeometryPtr& shape : {ellipsoid, sphere}) {
        fcl::CollisionRequestd crequest;
        fcl::CollisionResultd cresult;
        fcl::DistanceRequestd drequest;
        fcl::DistanceResultd dresult;
        if (x > 1e100) {
          test::expectInvalid([&] { fcl_quadric::collide(shape.get(), I, pieces.get(), far, crequest, cresult); },
                        "fcl_quadric::collide: the translation of tf2");
          test::expectInvalid([&] { fcl_quadric::distance(pieces.get(), far, shape.get(), I, drequest, dresult); },
                        "fcl_quadric::distance: the translation of tf1");
        } else {
          EXPECT_EQ(fcl_quadric::collide(shape.get(), I, pieces.get(), far, crequest, cresult), 0u);
          EXPECT_GT(fcl_quadric::distance(pieces.get(), far, shape.get(), I, drequest, dresult), 0.5 * x);
        }
      }
    }
  }
}

TEST(FrontDoorsBadInput, NonFiniteTransformThrowsInvalidArgument) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const GeometryPtr ellipsoid = std::make_shared<fcl::Ellipsoidd>(1.0, 2.0, 0.5);
  const GeometryPtr box = std::make_shared<fcl::Boxd>(1.0, 1.0, 1.0);
  fcl::Transform3d bad_p = fcl::Transform3d::Identity();
  bad_p.translation() = Eigen::Vector3d(0.0, nan, 0.0);
  fcl::Transform3d bad_R = fcl::Transform3d::Identity();
  bad_R.linear()(1, 2) = inf;
  const fcl::Transform3d I = fcl::Transform3d::Identity();
  fcl::CollisionRequestd crequest(1, true);
  fcl::CollisionResultd cresult;
  fcl::DistanceRequestd drequest(true, true);
  fcl::DistanceResultd dresult;
  for (const fcl::Transform3d* bad : {&bad_p, &bad_R}) {
    for (const GeometryPtr& other : {ellipsoid, box}) {
      EXPECT_TRUE(contains(invalidArgumentMessage([&] {
                             fcl_quadric::collide(ellipsoid.get(), I, other.get(), *bad, crequest, cresult);
                           }),
                           "fcl_quadric::collide: transform tf2 is not finite"));
      EXPECT_TRUE(contains(invalidArgumentMessage([&] {
                             fcl_quadric::distance(other.get(), *bad, ellipsoid.get(), I, drequest, dresult);
                           }),
                           "fcl_quadric::distance: transform tf1 is not finite"));
      // The object overloads read the objects' transforms (set without computing the AABB, which
      // would do arithmetic on the NaN).
      fcl::CollisionObjectd o1(ellipsoid, I), o2(other, I);
      o2.setTransform(*bad);
      EXPECT_TRUE(contains(invalidArgumentMessage([&] { fcl_quadric::collide(&o1, &o2, crequest, cresult); }),
                           "not finite"));
      EXPECT_TRUE(contains(invalidArgumentMessage([&] { fcl_quadric::distance(&o1, &o2, drequest, dresult); }),
                           "not finite"));
      // FCL's own entry point with QuadricSolver: the solver checks, for exact and delegated pairs.
      const QuadricSolverd solver;
      EXPECT_TRUE(contains(invalidArgumentMessage([&] { fcl::collide(&o1, &o2, &solver, crequest, cresult); }),
                           "fcl_quadric::QuadricSolver: transform tf2 is not finite"));
      EXPECT_TRUE(contains(invalidArgumentMessage([&] { fcl::distance(&o1, &o2, &solver, drequest, dresult); }),
                           "fcl_quadric::QuadricSolver: transform tf2 is not finite"));
    }
  }
  EXPECT_EQ(cresult.numContacts(), 0u);
}

TEST(FrontDoorsBadInput, NonRigidPoseOrBadRadiusOfAnExactPairThrowsNamingTheOperand) {
  const fcl::Transform3d I = fcl::Transform3d::Identity();
  fcl::Transform3d shear = fcl::Transform3d::Identity();
  shear.linear()(0, 1) = 1e-3;
  const fcl::Ellipsoidd e(1.0, 2.0, 0.5);
  const fcl::Sphered zero(0.0);
  fcl::CollisionRequestd request;
  fcl::CollisionResultd result;
  const std::string m1 = invalidArgumentMessage([&] { fcl_quadric::collide(&e, shear, &e, I, request, result); });
  EXPECT_TRUE(contains(m1, "o1 (fcl::Ellipsoid)")) << m1;
  EXPECT_TRUE(contains(m1, "not a rotation")) << m1;
  const std::string m2 = invalidArgumentMessage([&] { fcl_quadric::collide(&e, I, &zero, I, request, result); });
  EXPECT_TRUE(contains(m2, "o2 (fcl::Sphere)")) << m2;
  EXPECT_TRUE(contains(m2, "radius")) << m2;
  const fcl::Ellipsoidd negative(1.0, -1.0, 1.0);
  fcl::DistanceRequestd drequest;
  fcl::DistanceResultd dresult;
  EXPECT_TRUE(contains(invalidArgumentMessage([&] { fcl_quadric::distance(&negative, I, &e, I, drequest, dresult); }),
                       "o1 (fcl::Ellipsoid)"));
}

TEST(FrontDoorsBadInput, UnsupportedPairsAndZeroMaxContactsKeepFclBehaviour) {
  // FCL has no collision or distance function for fcl::TriangleP: FCL prints a warning on stderr
  // and returns 0 contacts (collide) or leaves the result untouched and returns max() (distance).
  const fcl::TriangleP<double> triangle(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0));
  const fcl::Ellipsoidd e(1.0, 1.0, 1.0);
  const fcl::Transform3d I = fcl::Transform3d::Identity();
  fcl::CollisionRequestd request;
  fcl::CollisionResultd result;
  EXPECT_EQ(fcl_quadric::collide(&triangle, I, &e, I, request, result), 0u);
  EXPECT_FALSE(result.isCollision());
  fcl::DistanceRequestd drequest;
  fcl::DistanceResultd dresult;
  EXPECT_EQ(fcl_quadric::distance(&e, I, &triangle, I, drequest, dresult), std::numeric_limits<double>::max());
  // num_max_contacts == 0: FCL's warning, 0 contacts, even for an overlapping pair.
  fcl::CollisionRequestd zero(0, false);
  EXPECT_EQ(fcl_quadric::collide(&e, I, &e, I, zero, result), 0u);
  EXPECT_FALSE(result.isCollision());
}

}  // namespace
}  // namespace front_doors_test
}  // namespace fcl_quadric
