// fcl_quadric::distance on the quadric shapes (convex ones, by GJK / EPA on support mappings):
// against the library's closed-form ellipsoid-cylinder distance, analytic placements of meshes,
// octree leaves and half-spaces, the sign of fcl_quadric::collide on the same poses, and a
// broad-phase manager against the pairwise minimum.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <array>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/broadphase/default_broadphase_callbacks.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/octree/octree.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/halfspace.h>
#include <fcl/geometry/shape/plane.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/bv/AABB.h>
#include <fcl/math/bv/OBB.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/math/bv/RSS.h>
#include <fcl/math/bv/kDOP.h>
#include <fcl/math/bv/kIOS.h>
#include <octomap/OcTree.h>

#include "fcl_quadric/algebra/quadric_matrix.h"
#include "fcl_quadric/fcl/collision.h"
#include "fcl_quadric/fcl/distance.h"
#include "fcl_quadric/fcl/quadric_shapes.h"
#include "fcl_quadric/geometry/convex_distance.h"
#include "fcl_quadric/geometry/convex_support.h"
#include "fcl_quadric/geometry/ellipsoid_cylinder.h"
#include "support/fcl_fixtures.h"
#include "support/expect_invalid.h"
#include "support/random_ellipsoids.h"

namespace fcl_quadric {
namespace {

using Transform = fcl::Transform3<double>;

using test::pose;

double dist(const fcl::CollisionGeometry<double>& a, const Transform& ta, const fcl::CollisionGeometry<double>& b,
            const Transform& tb, bool signed_distance, fcl::DistanceResult<double>* out = nullptr) {
  fcl::DistanceRequest<double> req(true);
  req.enable_signed_distance = signed_distance;
  fcl::DistanceResult<double> res;
  const double d = fcl_quadric::distance(&a, ta, &b, tb, req, res);
  EXPECT_EQ(d, res.min_distance);
  if (out) *out = res;
  return d;
}

bool collides(const fcl::CollisionGeometry<double>& a, const Transform& ta, const fcl::CollisionGeometry<double>& b,
              const Transform& tb) {
  fcl::CollisionRequest<double> req;
  fcl::CollisionResult<double> res;
  return fcl_quadric::collide(&a, ta, &b, tb, req, res) > 0;
}

/// Distance from x to the triangle a b c: to its plane where the projection lies inside (signs of
/// the three edge cross products), else to the nearest edge segment.
double pointTriangleDistance(const Eigen::Vector3d& x, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                             const Eigen::Vector3d& c) {
  const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
  const Eigen::Vector3d q = x - n.dot(x - a) * n;
  const bool inside = (b - a).cross(q - a).dot(n) >= 0.0 && (c - b).cross(q - b).dot(n) >= 0.0 &&
                      (a - c).cross(q - c).dot(n) >= 0.0;
  if (inside) return (x - q).norm();
  auto segment = [&](const Eigen::Vector3d& p0, const Eigen::Vector3d& p1) {
    const double t = std::clamp((x - p0).dot(p1 - p0) / (p1 - p0).squaredNorm(), 0.0, 1.0);
    return (x - (p0 + t * (p1 - p0))).norm();
  };
  return std::min({segment(a, b), segment(b, c), segment(c, a)});
}

/// The checks of the constructed-gap tests below: a shape (pose ts) and a partner (pose tp) at the
/// constructed signed gap g, in both argument orders: collide reports a contact exactly when
/// g < 0; for g > 0 the distance is g within `tol` and the witnesses lie at that distance within
/// `witness_tol`. Returns the number of distances checked (two for g > 0, else none).
int expectConstructedGap(const fcl::CollisionGeometry<double>& shape, const Transform& ts,
                         const fcl::CollisionGeometry<double>& partner, const Transform& tp, double g, double tol,
                         double witness_tol, const std::string& where) {
  int checked = 0;
  for (bool shape_first : {true, false}) {
    const std::string at = where + " gap " + std::to_string(g) + (shape_first ? ", shape first" : ", partner first");
    const bool hit = shape_first ? collides(shape, ts, partner, tp) : collides(partner, tp, shape, ts);
    EXPECT_EQ(hit, g < 0.0) << at;
    if (g < 0.0) continue;
    fcl::DistanceResult<double> res;
    const double d = shape_first ? dist(shape, ts, partner, tp, false, &res) : dist(partner, tp, shape, ts, false, &res);
    EXPECT_NEAR(d, g, tol) << at;
    EXPECT_NEAR((res.nearest_points[1] - res.nearest_points[0]).norm(), d, witness_tol) << at;
    ++checked;
  }
  return checked;
}

/// A mesh (pose tm) of the vertices w given in a shape's frame (pose ts): the constructed-gap
/// tests build their partners where the shape's geometry is known, then pose them.
std::shared_ptr<fcl::BVHModel<fcl::OBBRSS<double>>> meshInFrame(const std::vector<Eigen::Vector3d>& w,
                                                                const std::vector<fcl::Triangle>& tris,
                                                                const Transform& ts, const Transform& tm) {
  std::vector<Eigen::Vector3d> in_mesh_frame;
  for (const Eigen::Vector3d& x : w) in_mesh_frame.push_back(tm.inverse() * (ts * x));
  auto mesh = std::make_shared<fcl::BVHModel<fcl::OBBRSS<double>>>();
  mesh->beginModel();
  mesh->addSubModel(in_mesh_frame, tris);
  mesh->endModel();
  return mesh;
}

/// A unit normal n at the apex of the nappe x^2/a^2 + y^2/b^2 <= z^2, z >= 0, at azimuth th, in
/// the nappe's polar cone (the nappe lies in x.n <= 0: tan(al) <= 1 / |(a cos th, b sin th)|) with
/// -n inside the nappe (tan(al) <= 1 / |(cos th / a, sin th / b)|), so that -g n overlaps it;
/// u in [0, 1) picks the angle al from the axis, up to 0.9 of the tighter limit.
Eigen::Vector3d coneApexNormal(double a, double b, double th, double u) {
  const double c = std::cos(th), si = std::sin(th);
  const double limit = std::min(1.0 / std::hypot(a * c, b * si), 1.0 / std::hypot(c / a, si / b));
  const double al = std::atan(0.9 * limit) * u;
  return Eigen::Vector3d(std::sin(al) * c, std::sin(al) * si, -std::cos(al));
}

/// An elliptic cylinder near a sliver triangle (edges 0.54 / 0.34 / 0.20, height 3.6e-7) of a
/// rotated and translated mesh, at gaps of 3.8e-7, 3.8e-9 and 3.8e-11 (docs/reliability.md finding
/// 34 (3)). The witness refinement returned a mesh point 1.14 times the gap off the triangle and a
/// distance ~4,000 times too small (8.9e-11 for 3.8e-7). Checked: the mesh witness lies on the
/// triangle, the distance is the witnesses' distance, and it equals the distance to the same
/// triangle given in world coordinates on an unposed mesh (a path the audit's long-double oracle
/// confirmed) to 1e-14 of the scale, in both argument orders.
TEST(QuadricShapeDistance, PosedSliverTriangleGivesItsOwnWitnessAndTheUnposedDistance) {
  Eigen::Matrix3d R, TR;
  R << 0.4133184690498094, -0.038260885743602494, 0.90978236285632441, -0.21509878167035679, 0.96673907030122219,
      0.13837660234684493, -0.88481656701615274, -0.25288668326988606, 0.39134124259845959;
  TR << 0.096273714534469867, 0.41345750754173016, -0.90541938423424284, -0.53493052957328846, -0.74562066555178586,
      -0.39736526223684088, -0.83939305478433446, 0.52259230051684868, 0.14938737235901545;
  Transform T = Transform::Identity();
  T.linear() = TR;
  T.translation() = Eigen::Vector3d(1.3787408736671551, -1.0069062898683185, 0.19619295288773975);
  const Eigen::Vector3d v[3] = {Eigen::Vector3d(0.49856544231859268, 0.53449225458017557, -1.1092860562720752),
                                Eigen::Vector3d(0.46271257712077751, 0.42033316355663286, -0.58429247941899065),
                                Eigen::Vector3d(0.48529998219540105, 0.49225319090146474, -0.91503813283643398)};
  auto posed = std::make_shared<fcl::BVHModel<fcl::OBBRSS<double>>>();
  posed->beginModel();
  posed->addTriangle(v[0], v[1], v[2]);
  posed->endModel();
  Eigen::Vector3d w[3];
  for (int k = 0; k < 3; ++k) w[k] = T * v[k];
  auto world = std::make_shared<fcl::BVHModel<fcl::OBBRSS<double>>>();
  world->beginModel();
  world->addTriangle(w[0], w[1], w[2]);
  world->endModel();
  const EllipticCylinder<double> cylinder(0.45572243593694611, 0.55126050757025358, 0.63946530401256163);
  const double centres[3][3] = {{3.0658708825632588, -1.6809445666841452, -0.094624471000806967},
                                {3.0658704261359446, -1.6809441314779305, -0.09462452621047146},
                                {3.0658704215716718, -1.680944127125868, -0.094624526762573}};
  for (const auto& c : centres) {
    Transform tc = Transform::Identity();
    tc.linear() = R;
    tc.translation() = Eigen::Vector3d(c[0], c[1], c[2]);
    const double scale = 3.0;  // the sizes and positions are O(1)
    const double unposed = dist(*world, Transform::Identity(), cylinder, tc, false);
    ASSERT_GT(unposed, 0.0);
    for (bool mesh_first : {true, false}) {
      fcl::DistanceResult<double> r;
      const double d = mesh_first ? dist(*posed, T, cylinder, tc, false, &r) : dist(cylinder, tc, *posed, T, false, &r);
      EXPECT_NEAR(d, unposed, 1e-14 * scale) << "gap " << unposed << ", mesh first " << mesh_first;
      const Eigen::Vector3d p_mesh = r.nearest_points[mesh_first ? 0 : 1], p_cyl = r.nearest_points[mesh_first ? 1 : 0];
      const Eigen::Vector3d y = T.inverse() * p_mesh;
      EXPECT_LE(pointTriangleDistance(y, v[0], v[1], v[2]), 1e-12 * scale);
      EXPECT_NEAR((p_cyl - p_mesh).norm(), d, 1e-14 * scale);
    }
  }
}

/// An elliptic cylinder against small meshes whose nearest point to it is known by construction
/// (docs/reliability.md finding 34): s on the cylinder's side with outward unit normal n, and a
/// mesh inside the half-space (x - p).n >= 0 through p = s + g n, touching its plane at p only.
/// The cylinder lies in (x - s).n <= 0, so the distance is g (to the construction's rounding,
/// ~1e-16 here). The mesh's nearest feature is, by kind: 0 a vertex shared by three triangles (a
/// pyramid's apex), 1 an edge shared by two (a wedge), 2 a face (a triangle in the tangent plane),
/// 3 the sharp vertex of a sliver (angle 2e-3 to 2e-7). GJK stalls near vertices, and the
/// triangle's half-space region pins a sliver's vertex only to ~u / angle: before session 40 the
/// apex gave distances up to 2 relative too large at a gap of 3e-9 and the sliver up to 4e-6
/// absolute; and below ~1e-9 of the scale the region engine's touching band made both collide and
/// distance report contact (~0.5 s a query for the face). Gaps 3e-5 to 3e-11 of a scale ~3, random
/// poses of both, both argument orders: the distance within the accuracy documented in distance.h,
/// 1e-10 relative plus 1e-14 of the scale, no contact from collide; and moved by -g into the
/// cylinder, collide reports the overlap.
TEST(QuadricShapeDistance, MeshVerticesEdgesFacesAndSliverTipsNearAnEllipticCylinderGiveTheConstructedGap) {
  std::mt19937_64 rng(40);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int checked = 0;
  for (int kind = 0; kind < 4; ++kind) {
    for (int trial = 0; trial < 8; ++trial) {
      const double a = 0.3 + 0.9 * unit(rng), b = 0.3 + 0.9 * unit(rng), lz = 0.5 + 1.5 * unit(rng);
      const EllipticCylinder<double> cylinder(a, b, lz);
      const double th = 2.0 * M_PI * unit(rng), z = (unit(rng) - 0.5) * 0.8 * lz;
      const Eigen::Vector3d s(a * std::cos(th), b * std::sin(th), z);
      const Eigen::Vector3d n = Eigen::Vector3d(std::cos(th) / a, std::sin(th) / b, 0.0).normalized();
      const Eigen::Vector3d t1 = Eigen::Vector3d::UnitZ(), t2 = n.cross(t1);  // the tangent plane's axes
      const double phi = 2.0 * M_PI * unit(rng);
      const Eigen::Vector3d e1 = std::cos(phi) * t1 + std::sin(phi) * t2, e2 = n.cross(e1);
      const Transform tc = pose(test::randomRotation(rng), test::randomUnitVector(rng));
      const Transform tm = pose(test::randomRotation(rng), test::randomUnitVector(rng));
      const double H = 0.3 + 0.5 * unit(rng), r = 0.2 + 0.3 * unit(rng);
      const double beta = 1.4 * unit(rng), eps = std::pow(10.0, -3.0 - 4.0 * unit(rng));
      for (double g : {3e-5, 3e-7, 3e-9, 3e-11, -3e-5, -3e-7, -3e-9, -3e-11}) {
        const Eigen::Vector3d p = s + g * n;  // in the cylinder's frame, as the vertices below
        std::vector<Eigen::Vector3d> w;
        std::vector<fcl::Triangle> tris;
        if (kind == 0) {
          w.push_back(p);
          for (int k = 0; k < 3; ++k) {
            const double f = 2.0 * M_PI * k / 3.0;
            w.push_back(p + H * n + r * (std::cos(f) * e1 + std::sin(f) * e2));
          }
          tris = {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {1, 3, 2}};
        } else if (kind == 1) {  // the edge along t2, so that p is its only nearest point
          const Eigen::Vector3d o = n.cross(t2);
          w = {p - r * t2,          p + r * t2,          p - r * t2 + H * n + r * o,
               p + r * t2 + H * n + r * o, p - r * t2 + H * n - r * o, p + r * t2 + H * n - r * o};
          tris = {{0, 1, 3}, {0, 3, 2}, {0, 4, 5}, {0, 5, 1}, {2, 3, 5}, {2, 5, 4}, {0, 2, 4}, {1, 5, 3}};
        } else if (kind == 2) {
          for (int k = 0; k < 3; ++k) {
            const double f = phi + 2.0 * M_PI * k / 3.0;
            w.push_back(p + r * (std::cos(f) * t1 + std::sin(f) * t2));
          }
          w.push_back(p + H * n);
          tris = {{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {2, 3, 0}};
        } else {
          const Eigen::Vector3d dir = std::cos(beta) * n + std::sin(beta) * e1;
          w = {p, p + H * (dir + eps * e2), p + H * (dir - eps * e2)};
          tris = {{0, 1, 2}};
        }
        const auto mesh = meshInFrame(w, tris, tc, tm);
        const double scale = a + b + lz + H + r + (tc.translation() - tm.translation()).norm();
        checked += expectConstructedGap(cylinder, tc, *mesh, tm, g, 1e-10 * g + 1e-14 * scale, 1e-14 * scale,
                                        "kind " + std::to_string(kind) + " trial " + std::to_string(trial));
      }
    }
  }
  EXPECT_EQ(checked, 4 * 8 * 4 * 2);
}

/// One nappe of a cone (a `Quadric`, whose support mapping is enumerated: a Region support) by its
/// apex against a mesh's vertex (a pyramid's apex) and a face (a triangle in the plane through
/// s + g n), with n in the cone's polar cone and -n inside it, as in the tests around this one:
/// the distance is g. Before session 41 the certificate of docs/algorithms.md section 12 left
/// Region supports to the region engine, whose touching band made these contact at gaps of 3e-9
/// and 3e-11 (on a scratch driver 30 of 120 vertex and 60 of 120 face answers; this test: 72
/// failed checks with the code before the session). Both argument orders: no contact and the
/// distance to 1e-10 relative plus 1e-13 at +g, a contact at -g.
TEST(QuadricShapeDistance, AConesApexNearMeshVerticesAndFacesGivesTheConstructedGap) {
  std::mt19937_64 rng(411);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double a = 0.6, b = 0.9, lz = 1.2;
  const Quadric<double> cone =
      Quadric<double>::ellipticCone(a, b, 1.0, {{Eigen::Vector3d(0, 0, -1), 0.0}, {Eigen::Vector3d(0, 0, 1), lz}});
  int checked = 0;
  for (int kind = 0; kind < 2; ++kind) {
    for (int trial = 0; trial < 4; ++trial) {
      const double th = 2.0 * M_PI * unit(rng);
      const Eigen::Vector3d n = coneApexNormal(a, b, th, unit(rng));
      const Eigen::Vector3d t1 = n.unitOrthogonal(), t2 = n.cross(t1);
      const Transform tc = pose(test::randomRotation(rng), test::randomUnitVector(rng));
      const Transform tm = pose(test::randomRotation(rng), test::randomUnitVector(rng));
      const double H = 0.3 + 0.5 * unit(rng), r = 0.2 + 0.3 * unit(rng), phi = 2.0 * M_PI * unit(rng);
      for (double g : {3e-5, 3e-7, 3e-9, 3e-11, -3e-5, -3e-7, -3e-9, -3e-11}) {
        const Eigen::Vector3d p = g * n;  // the apex is the origin of the cone's frame
        std::vector<Eigen::Vector3d> w;
        std::vector<fcl::Triangle> tris;
        for (int k = 0; k < 3; ++k) {
          const double f = phi + 2.0 * M_PI * k / 3.0;
          w.push_back(p + (kind == 0 ? H : 0.0) * n + r * (std::cos(f) * t1 + std::sin(f) * t2));
        }
        if (kind == 0) {  // a pyramid: apex p, base H above it
          w.insert(w.begin(), p);
          tris = {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {1, 3, 2}};
        } else {  // a tetrahedron whose face lies in the plane, around p
          w.push_back(p + H * n);
          tris = {{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {2, 3, 0}};
        }
        const auto mesh = meshInFrame(w, tris, tc, tm);
        checked += expectConstructedGap(cone, tc, *mesh, tm, g, 1e-10 * g + 1e-13, 3e-14,
                                        "kind " + std::to_string(kind) + " trial " + std::to_string(trial));
      }
    }
  }
  EXPECT_EQ(checked, 2 * 4 * 4 * 2);
}

/// Convex quadric shapes against FCL primitives and another convex quadric shape, at a gap known by
/// construction as in the mesh test above: s on the shape's boundary with outward unit normal n
/// such that the shape lies in (x - s).n <= 0, and the partner posed so that its support point
/// towards -n (computed here in closed form, independently of the library's support mappings) is
/// p = s + g n: the partner lies in (x - p).n >= 0, and the distance is g. Shapes: an elliptic
/// cylinder's side, a clipped ellipsoid, one nappe of a cone by its side and by its apex (n in the
/// cone's polar cone, -n inside it, so that -g n overlaps). Partners: an fcl::Box by a vertex (a
/// random rotation) and by a face (lying in the tangent plane: against the cylinder's side it
/// touches along a ruling), an fcl::Cone (apex or rim), fcl::Capsule, fcl::Ellipsoid and an
/// EllipticCylinder. Before session 41 collide and distance reported contact at gaps of 3e-9 and
/// 3e-11 (the region engine's touching band; on a scratch driver 2,404 of 16,000 answers at
/// positive gaps, among them 1,494 of the 1,600 with the cone's own apex nearest and 388 of the 400
/// box faces in the tangent plane of a ruled surface: docs/reliability.md finding 35), and a cone's
/// apex was not refined (distances up to 3.8e-4 relative too far at a gap of 3e-7); this test
/// failed 324 checks with that code. Both argument orders: no contact and the distance
/// within 1e-10 relative plus 1e-13 absolute (the construction's and the support points' rounding
/// on a scale of ~3) at +g, a contact at -g.
TEST(QuadricShapeDistance, ConvexShapesNearPrimitivesGiveTheConstructedGapAndCollideAgrees) {
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double a = 0.55, b = 0.8, lz = 1.3;
  const EllipticCylinder<double> cylinder(a, b, lz);
  const Quadric<double> clipped = Quadric<double>::ellipsoid(a, b, lz, {{Eigen::Vector3d(0, 0, 1), 0.5 * lz}});
  const Quadric<double> cone =
      Quadric<double>::ellipticCone(a, b, 1.0, {{Eigen::Vector3d(0, 0, -1), 0.0}, {Eigen::Vector3d(0, 0, 1), lz}});
  // The partners, with their local support mappings in closed form.
  const double r1 = 0.35, r2 = 0.25, r3 = 0.45;
  const fcl::Box<double> box(2 * r1, 2 * r2, 2 * r3);
  const fcl::Cone<double> fcone(r1, 2 * r3);
  const fcl::Capsule<double> capsule(r2, 2 * r3);
  const fcl::Ellipsoid<double> ellipsoid(r1, r2, r3);
  const EllipticCylinder<double> ecyl(r2, r1, 2 * r3);
  auto sgn = [](double v) { return v >= 0.0 ? 1.0 : -1.0; };
  auto rim = [](double ra, double rb, const Eigen::Vector3d& d) {  // the ellipse's point with outward normal along d.xy
    const double l = std::hypot(ra * d.x(), rb * d.y());
    return l > 0.0 ? Eigen::Vector2d(ra * ra * d.x() / l, rb * rb * d.y() / l) : Eigen::Vector2d::Zero();
  };
  auto partnerSupport = [&](int kind, const Eigen::Vector3d& d) -> Eigen::Vector3d {
    switch (kind) {
      case 0:
      case 1: return Eigen::Vector3d(sgn(d.x()) * r1, sgn(d.y()) * r2, sgn(d.z()) * r3);
      case 2: {
        const Eigen::Vector3d apex(0, 0, r3);
        const Eigen::Vector2d q = rim(r1, r1, d);
        const Eigen::Vector3d base(q.x(), q.y(), -r3);
        return d.dot(apex) >= d.dot(base) ? apex : base;
      }
      case 3: return Eigen::Vector3d(0, 0, sgn(d.z()) * r3) + r2 * d.normalized();
      case 4: {
        const Eigen::Vector3d q = Eigen::Vector3d(r1 * r1 * d.x(), r2 * r2 * d.y(), r3 * r3 * d.z());
        return q / std::sqrt(d.dot(q));
      }
      default: {
        const Eigen::Vector2d q = rim(r2, r1, d);
        return Eigen::Vector3d(q.x(), q.y(), sgn(d.z()) * r3);
      }
    }
  };
  const fcl::CollisionGeometry<double>* partners[6] = {&box, &box, &fcone, &capsule, &ellipsoid, &ecyl};
  int checked = 0;
  for (int shape_kind = 0; shape_kind < 4; ++shape_kind) {
    const fcl::CollisionGeometry<double>& shape =
        shape_kind == 0 ? static_cast<const fcl::CollisionGeometry<double>&>(cylinder)
                        : shape_kind == 1 ? static_cast<const fcl::CollisionGeometry<double>&>(clipped) : cone;
    for (int kind = 0; kind < 6; ++kind) {
      for (int trial = 0; trial < 3; ++trial) {
        const double th = 2.0 * M_PI * unit(rng);
        Eigen::Vector3d s, n;
        if (shape_kind == 0) {
          s = Eigen::Vector3d(a * std::cos(th), b * std::sin(th), (unit(rng) - 0.5) * 0.8 * lz);
          n = Eigen::Vector3d(std::cos(th) / a, std::sin(th) / b, 0.0);
        } else if (shape_kind == 1) {  // below the clip z = lz / 2
          const double zz = -0.9 + 1.2 * unit(rng), rr = std::sqrt(1.0 - zz * zz);
          s = Eigen::Vector3d(a * rr * std::cos(th), b * rr * std::sin(th), lz * zz);
          n = Eigen::Vector3d(rr * std::cos(th) / a, rr * std::sin(th) / b, zz / lz);
        } else if (shape_kind == 2) {  // the cone's side, x^2/a^2 + y^2/b^2 <= z^2
          const double z = lz * (0.1 + 0.8 * unit(rng));
          s = Eigen::Vector3d(a * z * std::cos(th), b * z * std::sin(th), z);
          n = Eigen::Vector3d(2.0 * s.x() / (a * a), 2.0 * s.y() / (b * b), -2.0 * z);
        } else {  // its apex
          s = Eigen::Vector3d::Zero();
          n = coneApexNormal(a, b, th, unit(rng));
        }
        n.normalize();
        Eigen::Matrix3d Rp = test::randomRotation(rng);
        if (kind == 1) {  // the box's -z face in the tangent plane: Rp e_z = n
          const Eigen::Vector3d x0 = (std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY());
          const Eigen::Vector3d xx = (x0 - x0.dot(n) * n).normalized();
          Rp.col(0) = xx;
          Rp.col(1) = n.cross(xx);
          Rp.col(2) = n;
        }
        const Transform tc = pose(test::randomRotation(rng), test::randomUnitVector(rng));
        const Eigen::Vector3d local = kind == 1 ? Eigen::Vector3d(0, 0, -r3) : partnerSupport(kind, Rp.transpose() * -n);
        for (double g : {3e-5, 3e-7, 3e-9, 3e-11, -3e-5, -3e-7, -3e-9, -3e-11}) {
          const Eigen::Vector3d p = s + g * n;  // the shape's frame
          const Transform tp = pose(tc.linear() * Rp, tc * (p - Rp * local));
          const double scale = 3.0;
          checked += expectConstructedGap(shape, tc, *partners[kind], tp, g, 1e-10 * g + 1e-13, 1e-14 * scale,
                                          "shape " + std::to_string(shape_kind) + " partner " + std::to_string(kind) +
                                              " trial " + std::to_string(trial));
        }
      }
    }
  }
  EXPECT_EQ(checked, 4 * 6 * 3 * 4 * 2);
}

TEST(QuadricShapeDistance, CircularCylinderAgainstAnEllipsoidMatchesTheClosedFormKernelInBothOrders) {
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> u(0.3, 1.2);
  int separated = 0, overlapping = 0;
  for (int i = 0; i < 300; ++i) {
    const double r = u(rng), L = 2 * u(rng);
    const EllipticCylinder<double> cyl(r, r, L);
    const Ellipsoid e = test::anchorEllipsoid(rng);
    const fcl::Ellipsoid<double> fe(e.radii());
    const Eigen::Matrix3d R = test::randomRotation(rng);
    const Eigen::Vector3d p = e.center() + (e.maxRadius() + 2.0 * u(rng) - 1.0) * test::randomUnitVector(rng);
    const SignedDistanceResult ref = signedDistanceEllipsoidCylinder(e, r, L, R, p);
    if (ref.status == Separation::Touching) continue;
    const Transform tc = pose(R, p), te = pose(e.rotation(), e.center());
    for (bool order : {false, true}) {
      fcl::DistanceResult<double> res;
      const double d = order ? dist(fe, te, cyl, tc, true, &res) : dist(cyl, tc, fe, te, true, &res);
      EXPECT_NEAR(d, ref.distance, 1e-7 * (1 + std::abs(ref.distance))) << i;
      // Nearest points in FCL's argument order: p[0] on o1.
      const Eigen::Vector3d on_e = order ? res.nearest_points[0] : res.nearest_points[1];
      if (ref.status == Separation::Separated) {
        EXPECT_NEAR(e.implicit(on_e), 0.0, 1e-7) << i;
        EXPECT_NEAR((res.nearest_points[0] - res.nearest_points[1]).norm(), d, 1e-9) << i;
      }
      const double unsigned_d = order ? dist(fe, te, cyl, tc, false) : dist(cyl, tc, fe, te, false);
      EXPECT_EQ(unsigned_d, ref.status == Separation::Overlapping ? -1.0 : d);
    }
    (ref.status == Separation::Separated ? separated : overlapping)++;
  }
  EXPECT_GT(separated, 60);
  EXPECT_GT(overlapping, 60);
}

TEST(QuadricShapeDistance, SignAgreesWithCollideOnClippedQuadricsIncludingNearContact) {
  // A paraboloid cup and an elliptic cylinder, random poses; half of them pushed to within 1e-9 of
  // contact along the reported normal.
  std::mt19937_64 rng(22);
  const Quadric<double> cup = Quadric<double>::ellipticParaboloid(0.5, 0.7, {{Eigen::Vector3d(0, 0, 1), 1.0}});
  const EllipticCylinder<double> rod(0.3, 0.15, 1.2);
  std::uniform_real_distribution<double> c(-1.2, 1.2);
  int disagreements = 0, near = 0;
  for (int i = 0; i < 200; ++i) {
    Transform ta = pose(test::randomRotation(rng), Eigen::Vector3d(c(rng), c(rng), c(rng)));
    const Transform tb = pose(test::randomRotation(rng), Eigen::Vector3d(c(rng), c(rng), c(rng)));
    fcl::DistanceResult<double> res;
    double d = dist(cup, ta, rod, tb, true, &res);
    if (i % 2 == 1 && d > 0) {  // move the cup to 1e-9 short of touching
      const Eigen::Vector3d n = (res.nearest_points[1] - res.nearest_points[0]).normalized();
      ta.translation() += (d - 1e-9) * n;
      d = dist(cup, ta, rod, tb, true);
      ++near;
    }
    disagreements += (d <= 0.0) != collides(cup, ta, rod, tb);
  }
  EXPECT_EQ(disagreements, 0);
  EXPECT_GT(near, 40);
}

TEST(QuadricShapeDistance, MeshOctreeAndHalfspacePartnersAtAnalyticDistances) {
  // An elliptic cylinder (semi-axes 0.5, 0.3, length 2) on the origin.
  const EllipticCylinder<double> cyl(0.5, 0.3, 2.0);
  const Transform I = Transform::Identity();
  // A box mesh (12 triangles) of half side 0.25 centred at x = 2: distance 2 - 0.25 - 0.5.
  fcl::BVHModel<fcl::OBBRSS<double>> mesh;
  mesh.beginModel();
  const fcl::Box<double> box(0.5, 0.5, 0.5);
  std::vector<Eigen::Vector3d> v;
  for (int k = 0; k < 8; ++k) v.emplace_back(k & 1 ? 0.25 : -0.25, k & 2 ? 0.25 : -0.25, k & 4 ? 0.25 : -0.25);
  const int faces[12][3] = {{0, 1, 3}, {0, 3, 2}, {4, 6, 7}, {4, 7, 5}, {0, 4, 5}, {0, 5, 1},
                            {2, 3, 7}, {2, 7, 6}, {0, 2, 6}, {0, 6, 4}, {1, 5, 7}, {1, 7, 3}};
  for (const auto& f : faces) mesh.addTriangle(v[f[0]], v[f[1]], v[f[2]]);
  mesh.endModel();
  for (bool order : {false, true}) {
    fcl::DistanceResult<double> res;
    const Transform tm = pose(Eigen::Matrix3d::Identity(), {2, 0, 0});
    const double d = order ? dist(mesh, tm, cyl, I, false, &res) : dist(cyl, I, mesh, tm, false, &res);
    EXPECT_NEAR(d, 1.25, 1e-9);
    const int tri = order ? res.b1 : res.b2;
    ASSERT_GE(tri, 0);
    ASSERT_LT(tri, 12);
    // The reported triangle reaches the facing side x = 1.75, where its nearest point lies.
    double x_min = 1e9;
    for (int k = 0; k < 3; ++k) x_min = std::min(x_min, v[faces[tri][k]].x() + 2.0);
    EXPECT_NEAR(x_min, 1.75, 1e-12);
    EXPECT_NEAR((order ? res.nearest_points[0] : res.nearest_points[1]).x(), 1.75, 1e-9);
    // Overlapping mesh: -1 (FCL's value) or minus the depth with signed distance.
    const Transform inside = pose(Eigen::Matrix3d::Identity(), {0.6, 0, 0});  // box from 0.35 to 0.85
    EXPECT_EQ(order ? dist(mesh, inside, cyl, I, false) : dist(cyl, I, mesh, inside, false), -1.0);
    EXPECT_NEAR(order ? dist(mesh, inside, cyl, I, true) : dist(cyl, I, mesh, inside, true), -0.15, 1e-7);
  }
  // One octree leaf beside the cylinder's curved side along y (semi-axis 0.3).
  auto tree = std::make_shared<octomap::OcTree>(0.1);
  tree->updateNode(octomap::point3d(0.02f, 1.02f, 0.02f), true);
  const fcl::OcTree<double> fcl_tree(tree);
  const auto leaves = fcl_tree.toBoxes();
  ASSERT_EQ(leaves.size(), 1u);
  const double leaf_lo_y = leaves[0][1] - 0.5 * leaves[0][3];
  const double x_lo = leaves[0][0] - 0.5 * leaves[0][3], x_hi = leaves[0][0] + 0.5 * leaves[0][3];
  ASSERT_LE(x_lo, 0.0);
  ASSERT_GE(x_hi, 0.0);  // the leaf spans x = 0, where the ellipse reaches y = 0.3
  EXPECT_NEAR(dist(fcl_tree, I, cyl, I, false), leaf_lo_y - 0.3, 1e-9);
  // A half-space z <= -1.5 below the cylinder tilted by theta about x: lowest point at
  // -(b |sin| + h |cos|).
  const fcl::Halfspace<double> floor(Eigen::Vector3d(0, 0, 1), -1.5);
  for (double theta : {0.0, 0.4, 1.2, -2.0}) {
    const Transform t = pose(Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitX()).toRotationMatrix(), Eigen::Vector3d::Zero());
    const double lowest = -(0.3 * std::abs(std::sin(theta)) + 1.0 * std::abs(std::cos(theta)));
    EXPECT_NEAR(dist(cyl, t, floor, I, true), lowest + 1.5, 1e-12) << theta;
    EXPECT_NEAR(dist(floor, I, cyl, t, true), lowest + 1.5, 1e-12) << theta;
    // Within 1e-9 of contact the sign is collide's.
    for (double gap : {1e-9, 1e-10, -1e-10, -1e-9}) {
      const Transform near = pose(t.linear(), Eigen::Vector3d(0, 0, -1.5 - lowest + gap));
      EXPECT_EQ(dist(cyl, near, floor, I, true) <= 0.0, collides(cyl, near, floor, I)) << theta << " " << gap;
    }
  }
}

// The BVH / octree traversals (culling by node boxes, best-first pruning) against the same
// queries answered piece by piece without them: each triangle as its own one-triangle mesh, each
// occupied leaf as an fcl::Box at its centre.
/// The triangles as a BVHModel of the BV type.
template <typename BV>
std::shared_ptr<fcl::BVHModel<BV>> soupOf(const std::vector<std::array<Eigen::Vector3d, 3>>& tris) {
  auto m = std::make_shared<fcl::BVHModel<BV>>();
  m->beginModel();
  for (const auto& t : tris) m->addTriangle(t[0], t[1], t[2]);
  m->endModel();
  return m;
}

// The mesh traversals (node tests, GJK screening of each triangle, pruning by the best distance)
// against the same queries on every triangle alone, for each of FCL's eight BV types; the octree
// traversal against every leaf as a box.
TEST(QuadricShapeDistance, MeshAndOcTreeTraversalsMatchPieceByPieceQueries) {
  std::mt19937_64 rng(24);
  std::uniform_real_distribution<double> u(-2.0, 2.0), small(-0.3, 0.3);
  std::vector<std::array<Eigen::Vector3d, 3>> tris;
  for (int i = 0; i < 400; ++i) {
    const Eigen::Vector3d c(u(rng), u(rng), u(rng));
    tris.push_back({c + Eigen::Vector3d(small(rng), small(rng), small(rng)),
                    c + Eigen::Vector3d(small(rng), small(rng), small(rng)),
                    c + Eigen::Vector3d(small(rng), small(rng), small(rng))});
  }
  const std::vector<std::shared_ptr<const fcl::CollisionGeometry<double>>> soups{
      soupOf<fcl::OBBRSS<double>>(tris),     soupOf<fcl::OBB<double>>(tris),
      soupOf<fcl::RSS<double>>(tris),        soupOf<fcl::kIOS<double>>(tris),
      soupOf<fcl::AABB<double>>(tris),       soupOf<fcl::KDOP<double, 16>>(tris),
      soupOf<fcl::KDOP<double, 18>>(tris),   soupOf<fcl::KDOP<double, 24>>(tris)};
  auto octo = std::make_shared<octomap::OcTree>(0.25);
  for (int i = 0; i < 150; ++i)
    octo->updateNode(octomap::point3d(float(u(rng)), float(u(rng)), float(u(rng))), true);
  const fcl::OcTree<double> tree(octo);
  const auto leaves = tree.toBoxes();
  const EllipticCylinder<double> cyl(0.35, 0.2, 0.8);
  const Quadric<double> cup = Quadric<double>::ellipticParaboloid(0.4, 0.3, {{Eigen::Vector3d(0, 0, 1), 0.5}});
  int collisions = 0, near_contacts = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const fcl::CollisionGeometry<double>& shape = trial % 2 ? static_cast<const fcl::CollisionGeometry<double>&>(cyl) : cup;
    const Eigen::Matrix3d Rs = test::randomRotation(rng);
    const double x = u(rng), y = u(rng), z = u(rng);
    const Transform ts = pose(Rs, Eigen::Vector3d(x, y, z));
    const Eigen::Matrix3d Rm = test::randomRotation(rng);
    const double mx = small(rng), my = small(rng), mz = small(rng);
    const Transform tm = pose(Rm, Eigen::Vector3d(mx, my, mz));
    // Mesh. The oracle: GJK / EPA of the shape's support mapping and each world triangle, with no
    // traversal (a one-triangle BVHModel would go through the node test under test). A trial with
    // a triangle within 1e-7 of contact is left out of the flag comparison (the front door's
    // engine decides there).
    const ConvexSupport support = trial % 2 ? ConvexSupport::ellipticCylinder(0.35, 0.2, 0.4)
                                            : *ConvexSupport::fromRegion(cup.region(), cup.localBox());
    bool any = false, near_contact = false;
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto& t : tris) {
      const SignedDistanceResult d = convexSignedDistance(support, Rs, ts.translation(),
                                                          ConvexSupport::points({tm * t[0], tm * t[1], tm * t[2]}),
                                                          Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
      any = any || d.status != Separation::Separated;
      near_contact = near_contact || std::abs(d.distance) < 1e-7;
      nearest = std::min(nearest, d.distance);
    }
    near_contacts += near_contact;
    for (std::size_t k = 0; k < soups.size(); ++k) {
      const fcl::CollisionGeometry<double>& soup = *soups[k];
      if (!near_contact) {
        EXPECT_EQ(collides(shape, ts, soup, tm), any) << trial << " BV type " << k;
        EXPECT_EQ(collides(soup, tm, shape, ts), any) << trial << " BV type " << k;
      }
      EXPECT_NEAR(dist(shape, ts, soup, tm, true), nearest, 1e-9) << trial << " BV type " << k;
    }
    collisions += any;
    // Octree.
    any = false;
    nearest = std::numeric_limits<double>::infinity();
    for (const auto& b : leaves) {
      const fcl::Box<double> box(b[3], b[3], b[3]);
      const Transform tb = tm * pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(b[0], b[1], b[2]));
      any = any || collides(shape, ts, box, tb);
      nearest = std::min(nearest, dist(shape, ts, box, tb, true));
    }
    EXPECT_EQ(collides(shape, ts, tree, tm), any) << trial;
    EXPECT_NEAR(dist(tree, tm, shape, ts, true), nearest, 1e-12) << trial;
    collisions += any;
  }
  EXPECT_GT(collisions, 10);
  EXPECT_LE(near_contacts, 2);
}

TEST(QuadricShapeDistance, BroadPhaseDistanceIsThePairwiseMinimum) {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> c(-4, 4);
  std::vector<std::shared_ptr<fcl::CollisionGeometry<double>>> shapes = {
      std::make_shared<EllipticCylinder<double>>(0.4, 0.2, 1.0),
      std::make_shared<Quadric<double>>(Quadric<double>::ellipsoid(0.5, 0.3, 0.2, {{Eigen::Vector3d(1, 0, 0), 0.2}})),
      std::make_shared<fcl::Sphere<double>>(0.3)};
  std::vector<std::unique_ptr<fcl::CollisionObject<double>>> objects;
  for (int i = 0; i < 12; ++i)
    objects.push_back(std::make_unique<fcl::CollisionObject<double>>(
        shapes[i % shapes.size()], pose(test::randomRotation(rng), Eigen::Vector3d(c(rng), c(rng), c(rng)))));
  double expected = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < objects.size(); ++i)
    for (std::size_t j = i + 1; j < objects.size(); ++j) {
      fcl::DistanceRequest<double> req;
      fcl::DistanceResult<double> res;
      expected = std::min(expected, fcl_quadric::distance(objects[i].get(), objects[j].get(), req, res));
    }
  fcl::DynamicAABBTreeCollisionManager<double> manager;
  for (auto& o : objects) manager.registerObject(o.get());
  manager.setup();
  fcl::DefaultDistanceData<double> data;
  manager.distance(&data, fcl_quadric::defaultDistanceFunction<double>);
  EXPECT_NEAR(data.result.min_distance, expected, 1e-12);
}

