// nearest_points.h: Newton's method on the distance's KKT system, against an exact construction.
// A small ellipsoid is placed so that its support point along -n lies at p + g n, where p is a
// point of a model's boundary with outward normal n (a face, an edge's or a vertex's normal cone):
// the plane through p normal to n supports the model near p and the plane through p + g n the
// ellipsoid, so the distance is g and the nearest points are p and p + g n (locally: the
// ellipsoid's curvature exceeds the model's concave curvature in every case below). The refinement
// starts from points of both surfaces displaced along them, as GJK or the branch and bound leave
// them near contact, and must reach g to rounding at gaps from 1e-3 down to 1e-10 of the size.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "fcl_quadric/algebra/quadric_matrix.h"
#include "fcl_quadric/geometry/nearest_points.h"
#include "fcl_quadric/geometry/quadric_region.h"
#include "support/random_ellipsoids.h"

namespace fcl_quadric {
namespace {

using Op = QuadricRegion::Op;

/// A model in its own frame with a boundary point p, an outward normal n there (unit), the atom
/// p is projected back onto after a displacement, and the size.
struct Model {
  std::string name;
  QuadricRegion region;
  Eigen::Vector3d p, n;
  Eigen::Matrix4d face;
  double size;
};

Eigen::Vector3d gradientOf(const Eigen::Matrix4d& Q, const Eigen::Vector3d& x) {
  return 2.0 * (Q.topLeftCorner<3, 3>() * x + Q.topRightCorner<3, 1>());
}

double valueOf(const Eigen::Matrix4d& Q, const Eigen::Vector3d& x) {
  const Eigen::Vector4d X(x[0], x[1], x[2], 1.0);
  return X.dot(Q * X);
}

Eigen::Matrix4d planeAtom(const Eigen::Vector3d& n, double d) {  // n.x - d <= 0, as 2 b.x + c
  Eigen::Matrix4d Q = Eigen::Matrix4d::Zero();
  Q.topRightCorner<3, 1>() = 0.5 * n;
  Q.bottomLeftCorner<1, 3>() = 0.5 * n.transpose();
  Q(3, 3) = -d;
  return Q;
}

std::vector<Model> models() {
  std::vector<Model> out;
  const Eigen::Vector3d ez = Eigen::Vector3d::UnitZ();
  {  // The side of a capped elliptic cylinder (convex).
    const Eigen::Matrix4d Q = quadric::ellipticCylinder(0.6, 0.3);
    const QuadricRegion r = QuadricRegion::combine(
        Op::Intersection, {QuadricRegion::atom(Q), QuadricRegion::halfspace(ez, 1.0), QuadricRegion::halfspace(-ez, 1.0)});
    const Eigen::Vector3d p(0.6 * std::cos(0.9), 0.3 * std::sin(0.9), 0.3);
    out.push_back({"elliptic cylinder side", r, p, gradientOf(Q, p).normalized(), Q, 1.2});
  }
  {  // The side of a cone clipped to 0 <= z <= 2 (convex, not positive semidefinite).
    const Eigen::Matrix4d Q = quadric::ellipticCone(1.0, 1.0, 1.0);
    const QuadricRegion r = QuadricRegion::combine(
        Op::Intersection, {QuadricRegion::atom(Q), QuadricRegion::halfspace(ez, 2.0), QuadricRegion::halfspace(-ez, 0.0)});
    const Eigen::Vector3d p(0.6, 0.8, 1.0);
    out.push_back({"cone side", r, p, gradientOf(Q, p).normalized(), Q, 2.5});
  }
  {  // A one-sheet hyperboloid clipped to |z| <= 2, from outside (a saddle: not convex).
    const Eigen::Matrix4d Q = quadric::hyperboloidOneSheet(1.0, 1.0, 1.0);
    const QuadricRegion r = QuadricRegion::combine(
        Op::Intersection, {QuadricRegion::atom(Q), QuadricRegion::halfspace(ez, 2.0), QuadricRegion::halfspace(-ez, 2.0)});
    const double z = 0.5, rr = std::sqrt(1.0 + z * z);
    const Eigen::Vector3d p(rr * std::cos(0.7), rr * std::sin(0.7), z);
    out.push_back({"hyperboloid outside", r, p, gradientOf(Q, p).normalized(), Q, 2.8});
  }
  {  // A paraboloid clipped at z <= 2, near its vertex.
    const Eigen::Matrix4d Q = quadric::ellipticParaboloid(1.0, 0.8);
    const QuadricRegion r = QuadricRegion::combine(Op::Intersection, {QuadricRegion::atom(Q), QuadricRegion::halfspace(ez, 2.0)});
    const Eigen::Vector3d p(0.3, -0.2, 0.09 + 0.0625);
    out.push_back({"paraboloid", r, p, gradientOf(Q, p).normalized(), Q, 2.0});
  }
  {  // The bore of a ring (ellipsoid minus cylinder): a concave surface, from inside the bore.
    const Eigen::Matrix4d E = quadric::ellipsoid({1.0, 1.0, 0.5}), C = quadric::ellipticCylinder(0.5, 0.5);
    const QuadricRegion r = QuadricRegion::combine(Op::Difference, {QuadricRegion::atom(E), QuadricRegion::atom(C)});
    const Eigen::Vector3d p(0.5, 0.0, 0.1);
    out.push_back({"ring bore", r, p, Eigen::Vector3d(-1.0, 0.0, 0.0), -C, 1.2});
  }
  {  // The rim of a lens (two balls' intersection): an edge, the normal bisecting the two faces'.
    const Eigen::Matrix4d A = quadric::posedEllipsoid(Eigen::Vector3d::Constant(1.25), Eigen::Matrix3d::Identity(), -0.75 * ez);
    const Eigen::Matrix4d B = quadric::posedEllipsoid(Eigen::Vector3d::Constant(1.25), Eigen::Matrix3d::Identity(), 0.75 * ez);
    const QuadricRegion r = QuadricRegion::combine(Op::Intersection, {QuadricRegion::atom(A), QuadricRegion::atom(B)});
    const Eigen::Vector3d p(std::cos(0.4), std::sin(0.4), 0.0);
    out.push_back({"lens rim", r, p, Eigen::Vector3d(p[0], p[1], 0.2).normalized(), A, 1.5});
  }
  {  // A corner of a box: a vertex, the normal inside its normal cone.
    std::vector<QuadricRegion> planes;
    for (int k = 0; k < 3; ++k) {
      planes.push_back(QuadricRegion::halfspace(Eigen::Vector3d::Unit(k), 0.5));
      planes.push_back(QuadricRegion::halfspace(-Eigen::Vector3d::Unit(k), 0.5));
    }
    const Eigen::Vector3d p = Eigen::Vector3d::Constant(0.5);
    out.push_back({"box corner", QuadricRegion::combine(Op::Intersection, planes), p, Eigen::Vector3d(1.0, 0.7, 0.4).normalized(),
                   planeAtom(Eigen::Vector3d::UnitX(), 0.5), 0.9});
  }
  {  // A vertex (angle 120 degrees) of a mesh triangle, as the FCL layer builds it: its plane as two
     // opposite half-spaces and three edge half-spaces, a region of zero thickness. The plane pair
     // is one equality constraint (twinAtoms); as two inequalities it filled two of the three
     // active places, and the vertex was never reached (refinement failed; finding 34 (2)).
    const Eigen::Vector3d v1(1.0, 0.0, 0.0), v2(-0.5, std::sqrt(0.75), 0.0);
    std::vector<QuadricRegion> parts{QuadricRegion::halfspace(ez, 0.0), QuadricRegion::halfspace(-ez, 0.0)};
    const Eigen::Vector3d pts[3] = {Eigen::Vector3d::Zero(), v1, v2};
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d inward = ez.cross(pts[(i + 1) % 3] - pts[i]);
      parts.push_back(QuadricRegion::halfspace(-inward, -inward.dot(pts[i])));
    }
    // The normal: up, tilted away from both edges at the vertex (into the polar of its angle).
    const Eigen::Vector3d n = (0.8 * ez - 0.6 * (v1 + v2).normalized()).normalized();
    out.push_back({"triangle vertex", QuadricRegion::combine(Op::Intersection, parts), Eigen::Vector3d::Zero(), n,
                   planeAtom(ez, 0.0), 1.2});
  }
  return out;
}

/// x moved onto the surface of Q by Newton steps along the gradient (the test's own projection).
Eigen::Vector3d projectOnto(const Eigen::Matrix4d& Q, Eigen::Vector3d x) {
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d g = gradientOf(Q, x);
    x -= valueOf(Q, x) / g.squaredNorm() * g;
  }
  return x;
}

