// A sphere against a capped elliptic cylinder in closed form (signedDistanceSphereEllipticCylinder,
// sphere_solid.h) and its 2D solver (detail::closestPointPrincipal<2>, point_ellipsoid.h), checked
// against a 50-digit oracle (the secular equation bisected in boost::multiprecision), against
// tangent constructions whose distance is known by construction, and against the independent
// closed form of the circular cylinder.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>

#include <Eigen/Geometry>

#include "fcl_quadric/geometry/point_ellipsoid.h"
#include "fcl_quadric/geometry/sphere_solid.h"
#include "support/point_ellipsoid_oracle.h"

namespace fcl_quadric {
namespace {
namespace sphere_elliptic_cylinder_test {

double ellipseOracle(double e0, double e1, const Eigen::Vector2d& y) {
  return test::pointEllipsoidOracle<2>(Eigen::Vector2d(e0, e1), y);
}

/// The signed distance of the local point x to { u^2/a^2 + v^2/b^2 <= 1, |w| <= h }: the solid is
/// the product of the filled ellipse and [-h, h], so outside it is the norm of the positive parts
/// of the two signed distances, inside the larger (nearer) of them.
double cylinderOracle(double a, double b, double h, const Eigen::Vector3d& x) {
  const double side = ellipseOracle(a, b, Eigen::Vector2d(x.x(), x.y()));
  const double cap = std::fabs(x.z()) - h;
  if (side <= 0.0 && cap <= 0.0) return std::max(side, cap);
  return std::hypot(std::max(side, 0.0), std::max(cap, 0.0));
}

double logUniform(std::mt19937_64& rng, double lo, double hi) {
  return std::exp(std::uniform_real_distribution<double>(std::log(lo), std::log(hi))(rng));
}

Eigen::Matrix3d randomRotation(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  return Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
}

TEST(ClosestPointOnEllipseInDouble, MatchesAFiftyDigitOracleInsideOutsideAndNearTheAxes) {
  std::mt19937_64 rng(4501);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), angle(0.0, 6.283185307179586);
  double worst = 0.0;
  for (int k = 0; k < 4000; ++k) {
    const double e0 = logUniform(rng, 1e-3, 1e2);
    double e1 = e0 * logUniform(rng, 1e-3, 1e3);
    if (k % 5 == 0) e1 = e0 * (1.0 + 1e-9 * unit(rng));  // nearly circular
    const double size = std::max(e0, e1);
    const double phi = angle(rng);
    // Radii from the centre to far outside, and near the boundary.
    double rho = size * (k % 3 == 0 ? 3.0 * std::fabs(unit(rng)) : 0.2 + 1.6 * std::fabs(unit(rng)));
    Eigen::Vector2d y(rho * std::cos(phi), rho * std::sin(phi));
    if (k % 11 == 0) y[0] *= 1e-12;  // next to an axis
    if (k % 13 == 0) y[1] *= 1e-12;
    if (y[0] == 0.0 || y[1] == 0.0) continue;
    Eigen::Vector2d x;
    const double d = detail::closestPointPrincipal<2>(Eigen::Vector2d(e0, e1), y, &x);
    const double oracle = ellipseOracle(e0, e1, y);
    const double scale = y.norm() + size;
    worst = std::max(worst, std::fabs(d - oracle) / scale);
    ASSERT_NEAR(d, oracle, 4e-15 * scale) << "e " << e0 << " " << e1 << " y " << y.transpose();
    // The point is on the ellipse, on y's side of both axes, and at the distance returned.
    EXPECT_NEAR((x[0] / e0) * (x[0] / e0) + (x[1] / e1) * (x[1] / e1), 1.0, 1e-14);
    EXPECT_GE(x[0] * y[0], 0.0);
    EXPECT_GE(x[1] * y[1], 0.0);
    EXPECT_NEAR((x - y).norm(), std::fabs(d), 4e-15 * scale);
  }
  RecordProperty("worst_relative_error", std::to_string(worst));
}

TEST(ClosestPointOnEllipseInDouble, PointsOnAnAxisAreTheLimitsOfTheirNeighbours) {
  // On the major axis (Eberly's closed-form case) the distance is continuous: it matches the
  // solver's answer 1e-13 off the axis, inside the evolute's cusp and beyond it, and at the centre.
  for (const double e1 : {0.3, 0.7, 2.0}) {
    const double e0 = 1.0;
    const int major = e0 >= e1 ? 0 : 1;
    const double emaj = std::max(e0, e1);
    for (const double s : {0.0, 0.1, 0.4, 0.9, 1.0, 1.5, 4.0}) {
      Eigen::Vector2d y = Eigen::Vector2d::Zero(), near = Eigen::Vector2d::Zero(), x, xn;
      y[major] = s * emaj;
      near = y;
      near[1 - major] = 1e-13;
      const double d = detail::closestPointPrincipal<2>(Eigen::Vector2d(e0, e1), y, &x);
      const double dn = detail::closestPointPrincipal<2>(Eigen::Vector2d(e0, e1), near, &xn);
      EXPECT_NEAR(d, dn, 1e-12) << "e1 " << e1 << " s " << s;
      EXPECT_NEAR((x[0] / e0) * (x[0] / e0) + (x[1] / e1) * (x[1] / e1), 1.0, 1e-14);
    }
  }
}

/// A random capped elliptic cylinder (semi-axes 0.05-5, aspect up to 1:100, length 0.01-10), posed.
struct PosedCylinder {
  double a, b, length;
  Eigen::Matrix3d R;
  Eigen::Vector3d p;
};
PosedCylinder randomCylinder(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  PosedCylinder c;
  c.a = logUniform(rng, 0.05, 5.0);
  c.b = std::clamp(c.a * logUniform(rng, 0.1, 10.0), 0.05, 5.0);
  c.length = logUniform(rng, 0.01, 10.0);
  c.R = randomRotation(rng);
  c.p = Eigen::Vector3d(unit(rng), unit(rng), unit(rng)) * logUniform(rng, 1e-3, 1e3);
  return c;
}

TEST(SphereEllipticCylinder, SignedDistancesWitnessesAndStatusesMatchTheOracle) {
  std::mt19937_64 rng(4502);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int separated = 0, overlapping = 0, inside = 0;
  for (int k = 0; k < 3000; ++k) {
    const PosedCylinder cyl = randomCylinder(rng);
    const double h = 0.5 * cyl.length;
    const Eigen::Vector3d extent(cyl.a, cyl.b, h);
    // Centres inside, near and far from the solid (local), the radius from 0 to twice the size.
    const double spread = k % 4 == 0 ? 0.9 : (k % 4 == 1 ? 1.3 : 4.0);
    Eigen::Vector3d local = spread * Eigen::Vector3d(unit(rng), unit(rng), unit(rng)).cwiseProduct(extent);
    if (local.x() == 0.0 || local.y() == 0.0) continue;
    const double r = k % 10 == 0 ? 0.0 : logUniform(rng, 1e-3, 2.0) * extent.maxCoeff();
    const Eigen::Vector3d c = cyl.p + cyl.R * local;
    const SignedDistanceResult d = signedDistanceSphereEllipticCylinder(c, r, cyl.a, cyl.b, cyl.length, cyl.R, cyl.p);
    // The oracle on the centre as the kernel sees it in the cylinder's frame.
    const Eigen::Vector3d x = cyl.R.transpose() * (c - cyl.p);
    const double oracle = cylinderOracle(cyl.a, cyl.b, h, x) - r;
    const double scale = x.norm() + extent.norm() + r;
    ASSERT_TRUE(d.converged) << k;
    if (oracle > 1e-10 * scale) {
      ASSERT_EQ(d.status, Separation::Separated) << k << " oracle " << oracle;
      ++separated;
    } else if (oracle < -1e-10 * scale) {
      ASSERT_EQ(d.status, Separation::Overlapping) << k << " oracle " << oracle;
      ++overlapping;
      inside += oracle + r < 0.0;
    }
    if (d.status != Separation::Touching) {
      ASSERT_NEAR(d.distance, oracle, 1e-13 * scale) << k;
    }
    // The collide-only entry (its own pre-tests first): the same verdict, and a common point.
    Eigen::Vector3d common;
    const std::optional<bool> hit =
        detail::sphereEllipticCylinderContact(c, r, cyl.a, cyl.b, cyl.length, cyl.R, cyl.p, &common);
    ASSERT_TRUE(hit.has_value()) << k;
    if (std::fabs(oracle) > 1e-10 * scale) {
      ASSERT_EQ(*hit, oracle < 0.0) << k << " oracle " << oracle;
    }
    if (*hit) {
      const Eigen::Vector3d w = cyl.R.transpose() * (common - cyl.p);
      const double tol = 1e-12 * (scale + cyl.p.norm());
      EXPECT_LE((w.x() / cyl.a) * (w.x() / cyl.a) + (w.y() / cyl.b) * (w.y() / cyl.b), 1.0 + 1e-12) << k;
      EXPECT_LE(std::fabs(w.z()), h + tol) << k;
      EXPECT_LE((common - c).norm(), r + tol) << k;
    }
    // Witnesses: point_b on the cylinder's surface, point_a on the sphere, their difference the
    // distance along the unit normal.
    EXPECT_NEAR(d.normal.norm(), 1.0, 1e-14);
    const Eigen::Vector3d wb = cyl.R.transpose() * (d.point_b - cyl.p);
    const double side = (wb.x() / cyl.a) * (wb.x() / cyl.a) + (wb.y() / cyl.b) * (wb.y() / cyl.b) - 1.0;
    const double cap = std::fabs(wb.z()) - h;
    EXPECT_LE(std::max(side * extent.minCoeff(), cap), 1e-12 * (scale + cyl.p.norm())) << k;
    EXPECT_GE(std::max(side * extent.maxCoeff(), cap), -1e-12 * (scale + cyl.p.norm())) << k;
    const double world = scale + c.norm();  // (world points carry the rounding of |c|)
    EXPECT_NEAR((d.point_a - c).norm(), r, 1e-13 * world);
    EXPECT_LE((d.point_b - d.point_a - d.distance * d.normal).norm(), 1e-12 * world) << k;
  }
  // Every kind of configuration was met.
  EXPECT_GT(separated, 1000);
  EXPECT_GT(overlapping, 300);
  EXPECT_GT(inside, 100);
}

TEST(SphereEllipticCylinder, TangentConstructionsAreDecidedOnTheirSide) {
  // A boundary point q of the solid with an outward normal m of its normal cone (the side's
  // normal, a cap's, or at the rim any mix of the two): the centre q + (r + g) m has q as its
  // nearest point, so the signed distance is g exactly (up to the rounding of the construction).
  std::mt19937_64 rng(4503);
  std::uniform_real_distribution<double> unit(0.0, 1.0), angle(0.0, 6.283185307179586);
  for (int k = 0; k < 2000; ++k) {
    const PosedCylinder cyl = randomCylinder(rng);
    const double h = 0.5 * cyl.length;
    const double phi = angle(rng);
    const Eigen::Vector2d e(cyl.a * std::cos(phi), cyl.b * std::sin(phi));
    const Eigen::Vector3d side_n = Eigen::Vector3d(e.x() / (cyl.a * cyl.a), e.y() / (cyl.b * cyl.b), 0).normalized();
    const double zsign = unit(rng) < 0.5 ? -1.0 : 1.0;
    Eigen::Vector3d q, m;
    switch (k % 3) {
      case 0:  // the side
        q = Eigen::Vector3d(e.x(), e.y(), (2.0 * unit(rng) - 1.0) * h);
        m = side_n;
        break;
      case 1:  // a cap
        q = Eigen::Vector3d(e.x(), e.y(), zsign * h) * unit(rng);
        q.z() = zsign * h;
        m = Eigen::Vector3d(0, 0, zsign);
        break;
      default: {  // the rim
        const double w = unit(rng);
        q = Eigen::Vector3d(e.x(), e.y(), zsign * h);
        m = ((1.0 - w) * side_n + w * Eigen::Vector3d(0, 0, zsign)).normalized();
      }
    }
    const double size = Eigen::Vector3d(cyl.a, cyl.b, h).norm();
    const double r = size * (0.01 + unit(rng));
    for (const double rel : {1e-3, 1e-6, 1e-9, -1e-9, -1e-6, -1e-3}) {
      const double g = rel * (size + r);  // |g| < r: the centre stays outside the solid
      const Eigen::Vector3d c = cyl.p + cyl.R * (q + (r + g) * m);
      const SignedDistanceResult d =
          signedDistanceSphereEllipticCylinder(c, r, cyl.a, cyl.b, cyl.length, cyl.R, cyl.p);
      ASSERT_EQ(d.status, rel > 0 ? Separation::Separated : Separation::Overlapping)
          << k << " rel " << rel << " kind " << k % 3;
      EXPECT_NEAR(d.distance, g, 1e-12 * (size + r + cyl.p.norm())) << k << " rel " << rel;
    }
  }
}

TEST(SphereEllipticCylinder, CircularCylindersAgreeWithTheMeridianClosedForm) {
  // a = b: the same solid as signedDistanceSphereCylinder's, computed there in the meridian
  // half-plane (a different method).
  std::mt19937_64 rng(4504);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int k = 0; k < 2000; ++k) {
    PosedCylinder cyl = randomCylinder(rng);
    cyl.b = cyl.a;
    const Eigen::Vector3d extent(cyl.a, cyl.a, 0.5 * cyl.length);
    const Eigen::Vector3d c =
        cyl.p + cyl.R * (2.0 * Eigen::Vector3d(unit(rng), unit(rng), unit(rng)).cwiseProduct(extent));
    const double r = extent.maxCoeff() * std::fabs(unit(rng));
    const SignedDistanceResult e = signedDistanceSphereEllipticCylinder(c, r, cyl.a, cyl.a, cyl.length, cyl.R, cyl.p);
    const SignedDistanceResult m = signedDistanceSphereCylinder(c, r, cyl.a, cyl.length, cyl.R, cyl.p);
    const double scale = (c - cyl.p).norm() + extent.norm() + r;
    EXPECT_NEAR(e.distance, m.distance, 1e-13 * scale) << k;
    if (std::fabs(m.distance) > 1e-10 * scale) {
      EXPECT_EQ(e.status, m.status) << k;
    }
    EXPECT_LE((e.point_b - m.point_b).norm(), 1e-9 * scale) << k;
  }
}

TEST(SphereEllipticCylinder, BadInputIsRefusedNamingTheValue) {
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  const Eigen::Vector3d c(2, 0, 0), p = Eigen::Vector3d::Zero();
  auto message = [&](auto call) -> std::string {
    try {
      call();
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "no exception";
  };
  EXPECT_NE(message([&] { signedDistanceSphereEllipticCylinder(c, 1, 0.0, 1, 1, I, p); }).find("semi-axis a"),
            std::string::npos);
  EXPECT_NE(message([&] { signedDistanceSphereEllipticCylinder(c, 1, 1, -2.0, 1, I, p); }).find("semi-axis b"),
            std::string::npos);
  EXPECT_NE(message([&] { signedDistanceSphereEllipticCylinder(c, 1, 1, 1, NAN, I, p); }).find("length"),
            std::string::npos);
  EXPECT_NE(message([&] { signedDistanceSphereEllipticCylinder(c, -1, 1, 1, 1, I, p); }).find("sphere radius"),
            std::string::npos);
  EXPECT_NE(message([&] { signedDistanceSphereEllipticCylinder(Eigen::Vector3d(INFINITY, 0, 0), 1, 1, 1, 1, I, p); })
                .find("sphere centre"),
            std::string::npos);
  EXPECT_NE(message([&] { signedDistanceSphereEllipticCylinder(c, 1, 1, 1, 1, 2.0 * I, p); }).find("rotation"),
            std::string::npos);
}

}  // namespace sphere_elliptic_cylinder_test
}  // namespace
}  // namespace fcl_quadric
