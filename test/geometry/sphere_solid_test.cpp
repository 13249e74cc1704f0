// A sphere against a box, capsule, cylinder, cone and triangle in closed form (sphere_solid.h),
// checked against two independent oracles: tangent constructions (a support point q of the solid
// along m, the centre at q + (r + g) m, so the signed distance is g and the nearest point q), and
// the general ellipsoid kernels on a nearly spherical ellipsoid (within r * delta of the sphere,
// so their signed distances differ by at most that).
#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include <Eigen/Geometry>

#include "fcl_quadric/geometry/ellipsoid_capsule.h"
#include "fcl_quadric/geometry/ellipsoid_cylinder.h"
#include "fcl_quadric/geometry/ellipsoid_polytope.h"
#include "fcl_quadric/geometry/sphere_solid.h"
#include "support/random_ellipsoids.h"

namespace fcl_quadric {
namespace sphere_solid_test {
namespace {

enum Kind { kBox, kCapsule, kCylinder, kCone, kTriangle };
constexpr Kind kKinds[] = {kBox, kCapsule, kCylinder, kCone, kTriangle};
const char* kindName(Kind k) {
  static const char* names[] = {"box", "capsule", "cylinder", "cone", "triangle"};
  return names[k];
}

struct Solid {
  Kind kind = kBox;
  Eigen::Vector3d half = Eigen::Vector3d::Zero();
  double radius = 0.0, length = 0.0;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  Eigen::Vector3d v[3];  // triangle vertices (world)
};

Solid randomSolid(Kind kind, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> size(0.2, 1.5), pos(-2.0, 2.0);
  Solid s;
  s.kind = kind;
  s.half = Eigen::Vector3d(size(rng), size(rng), size(rng));
  s.radius = size(rng);
  s.length = 2.0 * size(rng);
  s.R = test::randomRotation(rng);
  s.p = Eigen::Vector3d(pos(rng), pos(rng), pos(rng));
  for (Eigen::Vector3d& x : s.v) x = s.p + 1.5 * test::randomUnitVector(rng);
  return s;
}

SignedDistanceResult closedForm(const Solid& s, const Eigen::Vector3d& c, double r) {
  switch (s.kind) {
    case kBox: return signedDistanceSphereBox(c, r, s.half, s.R, s.p);
    case kCapsule: return signedDistanceSphereCapsule(c, r, s.radius, s.length, s.R, s.p);
    case kCylinder: return signedDistanceSphereCylinder(c, r, s.radius, s.length, s.R, s.p);
    case kCone: return signedDistanceSphereCone(c, r, s.radius, s.length, s.R, s.p);
    case kTriangle: return signedDistanceSphereTriangle(c, r, s.v[0], s.v[1], s.v[2]);
  }
  return {};
}

SignedDistanceResult generalKernel(const Solid& s, const Ellipsoid& e) {
  switch (s.kind) {
    case kBox: return signedDistanceEllipsoidBox(e, s.half, s.R, s.p);
    case kCapsule: return signedDistanceEllipsoidCapsule(e, s.radius, s.length, s.R, s.p);
    case kCylinder: return signedDistanceEllipsoidCylinder(e, s.radius, s.length, s.R, s.p);
    case kCone: return signedDistanceEllipsoidCone(e, s.radius, s.length, s.R, s.p);
    case kTriangle: return signedDistanceEllipsoidTriangle(e, s.v[0], s.v[1], s.v[2]);
  }
  return {};
}

double scaleOf(const Solid& s, const Eigen::Vector3d& c, double r) {
  return (c - s.p).norm() + r + s.half.sum() + s.radius + s.length + 3.0;
}

/// A point q of the solid and a unit direction m in its normal cone there (world frame), drawn
/// so that faces, edges and vertices of each solid all occur (`feature` picks which).
void supportPair(const Solid& s, int feature, std::mt19937_64& rng, Eigen::Vector3d* q, Eigen::Vector3d* m) {
  std::uniform_real_distribution<double> u01(0.0, 1.0), sym(-1.0, 1.0);
  const double h = 0.5 * s.length;
  Eigen::Vector3d ql, ml;  // local frame
  const double phi = 2.0 * M_PI * u01(rng);
  const Eigen::Vector3d radial(std::cos(phi), std::sin(phi), 0.0);
  switch (s.kind) {
    case kBox: {
      ml = test::randomUnitVector(rng);
      for (int i = 0; i < 3; ++i)
        if (i != feature % 3 && u01(rng) < 0.5) ml[i] = 0.0;  // a face or an edge, else a vertex
      ml.normalize();
      for (int i = 0; i < 3; ++i) ql[i] = ml[i] > 0 ? s.half[i] : ml[i] < 0 ? -s.half[i] : s.half[i] * sym(rng);
      break;
    }
    case kCapsule: {
      ml = test::randomUnitVector(rng);
      if (feature % 2 == 0) ml.z() = 0.0;  // the cylindrical part
      ml.normalize();
      const double z = ml.z() > 0 ? h : ml.z() < 0 ? -h : h * sym(rng);
      ql = Eigen::Vector3d(0, 0, z) + s.radius * ml;
      break;
    }
    case kCylinder: {
      const double zs = u01(rng) < 0.5 ? 1.0 : -1.0;
      if (feature % 3 == 0) {  // the side
        ml = radial;
        ql = s.radius * radial + Eigen::Vector3d(0, 0, h * sym(rng));
      } else if (feature % 3 == 1) {  // a cap
        ml = Eigen::Vector3d(0, 0, zs);
        const double rr = s.radius * std::sqrt(u01(rng));
        ql = rr * radial + Eigen::Vector3d(0, 0, zs * h);
      } else {  // the rim: between the side's and the cap's normals
        const double beta = 0.5 * M_PI * (0.02 + 0.96 * u01(rng));
        ml = std::cos(beta) * radial + Eigen::Vector3d(0, 0, zs * std::sin(beta));
        ql = s.radius * radial + Eigen::Vector3d(0, 0, zs * h);
      }
      break;
    }
    case kCone: {
      // The slant normal's angle from the axis is atan2(2h, R).
      const double slant = std::atan2(s.length, s.radius);
      const auto dir = [&](double theta) { return Eigen::Vector3d(std::sin(theta) * radial + Eigen::Vector3d(0, 0, std::cos(theta))); };
      if (feature % 4 == 0) {  // the slant side
        ml = dir(slant);
        const double t = u01(rng);
        ql = t * s.radius * radial + Eigen::Vector3d(0, 0, h - 2.0 * h * t);
      } else if (feature % 4 == 1) {  // the base
        ml = -Eigen::Vector3d::UnitZ();
        ql = s.radius * std::sqrt(u01(rng)) * radial + Eigen::Vector3d(0, 0, -h);
      } else if (feature % 4 == 2) {  // the apex
        ml = dir(slant * (0.02 + 0.96 * u01(rng)));
        ql = Eigen::Vector3d(0, 0, h);
      } else {  // the rim
        ml = dir(slant + (M_PI - slant) * (0.02 + 0.96 * u01(rng)));
        ql = s.radius * radial + Eigen::Vector3d(0, 0, -h);
      }
      break;
    }
    case kTriangle: {
      // Directly in the world frame.
      const Eigen::Vector3d n = (s.v[1] - s.v[0]).cross(s.v[2] - s.v[0]).normalized();
      const double side = u01(rng) < 0.5 ? 1.0 : -1.0;
      if (feature % 3 == 0) {  // the face
        double a = u01(rng), b = u01(rng);
        if (a + b > 1) a = 1 - a, b = 1 - b;
        *q = s.v[0] + a * (s.v[1] - s.v[0]) + b * (s.v[2] - s.v[0]);
        *m = side * n;
      } else if (feature % 3 == 1) {  // an edge: between the face normal and the edge's outward one
        const int k = static_cast<int>(3 * u01(rng)) % 3;
        const Eigen::Vector3d& a = s.v[k];
        const Eigen::Vector3d& b = s.v[(k + 1) % 3];
        const Eigen::Vector3d& o = s.v[(k + 2) % 3];
        Eigen::Vector3d out = (b - a).cross(n).normalized();
        if (out.dot(o - a) > 0) out = -out;
        const double beta = 0.5 * M_PI * (0.02 + 0.96 * u01(rng));
        *m = std::cos(beta) * out + std::sin(beta) * side * n;
        *q = a + u01(rng) * (b - a);
      } else {  // a vertex: the support point along a random direction
        *m = test::randomUnitVector(rng);
        int best = 0;
        for (int k = 1; k < 3; ++k)
          if (s.v[k].dot(*m) > s.v[best].dot(*m)) best = k;
        *q = s.v[best];
      }
      return;
    }
  }
  *q = s.p + s.R * ql;
  *m = (s.R * ml).normalized();
}

TEST(SphereSolid, TangentConstructionsGiveTheGapAndTheNearestPointToRounding) {
  std::mt19937_64 rng(20261130);
  std::uniform_real_distribution<double> ur(0.05, 1.0);
  const double gaps[] = {0.5, 1e-2, 1e-4, 1e-6, 1e-8, 1e-10, -1e-10, -1e-8, -1e-6, -1e-4, -1e-2};
  for (Kind kind : kKinds) {
    int counts[3] = {0, 0, 0};
    double worst = 0.0;
    for (int i = 0; i < 400; ++i) {
      const Solid s = randomSolid(kind, rng);
      Eigen::Vector3d q, m;
      supportPair(s, i, rng, &q, &m);
      const double r = ur(rng);
      for (double g : gaps) {
        if (r + g <= 0.0) continue;
        const Eigen::Vector3d c = q + (r + g) * m;
        const SignedDistanceResult d = closedForm(s, c, r);
        const double scale = scaleOf(s, c, r);
        const double tol = 64 * DBL_EPSILON * scale;
        ++counts[static_cast<int>(d.status)];
        worst = std::max(worst, std::fabs(d.distance - g) / scale);
        ASSERT_NEAR(d.distance, d.status == Separation::Touching ? 0.0 : g, tol)
            << kindName(kind) << " case " << i << " gap " << g;
        // The status is certain outside the touching band (2^-40 of the scale).
        if (std::fabs(g) > 1e-11 * scale) {
          ASSERT_EQ(d.status, g > 0 ? Separation::Separated : Separation::Overlapping) << kindName(kind) << " " << i;
        }
        // The nearest point of a convex solid is unique: q; the normal is -m.
        ASSERT_LT((d.point_b - q).norm(), 1e-12 * scale) << kindName(kind) << " case " << i << " gap " << g;
        ASSERT_LT((d.normal + m).norm(), 1e-9) << kindName(kind) << " case " << i << " gap " << g;
        ASSERT_NEAR((d.point_a - c).norm(), r, tol);
      }
    }
    // Every gap of 1e-10 and more is outside the band here: all three statuses must occur only
    // through the gaps, and none of these is Touching.
    EXPECT_GT(counts[0], 1000) << kindName(kind);
    EXPECT_GT(counts[2], 1000) << kindName(kind);
    EXPECT_EQ(counts[1], 0) << kindName(kind);
    RecordProperty(std::string("worst_relative_error_") + kindName(kind), std::to_string(worst));
  }
}

TEST(SphereSolid, AgreesWithTheGeneralKernelsOnANearlySphericalEllipsoid) {
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> ur(0.05, 1.2);
  const double delta = 1e-10;  // the ellipsoid (r, r, r (1 + delta)) is within r delta of the sphere
  for (Kind kind : kKinds) {
    int counts[3] = {0, 0, 0};
    for (int i = 0; i < 400; ++i) {
      const Solid s = randomSolid(kind, rng);
      const double r = ur(rng);
      const Eigen::Vector3d c = s.p + 1.3 * test::randomUnitVector(rng) * (0.2 + 2.0 * std::uniform_real_distribution<double>(0, 1)(rng));
      const SignedDistanceResult d = closedForm(s, c, r);
      ++counts[static_cast<int>(d.status)];
      const Ellipsoid near(Eigen::Vector3d(r, r, r * (1 + delta)), test::randomRotation(rng), c);
      const SignedDistanceResult k = generalKernel(s, near);
      const double scale = scaleOf(s, c, r);
      ASSERT_NEAR(d.distance, k.distance, r * delta + 1e-11 * scale) << kindName(kind) << " case " << i;
      if (std::fabs(d.distance) > 1e-8) {
        ASSERT_EQ(d.status, k.status) << kindName(kind) << " case " << i;
      }
      if (d.status == Separation::Separated && d.distance > 1e-3) {  // the normal moves by ~r delta / d
        ASSERT_LT((d.normal - k.normal).norm(), 1e-6) << kindName(kind) << " case " << i;
      }
      // Witnesses: point_a on the sphere, point_b - point_a = distance * normal.
      ASSERT_NEAR((d.point_a - c).norm(), r, 1e-14 * scale);
      if (d.status != Separation::Touching) {
        ASSERT_LT((d.point_b - d.point_a - d.distance * d.normal).norm(), 1e-13 * scale) << kindName(kind) << " " << i;
      }
      // Rigid motions of both leave the answer unchanged.
      const Eigen::Matrix3d M = test::randomRotation(rng);
      const Eigen::Vector3d t = 3.0 * test::randomUnitVector(rng);
      Solid moved = s;
      moved.R = M * s.R;
      moved.p = M * s.p + t;
      for (Eigen::Vector3d& x : moved.v) x = M * x + t;
      const SignedDistanceResult dm = closedForm(moved, M * c + t, r);
      ASSERT_NEAR(dm.distance, d.distance, 1e-13 * (scale + 3.0)) << kindName(kind) << " " << i;
    }
    EXPECT_GT(counts[0], 40) << kindName(kind);
    EXPECT_GT(counts[2], 40) << kindName(kind);
  }
}

/// The octahedron |x|_1 <= a (8 triangular faces) and the box |x_i| <= h_i (6 quadrilaterals),
/// posed by (R, p), as ConvexPolytope.
ConvexPolytope octahedron(double a, const Eigen::Matrix3d& R, const Eigen::Vector3d& p) {
  ConvexPolytope P;
  for (int i = 0; i < 3; ++i)
    for (double s : {a, -a}) P.vertices.push_back(p + R * (s * Eigen::Vector3d::Unit(i)));
  for (int x : {0, 1})
    for (int y : {2, 3})
      for (int z : {4, 5}) P.faces.push_back({x, y, z});
  return P;
}
ConvexPolytope boxPolytope(const Eigen::Vector3d& h, const Eigen::Matrix3d& R, const Eigen::Vector3d& p) {
  ConvexPolytope P;
  for (int i = 0; i < 8; ++i)
    P.vertices.push_back(p + R * Eigen::Vector3d(i & 1 ? h[0] : -h[0], i & 2 ? h[1] : -h[1], i & 4 ? h[2] : -h[2]));
  P.faces = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  return P;
}

// A sphere against a convex polytope (signedDistanceEllipsoidConvex hands spheres to the closed
// form): a box given as a polytope gets the box's closed form; an octahedron gets what the general
// polytope kernel gives a nearly spherical ellipsoid.
TEST(SphereSolid, ConvexPolytopesAgreeWithTheBoxAndWithTheGeneralKernel) {
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> u(-2.0, 2.0), ur(0.05, 1.2), size(0.2, 1.5);
  int counts[3] = {0, 0, 0};
  for (int i = 0; i < 600; ++i) {
    const Eigen::Matrix3d R = test::randomRotation(rng);
    const Eigen::Vector3d p(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng));
    const double r = ur(rng);
    const Ellipsoid ball = Ellipsoid::sphere(r, c);
    const double scale = (c - p).norm() + r + 6.0;
    const Eigen::Vector3d h(size(rng), size(rng), size(rng));
    const SignedDistanceResult as_box = signedDistanceSphereBox(c, r, h, R, p);
    const SignedDistanceResult as_polytope = signedDistanceEllipsoidConvex(ball, boxPolytope(h, R, p));
    ++counts[static_cast<int>(as_polytope.status)];
    ASSERT_NEAR(as_polytope.distance, as_box.distance, 1e-13 * scale) << "case " << i;
    ASSERT_EQ(as_polytope.status, as_box.status) << "case " << i;
    ASSERT_LT((as_polytope.point_b - as_box.point_b).norm(), 1e-12 * scale) << "case " << i;
    const ConvexPolytope oct = octahedron(size(rng), R, p);
    const SignedDistanceResult closed = signedDistanceEllipsoidConvex(ball, oct);
    const Ellipsoid near(Eigen::Vector3d(r, r, r * (1 + 1e-10)), test::randomRotation(rng), c);
    const SignedDistanceResult general = signedDistanceEllipsoidConvex(near, oct);
    ASSERT_NEAR(closed.distance, general.distance, 1e-10 * r + 1e-11 * scale) << "case " << i;
    if (std::fabs(closed.distance) > 1e-8) {
      ASSERT_EQ(closed.status, general.status) << "case " << i;
    }
  }
  EXPECT_GT(counts[0], 100);
  EXPECT_GT(counts[2], 100);
}

TEST(SphereSolid, DegenerateSolidsAnswerAsTheSegmentOrDiskTheyAre) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  const double r = 0.3, L = 1.6;
  for (int i = 0; i < 300; ++i) {
    const Eigen::Vector3d c(u(rng), u(rng), u(rng));
    // The axis segment from -L/2 to L/2: cone and cylinder of radius 0, capsule of radius 0, box
    // of zero cross-section, and the triangle (a, b, midpoint).
    const Eigen::Vector3d a(0, 0, -L / 2), b(0, 0, L / 2);
    const Eigen::Vector3d nearest(0, 0, std::clamp(c.z(), -L / 2, L / 2));
    const double segment = (c - nearest).norm() - r;
    for (const SignedDistanceResult& d :
         {signedDistanceSphereCone(c, r, 0.0, L, I, {0, 0, 0}), signedDistanceSphereCylinder(c, r, 0.0, L, I, {0, 0, 0}),
          signedDistanceSphereCapsule(c, r, 0.0, L, I, {0, 0, 0}), signedDistanceSphereBox(c, r, {0, 0, L / 2}, I, {0, 0, 0}),
          signedDistanceSphereTriangle(c, r, a, b, 0.5 * (a + b))}) {
      ASSERT_NEAR(d.distance, segment, 1e-14) << i;
      ASSERT_LT((d.point_b - nearest).norm(), 1e-14) << i;
    }
    // The disk of radius 0.8 in the plane z = 0: cone and cylinder of length 0.
    const double rho = std::hypot(c.x(), c.y());
    const double disk = std::hypot(std::max(rho - 0.8, 0.0), c.z()) - r;
    for (const SignedDistanceResult& d :
         {signedDistanceSphereCone(c, r, 0.8, 0.0, I, {0, 0, 0}), signedDistanceSphereCylinder(c, r, 0.8, 0.0, I, {0, 0, 0})}) {
      ASSERT_NEAR(d.distance, disk, 1e-14) << i;
    }
  }
  // A centre on a segment or a disk: depth r across it, the normal orthogonal to it.
  const SignedDistanceResult on_segment = signedDistanceSphereCylinder({0, 0, 0.1}, r, 0.0, L, I, {0, 0, 0});
  EXPECT_EQ(on_segment.status, Separation::Overlapping);
  EXPECT_NEAR(on_segment.distance, -r, 1e-15);
  EXPECT_NEAR(on_segment.normal.z(), 0.0, 1e-15);
  const SignedDistanceResult on_disk = signedDistanceSphereCone({0.2, 0.1, 0}, r, 0.8, 0.0, I, {0, 0, 0});
  EXPECT_NEAR(on_disk.distance, -r, 1e-15);
  EXPECT_NEAR(std::fabs(on_disk.normal.z()), 1.0, 1e-15);
  const SignedDistanceResult on_triangle = signedDistanceSphereTriangle({0.2, 0.2, 0}, r, {0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  EXPECT_NEAR(on_triangle.distance, -r, 1e-15);
  EXPECT_NEAR(std::fabs(on_triangle.normal.z()), 1.0, 1e-15);
}

// Cases of a session 36 audit (its own __float128 oracle), each wrong before the fix noted.
TEST(SphereSolid, NearlyDegenerateTrianglesAndExtremeSizesAreExact) {
  // A triangle whose vertices are collinear up to rounding: its plain cross product's direction
  // was noise, and a centre 0.042 deep was reported 0.503 away. Oracle: the general kernel on a
  // nearly spherical ellipsoid (radii r, r, r (1 + 1e-12)).
  {
    const Eigen::Vector3d a(0.13336951502944472, -0.010050575561086128, -0.73886592156309638),
        b(0.072669759960608316, 0.063273615219133994, 0.49868894700716915),
        t(0.08893068007870511, 0.043630721971062346, 0.16715909426292752),
        c(0.11115009755407491, 0.016790073204988109, -0.18585341365008443);
    const double r = 0.05;
    const SignedDistanceResult d = signedDistanceSphereTriangle(c, r, a, b, t);
    const Ellipsoid near(Eigen::Vector3d(r, r, r * (1 + 1e-12)), Eigen::Matrix3d::Identity(), c);
    const SignedDistanceResult k = signedDistanceEllipsoidTriangle(near, a, b, t);
    EXPECT_EQ(d.status, Separation::Overlapping);
    EXPECT_NEAR(d.distance, k.distance, 1e-13);
    EXPECT_NEAR(d.distance, -0.0423309734819364, 1e-13);
  }
  // A thin valid triangle (relative height ~1e-10): its status flipped (+2.4e-7 for -1.9e-7).
  {
    const Eigen::Vector3d a(-0.35879569367024289, 0.042299873466061788, 0.016030942890750355),
        b(0.42560055255610219, 0.5466324881771778, -0.78685570579890785),
        t(0.21687709370122071, 0.41243239711970131, -0.57321205430815425),
        c(0.3300464962107712, 0.48639592805578913, -0.68805420491383718);
    const double r = 0.0015515;
    const SignedDistanceResult d = signedDistanceSphereTriangle(c, r, a, b, t);
    const Ellipsoid near(Eigen::Vector3d(r, r, r * (1 + 1e-12)), Eigen::Matrix3d::Identity(), c);
    EXPECT_EQ(d.status, Separation::Overlapping);
    EXPECT_NEAR(d.distance, signedDistanceEllipsoidTriangle(near, a, b, t).distance, 1e-13);
  }
  // Triangles of 1e77 and 1e-85 (|u x v|^2 overflowed / underflowed), boxes and cones of 1e-170:
  // every length scales exactly, so the answer is the unit problem's times the scale.
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  for (double s : {1e77, 1e90, 1e-85, 1e-140}) {
    const SignedDistanceResult d = signedDistanceSphereTriangle(Eigen::Vector3d(0, 0, 0.1 * s), 0.0, Eigen::Vector3d(-s, -s, 0),
                                                                Eigen::Vector3d(s, -s, 0), Eigen::Vector3d(0, s, 0));
    EXPECT_EQ(d.status, Separation::Separated) << s;
    EXPECT_NEAR(d.distance / s, 0.1, 1e-15) << s;
    EXPECT_NEAR(d.normal.norm(), 1.0, 1e-15) << s;
  }
  for (double s : {1e-170, 1e-100, 1.0, 1e99}) {
    // A cone of radius and length s, the centre at its middle: depth s / (2 sqrt 2) from the slant.
    const SignedDistanceResult cone = signedDistanceSphereCone(Eigen::Vector3d::Zero(), 0.0, s, s, I, Eigen::Vector3d::Zero());
    EXPECT_EQ(cone.status, Separation::Overlapping) << s;
    EXPECT_NEAR(cone.distance / s, -1.0 / (2.0 * std::sqrt(2.0)), 1e-15) << s;
    EXPECT_NEAR(cone.normal.norm(), 1.0, 1e-15) << s;
  }
  // The band follows the rounding, not the solid's size: a unit ball 1e-6 above a box 2e6 wide,
  // and 8.5 above the apex of a flat cone 1e99 wide, are separated (both were "touching").
  EXPECT_NEAR(signedDistanceSphereBox(Eigen::Vector3d(0, 0, 2 + 1e-6), 1.0, Eigen::Vector3d(1e6, 1e6, 1), I,
                                      Eigen::Vector3d::Zero()).distance,
              1e-6, 1e-15);
  const SignedDistanceResult flat = signedDistanceSphereCone(Eigen::Vector3d(0, 0, 10), 1.0, 1e99, 1.0, I, Eigen::Vector3d::Zero());
  EXPECT_EQ(flat.status, Separation::Separated);
  EXPECT_NEAR(flat.distance, 8.5, 1e-14);
  // A convex cube of half side 1e-6 at (1e6, 1e6, 1e6), a ball of 1e-9 at its centre: 1e-6 + 1e-9
  // deep (the band was 2^-40 of the coordinates, 1e-6: "touching").
  ConvexPolytope cube = boxPolytope(Eigen::Vector3d::Constant(1e-6), I, Eigen::Vector3d::Constant(1e6));
  const SignedDistanceResult deep = signedDistanceEllipsoidConvex(Ellipsoid::sphere(1e-9, Eigen::Vector3d::Constant(1e6)), cube);
  EXPECT_EQ(deep.status, Separation::Overlapping);
  // (The vertices 1e6 +- 1e-6 are rounded to 1e6's ulp, 1.2e-10: the cube's faces are where they
  // rounded to, and the exact differences give them.)
  const volatile double big = 1e6, small = 1e-6;  // (no constant folding in another precision)
  const double h_plus = (big + small) - big, h_minus = big - (big - small);
  EXPECT_NEAR(deep.distance, -(std::min(h_plus, h_minus) + 1e-9), 1e-20);
  // Lengths beyond 1e100 are refused, as radii are (a capsule 1.7e308 long was measured wrong).
  EXPECT_THROW(signedDistanceSphereCapsule(Eigen::Vector3d(10, 0, 0), 1.0, 1.0, 1.7e308, I, Eigen::Vector3d::Zero()),
               std::invalid_argument);
  EXPECT_THROW(signedDistanceSphereBox(Eigen::Vector3d::Zero(), 1.0, Eigen::Vector3d(2e200, 1, 1), I, Eigen::Vector3d::Zero()),
               std::invalid_argument);
  EXPECT_THROW(signedDistanceEllipsoidCylinder(Ellipsoid({1, 2, 3}, I, Eigen::Vector3d::Zero()), 1e101, 1.0, I,
                                               Eigen::Vector3d(0, 0, 10)),
               std::invalid_argument);
}

// Two spheres: the distance in long double, and the exchanged arguments give the same distance
// bit for bit with mirrored witnesses (the audit found them differing by an ulp when sphere-sphere
// went through the capsule form).
TEST(SphereSolid, TwoSpheresAreSymmetricAndExact) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-3.0, 3.0), ur(0.01, 2.0);
  int counts[3] = {0, 0, 0};
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector3d ca(u(rng), u(rng), u(rng));
    const double ra = ur(rng), rb = ur(rng);
    Eigen::Vector3d cb(u(rng), u(rng), u(rng));
    if (i % 4 == 0) cb = ca + (ra + rb) * (1.0 + (i % 8 == 0 ? 1e-9 : -1e-9)) * test::randomUnitVector(rng);
    const SignedDistanceResult ab = signedDistanceSphereSphere(ca, ra, cb, rb), ba = signedDistanceSphereSphere(cb, rb, ca, ra);
    ++counts[static_cast<int>(ab.status)];
    ASSERT_EQ(ab.distance, ba.distance) << i;
    ASSERT_EQ(ab.status, ba.status) << i;
    ASSERT_EQ(ab.point_a, ba.point_b) << i;
    ASSERT_EQ(ab.normal, -ba.normal) << i;
    const long double dx = static_cast<long double>(cb.x()) - ca.x(), dy = static_cast<long double>(cb.y()) - ca.y(),
                      dz = static_cast<long double>(cb.z()) - ca.z();
    const long double exact = std::sqrt(dx * dx + dy * dy + dz * dz) - ra - rb;
    if (ab.status != Separation::Touching) {
      ASSERT_NEAR(ab.distance, static_cast<double>(exact), 4e-16 * (std::fabs(static_cast<double>(exact)) + ra + rb + 6.0)) << i;
    }
  }
  EXPECT_GT(counts[0], 100);
  EXPECT_GT(counts[2], 100);
}

