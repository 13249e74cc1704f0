// FCL's own traversal node templates instantiated with fcl_quadric's quadric shapes and
// QuadricSolver (issue 5: "against BVH meshes and fcl::OcTree through FCL's traversal node
// templates"). The nodes reach QuadricSolver's kQuadricShape kernels (quadric_solver.h) and
// QuadricShape::getBoundVertices (FCL's generic computeBV).
//
// Oracles, independent of the region engine:
//  - FCL's stock libccd answer on an fcl::Cylinder of the same radius and length with a margin:
//    if the cylinder shrunk by kMargin collides (stock fcl::collide, GST_LIBCCD), the quadric
//    shape must; if the cylinder grown by kMargin does not, it must not (the circular
//    EllipticCylinder is the same solid as fcl::Cylinder);
//  - stock fcl::distance (libccd) on the fcl::Cylinder for separated poses.
// And the front doors (our own traversal of the same hierarchies) must give the same verdicts.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <vector>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/octree/octree.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/utility.h>
#include <fcl/math/bv/AABB.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/detail/traversal/collision/mesh_shape_collision_traversal_node.h>
#include <fcl/narrowphase/detail/traversal/collision/shape_collision_traversal_node.h>
#include <fcl/narrowphase/detail/traversal/collision/shape_mesh_collision_traversal_node.h>
#include <fcl/narrowphase/detail/traversal/collision_node.h>
#include <fcl/narrowphase/detail/traversal/distance/mesh_shape_distance_traversal_node.h>
#include <fcl/narrowphase/detail/traversal/octree/collision/octree_shape_collision_traversal_node.h>
#include <fcl/narrowphase/detail/traversal/octree/collision/shape_octree_collision_traversal_node.h>
#include <fcl/narrowphase/detail/traversal/octree/distance/octree_shape_distance_traversal_node.h>
#include <fcl/narrowphase/distance.h>
#include <octomap/OcTree.h>

#include "fcl_quadric/fcl/collision.h"
#include "fcl_quadric/fcl/distance.h"
#include "fcl_quadric/fcl/quadric_shapes.h"
#include "fcl_quadric/fcl/quadric_solver.h"
#include "support/fcl_fixtures.h"
#include "support/random_ellipsoids.h"