/// A unit vector orthogonal to n.
Eigen::Vector3d tangentTo(const Eigen::Vector3d& n, std::mt19937_64& rng) {
  const Eigen::Vector3d v = test::randomUnitVector(rng);
  return (v - v.dot(n) * n).normalized();
}

struct Placement {
  QuadricRegion model, ball;  // posed in the world frame
  Eigen::Vector3d p, q;       // the nearest points: p on the model, q = p + g n on the ellipsoid
  Eigen::Vector3d start_model, start_ball;
  double scale;
};

/// The model under a random rigid motion and a small random ellipsoid at gap g along n; the
/// start points displaced along the surfaces by about `offset`.
Placement place(const Model& m, double g, double offset, std::mt19937_64& rng) {
  const Eigen::Matrix3d R = test::randomRotation(rng);
  const Eigen::Vector3d t = 3.0 * test::randomUnitVector(rng);
  const Eigen::Vector3d radii = test::randomRadii(rng, 0.15, 3.0);  // <= 0.15: curvature >= 2.2
  const Eigen::Matrix3d Re = test::randomRotation(rng);
  const Eigen::Matrix3d M = Re * radii.asDiagonal();  // E = { c + M u : |u| <= 1 }
  Placement out;
  out.p = R * m.p + t;
  const Eigen::Vector3d n = R * m.n;
  out.q = out.p + g * n;
  // The point of E with outward normal -n is c + M (M^T (-n)) / |M^T n|: c puts it at q.
  const Eigen::Vector3d c = out.q + M * (M.transpose() * n) / (M.transpose() * n).norm();
  out.model = m.region.transformed(R, t);
  out.ball = QuadricRegion::atom(quadric::affineEllipsoid(M, c));
  // Starts: E's point with normal -n tilted by ~offset / radius; the model's point moved by
  // `offset` along its surface (projected back onto the face atom).
  const Eigen::Vector3d m_dir = -n + (offset / radii.minCoeff()) * tangentTo(n, rng);
  out.start_ball = c + M * (M.transpose() * m_dir) / (M.transpose() * m_dir).norm();
  const Eigen::Matrix4d face = quadric::transform(m.face, quadric::affineTransform(R, t));
  // (At an edge or a vertex, a displacement away from the model is redrawn.)
  for (int attempt = 0; attempt < 16; ++attempt) {
    out.start_model = projectOnto(face, out.p + offset * tangentTo(n, rng));
    if (out.model.classifyPoint(out.start_model) >= 0) break;
  }
  out.scale = m.size + radii.maxCoeff() + (t - c).norm();
  return out;
}

