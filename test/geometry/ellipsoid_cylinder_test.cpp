// Ellipsoid vs cylinder and cone: exact closed-form oracle for spheres (point-to-solid distance
// minus the radius, including near-tangent pairs), a primal-dual gap with an independent support
// function, a dense parameter-grid oracle for the status, direction sampling for penetration
// depth, rigid-motion invariance, degenerate solids and bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "fcl_quadric/geometry/ellipsoid_capsule.h"
#include "fcl_quadric/geometry/ellipsoid_cylinder.h"
#include "fcl_quadric/tolerances.h"
#include "support/random_ellipsoids.h"

namespace fcl_quadric {
namespace {

enum class Kind { kCylinder, kCone };

struct Solid {
  Kind kind = Kind::kCylinder;
  double r = 1.0, L = 1.0;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  const char* name() const { return kind == Kind::kCylinder ? "cylinder" : "cone"; }
};

SignedDistanceResult kernel(const Ellipsoid& e, const Solid& s) {
  return s.kind == Kind::kCylinder ? signedDistanceEllipsoidCylinder(e, s.r, s.L, s.R, s.p)
                                   : signedDistanceEllipsoidCone(e, s.r, s.L, s.R, s.p);
}

// --- Independent oracles -----------------------------------------------------------------------

/// Distance from (x, y) to the segment (x0, y0)-(x1, y1) in the plane.
double segment2(double x, double y, double x0, double y0, double x1, double y1) {
  const double dx = x1 - x0, dy = y1 - y0, l2 = dx * dx + dy * dy;
  double t = l2 > 0 ? ((x - x0) * dx + (y - y0) * dy) / l2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(x - x0 - t * dx, y - y0 - t * dy);
}

/// Signed distance from a point to the solid (negative inside), from its axial profile: in the
/// half-plane (rho >= 0, z) the solid is a rectangle (cylinder) or a triangle (cone) and a
/// rotationally symmetric solid's distance is the profile's.
double pointSolidSignedDistance(const Solid& s, const Eigen::Vector3d& x) {
  const Eigen::Vector3d l = s.R.transpose() * (x - s.p);
  const double rho = std::hypot(l.x(), l.y()), z = l.z(), h = 0.5 * s.L;
  double d;
  bool inside;
  if (s.kind == Kind::kCylinder) {
    d = std::min({segment2(rho, z, 0, -h, s.r, -h), segment2(rho, z, s.r, -h, s.r, h), segment2(rho, z, s.r, h, 0, h)});
    inside = rho <= s.r && std::fabs(z) <= h;
  } else {
    d = std::min(segment2(rho, z, 0, -h, s.r, -h), segment2(rho, z, s.r, -h, 0, h));
    inside = z >= -h && z <= h && rho * s.L <= s.r * (h - z);
  }
  return inside ? -d : d;
}

/// Support point of the solid in direction m (libccd-style formulas, written independently).
Eigen::Vector3d supportPointSolid(const Solid& s, const Eigen::Vector3d& m) {
  const Eigen::Vector3d a = s.R.col(2);
  const Eigen::Vector3d rad = m - m.dot(a) * a;
  const double rn = rad.norm();
  // Along the axis the whole cap supports the solid: its centre (rad is rounding noise there).
  const Eigen::Vector3d rim = rn > 1e-12 * m.norm() ? Eigen::Vector3d(s.r * rad / rn) : Eigen::Vector3d::Zero();
  if (s.kind == Kind::kCylinder) return s.p + (m.dot(a) >= 0 ? 0.5 : -0.5) * s.L * a + rim;
  const Eigen::Vector3d apex = s.p + 0.5 * s.L * a, base = s.p - 0.5 * s.L * a + rim;
  return m.dot(apex) >= m.dot(base) ? apex : base;
}

double phiTest(const Ellipsoid& e, const Solid& s, const Eigen::Vector3d& n) {
  return -e.support(n) + n.dot(supportPointSolid(s, -n));
}

/// Membership of the closed solid, with an absolute slack.
bool inSolid(const Solid& s, const Eigen::Vector3d& x, double slack) {
  return pointSolidSignedDistance(s, x) <= slack;
}

Solid randomSolid(std::mt19937_64& rng, Kind kind) {
  std::uniform_real_distribution<double> u(-2.5, 2.5), ur(0.1, 1.5), ul(0.1, 3.0);
  Solid s;
  s.kind = kind;
  s.r = ur(rng);
  s.L = ul(rng);
  s.R = test::randomRotation(rng);
  s.p = Eigen::Vector3d(u(rng), u(rng), u(rng));
  return s;
}

/// A boundary point of the solid with a unit outward normal in its normal cone: feature 0 the
/// side (slant), 1 the base cap, 2 the top cap (cylinder) or the apex (cone), 3 a rim of the base,
/// 4 the top rim (cylinder).
void boundaryPoint(std::mt19937_64& rng, const Solid& s, int feature, Eigen::Vector3d* y, Eigen::Vector3d* nu) {
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  const double th = 2 * M_PI * u01(rng), h = 0.5 * s.L;
  const Eigen::Vector3d w(std::cos(th), std::sin(th), 0.0), ez(0, 0, 1);
  const double slant_len = std::hypot(s.L, s.r);
  const Eigen::Vector3d slant_n = s.kind == Kind::kCylinder ? w : Eigen::Vector3d((s.L * w + s.r * ez) / slant_len);
  Eigen::Vector3d ly = Eigen::Vector3d::Zero(), ln = Eigen::Vector3d::UnitZ();
  const double t = 0.05 + 0.9 * u01(rng), mix = 0.05 + 0.9 * u01(rng);
  switch (feature) {
    case 0:
      ly = s.kind == Kind::kCylinder ? Eigen::Vector3d(s.r * w + (2 * t - 1) * h * ez)
                                     : Eigen::Vector3d((1 - t) * (s.r * w - h * ez) + t * h * ez);
      ln = slant_n;
      break;
    case 1:
      ly = std::sqrt(t) * 0.95 * s.r * w - h * ez;
      ln = -ez;
      break;
    case 2:
      if (s.kind == Kind::kCylinder) {
        ly = std::sqrt(t) * 0.95 * s.r * w + h * ez;
        ln = ez;
      } else {  // apex: any direction in its normal cone (angle to the axis <= atan(L/r))
        ly = h * ez;
        ln = ((1 - mix) * ez + mix * slant_n).normalized();
      }
      break;
    case 3:
      ly = s.r * w - h * ez;
      ln = ((1 - mix) * (-ez) + mix * slant_n).normalized();
      break;
    default:
      ly = s.r * w + h * ez;
      ln = ((1 - mix) * ez + mix * w).normalized();
      break;
  }
  *y = s.p + s.R * ly;
  *nu = s.R * ln;
}

// --- Tests -------------------------------------------------------------------------------------

TEST(EllipsoidCylinder, SpheresMatchTheClosedFormIncludingPenetration) {
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> u(-3.0, 3.0), urs(0.2, 2.0);
  for (Kind kind : {Kind::kCylinder, Kind::kCone}) {
    int counts[3] = {0, 0, 0};
    double worst = 0.0;
    for (int i = 0; i < 2000; ++i) {
      const Solid s = randomSolid(rng, kind);
      const double rs = urs(rng);
      const Eigen::Vector3d c(u(rng), u(rng), u(rng));
      const Ellipsoid e = Ellipsoid::sphere(rs, c);
      const double truth = pointSolidSignedDistance(s, c) - rs;
      const SignedDistanceResult d = kernel(e, s);
      ++counts[static_cast<int>(d.status)];
      const double scale = (s.p - c).norm() + s.L + s.r + rs;
      if (truth > 1e-9 * scale) {
        ASSERT_EQ(d.status, Separation::Separated) << s.name() << " " << i;
      }
      if (truth < -1e-9 * scale) {
        ASSERT_EQ(d.status, Separation::Overlapping) << s.name() << " " << i;
      }
      ASSERT_NEAR(d.distance, truth, 1e-9 * scale) << s.name() << " " << i << " status " << static_cast<int>(d.status);
      worst = std::max(worst, std::fabs(d.distance - truth) / scale);
      if (d.status == Separation::Separated) {
        ASSERT_NEAR((d.point_b - d.point_a).norm(), d.distance, 1e-9 * scale);
        ASSERT_TRUE(inSolid(s, d.point_b, 1e-9 * scale)) << i;
      }
      ASSERT_NEAR(d.normal.norm(), 1.0, 1e-12);
    }
    std::printf("[ info     ] %s vs sphere: %d separated, %d touching, %d overlapping; worst |d - exact| / scale = %.3g\n",
                kind == Kind::kCylinder ? "cylinder" : "cone", counts[0], counts[1], counts[2], worst);
    EXPECT_GT(counts[static_cast<int>(Separation::Separated)], 300);
    EXPECT_GT(counts[static_cast<int>(Separation::Overlapping)], 200);
  }
}

TEST(EllipsoidCylinder, NearTangentSpheresAtRelativeGaps) {
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> urs(0.2, 2.0);
  for (Kind kind : {Kind::kCylinder, Kind::kCone}) {
    const int features = kind == Kind::kCylinder ? 5 : 4;
    int inward = 0, inward_overlapping = 0;
    double worst = 0.0;
    for (double gap : {1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8}) {
      for (int i = 0; i < 100; ++i) {
        const Solid s = randomSolid(rng, kind);
        Eigen::Vector3d y, nu;
        boundaryPoint(rng, s, i % features, &y, &nu);
        const double rs = urs(rng);
        for (int side : {+1, -1}) {
          const Eigen::Vector3d c = y + rs * (1.0 + side * gap) * nu;
          const Ellipsoid e = Ellipsoid::sphere(rs, c);
          const double truth = pointSolidSignedDistance(s, c) - rs;
          ASSERT_NEAR(truth, side * gap * rs, 1e-12 * (1 + rs)) << "construction";
          const SignedDistanceResult d = kernel(e, s);
          const double scale = (s.p - c).norm() + s.L + s.r + rs;
          if (side > 0) {
            ASSERT_EQ(d.status, Separation::Separated) << s.name() << " gap " << gap << " feature " << i % features;
          } else {
            ASSERT_NE(d.status, Separation::Separated) << s.name() << " gap " << gap << " feature " << i % features;
            ++inward;
            inward_overlapping += d.status == Separation::Overlapping;
          }
          ASSERT_NEAR(d.distance, truth, 1e-9 * scale) << s.name() << " gap " << gap << " feature " << i % features;
          worst = std::max(worst, std::fabs(d.distance - truth) / scale);
        }
      }
    }
    std::printf("[ info     ] %s near-tangent spheres: %d inward, %d certified Overlapping (rest Touching); worst "
                "|d - exact| / scale = %.3g\n",
                kind == Kind::kCylinder ? "cylinder" : "cone", inward, inward_overlapping, worst);
    EXPECT_GT(inward_overlapping, inward * 9 / 10);
  }
}

TEST(EllipsoidCylinder, SeparatedEllipsoidsHaveNoPrimalDualGap) {
  // Lower bound: phi(n) with an independent support function. Upper bound: |point_b - point_a|
  // with point_a on the ellipsoid and point_b in the solid. The exact distance lies in between.
  std::mt19937_64 rng(31);
  for (Kind kind : {Kind::kCylinder, Kind::kCone}) {
    int separated = 0;
    double worst = 0.0;
    for (int i = 0; i < 2000; ++i) {
      const Ellipsoid e = test::anchorEllipsoid(rng);
      const Solid s = randomSolid(rng, kind);
      const SignedDistanceResult d = kernel(e, s);
      if (d.status != Separation::Separated) continue;
      ++separated;
      const double scale = (s.p - e.center()).norm() + s.L + s.r + e.maxRadius();
      const double lower = phiTest(e, s, d.normal);
      const double upper = (d.point_b - d.point_a).norm();
      ASSERT_NEAR(e.implicit(d.point_a), 0.0, 1e-12) << i;
      ASSERT_TRUE(inSolid(s, d.point_b, 1e-10 * scale))
          << s.name() << " " << i << " sd " << pointSolidSignedDistance(s, d.point_b) << " d " << d.distance;
      ASSERT_LE(upper - lower, 1e-9 * scale) << s.name() << " " << i;
      ASSERT_NEAR(d.distance, lower, 1e-12 * scale);
      worst = std::max(worst, (upper - lower) / scale);
    }
    std::printf("[ info     ] %s vs ellipsoid: %d separated pairs, worst (primal - dual) / scale = %.3g\n",
                kind == Kind::kCylinder ? "cylinder" : "cone", separated, worst);
    EXPECT_GT(separated, 500);
  }
}

/// Slow oracle: min over the solid of |S^-1 R^T (y - c)|^2 by a dense grid in (t, s, theta) and
/// a coordinate-search polish.
double gridMinimum(const Ellipsoid& e, const Solid& s) {
  auto point = [&](double t, double sr, double th) {
    const double rho = s.kind == Kind::kCylinder ? s.r : s.r * (1 - t);
    return Eigen::Vector3d(s.p + (sr * rho * std::cos(th)) * s.R.col(0) + (sr * rho * std::sin(th)) * s.R.col(1) +
                           (s.L * (t - 0.5)) * s.R.col(2));
  };
  auto f = [&](double t, double sr, double th) {
    return e.implicit(point(std::clamp(t, 0.0, 1.0), std::clamp(sr, 0.0, 1.0), th)) + 1.0;
  };
  double bt = 0, bs = 0, bth = 0, best = 1e300;
  for (int i = 0; i <= 16; ++i)
    for (int j = 0; j <= 8; ++j)
      for (int k = 0; k < 24; ++k) {
        const double v = f(i / 16.0, j / 8.0, 2 * M_PI * k / 24);
        if (v < best) best = v, bt = i / 16.0, bs = j / 8.0, bth = 2 * M_PI * k / 24;
      }
  for (double step = 0.05; step > 1e-9; step *= 0.5) {
    bool moved = true;
    while (moved) {
      moved = false;
      for (int dim = 0; dim < 3; ++dim)
        for (int sg : {-1, 1}) {
          double t = bt, sr = bs, th = bth;
          (dim == 0 ? t : dim == 1 ? sr : th) += sg * step * (dim == 2 ? 6.0 : 1.0);
          t = std::clamp(t, 0.0, 1.0);
          sr = std::clamp(sr, 0.0, 1.0);
          const double v = f(t, sr, th);
          if (v < best) best = v, bt = t, bs = sr, bth = th, moved = true;
        }
    }
  }
  return best;
}

TEST(EllipsoidCylinder, StatusAgreesWithADenseGridOracleAwayFromTangency) {
  std::mt19937_64 rng(57);
  for (Kind kind : {Kind::kCylinder, Kind::kCone}) {
    int checked = 0;
    for (int i = 0; i < 300; ++i) {
      const Ellipsoid e = test::anchorEllipsoid(rng);
      const Solid s = randomSolid(rng, kind);
      const double m = gridMinimum(e, s);
      const SignedDistanceResult d = kernel(e, s);
      if (m < 0.98) {
        ASSERT_EQ(d.status, Separation::Overlapping) << s.name() << " " << i << " grid min " << m;
        ++checked;
      } else if (m > 1.02) {
        ASSERT_EQ(d.status, Separation::Separated) << s.name() << " " << i << " grid min " << m;
        ++checked;
      }
    }
    EXPECT_GT(checked, 250);
  }
}

TEST(EllipsoidCylinder, PenetrationDepthBeatsDirectionSampling) {
  std::mt19937_64 rng(91);
  const auto dirs = test::fibonacciSphere(4000);
  for (Kind kind : {Kind::kCylinder, Kind::kCone}) {
    int overlapping = 0;
    for (int i = 0; i < 800 && overlapping < 150; ++i) {
      const Ellipsoid e = test::anchorEllipsoid(rng);
      const Solid s = randomSolid(rng, kind);
      const SignedDistanceResult d = kernel(e, s);
      if (d.status != Separation::Overlapping) continue;
      ++overlapping;
      const double scale = (s.p - e.center()).norm() + s.L + s.r + e.maxRadius();
      double sampled = -1e300;
      for (const Eigen::Vector3d& n : dirs) sampled = std::max(sampled, phiTest(e, s, n));
      ASSERT_GE(d.distance, sampled - 1e-12 * scale) << s.name() << " " << i;
      ASSERT_LE(d.distance, sampled + 2e-2 * scale) << s.name() << " " << i;  // sampling resolution
      ASSERT_NEAR(phiTest(e, s, d.normal), d.distance, 1e-12 * scale);
    }
    EXPECT_GT(overlapping, 100);
  }
}

TEST(EllipsoidCylinder, InvariantUnderRigidMotions) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-50.0, 50.0);
  for (Kind kind : {Kind::kCylinder, Kind::kCone}) {
    for (int i = 0; i < 300; ++i) {
      const Ellipsoid e = test::anchorEllipsoid(rng);
      const Solid s = randomSolid(rng, kind);
      const Eigen::Matrix3d Q = test::randomRotation(rng);
      const Eigen::Vector3d t(u(rng), u(rng), u(rng));
      const Ellipsoid e2(e.radii(), Q * e.rotation(), Q * e.center() + t);
      Solid s2 = s;
      s2.R = Q * s.R;
      s2.p = Q * s.p + t;
      const SignedDistanceResult d1 = kernel(e, s), d2 = kernel(e2, s2);
      const double scale = (s.p - e.center()).norm() + s.L + s.r + e.maxRadius() + t.norm();
      if (std::fabs(d1.distance) > 1e-8 * scale) {
        ASSERT_EQ(d1.status, d2.status) << i;
      }
      ASSERT_NEAR(d1.distance, d2.distance, 1e-9 * scale) << s.name() << " " << i;
      if (d1.status == Separation::Separated && d1.distance > 1e-3) {
        ASSERT_NEAR((Q * d1.point_a + t - d2.point_a).norm(), 0.0, 1e-6 * scale) << i;
      }
    }
  }
}