namespace fcl_quadric {
namespace {

using Solver = QuadricSolver<double>;
using Cyl = EllipticCylinder<double>;
using test::pose;

constexpr double kRadius = 0.5, kLength = 1.2, kMargin = 1e-3;

/// A bumpy height field z = 0.3 sin(1.3 x) cos(1.1 y) on [-2, 2]^2, n x n cells, two triangles each.
template <typename BV>
std::shared_ptr<fcl::BVHModel<BV>> heightField(int n) {
  auto m = std::make_shared<fcl::BVHModel<BV>>();
  auto at = [&](int i, int j) {
    const double x = -2.0 + 4.0 * i / n, y = -2.0 + 4.0 * j / n;
    return Eigen::Vector3d(x, y, 0.3 * std::sin(1.3 * x) * std::cos(1.1 * y));
  };
  m->beginModel();
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      m->addTriangle(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      m->addTriangle(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  m->endModel();
  return m;
}

/// What stock FCL (libccd) says about the fcl::Cylinder grown by `grow` (negative: shrunk).
bool stockCollides(const fcl::CollisionGeometry<double>* other, const fcl::Transform3d& tf_other, double grow,
                   const fcl::Transform3d& tf_cyl) {
  const fcl::Cylinder<double> c(kRadius + grow, kLength + 2 * grow);
  fcl::CollisionResult<double> res;
  return fcl::collide(other, tf_other, &c, tf_cyl, fcl::CollisionRequest<double>(), res) > 0;
}

/// Checks `verdict` for the cylinder posed tf_cyl against `other` with the libccd margin oracle;
/// counts the poses the oracle decides.
void expectAgreesWithStockMargins(bool verdict, const fcl::CollisionGeometry<double>* other,
                                  const fcl::Transform3d& tf_other, const fcl::Transform3d& tf_cyl, int* decided_hit,
                                  int* decided_miss, const char* what) {
  if (stockCollides(other, tf_other, -kMargin, tf_cyl)) {
    EXPECT_TRUE(verdict) << what << ": the shrunk fcl::Cylinder collides\n" << tf_cyl.matrix();
    ++*decided_hit;
  } else if (!stockCollides(other, tf_other, kMargin, tf_cyl)) {
    EXPECT_FALSE(verdict) << what << ": the grown fcl::Cylinder is clear\n" << tf_cyl.matrix();
    ++*decided_miss;
  }
}

fcl::Transform3d randomPoseAbove(std::mt19937_64& rng, double spread, double height = 0.8) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  return pose(test::randomRotation(rng), Eigen::Vector3d(spread * u(rng), spread * u(rng), height * u(rng)));
}

// ---------------------------------------------------------------------------------------------

TEST(FclTraversalNodes, GenericComputeBVBoundsTheShapeThroughGetBoundVertices) {
  const Cyl cyl(0.7, 0.3, 1.5);
  std::mt19937_64 rng(5);
  for (int k = 0; k < 20; ++k) {
    const fcl::Transform3d tf = randomPoseAbove(rng, 2.0);
    fcl::AABB<double> aabb;
    fcl::OBBRSS<double> obbrss;
    fcl::computeBV(cyl, tf, aabb);
    fcl::computeBV(cyl, tf, obbrss);
    // Points of the solid (its rims and axis) are inside both bounding volumes.
    for (int i = 0; i < 16; ++i) {
      const double th = 2 * M_PI * i / 16;
      for (double z : {-0.75, 0.0, 0.75}) {
        const Eigen::Vector3d x = tf * Eigen::Vector3d(0.7 * std::cos(th), 0.3 * std::sin(th), z);
        EXPECT_TRUE(aabb.contain(x + 1e-12 * (x - aabb.center()))) << x.transpose();
        // The OBB of the eight corners of the local box contains the solid.
        const Eigen::Vector3d l = obbrss.obb.axis.transpose() * (x - obbrss.obb.To);
        EXPECT_TRUE((l.cwiseAbs() - obbrss.obb.extent).maxCoeff() <= 1e-9) << l.transpose();
      }
    }
    // The world AABB is exactly the posed local box's (the 8 corners' extent).
    const std::vector<Eigen::Vector3d> corners = cyl.getBoundVertices(tf);
    ASSERT_EQ(corners.size(), 8u);
    Eigen::Vector3d lo = corners[0], hi = corners[0];
    for (const Eigen::Vector3d& c : corners) lo = lo.cwiseMin(c), hi = hi.cwiseMax(c);
    EXPECT_LT((aabb.min_ - lo).norm() + (aabb.max_ - hi).norm(), 1e-12);
  }
  // An unbounded quadric shape has no bounding vertices.
  const Quadric<double> slab = Quadric<double>::ellipticCylinder(1.0, 1.0);
  EXPECT_THROW(slab.getBoundVertices(fcl::Transform3d::Identity()), std::invalid_argument);
}

TEST(FclTraversalNodes, MeshShapeNodesWithAQuadricShapeAgreeWithStockLibccdAndTheFrontDoor) {
  const auto obbrss = heightField<fcl::OBBRSS<double>>(6);
  const auto aabb = heightField<fcl::AABB<double>>(6);
  const Cyl cyl(kRadius, kRadius, kLength);
  const Solver solver;
  const fcl::Transform3d tf_mesh = pose(Eigen::AngleAxisd(0.2, Eigen::Vector3d(1, 2, 0).normalized()).toRotationMatrix(),
                                        Eigen::Vector3d(0.1, -0.2, 0.05));
  std::mt19937_64 rng(11);
  int hits = 0, misses = 0, contacts_checked = 0;
  for (int k = 0; k < 60; ++k) {
    const fcl::Transform3d tf_cyl = tf_mesh * randomPoseAbove(rng, 1.5, 1.2);
    fcl::CollisionRequest<double> request(1, /*enable_contact=*/true);

    // Oriented BVs: the mesh stays in its frame (shapeTriangleIntersect with tf2).
    fcl::CollisionResult<double> r_obbrss;
    fcl::detail::MeshShapeCollisionTraversalNodeOBBRSS<Cyl, Solver> n_obbrss;
    ASSERT_TRUE(fcl::detail::initialize(n_obbrss, *obbrss, tf_mesh, cyl, tf_cyl, &solver, request, r_obbrss));
    fcl::detail::collide(&n_obbrss);
    // AABB: FCL moves a copy of the mesh into the world (world-frame shapeTriangleIntersect).
    fcl::BVHModel<fcl::AABB<double>> aabb_copy(*aabb);
    fcl::Transform3d tf_copy = tf_mesh;
    fcl::CollisionResult<double> r_aabb;
    fcl::detail::MeshShapeCollisionTraversalNode<fcl::AABB<double>, Cyl, Solver> n_aabb;
    ASSERT_TRUE(fcl::detail::initialize(n_aabb, aabb_copy, tf_copy, cyl, tf_cyl, &solver, request, r_aabb));
    fcl::detail::collide(&n_aabb);
    // The shape first (FCL 0.7's oriented ShapeMesh*OBBRSS / RSS / kIOS / OBB collision nodes do
    // not compile for any shape: their leafTesting passes the request where the result goes,
    // shape_mesh_collision_traversal_node-inl.h:220-307; FCL itself swaps to MeshShape nodes).
    fcl::BVHModel<fcl::AABB<double>> aabb_copy2(*aabb);
    fcl::Transform3d tf_copy2 = tf_mesh;
    fcl::CollisionResult<double> r_shape_first;
    fcl::detail::ShapeMeshCollisionTraversalNode<Cyl, fcl::AABB<double>, Solver> n_shape_first;
    ASSERT_TRUE(
        fcl::detail::initialize(n_shape_first, cyl, tf_cyl, aabb_copy2, tf_copy2, &solver, request, r_shape_first));
    fcl::detail::collide(&n_shape_first);

    const bool hit = r_obbrss.isCollision();
    EXPECT_EQ(r_aabb.isCollision(), hit) << k;
    EXPECT_EQ(r_shape_first.isCollision(), hit) << k;
    fcl::CollisionResult<double> front;
    EXPECT_EQ(fcl_quadric::collide(obbrss.get(), tf_mesh, &cyl, tf_cyl, fcl::CollisionRequest<double>(), front) > 0, hit)
        << k;
    expectAgreesWithStockMargins(hit, obbrss.get(), tf_mesh, tf_cyl, &hits, &misses, "MeshShapeOBBRSS node");

    if (hit) {
      // The contact: a point of the triangle it names (within the engine's band), unit normal from
      // the mesh (o1) towards the cylinder; shape-first reports it from the cylinder.
      const fcl::Contact<double>& c = r_obbrss.getContact(0);
      EXPECT_NEAR(c.normal.norm(), 1.0, 1e-12);
      ASSERT_GE(c.b1, 0);
      const fcl::Triangle& t = obbrss->tri_indices[c.b1];
      const Eigen::Vector3d a = tf_mesh * obbrss->vertices[t[0]], b = tf_mesh * obbrss->vertices[t[1]],
                            d = tf_mesh * obbrss->vertices[t[2]];
      const Eigen::Vector3d n = (b - a).cross(d - a).normalized();
      EXPECT_LT(std::abs(n.dot(c.pos - a)), 1e-6) << "contact off the triangle's plane";
      // On the cylinder's solid too (its local coordinates within the band).
      const Eigen::Vector3d l = tf_cyl.inverse() * c.pos;
      EXPECT_LE(std::hypot(l.x(), l.y()), kRadius + 1e-6);
      EXPECT_LE(std::abs(l.z()), 0.5 * kLength + 1e-6);
      const fcl::Contact<double>& cs = r_shape_first.getContact(0);
      EXPECT_EQ(cs.o1, &cyl);
      EXPECT_NEAR(cs.normal.norm(), 1.0, 1e-12);
      ++contacts_checked;
    }
  }
  // Both verdicts occur and the stock oracle decides most poses.
  EXPECT_GE(hits, 10);
  EXPECT_GE(misses, 10);
  EXPECT_GE(hits + misses, 50);
  EXPECT_GE(contacts_checked, hits);
}

TEST(FclTraversalNodes, OcTreeShapeNodesWithAQuadricShapeAgreeWithStockLibccdAndTheFrontDoor) {
  // A floor (z in [-0.1, 0.1]) and a post of occupied cells at resolution 0.2.
  auto tree = std::make_shared<octomap::OcTree>(0.2);
  for (double x = -1.5; x <= 1.5; x += 0.2)
    for (double y = -1.5; y <= 1.5; y += 0.2) tree->updateNode(octomap::point3d(x, y, -0.05), true);
  for (double z = 0.1; z <= 1.0; z += 0.2) tree->updateNode(octomap::point3d(0.55, 0.35, z), true);
  const fcl::OcTree<double> octree(tree);
  const Cyl cyl(kRadius, kRadius, kLength);
  const Solver solver;
  const fcl::detail::OcTreeSolver<Solver> otsolver(&solver);
  const fcl::Transform3d tf_tree = pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.0, 0.0, -0.3));
  std::mt19937_64 rng(17);
  int hits = 0, misses = 0;
  for (int k = 0; k < 30; ++k) {
    fcl::Transform3d tf_cyl = randomPoseAbove(rng, 1.2);
    tf_cyl.translation().z() += 0.6;
    const fcl::CollisionRequest<double> request(1, true);
    fcl::CollisionResult<double> r1, r2;
    fcl::detail::OcTreeShapeCollisionTraversalNode<Cyl, Solver> n1;
    ASSERT_TRUE(fcl::detail::initialize(n1, octree, tf_tree, cyl, tf_cyl, &otsolver, request, r1));
    fcl::detail::collide(&n1);
    fcl::detail::ShapeOcTreeCollisionTraversalNode<Cyl, Solver> n2;
    ASSERT_TRUE(fcl::detail::initialize(n2, cyl, tf_cyl, octree, tf_tree, &otsolver, request, r2));
    fcl::detail::collide(&n2);
    const bool hit = r1.isCollision();
    EXPECT_EQ(r2.isCollision(), hit) << k;
    fcl::CollisionResult<double> front;
    EXPECT_EQ(fcl_quadric::collide(&octree, tf_tree, &cyl, tf_cyl, fcl::CollisionRequest<double>(), front) > 0, hit)
        << k;
    expectAgreesWithStockMargins(hit, &octree, tf_tree, tf_cyl, &hits, &misses, "OcTreeShape node");
    if (hit) {
      EXPECT_NEAR(r1.getContact(0).normal.norm(), 1.0, 1e-12);
    }
  }
  EXPECT_GE(hits, 5);
  EXPECT_GE(misses, 5);
}

TEST(FclTraversalNodes, ShapeNodeAnswersANonConvexCsgAsTheFrontDoorDoes) {
  // A ring (ellipsoid minus a bore) against a box and against a capped cylinder, both orders:
  // the node and the front door agree; a rod down the bore is clear, one through the body is not.
  using Csg = QuadricCSG<double>;
  auto outer = std::make_shared<Quadric<double>>(Quadric<double>::ellipsoid(1.0, 1.0, 0.4));
  auto bore = std::make_shared<Quadric<double>>(Quadric<double>::ellipticCylinder(0.5, 0.5));
  const Csg ring(Csg::Op::Difference, {{outer, fcl::Transform3d::Identity()}, {bore, fcl::Transform3d::Identity()}});
  const Cyl rod(0.3, 0.3, 2.0);
  const fcl::Box<double> box(0.3, 0.3, 2.0);
  const Solver solver;
  const fcl::Transform3d I = fcl::Transform3d::Identity();
  auto nodeCollides = [&](const auto& s1, const fcl::Transform3d& tf1, const auto& s2, const fcl::Transform3d& tf2) {
    using S1 = std::decay_t<decltype(s1)>;
    using S2 = std::decay_t<decltype(s2)>;
    fcl::CollisionResult<double> r;
    fcl::detail::ShapeCollisionTraversalNode<S1, S2, Solver> node;
    EXPECT_TRUE(fcl::detail::initialize(node, s1, tf1, s2, tf2, &solver, fcl::CollisionRequest<double>(1, true), r));
    fcl::detail::collide(&node);
    fcl::CollisionResult<double> front;
    EXPECT_EQ(fcl_quadric::collide(&s1, tf1, &s2, tf2, fcl::CollisionRequest<double>(), front) > 0, r.isCollision());
    return r.isCollision();
  };
  for (double x : {0.0, 0.1}) {  // down the bore: 0.5 - 0.3 - 0.1 = 0.1 clear of its wall
    const fcl::Transform3d down = pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(x, 0, 0));
    EXPECT_FALSE(nodeCollides(ring, I, rod, down)) << x;
    EXPECT_FALSE(nodeCollides(rod, down, ring, I)) << x;
    EXPECT_FALSE(nodeCollides(box, down, ring, I)) << x;  // box corner at 0.1 + 0.15 sqrt 2 = 0.31 < 0.5
  }
  const fcl::Transform3d through = pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.7, 0, 0));
  EXPECT_TRUE(nodeCollides(ring, I, rod, through));
  EXPECT_TRUE(nodeCollides(box, through, ring, I));
}