// A ring (ellipsoid (1, 1, 0.4) minus the cylinder of radius 0.5 about z): the front door's
// distance against closed forms on the outer face, in the bore (where the ring's convex cover,
// the whole ellipsoid, would say 0), under it against a half-space (its lowest points are the
// bore's rim, not the removed pole) and against a thin mesh pole threaded through the bore; both
// argument orders; overlaps follow collide (-1 unsigned, 0 signed: depth not computed); the
// certified lower bound never exceeds the distance.
TEST(QuadricShapeDistance, NonConvexRingMatchesClosedFormsAndAgreesWithCollide) {
  auto ball = std::make_shared<Quadric<double>>(Quadric<double>::ellipsoid(1.0, 1.0, 0.4));
  auto bore = std::make_shared<Quadric<double>>(Quadric<double>::ellipticCylinder(0.5, 0.5));
  const QuadricCSG<double> ring(QuadricRegion::Op::Difference, {{ball, Transform::Identity()}, {bore, Transform::Identity()}});
  const fcl::Sphere<double> s(0.2);
  std::mt19937_64 rng(3);
  for (int k = 0; k < 3; ++k) {
    // The ring posed anywhere; the partner placed in the ring's frame.
    const Eigen::Matrix3d R = k == 0 ? Eigen::Matrix3d::Identity() : test::randomRotation(rng);
    const Transform X = pose(R, Eigen::Vector3d(3.0 * k, -1.0, 2.0 * k));
    auto at = [&](const Eigen::Vector3d& local) { return pose(R, X * local); };
    struct Case {
      Eigen::Vector3d centre;
      double expected;
    };
    for (const Case& c : {Case{{2.0, 0, 0}, 0.8}, Case{{0.1, 0, 0}, 0.2}, Case{{0, 0.15, 0.1}, 0.5 - std::hypot(0.15, 0.0) - 0.2}}) {
      SCOPED_TRACE(testing::Message() << "pose " << k << " sphere at " << c.centre.transpose());
      fcl::DistanceResult<double> r1, r2;
      EXPECT_NEAR(dist(ring, X, s, at(c.centre), false, &r1), c.expected, 1e-9);
      EXPECT_NEAR(dist(s, at(c.centre), ring, X, false, &r2), c.expected, 1e-9);
      EXPECT_NEAR((r1.nearest_points[1] - X * c.centre).norm(), 0.2, 1e-9);  // on the sphere
      EXPECT_NEAR((r1.nearest_points[0] - r1.nearest_points[1]).norm(), r1.min_distance, 1e-9);
      EXPECT_NEAR((r2.nearest_points[0] - r1.nearest_points[1]).norm(), 0.0, 1e-6);
      EXPECT_FALSE(collides(ring, X, s, at(c.centre)));
      EXPECT_LE(*distanceLowerBound(&ring, X, &s, at(c.centre), 10.0), r1.min_distance + 1e-12);
    }
    // Overlapping the ring's material (x = 0.75 is between the bore and the outer face).
    const Transform inside = at({0.75, 0, 0});
    ASSERT_TRUE(collides(ring, X, s, inside));
    EXPECT_EQ(dist(ring, X, s, inside, false), -1.0);
    EXPECT_EQ(dist(ring, X, s, inside, true), 0.0);
  }
  // Under the ring, the half-space z <= -1: the lowest ring points are the bore's rim at
  // z = -0.4 sqrt(1 - 0.25) (the ellipsoid's pole, at -0.4, is removed).
  const fcl::Halfspace<double> floor(Eigen::Vector3d(0, 0, 1), -1.0);
  const Transform I = Transform::Identity();
  const double rim = 0.4 * std::sqrt(0.75);
  EXPECT_NEAR(dist(ring, I, floor, I, false), 1.0 - rim, 1e-9);
  EXPECT_NEAR(dist(floor, I, ring, I, false), 1.0 - rim, 1e-9);
  // A thin triangular pole (edges 0.1 from the axis) through the bore: 0.5 - 0.1 from the wall.
  const auto pole = test::meshOf(test::poleTriangles(0.1, 2.0));
  fcl::DistanceResult<double> rm;
  EXPECT_NEAR(dist(ring, I, *pole, I, false, &rm), 0.4, 1e-9);
  EXPECT_GE(rm.b2, 0);  // the nearest triangle's index
  // Two rings, the second turned 90 degrees about x and moved to x = 3.5: it reaches down to
  // (2.5, 0, 0), ring 1 up to (1, 0, 0), both on their outer faces: distance 1.5.
  const Transform turned = pose(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix(), {3.5, 0, 0});
  EXPECT_NEAR(dist(ring, I, ring, turned, false), 1.5, 1e-9);
  // Unsupported partners still throw, naming them.
  const fcl::Plane<double> plane(Eigen::Vector3d(0, 0, 1), 0.0);
  fcl::DistanceRequest<double> req;
  fcl::DistanceResult<double> res;
  test::expectInvalid([&] { fcl_quadric::distance(&ring, I, &plane, I, req, res); }, "o2 has node type");
}