TEST(EllipsoidCylinder, DegenerateSolids) {
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> u(-3.0, 3.0), ul(0.0, 3.0);
  for (int i = 0; i < 300; ++i) {
    const Ellipsoid e = test::anchorEllipsoid(rng);
    const Eigen::Matrix3d R = test::randomRotation(rng);
    const Eigen::Vector3d p(u(rng), u(rng), u(rng));
    const double L = ul(rng);
    // Radius 0: both solids are the axis segment, the capsule of radius 0.
    const SignedDistanceResult seg = signedDistanceEllipsoidCapsule(e, 0.0, L, R, p);
    for (const SignedDistanceResult& d :
         {signedDistanceEllipsoidCylinder(e, 0.0, L, R, p), signedDistanceEllipsoidCone(e, 0.0, L, R, p)}) {
      ASSERT_EQ(d.status, seg.status) << i;
      ASSERT_NEAR(d.distance, seg.distance, 1e-9 * (1 + std::fabs(seg.distance))) << i;
    }
    // Length 0: a disk; the cylinder and the cone are the same disk.
    const double r = 0.1 + ul(rng);
    const SignedDistanceResult c0 = signedDistanceEllipsoidCylinder(e, r, 0.0, R, p);
    const SignedDistanceResult k0 = signedDistanceEllipsoidCone(e, r, 0.0, R, p);
    ASSERT_EQ(c0.status, k0.status) << i;
    ASSERT_NEAR(c0.distance, k0.distance, 1e-9) << i;
  }
  // A point (radius and length 0) at the ellipsoid's centre and far away.
  const Ellipsoid e({1, 2, 3}, Eigen::Matrix3d::Identity(), {0, 0, 0});
  EXPECT_EQ(signedDistanceEllipsoidCylinder(e, 0, 0, Eigen::Matrix3d::Identity(), {0, 0, 0}).status,
            Separation::Overlapping);
  EXPECT_NEAR(signedDistanceEllipsoidCone(e, 0, 0, Eigen::Matrix3d::Identity(), {3, 0, 0}).distance, 2.0, 1e-14);
  // Axis-aligned exact values: cylinder cap at distance 0.5 above the ellipsoid's top.
  EXPECT_NEAR(signedDistanceEllipsoidCylinder(e, 0.5, 1.0, Eigen::Matrix3d::Identity(), {0, 0, 4}).distance, 0.5, 1e-14);
  EXPECT_NEAR(signedDistanceEllipsoidCone(e, 0.5, 1.0, Eigen::Matrix3d::Identity(), {0, 0, 4}).distance, 0.5, 1e-14);
  EXPECT_EQ(signedDistanceEllipsoidCylinder(e, 0.5, 1.0, Eigen::Matrix3d::Identity(), {0, 0, 3.5}).status,
            Separation::Touching);
  // Axis-aligned poses (zero principal coordinates): side at x = 3, apex above the top.
  EXPECT_NEAR(signedDistanceEllipsoidCylinder(e, 0.5, 1.0, Eigen::Matrix3d::Identity(), {3, 0, 0}).distance, 1.5, 1e-14);
  const Eigen::Matrix3d flip = Eigen::Vector3d(1, -1, -1).asDiagonal();  // apex down
  EXPECT_NEAR(signedDistanceEllipsoidCone(e, 0.5, 1.0, flip, {0, 0, 4}).distance, 0.5, 1e-14);
  EXPECT_EQ(signedDistanceEllipsoidCone(e, 0.5, 1.0, flip, {0, 0, 2}).status, Separation::Overlapping);
}