/// The rounding band of the surfaces through x: the largest eps |X|^T |Q| |X| / |grad g(x)| over
/// the atoms of the region whose surfaces pass within 1e-6 of x. A small ellipsoid's 4x4 matrix
/// far from the origin holds terms ~ |c|^2 / r^2 that cancel to O(1) on its surface, so its
/// surface is represented only to ~eps |c|^2 / r: the exactness any method on these matrices can
/// reach.
double roundingBand(const QuadricRegion& region, const Eigen::Vector3d& x) {
  double band = 0.0;
  for (const Eigen::Matrix4d& Q : region.signedAtoms()) {
    const double gn = gradientOf(Q, x).norm();
    if (!(gn > 0.0) || std::fabs(valueOf(Q, x)) > 1e-6 * gn) continue;
    const Eigen::Vector4d X(std::fabs(x[0]), std::fabs(x[1]), std::fabs(x[2]), 1.0);
    band = std::max(band, std::numeric_limits<double>::epsilon() * X.dot(Q.cwiseAbs() * X) / gn);
  }
  return band;
}

TEST(NearestPoints, ReachTheConstructedDistanceToRoundingAtEveryGap) {
  std::mt19937_64 rng(35);
  int cases = 0;
  for (const Model& m : models()) {
    for (double g : {1e-3, 1e-6, 1e-8, 1e-10}) {
      for (int trial = 0; trial < 6; ++trial) {
        const double offset = trial < 3 ? 1e-3 : 1e-5;
        const Placement s = place(m, g, offset, rng);
        ASSERT_GE(s.model.classifyPoint(s.start_model), 0) << m.name;
        const std::optional<NearestPoints> r = refineNearestPoints(s.ball, s.model, s.start_ball, s.start_model, s.scale);
        ASSERT_TRUE(r.has_value()) << m.name << " gap " << g << " trial " << trial;
        // Exact to the surfaces' rounding bands (a few times 1e-15 here; roundingBand()).
        const double tol = 8.0 * (roundingBand(s.model, s.p) + roundingBand(s.ball, s.q));
        EXPECT_NEAR(r->distance, g, tol) << m.name << " gap " << g << " trial " << trial;
        EXPECT_NEAR((r->point_b - r->point_a).norm(), r->distance, 1e-16);
        EXPECT_LT((r->point_b - s.p).norm(), 1e-7) << m.name << " gap " << g;
        EXPECT_LT((r->point_a - s.q).norm(), 1e-7) << m.name << " gap " << g;
        EXPECT_GE(s.model.classifyPoint(r->point_b), 0);
        EXPECT_GE(s.ball.classifyPoint(r->point_a), 0);
        // In the other order: the same pair, swapped.
        const std::optional<NearestPoints> w = refineNearestPoints(s.model, s.ball, s.start_model, s.start_ball, s.scale);
        ASSERT_TRUE(w.has_value()) << m.name << " gap " << g << " swapped";
        EXPECT_NEAR(w->distance, r->distance, tol);
        ++cases;
      }
    }
  }
  EXPECT_EQ(cases, 8 * 4 * 6);
}