TEST(FclTraversalNodes, DistanceNodesWithAQuadricShapeMatchStockLibccdAndTheFrontDoor) {
  const auto obbrss = heightField<fcl::OBBRSS<double>>(6);
  const Cyl cyl(kRadius, kRadius, kLength);
  const fcl::Cylinder<double> stock(kRadius, kLength);
  const Solver solver;
  const fcl::Transform3d tf_mesh = fcl::Transform3d::Identity();
  std::mt19937_64 rng(23);
  int compared = 0;
  for (int k = 0; k < 25; ++k) {
    fcl::Transform3d tf_cyl = randomPoseAbove(rng, 1.5);
    tf_cyl.translation().z() += 1.0;  // mostly clear of the field
    const fcl::DistanceRequest<double> request(true);
    fcl::DistanceResult<double> r;
    fcl::detail::MeshShapeDistanceTraversalNodeOBBRSS<Cyl, Solver> node;
    ASSERT_TRUE(fcl::detail::initialize(node, *obbrss, tf_mesh, cyl, tf_cyl, &solver, request, r));
    fcl::detail::distance(&node);
    fcl::DistanceResult<double> front;
    fcl_quadric::distance(obbrss.get(), tf_mesh, &cyl, tf_cyl, request, front);
    fcl::DistanceResult<double> libccd;
    fcl::distance(obbrss.get(), tf_mesh, &stock, tf_cyl, request, libccd);
    if (front.min_distance < 0.0) {
      EXPECT_LT(r.min_distance, 0.0) << k;
      continue;
    }
    EXPECT_NEAR(r.min_distance, front.min_distance, 1e-9) << k;
    if (libccd.min_distance > kMargin) {
      // libccd's GJK stops at distance_tolerance 1e-6.
      EXPECT_NEAR(r.min_distance, libccd.min_distance, 1e-5) << k;
      ++compared;
    }
    // The witness points are that far apart.
    EXPECT_NEAR((r.nearest_points[0] - r.nearest_points[1]).norm(), r.min_distance, 1e-8) << k;
  }
  EXPECT_GE(compared, 15);

  // OcTree distance node: a floor of cells below the cylinder, against stock libccd.
  auto tree = std::make_shared<octomap::OcTree>(0.2);
  for (double x = -1.0; x <= 1.0; x += 0.2)
    for (double y = -1.0; y <= 1.0; y += 0.2) tree->updateNode(octomap::point3d(x, y, -0.05), true);
  const fcl::OcTree<double> octree(tree);
  const fcl::detail::OcTreeSolver<Solver> otsolver(&solver);
  for (double h : {0.8, 1.0}) {
    const fcl::Transform3d tf_cyl = pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.05, 0.02, h));
    fcl::DistanceResult<double> r;
    fcl::detail::OcTreeShapeDistanceTraversalNode<Cyl, Solver> node;
    ASSERT_TRUE(fcl::detail::initialize(node, octree, fcl::Transform3d::Identity(), cyl, tf_cyl, &otsolver,
                                        fcl::DistanceRequest<double>(true), r));
    fcl::detail::distance(&node);
    // The floor's top is at z = 0 (cells [-0.2, 0] for resolution 0.2): the gap is h - L/2.
    EXPECT_NEAR(r.min_distance, h - 0.5 * kLength, 1e-8) << h;
  }
}

