// Certified distance lower bounds (fcl_quadric::distanceLowerBound) for non-convex quadric shapes
// and FCL box / cylinder primitives against meshes, octrees, half-spaces and primitives, and the
// exact distance of unions of convex quadric shapes. The oracle of a bound d is independent of the
// bound's construction: the exact Minkowski sum of the partner piece with the ball of radius
// d (1 - 1e-6) (a CSG union of slabs, capped cylinders and balls) must not overlap the shape
// (collideRegions: Separated or Touching), i.e. no point of the shape is closer than that.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <random>
#include <vector>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/octree/octree.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/halfspace.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/bv/OBBRSS.h>
#include <octomap/OcTree.h>

#include "fcl_quadric/algebra/quadric_matrix.h"
#include "fcl_quadric/fcl/collision.h"
#include "fcl_quadric/fcl/distance.h"
#include "fcl_quadric/fcl/quadric_shapes.h"
#include "fcl_quadric/geometry/convex_cover.h"
#include "fcl_quadric/geometry/quadric_region.h"
#include "fcl_quadric/geometry/region_distance_bound.h"
#include "support/fcl_fixtures.h"
#include "support/expect_invalid.h"
#include "support/random_ellipsoids.h"

namespace fcl_quadric {
namespace {

using Transform = fcl::Transform3<double>;
using Op = QuadricRegion::Op;

using test::pose;

/// The solid {x : |x - a|^2 - ((x - a).u)^2 <= r^2, 0 <= (x - a).u <= |b - a|}: the segment a-b
/// grown by r, without its end balls.
QuadricRegion cappedCylinder(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double r) {
  const Eigen::Vector3d u = (b - a).normalized();
  const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - u * u.transpose();
  Eigen::Matrix4d Q = Eigen::Matrix4d::Zero();
  Q.topLeftCorner<3, 3>() = P;
  Q.topRightCorner<3, 1>() = -P * a;
  Q.bottomLeftCorner<1, 3>() = (-P * a).transpose();
  Q(3, 3) = a.dot(P * a) - r * r;
  return QuadricRegion::combine(Op::Intersection, {QuadricRegion::atom(Q), QuadricRegion::halfspace(-u, -u.dot(a)),
                                                   QuadricRegion::halfspace(u, u.dot(b))});
}

QuadricRegion ball(const Eigen::Vector3d& c, double r) {
  return QuadricRegion::atom(quadric::posedEllipsoid(Eigen::Vector3d::Constant(r), Eigen::Matrix3d::Identity(), c));
}

/// The triangle's exact r-neighbourhood: its prism of half thickness r, three edge cylinders and
/// three vertex balls.
QuadricRegion triangleMinkowski(const std::array<Eigen::Vector3d, 3>& p, double r) {
  const Eigen::Vector3d n = (p[1] - p[0]).cross(p[2] - p[0]).normalized();
  std::vector<QuadricRegion> prism{QuadricRegion::halfspace(n, n.dot(p[0]) + r),
                                   QuadricRegion::halfspace(-n, -n.dot(p[0]) + r)};
  std::vector<QuadricRegion> parts;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d& a = p[i];
    const Eigen::Vector3d& b = p[(i + 1) % 3];
    const Eigen::Vector3d out = (b - a).cross(n);
    prism.push_back(QuadricRegion::halfspace(out, out.dot(a)));
    parts.push_back(cappedCylinder(a, b, r));
    parts.push_back(ball(a, r));
  }
  parts.push_back(QuadricRegion::combine(Op::Intersection, prism));
  return QuadricRegion::combine(Op::Union, parts);
}

/// The box c +- h's exact r-neighbourhood: three grown slabs, twelve edge cylinders, eight balls.
QuadricRegion boxMinkowski(const Eigen::Vector3d& c, const Eigen::Vector3d& h, double r) {
  std::vector<QuadricRegion> parts;
  for (int k = 0; k < 3; ++k) {
    std::vector<QuadricRegion> planes;
    for (int i = 0; i < 3; ++i) {
      const double g = h[i] + (i == k ? r : 0.0);
      planes.push_back(QuadricRegion::halfspace(Eigen::Vector3d::Unit(i), c[i] + g));
      planes.push_back(QuadricRegion::halfspace(-Eigen::Vector3d::Unit(i), -(c[i] - g)));
    }
    parts.push_back(QuadricRegion::combine(Op::Intersection, planes));
  }
  for (int v = 0; v < 8; ++v) {
    const Eigen::Vector3d s((v & 1) ? 1 : -1, (v & 2) ? 1 : -1, (v & 4) ? 1 : -1);
    const Eigen::Vector3d corner = c + s.cwiseProduct(h);
    parts.push_back(ball(corner, r));
    for (int i = 0; i < 3; ++i)
      if (s[i] < 0) {  // each edge once: from its -i end
        Eigen::Vector3d other = corner;
        other[i] = c[i] + h[i];
        parts.push_back(cappedCylinder(corner, other, r));
      }
  }
  return QuadricRegion::combine(Op::Union, parts);
}

/// True if the shape (region in its frame, posed by tf_s) and the neighbourhood (world frame,
/// bounded by box) certainly overlap: the bound was too large.
bool overlaps(const QuadricShape<double>& s, const Transform& tf_s, const QuadricRegion& hood, const Box3& hood_box) {
  const Transform inv = tf_s.inverse();  // world -> shape frame
  return collideRegions(s.region(), s.localBox(), hood, hood_box, inv.linear(), inv.translation()).relation ==
         RegionRelation::Overlapping;
}

std::shared_ptr<QuadricCSG<double>> makeRing() {
  auto outer = std::make_shared<Quadric<double>>(Quadric<double>::ellipsoid(1.0, 1.0, 0.4));
  auto bore = std::make_shared<Quadric<double>>(Quadric<double>::ellipticCylinder(0.5, 0.5));
  return std::make_shared<QuadricCSG<double>>(Op::Difference, std::vector<QuadricCSG<double>::Child>{
                                                                  {outer, Transform::Identity()}, {bore, Transform::Identity()}});
}

TEST(ConvexCover, UnionsAreExactAndDifferencesAreCoveredByTheirFirstOperand) {
  auto e1 = std::make_shared<Quadric<double>>(Quadric<double>::ellipsoid(1.0, 0.5, 0.5));
  auto e2 = std::make_shared<Quadric<double>>(Quadric<double>::ellipsoid(0.3, 0.3, 1.2));
  const QuadricCSG<double> cross(Op::Union, {{e1, Transform::Identity()}, {e2, pose(Eigen::Matrix3d::Identity(), {0.5, 0, 0})}});
  const ConvexCover c = convexCover(cross.region(), cross.localBox());
  EXPECT_TRUE(c.exact);
  ASSERT_EQ(c.pieces.size(), 2u);
  // Each piece's support along +-axes is the corresponding ellipsoid's extent.
  EXPECT_NEAR(c.pieces[0].support(Eigen::Vector3d::UnitX()).x(), 1.0, 1e-9);
  EXPECT_NEAR(c.pieces[1].support(Eigen::Vector3d::UnitZ()).z(), 1.2, 1e-9);
  const auto ring = makeRing();
  const ConvexCover r = convexCover(ring->region(), ring->localBox());
  EXPECT_FALSE(r.exact);
  ASSERT_EQ(r.pieces.size(), 1u);
  EXPECT_NEAR(r.pieces[0].support(Eigen::Vector3d::UnitX()).x(), 1.0, 1e-9);
  // Every point of the ring lies in its cover: sampled interior points satisfy n.x <= h(n).
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto dirs = test::fibonacciSphere(64);
  int inside = 0;
  for (int i = 0; i < 4000; ++i) {
    const Eigen::Vector3d x(u(rng), u(rng), 0.4 * u(rng));
    if (ring->region().classifyPoint(x) <= 0) continue;
    ++inside;
    for (const Eigen::Vector3d& n : dirs) EXPECT_LE(n.dot(x), n.dot(r.pieces[0].support(n)) + 1e-12);
  }
  EXPECT_GT(inside, 500);
  EXPECT_THROW(convexCover(ring->region(), Box3{Eigen::Vector3d::Ones(), Eigen::Vector3d::Zero()}), std::invalid_argument);
}

// Since session 43 a cover's pieces skip the model box's faces when they lie inside it
// (ConvexSupport::BoxRole::Contains): a union's pieces are then its operands exactly, and a piece
// that reaches beyond the box (a superset) is still cut by it.
TEST(ConvexCover, PiecesInsideTheBoxAreTheOperandsAndPiecesBeyondItAreCutByIt) {
  const auto rod = std::make_shared<EllipticCylinder<double>>(0.3, 0.4, 2.0);
  std::vector<QuadricCSG<double>::Child> children;
  std::vector<Transform> poses;
  for (int k = 0; k < 3; ++k) {
    poses.push_back(pose(Eigen::AngleAxisd(0.4 + 0.45 * k, Eigen::Vector3d(1, k, 0.5).normalized()).toRotationMatrix(),
                         {0.3 * k, 0.1 * k, 0.0}));
    children.push_back({rod, poses.back()});
  }
  const QuadricCSG<double> link(Op::Union, children);
  const ConvexCover c = convexCover(link.region(), link.localBox());
  EXPECT_TRUE(c.exact);
  ASSERT_EQ(c.pieces.size(), 3u);
  const ConvexSupport closed = ConvexSupport::ellipticCylinder(0.3, 0.4, 1.0);
  const auto dirs = test::fibonacciSphere(200);
  std::vector<bool> matched(3, false);
  for (const ConvexSupport& piece : c.pieces) {
    // The operand whose closed-form support this piece has in every direction.
    int match = -1;
    for (int k = 0; k < 3 && match < 0; ++k) {
      bool all = true;
      for (const Eigen::Vector3d& n : dirs) {
        const Eigen::Vector3d x = poses[k] * closed.support(poses[k].linear().transpose() * n);
        all = all && std::abs(n.dot(piece.support(n)) - n.dot(x)) <= 1e-10;
      }
      if (all) match = k;
    }
    ASSERT_GE(match, 0);
    EXPECT_FALSE(matched[match]);
    matched[match] = true;
  }
  // A capped cylinder of radius 0.9 cut by a one-sheet hyperboloid of waist 0.5 (|z| <= 0.5, where
  // its radius reaches 0.5 sqrt 2): the cover drops the hyperboloid, and its piece is the capped
  // cylinder cut by the model's box (the disk cuts the box's vertical edges).
  const auto can = std::make_shared<Quadric<double>>(Quadric<double>::ellipticCylinder(
      0.9, 0.9, {{Eigen::Vector3d::UnitZ(), 0.5}, {-Eigen::Vector3d::UnitZ(), 0.5}}));
  const auto waist = std::make_shared<Quadric<double>>(Quadric<double>::hyperboloidOneSheet(0.5, 0.5, 0.5));
  const QuadricCSG<double> spool(Op::Intersection, {{can, Transform::Identity()}, {waist, Transform::Identity()}});
  const Box3& box = spool.localBox();
  EXPECT_NEAR(box.hi.x(), 0.5 * std::sqrt(2.0), 1e-6);
  const ConvexCover sc = convexCover(spool.region(), box);
  EXPECT_FALSE(sc.exact);
  ASSERT_EQ(sc.pieces.size(), 1u);
  // The square |x|, |y| <= h cut by the disk of radius 0.9: arcs of the circle inside the square
  // (sampled) and the 8 points where the circle meets the square's sides.
  const double h = box.hi.x(), y_cut = std::sqrt(0.81 - h * h);
  std::vector<Eigen::Vector2d> rim;
  for (int k = 0; k < 7200; ++k) {
    const double t = 2 * M_PI * k / 7200;
    const Eigen::Vector2d q(0.9 * std::cos(t), 0.9 * std::sin(t));
    if (std::abs(q.x()) <= h && std::abs(q.y()) <= h) rim.push_back(q);
  }
  for (int k = 0; k < 8; ++k) {
    const double a = k & 1 ? h : -h, b = k & 2 ? y_cut : -y_cut;
    rim.push_back(k & 4 ? Eigen::Vector2d(a, b) : Eigen::Vector2d(b, a));
  }
  for (const Eigen::Vector3d& n : dirs) {
    double best = -1e300;
    for (const Eigen::Vector2d& q : rim) best = std::max(best, n.x() * q.x() + n.y() * q.y() + std::abs(n.z()) * 0.5);
    const double got = n.dot(sc.pieces[0].support(n));
    EXPECT_GE(got, best - 1e-9);  // sampled points of the solid
    EXPECT_LE(got, best + 1e-6);  // the arcs' sampling (0.9 (1 - cos(pi / 7200)) < 1e-7) and the box's pad
  }
}

TEST(QuadricShapeDistance, UnionOfEllipsoidsIsTheNearestChildInBothOrdersAndSigns) {
  // Oracle: the closed-form ellipsoid distance of each child (fcl::Ellipsoid through the front
  // door: the thesis ch.4 path, not GJK), the smaller one; for overlaps the deepest child.
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> pos(-1.3, 1.3);
  const Eigen::Vector3d r1(1.0, 0.5, 0.4), r2(0.3, 0.3, 1.2);
  const Transform X2 = pose(test::randomRotation(rng), {0.6, 0.1, 0.0});
  auto e1 = std::make_shared<Quadric<double>>(Quadric<double>::ellipsoid(r1.x(), r1.y(), r1.z()));
  auto e2 = std::make_shared<Quadric<double>>(Quadric<double>::ellipsoid(r2.x(), r2.y(), r2.z()));
  const QuadricCSG<double> both(Op::Union, {{e1, Transform::Identity()}, {e2, X2}});
  const fcl::Ellipsoid<double> c1(r1), c2(r2);
  const fcl::Box<double> box(0.4, 0.2, 0.6);
  int overlapping = 0;
  for (int i = 0; i < 150; ++i) {
    const Transform tf_u = pose(test::randomRotation(rng), {pos(rng), pos(rng), pos(rng)});
    const Transform tf_b = pose(test::randomRotation(rng), {pos(rng), pos(rng), pos(rng)});
    for (const bool signed_distance : {false, true}) {
      fcl::DistanceRequest<double> req(true);
      req.enable_signed_distance = signed_distance;
      fcl::DistanceResult<double> r_a, r_b, r_u, r_swapped;
      const double d1 = fcl_quadric::distance(&c1, tf_u, &box, tf_b, req, r_a);
      const double d2 = fcl_quadric::distance(&c2, tf_u * X2, &box, tf_b, req, r_b);
      const double expected = std::min(d1, d2);
      const double d = fcl_quadric::distance(&both, tf_u, &box, tf_b, req, r_u);
      const double ds = fcl_quadric::distance(&box, tf_b, &both, tf_u, req, r_swapped);
      if (expected < 0.0) {
        overlapping += signed_distance;
        if (!signed_distance) {
          EXPECT_EQ(d, -1.0) << i;
          EXPECT_EQ(ds, -1.0) << i;
          continue;
        }
      }
      const double tol = 1e-7 * (1.0 + std::abs(expected));
      EXPECT_NEAR(d, expected, tol) << i << " signed " << signed_distance;
      EXPECT_NEAR(ds, expected, tol) << i << " signed " << signed_distance;
      if (expected > 0.0) {
        EXPECT_NEAR((r_u.nearest_points[0] - r_u.nearest_points[1]).norm(), d, 1e-7) << i;
      }
    }
  }
  EXPECT_GT(overlapping, 5);
}

TEST(DistanceLowerBound, RingAgainstMeshOctreeBoxAndHalfspaceNeverExceedsTheDistance) {
  const auto ring = makeRing();
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> pos(-1.6, 1.6), unit(-1.0, 1.0);
  // A mesh of a few random triangles, an octree of a few cells, a box and a half-space.
  auto mesh = std::make_shared<fcl::BVHModel<fcl::OBBRSS<double>>>();
  std::vector<std::array<Eigen::Vector3d, 3>> tris;
  mesh->beginModel();
  for (int t = 0; t < 6; ++t) {
    const Eigen::Vector3d c(pos(rng), pos(rng), pos(rng));
    std::array<Eigen::Vector3d, 3> p;
    for (auto& v : p) v = c + 0.4 * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
    tris.push_back(p);
    mesh->addTriangle(p[0], p[1], p[2]);
  }
  mesh->endModel();
  auto octo = std::make_shared<octomap::OcTree>(0.25);
  for (int k = 0; k < 5; ++k) {
    const octomap::point3d q(float(pos(rng)), float(pos(rng)), float(pos(rng)));
    octo->updateNode(q, true);
  }
  octo->updateInnerOccupancy();
  const fcl::OcTree<double> tree(octo);
  std::vector<std::array<Eigen::Vector3d, 2>> leaves;
  for (const auto& b : tree.toBoxes())  // (x, y, z, side, cost, threshold)
    leaves.push_back({Eigen::Vector3d(b[0], b[1], b[2]), Eigen::Vector3d::Constant(0.5 * b[3])});
  ASSERT_FALSE(leaves.empty());
  const fcl::Box<double> box(0.5, 0.3, 0.4);
  const fcl::Halfspace<double> half(Eigen::Vector3d(0.3, -0.2, 1.0), 0.1);
  const Transform I = Transform::Identity();
  int positive = 0, checked = 0;
  for (int i = 0; i < 40; ++i) {
    const Transform tf = pose(test::randomRotation(rng), 1.2 * Eigen::Vector3d(unit(rng), unit(rng), unit(rng)));
    auto check = [&](double d, const QuadricRegion& hood_of_delta, const Box3& hood_box) {
      ++checked;
      positive += d > 0.0;
      EXPECT_FALSE(overlaps(*ring, tf, hood_of_delta, hood_box)) << i << " bound " << d;
    };
    // Mesh: the bound holds against every triangle.
    const double dm = *distanceLowerBound(ring.get(), tf, mesh.get(), I, 10.0);
    if (dm > 0.0) {
      const double r = dm * (1.0 - 1e-6);
      for (const auto& p : tris) {
        Box3 b{p[0].cwiseMin(p[1]).cwiseMin(p[2]) - Eigen::Vector3d::Constant(r + 1e-9),
               p[0].cwiseMax(p[1]).cwiseMax(p[2]) + Eigen::Vector3d::Constant(r + 1e-9)};
        check(dm, triangleMinkowski(p, r), b);
      }
    }
    const double dt = *distanceLowerBound(ring.get(), tf, &tree, I, 10.0);
    if (dt > 0.0) {
      const double r = dt * (1.0 - 1e-6);
      for (const auto& [c, h] : leaves)
        check(dt, boxMinkowski(c, h, r), Box3{c - h - Eigen::Vector3d::Constant(r + 1e-9), c + h + Eigen::Vector3d::Constant(r + 1e-9)});
    }
    const Transform tf_box = pose(test::randomRotation(rng), {pos(rng), pos(rng), pos(rng)});
    const double db = *distanceLowerBound(ring.get(), tf, &box, tf_box, 10.0);
    EXPECT_EQ(db, *distanceLowerBound(&box, tf_box, ring.get(), tf, 10.0)) << i;
    if (db > 0.0) {
      // In the box's frame: the ring posed by tf_box^-1 tf.
      const double r = db * (1.0 - 1e-6);
      const Eigen::Vector3d h = 0.5 * box.side;
      ++checked;
      positive += 1;
      EXPECT_FALSE(overlaps(*ring, tf_box.inverse() * tf, boxMinkowski(Eigen::Vector3d::Zero(), h, r),
                            Box3{-h - Eigen::Vector3d::Constant(r + 1e-9), h + Eigen::Vector3d::Constant(r + 1e-9)}))
          << i;
    }
    const double dh = *distanceLowerBound(ring.get(), tf, &half, I, 10.0);
    if (dh > 0.0) {
      const double r = dh * (1.0 - 1e-6);
      const Eigen::Vector3d n = half.n.normalized();
      ++checked;
      positive += 1;
      const Box3 far_box{Eigen::Vector3d::Constant(-10), Eigen::Vector3d::Constant(10)};
      EXPECT_FALSE(overlaps(*ring, tf, QuadricRegion::halfspace(n, half.d / half.n.norm() + r), far_box)) << i;
    }
  }
  EXPECT_GT(checked, 40);
  EXPECT_GT(positive, 20);
}

TEST(DistanceLowerBound, ARingThreadedOnAThinMeshPoleIsCertifiedClearOfIt) {
  // The pole (a thin triangular prism along z through the bore, radius 0.5) is inside the
  // ring's cover (the outer ellipsoid), so the cover alone gives 0; the engine's bound against
  // each triangle's delta-prism must certify the clearance: the pole's edges are 0.1 from the
  // axis, the bore wall 0.5, so the distance is 0.4 (minus the offset of the pole from the axis).
  const auto ring = makeRing();
  const std::array<Eigen::Vector3d, 3> rim = test::poleRim(0.1);
  const std::vector<std::array<Eigen::Vector3d, 3>> sides = test::poleTriangles(0.1, 2.0);
  const auto pole = test::meshOf(sides);
  const Transform I = Transform::Identity();
  const Transform shifted = pose(Eigen::Matrix3d::Identity(), {0.15, 0, 0});
  // The triangles' delta-prisms reach up to 1.0824 delta from an edge (region_distance_bound.h),
  // and the bisection stops within 2^-10 of the bound: the bound is within those of the distance.
  const double keep = (1.0 - 1.0 / 1024.0) / 1.0824;
  const double centred = *distanceLowerBound(ring.get(), I, pole.get(), I, 10.0);
  EXPECT_GT(centred, 0.4 * keep);
  EXPECT_LE(centred, 0.4 + 1e-9);
  // Shifted: the bore wall is 0.5 from (0.15, 0, 0); the pole's farthest points from there are its
  // vertices at 120 and 240 degrees.
  double farthest = 0.0;
  for (const Eigen::Vector3d& v : rim) farthest = std::max(farthest, (v - shifted.translation()).norm());
  const double off = *distanceLowerBound(ring.get(), shifted, pole.get(), I, 10.0);
  EXPECT_GT(off, (0.5 - farthest) * keep);
  EXPECT_LE(off, 0.5 - farthest + 1e-9);
  // The oracle of the random test sees a bound that is too large: the pole's 0.41-neighbourhood
  // (true distance 0.4) overlaps the centred ring.
  bool seen = false;
  for (const std::array<Eigen::Vector3d, 3>& t : sides)
    seen = seen || overlaps(*ring, I, triangleMinkowski(t, 0.41),
                            Box3{Eigen::Vector3d(-0.6, -0.6, -2.5), Eigen::Vector3d(0.6, 0.6, 2.5)});
  EXPECT_TRUE(seen);
  // Near contact the bound stays relative to the distance (the bisection starts by halving).
  const double gap = 1e-4;
  const Transform near = pose(Eigen::Matrix3d::Identity(), {std::sqrt(0.25 - 0.0075) - 0.05 - gap, 0, 0});
  double far_edge = 0.0;
  for (const Eigen::Vector3d& v : rim) far_edge = std::max(far_edge, (v - near.translation()).norm());
  const double close = *distanceLowerBound(ring.get(), near, pole.get(), I, 10.0);
  EXPECT_GT(close, (0.5 - far_edge) * keep);
  EXPECT_LE(close, 0.5 - far_edge + 1e-12);
  // The ring moved onto the pole: contact.
  EXPECT_EQ(*distanceLowerBound(ring.get(), pose(Eigen::Matrix3d::Identity(), {0.45, 0, 0}), pole.get(), I, 10.0), 0.0);
}

// grownRegion contains the delta-neighbourhood: points of a ring, a wedge-like difference and a
// union moved by less than delta are never certified outside the grown region.
TEST(GrownRegion, ContainsEveryPointWithinDeltaOfTheRegion) {
  const auto ring = makeRing();
  auto slab = std::make_shared<Quadric<double>>(Quadric<double>::halfspace(Eigen::Vector3d(0.3, 1.0, 0.2), 0.1));
  auto rod = std::make_shared<EllipticCylinder<double>>(0.3, 0.2, 1.5);
  auto cut = std::make_shared<QuadricCSG<double>>(Op::Difference, std::vector<QuadricCSG<double>::Child>{
                                                                       {ring, Transform::Identity()}, {slab, Transform::Identity()}});
  std::mt19937_64 rng(41);
  const QuadricCSG<double> both(Op::Union, {{cut, Transform::Identity()}, {rod, pose(test::randomRotation(rng), {0.8, 0, 0})}});
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const QuadricShape<double>* shape : {static_cast<const QuadricShape<double>*>(ring.get()),
                                            static_cast<const QuadricShape<double>*>(cut.get()),
                                            static_cast<const QuadricShape<double>*>(&both)}) {
    const Box3 box = shape->localBox();
    int inside = 0;
    for (const double delta : {0.01, 0.1, 0.3, 0.7}) {
      const std::optional<QuadricRegion> g = grownRegion(shape->region(), delta);
      ASSERT_TRUE(g.has_value());
      for (int i = 0; i < 3000; ++i) {
        const Eigen::Vector3d y = box.center() + box.halfWidth().cwiseProduct(Eigen::Vector3d(u(rng), u(rng), u(rng)));
        if (shape->region().classifyPoint(y) < 0) continue;  // keep points of the solid (and its boundary band)
        ++inside;
        Eigen::Vector3d step(u(rng), u(rng), u(rng));
        if (step.norm() > 1.0) step /= step.norm();
        EXPECT_GE(g->classifyPoint(y + delta * step), 0) << delta << " " << y.transpose();
      }
    }
    EXPECT_GT(inside, 1000);
  }
  // Atoms that cannot be grown: a hyperboloid.
  Eigen::Matrix4d H = quadric::ellipsoid({1, 1, 1});
  H(2, 2) = -1.0;  // x^2 + y^2 - z^2 <= 1
  EXPECT_FALSE(grownRegion(QuadricRegion::atom(H), 0.1));
}