// Distance bounds of a point x from the solid { y : |S^-1 R^T (y - c)| <= 1 } along the outward
// direction m, in long double (64-bit significand), independent of the library: lower =
// m.x - h(m) with the exact support h(m) = m.c + |S R^-1 m| (R^-1 m solved by Cramer's rule, as R
// is orthogonal only to rounding and a long radius magnifies the difference to R^T m), upper =
// the Euclidean distance of x (Lagrange multiplier of the nearest point by bisection).
struct LongDoubleBounds {
  long double lower, upper;
};
LongDoubleBounds pointBoundsAlong(const Ellipsoid& e, const Eigen::Vector3d& x, const Eigen::Vector3d& m) {
  typedef long double F;
  F R[3][3], r[3], w[3], z[3];
  for (int i = 0; i < 3; ++i) {
    r[i] = e.radii()[i];
    for (int j = 0; j < 3; ++j) R[i][j] = e.rotation()(i, j);
  }
  auto det3 = [](F a[3][3]) {
    return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
           a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  };
  const F D = det3(R);
  for (int k = 0; k < 3; ++k) {  // z = R^-1 m
    F A[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) A[i][j] = j == k ? F(m[i]) : R[i][j];
    z[k] = det3(A) / D;
  }
  F h = 0, mx = 0;
  for (int i = 0; i < 3; ++i) {
    h += (r[i] * z[i]) * (r[i] * z[i]);
    mx += F(m[i]) * (F(x[i]) - F(e.center()[i]));
    w[i] = 0;
    for (int j = 0; j < 3; ++j) w[i] += R[j][i] * (F(x[j]) - F(e.center()[j]));  // R^T (x - c)
  }
  auto g = [&](F t) {
    F v = -1;
    for (int i = 0; i < 3; ++i) v += (r[i] * w[i] / (r[i] * r[i] + t)) * (r[i] * w[i] / (r[i] * r[i] + t));
    return v;
  };
  F lo = 0, hi = 1;
  while (g(hi) > 0) hi *= 2;
  for (int it = 0; it < 200; ++it) (g(0.5L * (lo + hi)) > 0 ? lo : hi) = 0.5L * (lo + hi);
  F d2 = 0;
  for (int i = 0; i < 3; ++i) {
    const F y = r[i] * r[i] * w[i] / (r[i] * r[i] + hi);
    d2 += (y - w[i]) * (y - w[i]);
  }
  return {mx - std::sqrt(h), g(0) <= 0 ? F(0) : std::sqrt(d2)};
}

