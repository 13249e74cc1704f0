// Every documented bad-input behaviour of the algebra, geometry and continuous layers that had no
// test of its own (issue 8 audit of include/fcl_quadric/**; docs/reliability.md lists them): the
// documented std::invalid_argument, or the documented NaN-free answer.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "support/expect_invalid.h"
#include "fcl_quadric/algebra/bivariate_bernstein.h"
#include "fcl_quadric/algebra/polynomial.h"
#include "fcl_quadric/algebra/polynomial_matrix.h"
#include "fcl_quadric/algebra/quadric_matrix.h"
#include "fcl_quadric/continuous/ccd_function.h"
#include "fcl_quadric/continuous/ellipse_ccd.h"
#include "fcl_quadric/continuous/ellipsoid_ccd.h"
#include "fcl_quadric/continuous/motion_matrix.h"
#include "fcl_quadric/geometry/characteristic_polynomial.h"
#include "fcl_quadric/geometry/ellipsoid.h"
#include "fcl_quadric/geometry/ellipsoid_plane.h"
#include "fcl_quadric/geometry/ellipsoid_polytope.h"
#include "fcl_quadric/geometry/separating_plane.h"

namespace fcl_quadric {
namespace {

using test::expectInvalid;

const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

TEST(DocumentedErrors, AlgebraRejectsNonFiniteInputAndExcessiveDegree) {
  expectInvalid([] { (void)Polynomial({1.0, 2.0})(kNaN); }, "");
  expectInvalid([] { (void)PolynomialMatrix4::fromCoefficients({Eigen::Matrix4d::Identity(), Eigen::Matrix4d::Constant(kInf)}); },
                "");
  const BivariateBernstein F(Eigen::MatrixXd::Ones(2, 3));
  expectInvalid([&] { (void)F.atT(kNaN); }, "");
  EXPECT_NO_THROW((void)F.atT(0.5));
  // ccdFunction / bernsteinDeterminant: degree in t above the binomial table (400).
  PolynomialMatrix4 high(Eigen::Matrix4d::Identity());
  high(0, 0) = Polynomial::monomial(401);
  expectInvalid([&] { (void)bernsteinDeterminant(high); }, "");
  expectInvalid([&] { (void)ccdFunction(high, PolynomialMatrix4(Eigen::Matrix4d::Identity())); }, "");
  // The quadric builders name the parameter.
  expectInvalid([] { (void)quadric::ellipticCone(1.0, 0.0, 1.0); }, "quadric::ellipticCone");
  expectInvalid([] { (void)quadric::hyperboloidTwoSheets(1.0, 1.0, kNaN); }, "quadric::hyperboloidTwoSheets");
  expectInvalid([] { (void)quadric::planePair(Eigen::Vector3d(0, 0, 2), 0.0, 1.0); }, "quadric::planePair");
  expectInvalid([] { (void)quadric::posedEllipsoid(Eigen::Vector3d(1, -1, 1), Eigen::Matrix3d::Identity(),
                                                    Eigen::Vector3d::Zero()); },
                "quadric::ellipsoid");
  expectInvalid([] { (void)quadric::affineEllipsoid(Eigen::Matrix3d::Zero(), Eigen::Vector3d::Zero()); }, "");
}

TEST(DocumentedErrors, GeometryEntryPoints) {
  const Ellipsoid e({1, 2, 3}, Eigen::Matrix3d::Identity(), {1, 0, 0});
  expectInvalid([] { (void)Ellipsoid::sphere(-1.0, Eigen::Vector3d::Zero()); }, "radius");
  expectInvalid([] { (void)Ellipsoid::sphere(1.0, Eigen::Vector3d(kNaN, 0, 0)); }, "centre");
  // supportPoint(0): every point attains h(0) = 0; the centre is returned, never NaN.
  EXPECT_EQ(e.supportPoint(Eigen::Vector3d::Zero()), e.center());
  EXPECT_EQ(e.support(Eigen::Vector3d::Zero()), 0.0);
  // Tiny and huge directions give the support point of their direction (no under/overflow).
  EXPECT_TRUE(e.supportPoint(Eigen::Vector3d(1e-300, 0, 0)).isApprox(Eigen::Vector3d(2, 0, 0)));
  EXPECT_TRUE(e.supportPoint(Eigen::Vector3d(0, 0, -1e300)).isApprox(Eigen::Vector3d(1, 0, -3)));
  EXPECT_EQ(e.normalAt(e.center()), Eigen::Vector3d::Zero());
  // Plane entry points share classifyEllipsoidPlane's validation.
  expectInvalid([&] { (void)ellipsoidPlaneQuadratic(e, Eigen::Vector3d::Zero(), 1.0); }, "");
  expectInvalid([&] { (void)ellipsoidHalfspace(e, Eigen::Vector3d(0, 0, 1), kInf); }, "");
  // Signed distances to polytopes validate like the classifications.
  expectInvalid([&] { (void)signedDistanceEllipsoidBox(e, Eigen::Vector3d(1, -1, 1), Eigen::Matrix3d::Identity(),
                                                       Eigen::Vector3d(5, 0, 0)); },
                "");
  expectInvalid([&] { (void)signedDistanceEllipsoidTriangle(e, Eigen::Vector3d(5, 0, 0), Eigen::Vector3d(kNaN, 1, 0),
                                                            Eigen::Vector3d(5, 0, 1)); },
                "triangle vertex b");
  // A zero normal gives the degenerate plane, which is never certified.
  const Ellipsoid far({1, 1, 1}, Eigen::Matrix3d::Identity(), {10, 0, 0});
  const Plane p = planeWithNormal(Eigen::Vector3d::Zero(), e, far);
  EXPECT_EQ(p.normal, Eigen::Vector3d::Zero());
  EXPECT_FALSE(planeSeparates(p, e, far));
  EXPECT_TRUE(planeSeparates(planeWithNormal(Eigen::Vector3d(1, 0, 0), e, far), e, far));
  Plane nan_plane;
  nan_plane.normal = Eigen::Vector3d(kNaN, 0, 0);
  EXPECT_FALSE(planeSeparates(nan_plane, e, far));
  // classifyBySubresultants: only the quartic of two ellipsoids.
  const auto f = characteristicPolynomial(e, far);
  EXPECT_EQ(classifyBySubresultants(f), Separation::Separated);
  expectInvalid([&] { (void)classifyBySubresultants({f[0], f[1], f[2], f[3], 0.0}); }, "f[4]");
  expectInvalid([&] { (void)classifyBySubresultants({f[0], kNaN, f[2], f[3], f[4]}); }, "f[1]");
}

TEST(DocumentedErrors, ContinuousEntryPoints) {
  const MotionMatrix m = MotionMatrix::fromPoses(Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(),
                                                 Eigen::Matrix3d::Identity(), Eigen::Vector3d(1, 0, 0));
  expectInvalid([&] { (void)m.evaluate(kNaN); }, "non-finite t");
  expectInvalid([&] { (void)m.restricted(0.5, 0.5); }, "");
  expectInvalid([&] { (void)m.restricted(-0.1, 0.5); }, "");
  expectInvalid([&] { (void)m.restricted(0.2, 1.5); }, "");
  EXPECT_NO_THROW((void)m.restricted(0.25, 0.75));
  const PiecewiseMotion pw = PiecewiseMotion::fromKeyframes(
      {0.0, 0.5, 1.0}, {Eigen::Isometry3d::Identity(), Eigen::Isometry3d(Eigen::Translation3d(1, 0, 0)),
                        Eigen::Isometry3d(Eigen::Translation3d(2, 0, 0))});
  expectInvalid([&] { (void)pw.evaluate(kInf); }, "non-finite t");
  expectInvalid([&] { (void)pw.restricted(0.25, 0.75); }, "not inside one piece");
  EXPECT_NO_THROW((void)pw.restricted(0.5, 0.75));
  Eigen::Matrix4d Q = quadric::ellipsoid(Eigen::Vector3d::Ones());
  Q(0, 1) = kNaN;
  expectInvalid([&] { (void)movingQuadric(Q, m); }, "");
  const MovingEllipsoid me{Ellipsoid({1, 1, 1}, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()), pw};
  expectInvalid([&] { (void)ellipsoidAt(me, kNaN); }, "");
  EXPECT_TRUE(ellipsoidAt(me, 0.75).center().isApprox(Eigen::Vector3d(1.5, 0, 0)));
  // Planar and 3D ellipses: non-finite angle / centre / time.
  expectInvalid([] { (void)ellipseMatrix(1.0, 1.0, kNaN, Eigen::Vector2d::Zero()); }, "non-finite angle or centre");
  expectInvalid([] { (void)ellipseMatrix(1.0, 1.0, 0.0, Eigen::Vector2d(kInf, 0)); }, "non-finite angle or centre");
  const MovingEllipse2 e2(1.0, 0.5, PolynomialMatrix3(Eigen::Matrix3d::Identity()));
  expectInvalid([&] { (void)e2.conicAt(kNaN); }, "");
  expectInvalid([&] { (void)e2.centerAt(kInf); }, "");
  const MovingEllipse3 e3(1.0, 0.5, PolynomialMatrix4(Eigen::Matrix4d::Identity()));
  expectInvalid([&] { (void)e3.centerAt(kNaN); }, "");
  expectInvalid([&] { (void)classifyEllipses3(e3, e3, kNaN); }, "");
  EXPECT_NE(classifyEllipses3(e3, e3, 0.5), Separation::Separated);
}

}  // namespace
}  // namespace fcl_quadric