// Two interlocked rings (each through the other's bore, not touching): their covers (outer
// ellipsoids) overlap, and the grown-atom bound certifies the clearance; it stays below the
// distance between sampled points of the two solids; moved into contact it is 0.
TEST(DistanceLowerBound, InterlockedRingsAreCertifiedClear) {
  // Thin links of a chain: outer ellipsoid (1, 1, 0.15), bore 0.6; the second one turned a
  // quarter about x (its bore along y) and centred at (0.8, 0, 0).
  auto outer = std::make_shared<Quadric<double>>(Quadric<double>::ellipsoid(1.0, 1.0, 0.15));
  auto hole = std::make_shared<Quadric<double>>(Quadric<double>::ellipticCylinder(0.6, 0.6));
  const auto ring = std::make_shared<QuadricCSG<double>>(
      Op::Difference, std::vector<QuadricCSG<double>::Child>{{outer, Transform::Identity()}, {hole, Transform::Identity()}});
  const Transform I = Transform::Identity();
  const Transform linked = pose(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix(), {0.8, 0, 0});
  fcl::CollisionRequest<double> creq;
  fcl::CollisionResult<double> cres;
  ASSERT_EQ(fcl_quadric::collide(ring.get(), I, ring.get(), linked, creq, cres), 0u);
  const double d = *distanceLowerBound(ring.get(), I, ring.get(), linked, 10.0);
  EXPECT_GT(d, 0.0);
  EXPECT_EQ(*distanceLowerBound(ring.get(), linked, ring.get(), I, 10.0) > 0.0, true);
  // Sampled points of both solids: the distance between any two is at least the true distance.
  std::mt19937_64 rng(43);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::Vector3d> pa, pb;
  while (pa.size() < 3000 || pb.size() < 3000) {
    const Eigen::Vector3d x(u(rng), u(rng), 0.15 * u(rng));
    if (ring->region().classifyPoint(x) <= 0) continue;
    if (pa.size() < 3000) pa.push_back(x);
    else pb.push_back(linked * x);
  }
  double sampled = std::numeric_limits<double>::infinity();
  for (const auto& x : pa)
    for (const auto& y : pb) sampled = std::min(sampled, (x - y).norm());
  EXPECT_LE(d, sampled);
  const Transform touching = pose(linked.linear(), {0.2, 0, 0});  // B's outer tip (x = -0.8) in A
  ASSERT_GT(fcl_quadric::collide(ring.get(), I, ring.get(), touching, creq, cres), 0u);
  EXPECT_EQ(*distanceLowerBound(ring.get(), I, ring.get(), touching, 10.0), 0.0);
}