// Near contact: a ball at a known gap from a clipped one-sheet hyperboloid's waist (x^2 + y^2 -
// z^2 <= 1, |z| <= 1: not convex, so the branch and bound answers), from a ring's outer face, and
// from an elliptic cylinder's side and rim (convex: GJK answers), under random rigid poses, in
// both argument orders and both distance modes. The branch and bound stops at 1e-6 of the scale
// and GJK's accuracy is ~1e-13 of it; their witnesses refined by Newton's method
// (nearest_points.h) give the gap to rounding. Before the refinement (a scratch driver of session
// 36) the hyperboloid's distances were up to 3e-6 too large (2.8e-6 at a gap of 1e-10), the
// cylinder side's 5e-7 at gaps of 1e-8 and 1e-10 (GJK's witnesses), 3.8e-13 at 1e-4.
TEST(QuadricShapeDistance, QuadricShapesNearContactGetTheGapToRounding) {
  using Clip = HalfspaceClip<double>;
  const Quadric<double> hyp =
      Quadric<double>::hyperboloidOneSheet(1.0, 1.0, 1.0, {Clip{{0, 0, 1}, 1.0}, Clip{{0, 0, -1}, 1.0}});
  auto ball = std::make_shared<Quadric<double>>(Quadric<double>::ellipsoid(1.0, 1.0, 1.0));
  auto bore = std::make_shared<Quadric<double>>(Quadric<double>::ellipticCylinder(0.6, 0.6));
  const QuadricCSG<double> ring(QuadricRegion::Op::Difference, {{ball, Transform::Identity()}, {bore, Transform::Identity()}});
  const EllipticCylinder<double> cylinder(1.0, 0.6, 2.0);
  const fcl::Sphere<double> s(0.2);
  std::mt19937_64 rng(36);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  const char* names[] = {"hyperboloid", "ring", "cylinder side", "cylinder rim"};
  for (int model = 0; model < 4; ++model) {
    const fcl::CollisionGeometry<double>& shape = model == 0   ? static_cast<const fcl::CollisionGeometry<double>&>(hyp)
                                                  : model == 1 ? static_cast<const fcl::CollisionGeometry<double>&>(ring)
                                                               : cylinder;
    for (double gap : {1e-3, 1e-6, 1e-9}) {
      for (int i = 0; i < 3; ++i) {
        // The surface point and its outward normal: the hyperboloid's waist (nearest point of
        // the surface to every point of its outward normal line up to x = 2, so to the ball's
        // centre at 1.2 + gap), the ring's outer sphere between polar angles 60 and 120 deg, the
        // cylinder's side (normal (cos phi / a, sin phi / b, 0)) or its top rim (that normal
        // tilted up by 0.2-1.4 rad, inside the rim's normal cone).
        const double phi = 2.0 * M_PI * u01(rng), theta = model == 1 ? M_PI / 3 * (1.0 + u01(rng)) : M_PI / 2;
        Eigen::Vector3d foot(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
        Eigen::Vector3d n = foot;
        if (model >= 2) {
          foot = Eigen::Vector3d(std::cos(phi), 0.6 * std::sin(phi), model == 2 ? 2.0 * u01(rng) - 1.0 : 1.0);
          n = Eigen::Vector3d(std::cos(phi), std::sin(phi) / 0.6, 0.0).normalized();
          if (model == 3) {
            const double tilt = 0.2 + 1.2 * u01(rng);
            n = std::cos(tilt) * n + std::sin(tilt) * Eigen::Vector3d::UnitZ();
          }
        }
        const Transform X = pose(test::randomRotation(rng), Eigen::Vector3d(u01(rng), u01(rng), u01(rng)));
        const Transform Y = pose(Eigen::Matrix3d::Identity(), X * (foot + (0.2 + gap) * n));
        SCOPED_TRACE(testing::Message() << names[model] << " gap " << gap << " case " << i);
        for (bool signed_distance : {false, true}) {
          fcl::DistanceResult<double> r;
          EXPECT_NEAR(dist(shape, X, s, Y, signed_distance, &r), gap, 1e-13);
          EXPECT_NEAR((r.nearest_points[0] - X * foot).norm(), 0.0, 1e-7);  // the surface point
          EXPECT_NEAR(dist(s, Y, shape, X, signed_distance), gap, 1e-13);
        }
        EXPECT_FALSE(collides(shape, X, s, Y));
      }
    }
  }
}

// A cone's nappe and a two-sheet hyperboloid's sheet, each selected by a clip, are convex shapes
// (their support mappings enumerate the apex and the indefinite atom's sections; docs/algorithms.md
// section 12): GJK and EPA answer them. A ball placed at a known gap along a direction of the
// normal cone at a boundary point (the apex, where any direction within 90 deg - atan(1/2) of
// the axis is one; the cone's side and rim; the sheet's vertex and side) has that point as its
// nearest, since the solid is convex, so the distance is the gap exactly, and for a small overlap
// (the centre still outside the solid) the signed distance is minus it. Before session 37 the
// branch and bound answered the cone, 1.9 ms per query at the apex, 1.5e-6 too far even at a gap
// of 1e-2 (a scratch driver).
TEST(QuadricShapeDistance, ConeNappesAndHyperboloidSheetsAreConvexAndExactNearContact) {
  using Clip = HalfspaceClip<double>;
  const Quadric<double> cone = Quadric<double>::ellipticCone(1.0, 1.0, 2.0, {Clip{{0, 0, -1}, 0.0}, Clip{{0, 0, 1}, 2.0}});
  const Quadric<double> sheet =
      Quadric<double>::hyperboloidTwoSheets(1.0, 1.0, 1.0, {Clip{{0, 0, -1}, 0.0}, Clip{{0, 0, 1}, 3.0}});
  ASSERT_TRUE(cone.convexSupport().has_value());
  ASSERT_TRUE(sheet.convexSupport().has_value());
  // Both nappes (a clip across the apex) are not convex.
  EXPECT_FALSE(Quadric<double>::ellipticCone(1.0, 1.0, 2.0, {Clip{{0, 0, -1}, 1.0}, Clip{{0, 0, 1}, 1.0}})
                   .convexSupport()
                   .has_value());
  const fcl::Sphere<double> s(0.2);
  std::mt19937_64 rng(37);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  const char* names[] = {"cone apex", "cone side", "cone rim", "sheet vertex", "sheet side"};
  for (int model = 0; model < 5; ++model) {
    const Quadric<double>& shape = model < 3 ? cone : sheet;
    for (double gap : {1e-2, 1e-4, 1e-6, -1e-4, -1e-2}) {
      for (int i = 0; i < 3; ++i) {
        const double phi = 2.0 * M_PI * u01(rng);
        const Eigen::Vector3d radial(std::cos(phi), std::sin(phi), 0.0);
        const Eigen::Vector3d side_normal = (radial - 0.5 * Eigen::Vector3d::UnitZ()).normalized();  // grad of x^2 + y^2 - z^2 / 4
        Eigen::Vector3d foot, n;
        if (model == 0) {  // tilted up to 1 rad off -z: inside the apex's normal cone (63.4 deg)
          const double tilt = u01(rng);
          foot.setZero();
          n = std::sin(tilt) * radial - std::cos(tilt) * Eigen::Vector3d::UnitZ();
        } else if (model == 1) {
          const double z = 0.3 + 1.4 * u01(rng);
          foot = 0.5 * z * radial + z * Eigen::Vector3d::UnitZ();
          n = side_normal;
        } else if (model == 2) {  // between the side's normal and the cap's
          const double w = u01(rng);
          foot = radial + 2.0 * Eigen::Vector3d::UnitZ();
          n = ((1.0 - w) * side_normal + w * Eigen::Vector3d::UnitZ()).normalized();
        } else if (model == 3) {
          foot = Eigen::Vector3d::UnitZ();
          n = -Eigen::Vector3d::UnitZ();
        } else {  // (sinh t cos phi, sinh t sin phi, cosh t), outward normal (x, y, -z)
          const double t = 0.3 + 1.2 * u01(rng);
          foot = std::sinh(t) * radial + std::cosh(t) * Eigen::Vector3d::UnitZ();
          n = Eigen::Vector3d(foot.x(), foot.y(), -foot.z()).normalized();
        }
        const Transform X = pose(test::randomRotation(rng), Eigen::Vector3d(u01(rng), u01(rng), u01(rng)));
        const Transform Y = pose(Eigen::Matrix3d::Identity(), X * (foot + (0.2 + gap) * n));
        SCOPED_TRACE(testing::Message() << names[model] << " gap " << gap << " case " << i);
        EXPECT_EQ(collides(shape, X, s, Y), gap < 0.0);
        for (bool signed_distance : {false, true}) {
          if (gap < 0.0 && !signed_distance) continue;  // -1 for an overlap (FCL's convention)
          // GJK's documented 1e-10 of the distance (refined to rounding within 1e-3 of the scale);
          // EPA's depths measured within 1e-12.
          const double tol = gap > 0.0 ? 1e-13 + 1e-10 * gap : 1e-11;
          fcl::DistanceResult<double> r;
          EXPECT_NEAR(dist(shape, X, s, Y, signed_distance, &r), gap, tol);
          EXPECT_NEAR(dist(s, Y, shape, X, signed_distance), gap, tol);
          if (gap > 0.0) {
            EXPECT_NEAR((r.nearest_points[0] - X * foot).norm(), 0.0, gap > 1e-3 ? 1e-5 : 1e-7);
          }
        }
      }
    }
  }
}

// An audit of session 37: a thin cone (x^2 + y^2 / 1e-6 <= 4 z^2, 0 <= z <= 1) posed 2e4 from
// the origin, a ball 2e-4 from its rim. GJK alone gave 2.000000001e-4; the refinement of its
// witnesses, run on the world-frame atoms (whose |t|^2 terms widen the membership band), moved a
// witness 3.4e-7 outside the cone and reported 1.99656e-4 (6.9e-5 at other poses). It now runs in
// the shape's frame.
TEST(QuadricShapeDistance, RefinementFarFromTheOriginStaysOnTheShape) {
  using Clip = HalfspaceClip<double>;
  const Quadric<double> cone = Quadric<double>::ellipticCone(1.0, 1e-3, 0.5, {Clip{{0, 0, -1}, 0.0}, Clip{{0, 0, 1}, 1.0}});
  const fcl::Sphere<double> s(0.2);
  std::mt19937_64 rng(371);
  // The rim point (2, 0, 1); its normal cone spans the side's normal (1, 0, -2) / sqrt(5) and +z.
  const Eigen::Vector3d foot(2.0, 0.0, 1.0);
  const Eigen::Vector3d n = (Eigen::Vector3d(1, 0, -2).normalized() + 2.5 * Eigen::Vector3d::UnitZ()).normalized();
  for (int i = 0; i < 4; ++i) {
    const Transform X = pose(test::randomRotation(rng), Eigen::Vector3d(12000, -9600, 12800));
    for (double gap : {2e-4, 1e-6}) {
      const Transform Y = pose(Eigen::Matrix3d::Identity(), X * (foot + (0.2 + gap) * n));
      // The placement rounds by ~eps |t| = 5e-12.
      SCOPED_TRACE(testing::Message() << "pose " << i << " gap " << gap);
      fcl::DistanceResult<double> r;
      EXPECT_NEAR(dist(cone, X, s, Y, false, &r), gap, 1e-10);
      EXPECT_NEAR(dist(s, Y, cone, X, true), gap, 1e-10);
      const Eigen::Vector3d local = X.inverse() * r.nearest_points[0];
      EXPECT_NEAR((local - foot).norm(), 0.0, 1e-6);
    }
  }
  // The audit's own case (its poses, printed to 17 digits): a box's vertex 2e-4 from the rim
  // point along a direction of its normal cone. The ball cases above pass with the world-frame
  // refinement too (checked); this one gave 1.99656e-4 with it.
  Transform X, Y;
  X.matrix() << 0.8251233534762803, -0.15745805384104644, 0.54256650544301699, 12000, 0.1995422538999686,
      0.97970226726581211, -0.019140439460674813, -9600, -0.52853981917787218, 0.12405816698153094, 0.83979475513282698,
      12800, 0, 0, 0, 1;
  Y.matrix() << 0.64584261516419628, 0.27435381159425132, 0.71247266789791885, 11999.890138379104, 0.51519529004291187,
      0.53208611708869158, -0.67190637526301189, -9600.922200971916, -0.56343689048150913, 0.80100833333067478,
      0.20229809781444452, 12801.517428704083, 0, 0, 0, 1;
  const fcl::Box<double> box(0.8, 0.4, 1.2);
  EXPECT_NEAR(dist(cone, X, box, Y, true), 2e-4, 1e-10);
  EXPECT_NEAR(dist(box, Y, cone, X, false), 2e-4, 1e-10);
}

}  // namespace
}  // namespace fcl_quadric