// Thin ellipsoids (radii L, 1, 1) against a capsule standing on its end and a cylinder and a cone
// standing on their base, at relative gaps of 1e-11 to 1e-3 near the support point along a
// direction m with (R^T m)_long ~ 1/L. The solids extend away from the ellipsoid along m, so their
// distance lies between the bounds of their nearest point along m (the base centre; for the
// capsule those of its end centre, less r), computed in long double. Before the absolute rounding terms (tolerances.h:
// "Supports", kUnitFrameRoundingBound) the capsule called separated pairs overlapping from a lower
// bound of the distance, and the witness of the cylinder and the cone called separated pairs
// overlapping at 1:10^6 and 1:10^9. Every certified status must agree with a decided oracle.
TEST(EllipsoidCylinder, ThinEllipsoidsNearTangencyAgreeWithExtendedPrecisionDistanceBounds) {
  std::mt19937_64 rng(59);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (double L : {1e3, 1e6}) {
    int decided = 0, oracle_sep = 0, oracle_ovl = 0;
    for (int i = 0; i < 40; ++i) {
      const Ellipsoid e(Eigen::Vector3d(L, 1.0, 1.0), test::randomRotation(rng), Eigen::Vector3d::Zero());
      const double x0 = u(rng) * 3.0 / L, y0 = u(rng), z0 = u(rng);
      const Eigen::Vector3d m = (e.rotation() * Eigen::Vector3d(x0, y0, z0)).normalized();
      const double h = e.support(m);
      const Eigen::Vector3d q = e.supportPoint(m);
      // A frame with its third axis along m.
      const Eigen::Vector3d t = (std::fabs(m.x()) < 0.6 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY());
      Eigen::Matrix3d R;
      R.col(2) = m;
      R.col(0) = (t - t.dot(m) * m).normalized();
      R.col(1) = m.cross(R.col(0));
      const double radius = 1.0, length = 1.0;
      for (double delta : {-1e-3, -1e-9, -1e-10, -1e-11, 1e-11, 1e-10, 1e-9, 1e-3}) {
        const Eigen::Vector3d x = q + (delta * h) * m;  // nearest centre of each solid
        const LongDoubleBounds b = pointBoundsAlong(e, x, m);
        const LongDoubleBounds end = pointBoundsAlong(e, x + radius * m, m);  // the capsule's end centre
        struct Case {
          const char* what;
          Separation status;
          long double lower, upper;  // bounds of the solid's distance
        };
        const Case cases[] = {
            {"capsule", signedDistanceEllipsoidCapsule(e, radius, length, R, x + (radius + 0.5 * length) * m).status,
             end.lower - radius, end.upper - radius},
            {"cylinder", signedDistanceEllipsoidCylinder(e, radius, length, R, x + (0.5 * length) * m).status, b.lower,
             b.upper},
            {"cone", signedDistanceEllipsoidCone(e, radius, length, R, x + (0.5 * length) * m).status, b.lower, b.upper},
        };
        for (const Case& c : cases) {
          const bool sep = c.lower > 0, ovl = c.upper < 0;
          oracle_sep += sep;
          oracle_ovl += ovl;
          if (c.status == Separation::Touching || !(sep || ovl)) continue;
          ++decided;
          ASSERT_EQ(c.status, sep ? Separation::Separated : Separation::Overlapping)
              << c.what << " L " << L << " case " << i << " delta " << delta;
        }
      }
    }
    EXPECT_GT(oracle_sep, 100) << "L " << L;  // not vacuous
    EXPECT_GT(oracle_ovl, 20) << "L " << L;
    EXPECT_GT(decided, 100) << "L " << L;
  }
}