TEST(DistanceLowerBound, FclBoxAndCylinderAgainstMeshAndOcTreeAreCertifiedGjkBounds) {
  // A wall of two triangles at x = 1 and a box / cylinder facing it: the distance is analytic.
  auto wall = std::make_shared<fcl::BVHModel<fcl::OBBRSS<double>>>();
  wall->beginModel();
  wall->addTriangle(Eigen::Vector3d(1, -3, -3), Eigen::Vector3d(1, 3, -3), Eigen::Vector3d(1, 3, 3));
  wall->addTriangle(Eigen::Vector3d(1, -3, -3), Eigen::Vector3d(1, 3, 3), Eigen::Vector3d(1, -3, 3));
  wall->endModel();
  const fcl::Box<double> box(0.4, 1.0, 1.0);
  const fcl::Cylinder<double> cyl(0.3, 1.0);
  const Transform I = Transform::Identity();
  const double db = *distanceLowerBound(&box, I, wall.get(), I, 10.0);
  EXPECT_LE(db, 0.8);
  EXPECT_GT(db, 0.8 - 1e-9);
  EXPECT_EQ(*distanceLowerBound(wall.get(), I, &box, I, 10.0), db);
  const double dc = *distanceLowerBound(&cyl, I, wall.get(), I, 10.0);
  EXPECT_LE(dc, 0.7);
  EXPECT_GT(dc, 0.7 - 1e-9);
  EXPECT_EQ(*distanceLowerBound(&cyl, I, wall.get(), I, 0.25), 0.25);  // capped
  EXPECT_EQ(*distanceLowerBound(&cyl, pose(Eigen::Matrix3d::Identity(), {0.8, 0, 0}), wall.get(), I, 10.0), 0.0);
  // An octree cell at x in [1, 1.25): the box's face at 0.2.
  auto octo = std::make_shared<octomap::OcTree>(0.25);
  octo->updateNode(octomap::point3d(1.1f, 0.1f, 0.1f), true);
  octo->updateInnerOccupancy();
  const fcl::OcTree<double> tree(octo);
  const double dt = *distanceLowerBound(&box, I, &tree, I, 10.0);
  EXPECT_LE(dt, 0.8);
  EXPECT_GT(dt, 0.8 - 1e-9);
  // No bound where the library's distance is exact or FCL's own pair is not a primitive one.
  const fcl::Sphere<double> s(0.3);
  EXPECT_FALSE(distanceLowerBound(&box, I, &s, I, 1.0).has_value());
  EXPECT_FALSE(distanceLowerBound(wall.get(), I, wall.get(), I, 1.0).has_value());
  // Bad input.
  Transform skew = I;
  skew.linear()(0, 1) = 0.5;
  test::expectInvalid([&] { distanceLowerBound(&box, skew, wall.get(), I, 1.0); }, "rotation of tf1");
  test::expectInvalid([&] { distanceLowerBound(&box, I, wall.get(), I, std::nan("")); }, "cap must be >= 0");
}

}  // namespace
}  // namespace fcl_quadric
