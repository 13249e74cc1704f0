// fcl_quadric::continuousCollide of quadric shapes against BVH meshes and fcl::OcTree (issue 5:
// the shapes must work wherever the front doors are used). Oracles: closed-form first contact
// times of a capped elliptic cylinder landing on a floor (a two-triangle mesh, a layer of octree
// cells; upright and tilted, floor or shape moving), and, on random rational motions over a
// terrain mesh, the static front door sampled densely in time (a sampled overlap must not come
// before the reported contact) and the distance front door at the reported time (the shape
// touches the mesh there).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/octree/octree.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/math/motion/interp_motion.h>
#include <octomap/OcTree.h>

#include "fcl_quadric/fcl/collision.h"
#include "fcl_quadric/fcl/continuous_collision.h"
#include "fcl_quadric/fcl/distance.h"
#include "fcl_quadric/fcl/quadric_shapes.h"
#include "fcl_quadric/fcl/rational_motion.h"
#include "support/fcl_fixtures.h"

namespace fcl_quadric {
namespace quadric_shape_mesh_ccd_test {
namespace {

using Transform = fcl::Transform3<double>;
using Mesh = fcl::BVHModel<fcl::OBBRSS<double>>;
using test::pose;

Transform at(const Eigen::Vector3d& p, const Eigen::Matrix3d& R = Eigen::Matrix3d::Identity()) { return pose(R, p); }

// The square [-h, h]^2 at height z as two triangles.
std::shared_ptr<Mesh> floorMesh(double h, double z) {
  auto m = std::make_shared<Mesh>();
  m->beginModel();
  m->addTriangle(Eigen::Vector3d(-h, -h, z), Eigen::Vector3d(h, -h, z), Eigen::Vector3d(h, h, z));
  m->addTriangle(Eigen::Vector3d(-h, -h, z), Eigen::Vector3d(h, h, z), Eigen::Vector3d(-h, h, z));
  m->endModel();
  return m;
}

struct Ccd {
  bool collide;
  double time;
  ContinuousCollideStats stats;
};

Ccd ccd(const fcl::CollisionGeometry<double>* a, const fcl::MotionBase<double>* ma, const fcl::CollisionGeometry<double>* b,
        const fcl::MotionBase<double>* mb) {
  fcl::ContinuousCollisionRequest<double> req;
  fcl::ContinuousCollisionResult<double> res;
  const double t = fcl_quadric::continuousCollide(a, ma, b, mb, req, res);
  EXPECT_EQ(t, res.time_of_contact);
  return {res.is_collide, res.time_of_contact, lastContinuousCollideStats()};
}

TEST(QuadricShapeMeshCcd, CylinderLandingOnAMeshFloorTouchesAtTheClosedFormTime) {
  const double a = 0.5, b = 0.3, L = 1.0;
  const EllipticCylinder<double> cyl(a, b, L);
  const auto floor = floorMesh(2.0, 0.0);
  const RationalMotion<double> still(Transform::Identity(), Transform::Identity());
  for (const double tilt : {0.0, 0.35}) {
    SCOPED_TRACE("tilt " + std::to_string(tilt));
    // Tilted about x: the lowest point of the rim is L/2 cos + b sin below the centre.
    const Eigen::Matrix3d R = Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitX()).toRotationMatrix();
    const double drop = 0.5 * L * std::cos(tilt) + b * std::sin(tilt);
    const double expected = (3.0 - drop) / 4.0;  // the centre goes from z = 3 to z = -1
    const RationalMotion<double> fall(at({0.2, -0.1, 3.0}, R), at({0.2, -0.1, -1.0}, R));
    for (const bool mesh_first : {false, true}) {
      const Ccd r = mesh_first ? ccd(floor.get(), &still, &cyl, &fall) : ccd(&cyl, &fall, floor.get(), &still);
      ASSERT_TRUE(r.collide);
      EXPECT_EQ(r.stats.path, ContinuousCollideStats::Path::Exact);
      EXPECT_LE(r.time, expected + 1e-12);  // never later than the true contact
      EXPECT_NEAR(r.time, expected, 1e-7);
      EXPECT_NEAR(r.stats.contact_point.z(), 0.0, 1e-6);
    }
    // The floor rising to the still cylinder instead: the same relative motion.
    const RationalMotion<double> tilted(at({0, 0, 0}, R), at({0, 0, 0}, R));
    const RationalMotion<double> rise(at({-0.2, 0.1, -3.0}), at({-0.2, 0.1, 1.0}));
    const Ccd r = ccd(&cyl, &tilted, floor.get(), &rise);
    ASSERT_TRUE(r.collide);
    EXPECT_LE(r.time, (3.0 - drop) / 4.0 + 1e-12);
    EXPECT_NEAR(r.time, (3.0 - drop) / 4.0, 1e-7);
  }
  // Beside the floor (the square ends at x = 2; the cylinder's half-width along x is 0.5): no contact.
  const RationalMotion<double> beside(at({2.6, 0.0, 3.0}), at({2.6, 0.0, -1.0}));
  const Ccd miss = ccd(&cyl, &beside, floor.get(), &still);
  EXPECT_FALSE(miss.collide);
  EXPECT_EQ(miss.time, 1.0);
  // Through the transforms overload (CCDM_TRANS), as FCL callers write it.
  fcl::ContinuousCollisionRequest<double> req;
  req.ccd_motion_type = fcl::CCDM_TRANS;
  fcl::ContinuousCollisionResult<double> res;
  fcl_quadric::continuousCollide(&cyl, at({0, 0, 3}), at({0, 0, -1}), floor.get(), Transform::Identity(),
                                 Transform::Identity(), req, res);
  ASSERT_TRUE(res.is_collide);
  EXPECT_NEAR(res.time_of_contact, (3.0 - 0.5 * L) / 4.0, 1e-7);
}

TEST(QuadricShapeMeshCcd, CylinderLandingOnOcTreeCellsTouchesAtTheClosedFormTime) {
  // One layer of occupied cells of side 0.25 below z = 0 (octomap's grid puts cell faces at
  // multiples of the resolution), under x, y in [-1, 1].
  auto tree = std::make_shared<octomap::OcTree>(0.25);
  for (double x = -0.875; x < 1.0; x += 0.25)
    for (double y = -0.875; y < 1.0; y += 0.25) tree->updateNode(octomap::point3d(x, y, -0.125), true);
  const fcl::OcTree<double> octree(tree);
  const EllipticCylinder<double> cyl(0.4, 0.25, 0.8);
  const RationalMotion<double> still(Transform::Identity(), Transform::Identity());
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitY()).toRotationMatrix();
  // Tilted about y: the semi-axis along x (0.4) tips down.
  const double drop = 0.4 * std::cos(0.5) + 0.4 * std::sin(0.5);
  const RationalMotion<double> fall(at({0.1, 0.05, 2.0}, R), at({0.1, 0.05, -2.0}, R));
  const Ccd r = ccd(&cyl, &fall, &octree, &still);
  ASSERT_TRUE(r.collide);
  EXPECT_LE(r.time, (2.0 - drop) / 4.0 + 1e-12);
  EXPECT_NEAR(r.time, (2.0 - drop) / 4.0, 1e-7);
  EXPECT_NEAR(r.stats.contact_point.z(), 0.0, 1e-6);
  // Sliding sideways above the cells (gap 0.05 below the lowest point): no contact.
  const RationalMotion<double> above(at({-3.0, 0.0, drop + 0.05}, R), at({3.0, 0.0, drop + 0.05}, R));
  EXPECT_FALSE(ccd(&octree, &still, &cyl, &above).collide);
}

TEST(QuadricShapeMeshCcd, RandomMotionsOverATerrainMatchTheSampledFrontDoors) {
  // A bumpy height field of 6 x 6 cells (72 triangles) over [-1.5, 1.5]^2.
  std::mt19937 rng(2611);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  const int n = 6;
  const double cell = 3.0 / n;
  std::vector<double> height((n + 1) * (n + 1));
  for (double& h : height) h = 0.3 * U(rng);
  auto vertex = [&](int i, int j) { return Eigen::Vector3d(-1.5 + i * cell, -1.5 + j * cell, height[i * (n + 1) + j]); };
  auto terrain = std::make_shared<Mesh>();
  terrain->beginModel();
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      terrain->addTriangle(vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1));
      terrain->addTriangle(vertex(i, j), vertex(i + 1, j + 1), vertex(i, j + 1));
    }
  terrain->endModel();
  const RationalMotion<double> still(Transform::Identity(), Transform::Identity());
  const int samples = 150;
  int contacts = 0, misses = 0;
  for (int trial = 0; trial < 8; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    const EllipticCylinder<double> cyl(0.15 + 0.2 * U(rng), 0.1 + 0.2 * U(rng), 0.3 + 0.5 * U(rng));
    auto rot = [&] {
      return Eigen::Quaterniond(U(rng) - 0.5, U(rng) - 0.5, U(rng) - 0.5, U(rng) - 0.5).normalized().toRotationMatrix();
    };
    // From above the terrain to a point at or below its top (some motions stay above it).
    const RationalMotion<double> m(at({2 * U(rng) - 1, 2 * U(rng) - 1, 1.2 + 0.5 * U(rng)}, rot()),
                                   at({2 * U(rng) - 1, 2 * U(rng) - 1, 0.8 * U(rng)}, rot()));
    const Ccd r = ccd(&cyl, &m, terrain.get(), &still);
    auto poseAt = [&](double t) {
      m.integrate(t);
      Transform tf;
      m.getCurrentTransform(tf);
      return tf;
    };
    // The static front door at sampled instants: no overlap before the reported contact.
    int first = -1;
    for (int k = 0; k <= samples && first < 0; ++k) {
      fcl::CollisionRequest<double> req;
      fcl::CollisionResult<double> res;
      if (fcl_quadric::collide(&cyl, poseAt(double(k) / samples), terrain.get(), Transform::Identity(), req, res) > 0)
        first = k;
    }
    if (first >= 0) {
      ASSERT_TRUE(r.collide) << "sampled overlap at t = " << double(first) / samples;
      EXPECT_LE(r.time, double(first) / samples + 1e-12);
    }
    if (!r.collide) {
      ++misses;
      continue;
    }
    ++contacts;
    // At the reported time the shape touches the terrain: the distance front door (convex shape
    // against a mesh) is zero to the engine's band, and it is clear a little earlier.
    fcl::DistanceRequest<double> dreq;
    fcl::DistanceResult<double> dres;
    fcl_quadric::distance(&cyl, poseAt(r.time), terrain.get(), Transform::Identity(), dreq, dres);
    EXPECT_LE(dres.min_distance, 1e-6);
    if (r.time > 1e-3) {
      fcl::DistanceResult<double> before;
      fcl_quadric::distance(&cyl, poseAt(r.time - 1e-3), terrain.get(), Transform::Identity(), dreq, before);
      EXPECT_GT(before.min_distance, 0.0);
    }
  }
  // The draw gives both kinds of motion.
  EXPECT_GE(contacts, 3);
  EXPECT_GE(misses, 1);
}

TEST(QuadricShapeMeshCcd, BadMotionsOfAMeshPartnerThrowNamingThem) {
  const EllipticCylinder<double> cyl(0.5, 0.3, 1.0);
  const auto floor = floorMesh(2.0, 0.0);
  const RationalMotion<double> fall(at({0, 0, 3}), at({0, 0, -1}));
  const fcl::InterpMotion<double> interp(Transform::Identity(), Transform::Identity());
  fcl::ContinuousCollisionRequest<double> req;
  fcl::ContinuousCollisionResult<double> res;
  try {
    fcl_quadric::continuousCollide(&cyl, &fall, floor.get(), &interp, req, res);
    ADD_FAILURE() << "InterpMotion of the mesh accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("motion2 is an fcl::InterpMotion"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace quadric_shape_mesh_ccd_test
}  // namespace fcl_quadric