TEST(EllipsoidCylinder, BadInputThrowsNamingTheValue) {
  const Ellipsoid e({1, 2, 3}, Eigen::Matrix3d::Identity(), {0, 0, 0});
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  const Eigen::Vector3d p(3, 0, 0);
  auto message = [](auto&& f) {
    try {
      f();
    } catch (const std::invalid_argument& ex) {
      return std::string(ex.what());
    }
    return std::string("no exception");
  };
  EXPECT_NE(message([&] { signedDistanceEllipsoidCylinder(e, -1.0, 1.0, I, p); }).find("cylinder radius"),
            std::string::npos);
  EXPECT_NE(message([&] { signedDistanceEllipsoidCylinder(e, 1.0, std::nan(""), I, p); }).find("cylinder length"),
            std::string::npos);
  EXPECT_NE(message([&] { signedDistanceEllipsoidCone(e, INFINITY, 1.0, I, p); }).find("cone radius"),
            std::string::npos);
  EXPECT_NE(message([&] { signedDistanceEllipsoidCone(e, 1.0, -2.0, I, p); }).find("cone length"), std::string::npos);
  EXPECT_NE(message([&] { signedDistanceEllipsoidCylinder(e, 1.0, 1.0, 2.0 * I, p); }).find("cylinder rotation"),
            std::string::npos);
  EXPECT_NE(message([&] { signedDistanceEllipsoidCone(e, 1.0, 1.0, I, Eigen::Vector3d(NAN, 0, 0)); }).find("cone centre"),
            std::string::npos);
}

}  // namespace
}  // namespace fcl_quadric