/// The triangle P1 P2 P3 as a one-triangle mesh (in its own frame): the front door's operand, the
/// way the solver's triangle kernels answered before session 32, and the stock oracle's operand.
/// (OBBRSS: FCL 0.7's distance table has no AABB mesh against a cylinder.)
std::shared_ptr<fcl::BVHModel<fcl::OBBRSS<double>>> oneTriangle(const Eigen::Vector3d& P1, const Eigen::Vector3d& P2,
                                                               const Eigen::Vector3d& P3) {
  auto m = std::make_shared<fcl::BVHModel<fcl::OBBRSS<double>>>();
  m->beginModel(1, 3);
  m->addTriangle(P1, P2, P3);
  m->endModel();
  return m;
}

TEST(FclTraversalNodes, SolverTriangleKernelsAgreeWithTheFrontDoorAndStockLibccdOnOneTriangle) {
  // Random triangles (edges 0.02 to 1.5, posed in their own frame) near a capped cylinder: the
  // solver's triangle kernels (GJK per leaf for a convex shape since session 32) must give the
  // front door's verdict and distance on the same triangle as a one-triangle mesh, the stock libccd
  // margin oracle's wherever it decides, and a contact on both solids; a distance certified by a
  // separating plane and not above stock fcl::distance's. Zero-area triangles (collinear
  // vertices) are skipped by collide (documented), even when the segment crosses the cylinder; a
  // ring (non-convex: the one-triangle mesh's way) agrees with the front door too.
  const Cyl cyl(kRadius, kRadius, kLength);
  const fcl::Cylinder<double> stock(kRadius, kLength);
  using Csg = QuadricCSG<double>;
  auto outer = std::make_shared<Quadric<double>>(Quadric<double>::ellipsoid(1.0, 1.0, 0.4));
  auto bore = std::make_shared<Quadric<double>>(Quadric<double>::ellipticCylinder(0.5, 0.5));
  const Csg ring(Csg::Op::Difference, {{outer, fcl::Transform3d::Identity()}, {bore, fcl::Transform3d::Identity()}});
  const Solver solver;
  std::mt19937_64 rng(32);
  std::uniform_real_distribution<double> u(-1.0, 1.0), edge(0.02, 1.5);
  int hits = 0, misses = 0, decided_hit = 0, decided_miss = 0, degenerate = 0, ring_hits = 0, ring_misses = 0,
      same_point = 0, distances_compared = 0;
  for (int k = 0; k < 1500; ++k) {
    const fcl::Transform3d tf_cyl = pose(test::randomRotation(rng), Eigen::Vector3d(u(rng), u(rng), u(rng)));
    const fcl::Transform3d tf_tri = pose(test::randomRotation(rng), Eigen::Vector3d(u(rng), u(rng), u(rng)));
    // A vertex near the cylinder's surface (in the triangle's frame), the others at random.
    const Eigen::Vector3d c = tf_tri.inverse() * (tf_cyl * Eigen::Vector3d(0.6 * u(rng), 0.6 * u(rng), 0.7 * u(rng)));
    const Eigen::Vector3d P1 = c + edge(rng) * Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    Eigen::Vector3d P2 = c + edge(rng) * Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    Eigen::Vector3d P3 = c + edge(rng) * Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    const bool collinear = k % 10 == 0;
    if (collinear) {  // P1, c and P2 on one segment through c; P3 on it too
      P2 = c - (P1 - c);
      P3 = c + 0.25 * (P1 - c);
    }
    const auto mesh = oneTriangle(P1, P2, P3);
    Eigen::Vector3d pos = Eigen::Vector3d::Zero(), n = Eigen::Vector3d::Zero();
    double depth = -1.0;
    const bool hit = solver.shapeTriangleIntersect(cyl, tf_cyl, P1, P2, P3, tf_tri, &pos, &depth, &n);
    // The world-frame overload (tf = the identity for the vertices): the same verdict.
    EXPECT_EQ(solver.shapeTriangleIntersect(cyl, tf_cyl, tf_tri * P1, tf_tri * P2, tf_tri * P3), hit) << k;
    fcl::CollisionResult<double> front;
    const bool front_hit =
        fcl_quadric::collide(&cyl, tf_cyl, mesh.get(), tf_tri, fcl::CollisionRequest<double>(1, true), front) > 0;
    ASSERT_EQ(hit, front_hit) << k;
    // The distance kernel: the front door's distance to the one-triangle mesh, to the bit where GJK
    // decides (the same computation), and witnesses that far apart.
    double dist = -2.0;
    Eigen::Vector3d w1 = Eigen::Vector3d::Zero(), w2 = Eigen::Vector3d::Zero();
    const bool clear = solver.shapeTriangleDistance(cyl, tf_cyl, P1, P2, P3, tf_tri, &dist, &w1, &w2);
    fcl::DistanceResult<double> front_d;
    fcl_quadric::distance(&cyl, tf_cyl, mesh.get(), tf_tri, fcl::DistanceRequest<double>(true), front_d);
    EXPECT_EQ(dist, front_d.min_distance) << k;
    EXPECT_EQ(clear, dist >= 0.0) << k;  // FCL's convention: false for an overlap (distance -1)
    if (!collinear) {
      EXPECT_EQ(dist > 0.0, !hit) << k;  // (a zero-area triangle has a distance, not a contact)
    }
    if (dist > 0.0) {
      EXPECT_NEAR((w1 - w2).norm(), dist, 1e-9) << k;
      EXPECT_LT((w1 - front_d.nearest_points[0]).norm(), 1e-12) << k;
      // Certified from both sides, independently of GJK: the plane normal to w2 - w1 bounds the
      // distance from below by the gap between the triangle's lowest vertex along it and the
      // cylinder's closed-form support (r |n_xy| + L/2 |n_z| in its frame); the witnesses, a point
      // of each solid, from above.
      const Eigen::Vector3d nrm = (w2 - w1) / dist, nl = tf_cyl.linear().transpose() * nrm;
      const double reach = nrm.dot(tf_cyl.translation()) + kRadius * std::hypot(nl.x(), nl.y()) +
                           0.5 * kLength * std::abs(nl.z());
      const double lowest = std::min({nrm.dot(tf_tri * P1), nrm.dot(tf_tri * P2), nrm.dot(tf_tri * P3)});
      EXPECT_LT(dist - (lowest - reach), 1e-9) << k;
      const Eigen::Vector3d l1 = tf_cyl.inverse() * w1, l2 = tf_tri.inverse() * w2;
      EXPECT_LE(std::max(std::hypot(l1.x(), l1.y()) - kRadius, std::abs(l1.z()) - 0.5 * kLength), 1e-9) << k;
      if (!collinear) {
        EXPECT_LT(std::abs((P2 - P1).cross(P3 - P1).normalized().dot(l2 - P1)), 1e-9) << k;
      }
      // Stock libccd's distance (the distance between two points it found: not below the true one,
      // up to its rounding) is not smaller than ours.
      fcl::DistanceResult<double> stock_d;
      fcl::distance(mesh.get(), tf_tri, &stock, tf_cyl, fcl::DistanceRequest<double>(true), stock_d);
      if (stock_d.min_distance > kMargin) {
        EXPECT_LE(dist, stock_d.min_distance + 1e-9) << k;
        ++distances_compared;
      }
    }
    if (collinear) {
      EXPECT_FALSE(hit) << k << ": a zero-area triangle is skipped";
      ++degenerate;
      continue;
    }
    expectAgreesWithStockMargins(hit, mesh.get(), tf_tri, tf_cyl, &decided_hit, &decided_miss, "triangle kernel");
    (hit ? hits : misses)++;
    if (hit) {
      // On the triangle's plane and inside the cylinder (within the engine's band); the unit
      // normal of the cylinder's nearest boundary there, as the front door's contact gives it.
      const Eigen::Vector3d tri_n = (P2 - P1).cross(P3 - P1).normalized();
      EXPECT_LT(std::abs(tri_n.dot(tf_tri.inverse() * pos - P1)), 1e-6) << k;
      const Eigen::Vector3d l = tf_cyl.inverse() * pos;
      EXPECT_LE(std::hypot(l.x(), l.y()), kRadius + 1e-6) << k;
      EXPECT_LE(std::abs(l.z()), 0.5 * kLength + 1e-6) << k;
      EXPECT_NEAR(n.norm(), 1.0, 1e-12) << k;
      EXPECT_EQ(depth, 0.0) << k;
      const fcl::Contact<double>& fc = front.getContact(0);
      if ((fc.pos - pos).norm() < 1e-12) {
        EXPECT_LT((fc.normal - n).norm(), 1e-9) << k;
        ++same_point;
      }
    }
    // The ring (every third triangle: its region engine is the test's slow part): not convex, so
    // the kernel takes the one-triangle mesh's way; the same verdict.
    if (k % 3 != 1) continue;
    const bool ring_hit = solver.shapeTriangleIntersect(ring, tf_cyl, P1, P2, P3, tf_tri);
    fcl::CollisionResult<double> ring_front;
    EXPECT_EQ(ring_hit, fcl_quadric::collide(&ring, tf_cyl, mesh.get(), tf_tri, fcl::CollisionRequest<double>(),
                                             ring_front) > 0)
        << k;
    (ring_hit ? ring_hits : ring_misses)++;
  }
  EXPECT_GE(hits, 300);
  EXPECT_GE(misses, 300);
  EXPECT_GE(decided_hit + decided_miss, hits + misses - 20);
  EXPECT_EQ(degenerate, 150);
  EXPECT_GE(same_point, hits / 2);  // GJK's common point: the front door's contact on the same triangle
  EXPECT_GE(distances_compared, 300);
  EXPECT_GE(ring_hits, 100);
  EXPECT_GE(ring_misses, 80);
  std::printf("triangle kernel: %d hits, %d misses (stock decides %d / %d), %d at the front door's point, "
              "ring %d / %d; %d distances against libccd\n",
              hits, misses, decided_hit, decided_miss, same_point, ring_hits, ring_misses, distances_compared);
}

