// The exact oracle is itself checked on configurations whose answer is known in closed form.
#include <gtest/gtest.h>

#include "support/exact_oracle.h"

namespace fcl_quadric {
namespace {

using test::exactCharacteristicPolynomial;
using test::exactClassify;
using test::Rational;

TEST(ExactOracle, ClassifiesUnitSpheresByCentreDistance) {
  const Ellipsoid a = Ellipsoid::sphere(1.0, Eigen::Vector3d::Zero());
  EXPECT_EQ(exactClassify(a, Ellipsoid::sphere(1.0, {2.5, 0, 0})), Separation::Separated);
  EXPECT_EQ(exactClassify(a, Ellipsoid::sphere(1.0, {2.0, 0, 0})), Separation::Touching);
  EXPECT_EQ(exactClassify(a, Ellipsoid::sphere(1.0, {1.5, 0, 0})), Separation::Overlapping);
  EXPECT_EQ(exactClassify(a, Ellipsoid::sphere(1.0, {0, 1.5, 1.5})), Separation::Separated);    // d^2 = 4.5
  EXPECT_EQ(exactClassify(a, Ellipsoid::sphere(1.0, {0, 1.25, 1.5})), Separation::Overlapping);  // d^2 = 3.8125
}

TEST(ExactOracle, SphereCharacteristicPolynomialMatchesClosedForm) {
  // Unit spheres, centres d apart: f(lambda) = -(lambda - 1)^2 (lambda^2 + (d^2 - 2) lambda + 1).
  const double d = 3.0;
  auto c = test::exactCharacteristicPolynomialUnscaled(Ellipsoid::sphere(1.0, Eigen::Vector3d::Zero()),
                                         Ellipsoid::sphere(1.0, {0, 0, d}));
  const Rational d2 = d * d;
  // (lambda^2 - 2 lambda + 1)(lambda^2 + (d2 - 2) lambda + 1), negated.
  const Rational e4 = -1, e3 = -(d2 - 2 - 2), e2 = -(1 - 2 * (d2 - 2) + 1), e1 = -((d2 - 2) - 2), e0 = -1;
  EXPECT_EQ(c[4], e4);
  EXPECT_EQ(c[3], e3);
  EXPECT_EQ(c[2], e2);
  EXPECT_EQ(c[1], e1);
  EXPECT_EQ(c[0], e0);
}

TEST(ExactOracle, AxisAlignedEllipsoidsTouchingAtTips) {
  // A = radii (1,2,3) at the origin, B = radii (2,1,1) centred at (3,0,0): they touch at (1,0,0).
  const Ellipsoid a({1, 2, 3}, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
  EXPECT_EQ(exactClassify(a, Ellipsoid({2, 1, 1}, Eigen::Matrix3d::Identity(), {3, 0, 0})), Separation::Touching);
  EXPECT_EQ(exactClassify(a, Ellipsoid({2, 1, 1}, Eigen::Matrix3d::Identity(), {3.0001, 0, 0})),
            Separation::Separated);
  EXPECT_EQ(exactClassify(a, Ellipsoid({2, 1, 1}, Eigen::Matrix3d::Identity(), {2.9999, 0, 0})),
            Separation::Overlapping);
}

TEST(ExactOracle, SturmCountsKnownRoots) {
  // (x+1)(x+2)(x-3)^2 (x+5): distinct roots below 0: -1, -2, -5.
  test::RationalPolynomial p{Rational(1)};
  auto mul = [&](const Rational& r) {  // p *= (x - r)
    test::RationalPolynomial q(p.size() + 1, Rational(0));
    for (size_t i = 0; i < p.size(); ++i) {
      q[i + 1] += p[i];
      q[i] -= r * p[i];
    }
    p = q;
  };
  for (int r : {-1, -2, 3, 3, -5}) mul(r);
  EXPECT_EQ(test::exactDistinctRootsBelow(p, Rational(0)), 3);
  EXPECT_EQ(test::exactDistinctRootsBelow(p, Rational(4)), 4);
  EXPECT_EQ(test::exactDistinctRootsBelow(p, Rational(-3)), 1);
}

}  // namespace
}  // namespace fcl_quadric
