// Ellipsoid vs box and triangle: compared with an independent projected-gradient minimisation in
// long double, with exact constructions at tangency, and with sampled points.
#include <gtest/gtest.h>

#include <random>

#include <gmpxx.h>

#include "fcl_quadric/geometry/ellipsoid_polytope.h"
#include "support/exact_oracle.h"
#include "support/random_ellipsoids.h"

namespace fcl_quadric {
namespace {

/// Independent oracle: min over the polytope of |S^-1 R^T (y - p)|^2 by projected gradient
/// descent in long double (convex problem; many small steps). `project` maps parameters onto the
/// domain; `point(s)` gives the world point.
template <class Project, class Point>
long double oracleMin(const Ellipsoid& e, int dim, Project project, Point point) {
  auto f = [&](const long double* s) {
    const Eigen::Vector3d y = point(s);
    const Eigen::Matrix<long double, 3, 1> d = (e.rotation().transpose() * (y - e.center())).cast<long double>();
    long double v = 0;
    for (int i = 0; i < 3; ++i) v += (d[i] / e.radii()[i]) * (d[i] / e.radii()[i]);
    return v;
  };
  long double best = 1e300L;
  // Multiple starts for safety (the problem is convex, so all should agree).
  for (int start = 0; start < 3; ++start) {
    long double s[3] = {0.1L * start, 0.2L * start, -0.1L * start};
    project(s);
    long double step = 0.1L;
    long double fs = f(s);
    for (int it = 0; it < 4000; ++it) {
      long double grad[3] = {0, 0, 0};
      for (int j = 0; j < dim; ++j) {
        long double sp[3] = {s[0], s[1], s[2]}, sm[3] = {s[0], s[1], s[2]};
        sp[j] += 1e-7L;
        sm[j] -= 1e-7L;
        grad[j] = (f(sp) - f(sm)) / 2e-7L;
      }
      long double t[3] = {s[0] - step * grad[0], s[1] - step * grad[1], s[2] - step * grad[2]};
      project(t);
      const long double ft = f(t);
      if (ft < fs) {
        for (int j = 0; j < 3; ++j) s[j] = t[j];
        fs = ft;
        step *= 1.2L;
      } else {
        step *= 0.5L;
      }
    }
    best = std::min(best, fs);
  }
  return best;
}

TEST(EllipsoidBox, AgreesWithProjectedGradientOracle) {
  std::mt19937_64 rng(101);
  std::uniform_real_distribution<double> u(-2.0, 2.0), uh(0.05, 2.0);
  int counts[3] = {0, 0, 0};
  for (int i = 0; i < 600; ++i) {
    const Ellipsoid e(test::randomRadii(rng, 1.5, 10.0), test::randomRotation(rng), {u(rng), u(rng), u(rng)});
    const Eigen::Vector3d h(uh(rng), uh(rng), uh(rng));
    const Eigen::Matrix3d R = test::randomRotation(rng);
    const Eigen::Vector3d c(u(rng), u(rng), u(rng));
    const EllipsoidPolytopeResult r = classifyEllipsoidBox(e, h, R, c);
    ++counts[static_cast<int>(r.status)];
    const long double oracle = oracleMin(
        e, 3, [](long double* s) { for (int j = 0; j < 3; ++j) s[j] = std::max(-1.0L, std::min(1.0L, s[j])); },
        [&](const long double* s) {
          return Eigen::Vector3d(c + R * Eigen::Vector3d(h[0] * double(s[0]), h[1] * double(s[1]), h[2] * double(s[2])));
        });
    // The library's minimum is exact: never above the oracle's (which may stop slightly high).
    ASSERT_LE(r.unit_distance2, double(oracle) + 1e-9 * (1 + double(oracle))) << "case " << i;
    ASSERT_NEAR(r.unit_distance2, double(oracle), 1e-6 * (1 + double(oracle))) << "case " << i;
    if (std::fabs(double(oracle) - 1.0) > 1e-6) {
      ASSERT_EQ(r.status, oracle < 1 ? Separation::Overlapping : Separation::Separated) << "case " << i;
    }
    ASSERT_EQ(ellipsoidBoxStatus(e, h, R, c), r.status) << "case " << i;  // the fast path agrees
    // The witness is a box point attaining the minimum.
    const Eigen::Vector3d local = R.transpose() * (r.closest - c);
    ASSERT_TRUE((local.cwiseAbs().array() <= h.array() * (1 + 1e-12) + 1e-12).all());
    ASSERT_NEAR(e.implicit(r.closest) + 1.0, r.unit_distance2, 1e-9 * (1 + r.unit_distance2));
  }
  EXPECT_GT(counts[0], 100);  // separated
  EXPECT_GT(counts[2], 100);  // overlapping
}

// The OcTree regime: small axis-aligned boxes whose corner touches the ellipsoid at a support
// point P (outward normal d), moved by a relative gap along d. The box lies in d.x >= d.P + delta
// and the ellipsoid in d.x <= d.P, so delta > 0 separates; for delta < 0 the corner P + delta d is
// inside. The fast status (whose descent pre-test decides most such boxes) and the full test must
// both give that answer at every gap down to 1e-9.
TEST(EllipsoidBox, SmallBoxesAtTheSurfaceAreDecidedOnTheRightSide) {
  std::mt19937_64 rng(103);
  std::uniform_real_distribution<double> u(-1.0, 1.0), uh(0.005, 0.05);
  int cases = 0;
  for (int i = 0; i < 400; ++i) {
    const Ellipsoid e(test::randomRadii(rng, 0.2, 5.0), test::randomRotation(rng), {u(rng), u(rng), u(rng)});
    Eigen::Vector3d d(u(rng), u(rng), u(rng));
    if (!(d.norm() > 0.1)) continue;
    d.normalize();
    const Eigen::Vector3d P = e.supportPoint(d);
    const Eigen::Vector3d h(uh(rng), uh(rng), uh(rng));
    const Eigen::Vector3d corner_offset = h.cwiseProduct(d.cwiseSign());
    const double scale = e.maxRadius() + e.center().norm();
    for (double gap : {1e-3, 1e-5, 1e-7, 1e-9}) {
      for (double sign : {1.0, -1.0}) {
        const Eigen::Vector3d c = P + corner_offset + (sign * gap * scale) * d;
        const Separation expected = sign > 0 ? Separation::Separated : Separation::Overlapping;
        ASSERT_EQ(ellipsoidBoxStatus(e, h, Eigen::Matrix3d::Identity(), c), expected) << "case " << i << " gap " << sign * gap;
        ASSERT_EQ(classifyEllipsoidBox(e, h, Eigen::Matrix3d::Identity(), c).status, expected) << "case " << i;
        ++cases;
      }
    }
  }
  EXPECT_GT(cases, 2500);
}

TEST(EllipsoidBox, TangencyConstructionsAreDecidedOnTheRightSide) {
  const Ellipsoid e({1, 2, 3}, Eigen::Matrix3d::Identity(), {0, 0, 0});
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  const Eigen::Vector3d h(0.5, 0.5, 0.5);
  // Face touching at x = 1.
  EXPECT_EQ(classifyEllipsoidBox(e, h, I, {1.5, 0, 0}).status, Separation::Touching);
  EXPECT_EQ(classifyEllipsoidBox(e, h, I, {1.5 + 1e-9, 0, 0}).status, Separation::Separated);
  EXPECT_EQ(classifyEllipsoidBox(e, h, I, {1.5 - 1e-9, 0, 0}).status, Separation::Overlapping);
  // Edge touching: the box edge at z = 3 above the top of the ellipsoid, tilted 45 degrees.
  const Eigen::Matrix3d Rz45 = Eigen::AngleAxisd(M_PI / 4, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const double lift = 0.5 * std::sqrt(2.0);
  EXPECT_EQ(classifyEllipsoidBox(e, h, Rz45, {0, 0, 3 + lift * (1 + 1e-9)}).status, Separation::Separated);
  EXPECT_EQ(classifyEllipsoidBox(e, h, Rz45, {0, 0, 3 + lift * (1 - 1e-9)}).status, Separation::Overlapping);
  // Box containing the ellipsoid and ellipsoid containing the box.
  EXPECT_EQ(classifyEllipsoidBox(e, {5, 5, 5}, I, {0, 0, 0}).status, Separation::Overlapping);
  EXPECT_EQ(classifyEllipsoidBox(e, {0.1, 0.1, 0.1}, I, {0, 0, 0}).status, Separation::Overlapping);
  // A flat box (zero extent) is a rectangle.
  EXPECT_EQ(classifyEllipsoidBox(e, {0.5, 0.5, 0.0}, I, {0, 0, 3.5}).status, Separation::Separated);
  EXPECT_EQ(classifyEllipsoidBox(e, {0.5, 0.5, 0.0}, I, {0, 0, 2.5}).status, Separation::Overlapping);
}

TEST(EllipsoidTriangle, AgreesWithProjectedGradientOracle) {
  std::mt19937_64 rng(103);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  int counts[3] = {0, 0, 0};
  for (int i = 0; i < 600; ++i) {
    const Ellipsoid e(test::randomRadii(rng, 1.5, 10.0), test::randomRotation(rng), {u(rng), u(rng), u(rng)});
    const Eigen::Vector3d a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng));
    const EllipsoidPolytopeResult r = classifyEllipsoidTriangle(e, a, b, c);
    ++counts[static_cast<int>(r.status)];
    const long double oracle = oracleMin(
        e, 2,
        [](long double* s) {
          // Euclidean projection onto the standard triangle {s >= 0, s0 + s1 <= 1}: the point itself
          // if inside, else the nearest of its projections onto the three edges.
          s[2] = 0;
          if (s[0] >= 0 && s[1] >= 0 && s[0] + s[1] <= 1) return;
          const long double P[3][2] = {{0, 0}, {1, 0}, {0, 1}};
          long double best[2] = {0, 0}, bd = 1e300L;
          for (int k = 0; k < 3; ++k) {
            const long double* p0 = P[k];
            const long double* p1 = P[(k + 1) % 3];
            const long double d0 = p1[0] - p0[0], d1 = p1[1] - p0[1];
            long double t = ((s[0] - p0[0]) * d0 + (s[1] - p0[1]) * d1) / (d0 * d0 + d1 * d1);
            t = std::max(0.0L, std::min(1.0L, t));
            const long double q0 = p0[0] + t * d0, q1 = p0[1] + t * d1;
            const long double dd = (q0 - s[0]) * (q0 - s[0]) + (q1 - s[1]) * (q1 - s[1]);
            if (dd < bd) {
              bd = dd;
              best[0] = q0;
              best[1] = q1;
            }
          }
          s[0] = best[0];
          s[1] = best[1];
        },
        [&](const long double* s) { return Eigen::Vector3d(a + double(s[0]) * (b - a) + double(s[1]) * (c - a)); });
    ASSERT_LE(r.unit_distance2, double(oracle) + 1e-9 * (1 + double(oracle))) << "case " << i;
    ASSERT_NEAR(r.unit_distance2, double(oracle), 1e-6 * (1 + double(oracle))) << "case " << i;
    if (std::fabs(double(oracle) - 1.0) > 1e-6) {
      ASSERT_EQ(r.status, oracle < 1 ? Separation::Overlapping : Separation::Separated) << "case " << i;
    }
  }
  EXPECT_GT(counts[0], 100);
  EXPECT_GT(counts[2], 50);
}

TEST(EllipsoidTriangle, TangencyAndDegenerateTriangles) {
  const Ellipsoid e({1, 2, 3}, Eigen::Matrix3d::Identity(), {0, 0, 0});
  // A triangle in the plane z = 3 containing the top point: touching; just above/below.
  EXPECT_EQ(classifyEllipsoidTriangle(e, {-1, -1, 3}, {1, -1, 3}, {0, 1, 3}).status, Separation::Touching);
  EXPECT_EQ(classifyEllipsoidTriangle(e, {-1, -1, 3 + 3e-9}, {1, -1, 3 + 3e-9}, {0, 1, 3 + 3e-9}).status,
            Separation::Separated);
  EXPECT_EQ(classifyEllipsoidTriangle(e, {-1, -1, 3 - 3e-9}, {1, -1, 3 - 3e-9}, {0, 1, 3 - 3e-9}).status,
            Separation::Overlapping);
  // Degenerate: a segment through the centre, and a point outside.
  EXPECT_EQ(classifyEllipsoidTriangle(e, {-5, 0, 0}, {5, 0, 0}, {0, 0, 0}).status, Separation::Overlapping);
  EXPECT_EQ(classifyEllipsoidTriangle(e, {2, 0, 0}, {2, 0, 0}, {2, 0, 0}).status, Separation::Separated);
  EXPECT_THROW(classifyEllipsoidTriangle(e, {0, 0, std::nan("")}, {1, 0, 0}, {0, 1, 0}), std::invalid_argument);
  EXPECT_THROW(classifyEllipsoidBox(e, {1, -1, 1}, Eigen::Matrix3d::Identity(), {0, 0, 0}), std::invalid_argument);
}

/// Signed distance of ellipsoid vs polytope: the dual value phi at the returned normal must be at
/// least the maximum of phi over 20,000 sampled directions (no better direction exists), the
/// witness points must realise it, and for separate pairs the primal (sampled polytope points'
/// distance to the ellipsoid) must not be below it.
template <class Make>
void checkPolytopeDistance(std::uint64_t seed, Make make, int cases) {
  std::mt19937_64 rng(seed);
  const auto dirs = test::fibonacciSphere(20000);
  int counts[3] = {0, 0, 0};
  for (int i = 0; i < cases; ++i) {
    std::vector<Eigen::Vector3d> verts;
    const Ellipsoid e = test::anchorEllipsoid(rng);
    const SignedDistanceResult d = make(rng, e, &verts);
    ++counts[static_cast<int>(d.status)];
    auto phi = [&](const Eigen::Vector3d& n) {
      double m = 1e300;
      for (const auto& v : verts) m = std::min(m, n.dot(v));
      return m - e.support(n);
    };
    double sampled = -1e300;
    for (const auto& n : dirs) sampled = std::max(sampled, phi(n));
    if (d.status == Separation::Touching) continue;
    ASSERT_EQ(d.distance > 0, d.status == Separation::Separated);
    ASSERT_NEAR(phi(d.normal), d.distance, 1e-12 * (1 + std::fabs(d.distance))) << "case " << i;
    ASSERT_GE(d.distance, sampled - 1e-12 * (1 + std::fabs(sampled))) << "case " << i << ": a better direction exists";
    ASSERT_NEAR(e.implicit(d.point_a), 0.0, 1e-12);
    ASSERT_NEAR((d.point_b - d.point_a).norm(), std::fabs(d.distance), 1e-12 * (1 + std::fabs(d.distance)));
  }
  EXPECT_GT(counts[0], cases / 10);
  EXPECT_GT(counts[2], cases / 10);
}

// Thin ellipsoids (radii L, 1, 1) against single points (a box with zero extents, a triangle with
// three equal vertices) just outside or inside the surface, near the support point along a
// direction m with (R^T m)_long ~ 1/L. There the point lies ~L from the centre, so the unit-frame
// coordinates S^-1 R^T (x - c) carry an absolute rounding of ~eps L, which their own magnitude (~1)
// does not bound: before the absolute term (tolerances.h, kUnitFrameRoundingBound) the
// certificates called such points inside or outside wrongly at L = 10^6 and 10^9. Exact oracle:
// |S^-1 R^T (x - c)|^2 - 1 in rationals, with the ellipsoid's stored R.
TEST(EllipsoidPolytope, PointsNearTheTipOfThinEllipsoidsAgreeWithTheExactInsideTest) {
  std::mt19937_64 rng(53);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto exactSide = [](const Ellipsoid& e, const Eigen::Vector3d& x) {  // -1 inside, 0 on, +1 outside
    return sgn(test::exactImplicit(e, x));
  };
  for (double L : {1e3, 1e6, 1e9}) {
    int inside = 0, outside = 0, decided = 0;
    for (int i = 0; i < 150; ++i) {
      const Ellipsoid e(Eigen::Vector3d(L, 1.0, 1.0), test::randomRotation(rng), Eigen::Vector3d::Zero());
      const double x0 = u(rng) * 3.0 / L, y0 = u(rng), z0 = u(rng);
      const Eigen::Vector3d m = (e.rotation() * Eigen::Vector3d(x0, y0, z0)).normalized();
      const Eigen::Vector3d q = e.supportPoint(m);
      const double h = e.support(m);
      for (double delta : {-1e-3, -1e-6, -1e-9, -1e-10, -1e-11, 1e-11, 1e-10, 1e-9, 1e-6, 1e-3}) {
        const Eigen::Vector3d x = q + (delta * h) * m;
        const int side = exactSide(e, x);
        (side < 0 ? inside : outside)++;
        const Separation box = classifyEllipsoidBox(e, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(), x).status;
        const Separation fast = ellipsoidBoxStatus(e, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(), x);
        const Separation tri = classifyEllipsoidTriangle(e, x, x, x).status;
        for (Separation s : {box, fast, tri}) {
          if (s == Separation::Touching) continue;
          ++decided;
          ASSERT_EQ(s == Separation::Overlapping ? -1 : 1, side) << "L " << L << " case " << i << " delta " << delta;
        }
      }
    }
    EXPECT_GT(inside, 100) << "L " << L;  // not vacuous: both sides occur near the surface,
    EXPECT_GT(outside, 100) << "L " << L;
    // and the points farther out are decided (the band grows with L: ~1e-5 relative at 1:10^9).
    EXPECT_GT(decided, L < 1e8 ? 1200 : 600) << "L " << L;
  }
}

TEST(EllipsoidBoxDistance, IsOptimalAgainstDirectionSampling) {
  std::uniform_real_distribution<double> u(-3.0, 3.0), uh(0.1, 2.0);
  checkPolytopeDistance(
      105,
      [&](std::mt19937_64& rng, const Ellipsoid& e, std::vector<Eigen::Vector3d>* verts) {
        const Eigen::Vector3d h(uh(rng), uh(rng), uh(rng));
        const Eigen::Matrix3d R = test::randomRotation(rng);
        const Eigen::Vector3d c(u(rng), u(rng), u(rng));
        for (int k = 0; k < 8; ++k)
          verts->push_back(c + R * Eigen::Vector3d((k & 1) ? h[0] : -h[0], (k & 2) ? h[1] : -h[1], (k & 4) ? h[2] : -h[2]));
        return signedDistanceEllipsoidBox(e, h, R, c);
      },
      600);
}

TEST(EllipsoidTriangleDistance, IsOptimalAgainstDirectionSampling) {
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  checkPolytopeDistance(
      107,
      [&](std::mt19937_64& rng, const Ellipsoid& e, std::vector<Eigen::Vector3d>* verts) {
        const Eigen::Vector3d a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng));
        *verts = {a, b, c};
        return signedDistanceEllipsoidTriangle(e, a, b, c);
      },
      600);
}

TEST(EllipsoidBoxDistance, AxisAlignedClosedForms) {
  const Ellipsoid e({1, 2, 3}, Eigen::Matrix3d::Identity(), {0, 0, 0});
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  SignedDistanceResult d = signedDistanceEllipsoidBox(e, {0.5, 0.5, 0.5}, I, {2.5, 0, 0});  // face at x = 2
  EXPECT_NEAR(d.distance, 1.0, 1e-14);
  EXPECT_NEAR((d.normal - Eigen::Vector3d::UnitX()).norm(), 0.0, 1e-12);
  d = signedDistanceEllipsoidBox(e, {0.5, 0.5, 0.5}, I, {1.25, 0, 0});  // face at x = 0.75
  EXPECT_NEAR(d.distance, -0.25, 1e-14);
}

}  // namespace
}  // namespace fcl_quadric