TEST(SphereSolid, BadInputNamesTheValue) {
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  const Eigen::Vector3d o = Eigen::Vector3d::Zero();
  const auto message = [](auto&& f) -> std::string {
    try {
      f();
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "no exception";
  };
  EXPECT_NE(message([&] { signedDistanceSphereBox(o, -1.0, {1, 1, 1}, I, o); }).find("sphere radius"), std::string::npos);
  EXPECT_NE(message([&] { signedDistanceSphereBox(o, 1.0, {1, std::nan(""), 1}, I, o); }).find("box half extent 1"),
            std::string::npos);
  EXPECT_NE(message([&] { signedDistanceSphereCylinder(o, 1.0, -2.0, 1.0, I, o); }).find("cylinder radius"),
            std::string::npos);
  EXPECT_NE(message([&] { signedDistanceSphereCone(o, 1.0, 1.0, INFINITY, I, o); }).find("cone length"), std::string::npos);
  EXPECT_NE(message([&] { signedDistanceSphereCapsule(o, 1.0, 1.0, 1.0, 2.0 * I, o); }).find("capsule rotation"),
            std::string::npos);
  EXPECT_NE(message([&] { signedDistanceSphereCapsule({1e300, 0, 0}, 1.0, 1.0, 1.0, I, o); }).find("sphere centre"),
            std::string::npos);
  EXPECT_NE(message([&] { signedDistanceSphereTriangle(o, 1.0, o, {1, 0, 0}, {0, NAN, 0}); }).find("triangle vertex c"),
            std::string::npos);
  // Through the ellipsoid kernels, which hand spheres to these: the same validation.
  const Ellipsoid ball = Ellipsoid::sphere(1.0, o);
  EXPECT_THROW(signedDistanceEllipsoidBox(ball, {1, -1, 1}, I, o), std::invalid_argument);
  EXPECT_THROW(signedDistanceEllipsoidCone(ball, 1.0, 1.0, I, {0, 0, 1e200}), std::invalid_argument);
}

}  // namespace
}  // namespace sphere_solid_test
}  // namespace fcl_quadric