TEST(FclTraversalNodes, SolverTriangleKernelsAnswerAtClosedFormsAndRejectBadInput) {
  const Cyl cyl(kRadius, kRadius, kLength);
  const Solver solver;
  const fcl::Transform3d I = fcl::Transform3d::Identity();
  // A horizontal triangle covering the axis collides at heights within the caps (|z| <= 0.6),
  // down to a relative gap of 1e-9, and not beyond.
  for (const double z : {0.0, 0.6 * (1 - 1e-9), 0.6 * (1 + 1e-9), -0.6 * (1 + 1e-9)}) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero(), n = Eigen::Vector3d::Zero();
    double depth = -1;
    const bool hit = solver.shapeTriangleIntersect(cyl, I, Eigen::Vector3d(-1, -1, z), Eigen::Vector3d(1, -1, z),
                                                   Eigen::Vector3d(0, 1, z), &c, &depth, &n);
    EXPECT_EQ(hit, std::abs(z) <= 0.6) << z;
    if (hit) {
      EXPECT_NEAR(c.z(), z, 1e-9);
      EXPECT_NEAR(n.norm(), 1.0, 1e-12);
      EXPECT_EQ(depth, 0.0);  // not computed for quadric shapes (documented)
    }
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(solver.shapeTriangleIntersect(cyl, I, Eigen::Vector3d(nan, 0, 0), Eigen::Vector3d(1, 0, 0),
                                             Eigen::Vector3d(0, 1, 0)),
               std::invalid_argument);
  // Above the top cap by 0.25: the distance is exact.
  double d = 0;
  Eigen::Vector3d p1 = Eigen::Vector3d::Zero(), p2 = Eigen::Vector3d::Zero();
  EXPECT_TRUE(solver.shapeTriangleDistance(cyl, I, Eigen::Vector3d(-1, -1, 0.85), Eigen::Vector3d(1, -1, 0.85),
                                           Eigen::Vector3d(0, 1, 0.85), &d, &p1, &p2));
  EXPECT_NEAR(d, 0.25, 1e-9);
  EXPECT_NEAR(p2.z(), 0.85, 1e-12);
  // Within 1e-8 of the scale of the cap the front door's collide decides the sign: the kernel
  // answers as the front door does on the triangle as a one-triangle mesh.
  for (const double z : {0.6, 0.6 * (1 + 1e-12), 0.6 * (1 + 1e-9), 0.6 * (1 - 1e-9)}) {
    const Eigen::Vector3d A(-1, -1, z), B(1, -1, z), C(0, 1, z);
    const bool clear = solver.shapeTriangleDistance(cyl, I, A, B, C, &d, &p1, &p2);
    EXPECT_EQ(clear, d >= 0.0) << z;  // FCL's convention: false for an overlap (distance -1)
    fcl::DistanceResult<double> front;
    fcl_quadric::distance(&cyl, I, oneTriangle(A, B, C).get(), I, fcl::DistanceRequest<double>(true), front);
    EXPECT_EQ(d, front.min_distance) << z;
    // Exact since session 40: a gap of 6e-13 is certified apart (certifiedApart), no longer
    // within the region engine's touching band.
    EXPECT_EQ(d > 0.0, z > 0.6) << z << " " << d;
    if (d > 0.0) {
      EXPECT_NEAR(d, z - 0.6, 1e-15) << z;
    }
  }
}

}  // namespace
}  // namespace fcl_quadric