TEST(NearestPoints, NeverReturnsAPairFartherThanTheStartOrOutsideTheModels) {
  // Starts far along the surfaces (up to 0.3 of the size): whatever is returned is a pair of
  // members no farther apart than the start, and never closer than the constructed distance
  // less rounding (which it would be only off the models or across them).
  std::mt19937_64 rng(7);
  int refined = 0;
  for (const Model& m : models())
    for (int trial = 0; trial < 40; ++trial) {
      const double g = std::pow(10.0, -1.0 - 8.0 * (trial % 9) / 8.0);
      const Placement s = place(m, g, 0.3 * (trial + 1) / 40.0, rng);
      if (s.model.classifyPoint(s.start_model) < 0) continue;  // the displaced start left the model
      const std::optional<NearestPoints> r = refineNearestPoints(s.ball, s.model, s.start_ball, s.start_model, s.scale);
      if (!r) continue;
      ++refined;
      EXPECT_LE(r->distance, (s.start_model - s.start_ball).norm());
      EXPECT_GE(r->distance, g - 8.0 * (roundingBand(s.model, s.p) + roundingBand(s.ball, s.q))) << m.name;
      EXPECT_GE(s.model.classifyPoint(r->point_b), 0);
      EXPECT_GE(s.ball.classifyPoint(r->point_a), 0);
    }
  EXPECT_GT(refined, 8 * 40 / 2);
}

TEST(NearestPoints, GivesNothingForCoincidentStartsInteriorPointsOrABadScale) {
  std::mt19937_64 rng(3);
  const Model m = models().front();
  const Placement s = place(m, 1e-3, 1e-3, rng);
  EXPECT_FALSE(refineNearestPoints(s.ball, s.model, s.start_model, s.start_model, s.scale));
  // A point deep inside the model is on none of its surfaces.
  const Eigen::Vector3d inside = s.p - 0.1 * (s.q - s.p).normalized();
  ASSERT_GT(s.model.classifyPoint(inside), 0);
  EXPECT_FALSE(refineNearestPoints(s.ball, s.model, s.start_ball, inside, s.scale));
  for (double bad : {0.0, -1.0, std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()})
    EXPECT_FALSE(refineNearestPoints(s.ball, s.model, s.start_ball, s.start_model, bad));
}

}  // namespace
}  // namespace fcl_quadric
