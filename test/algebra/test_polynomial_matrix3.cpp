// Tests of PolynomialMatrix3 and the conic pencil determinants against Eigen evaluated at sample
// points (numeric products, determinants, inverses).
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/LU>
#include <gtest/gtest.h>

#include "fcl_quadric/algebra/polynomial_matrix3.h"

namespace fcl_quadric {
namespace test_polynomial_matrix3 {
namespace {

Eigen::Matrix3d randomMatrix(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  Eigen::Matrix3d M;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) M(i, j) = d(rng);
  }
  return M;
}

PolynomialMatrix3 randomPolynomialMatrix(std::mt19937_64& rng, int degree) {
  std::vector<Eigen::Matrix3d> coeffs;
  for (int k = 0; k <= degree; ++k) coeffs.push_back(randomMatrix(rng));
  return PolynomialMatrix3::fromCoefficients(coeffs);
}

double maxAbs(const Eigen::Matrix3d& M) { return M.cwiseAbs().maxCoeff(); }

TEST(PolynomialMatrix3, ArithmeticMatchesEigenAtSamplePoints) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> td(-2.0, 2.0);
  for (int trial = 0; trial < 30; ++trial) {
    const PolynomialMatrix3 A = randomPolynomialMatrix(rng, trial % 4);
    const PolynomialMatrix3 B = randomPolynomialMatrix(rng, (trial + 1) % 3);
    const Polynomial q{0.5, -1.0, 0.25};
    for (int k = 0; k < 5; ++k) {
      const double t = td(rng);
      const Eigen::Matrix3d a = A.evaluate(t);
      const Eigen::Matrix3d b = B.evaluate(t);
      const double scale = 1.0 + maxAbs(a) * maxAbs(b);
      EXPECT_LT(maxAbs((A + B).evaluate(t) - (a + b)), 1e-12 * scale);
      EXPECT_LT(maxAbs((A - B).evaluate(t) - (a - b)), 1e-12 * scale);
      EXPECT_LT(maxAbs((A * B).evaluate(t) - a * b), 1e-12 * scale);
      EXPECT_LT(maxAbs(A.transpose().evaluate(t) - a.transpose()), 1e-15 * scale);
      EXPECT_LT(maxAbs((A * 3.0).evaluate(t) - 3.0 * a), 1e-12 * scale);
      EXPECT_LT(maxAbs((A * q).evaluate(t) - q(t) * a), 1e-12 * scale);
      EXPECT_NEAR(A.determinant()(t), a.determinant(), 1e-11 * (1.0 + std::pow(maxAbs(a), 3)));
    }
  }
}

TEST(PolynomialMatrix3, AdjugateTimesMatrixIsDeterminantTimesIdentity) {
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 30; ++trial) {
    const PolynomialMatrix3 M = randomPolynomialMatrix(rng, trial % 3);
    const PolynomialMatrix3 adj = M.adjugate();
    EXPECT_LE(adj.maxDegree(), 2 * M.maxDegree());
    const Polynomial det = M.determinant();
    for (double t : {-1.0, -0.3, 0.0, 0.7, 1.5}) {
      const Eigen::Matrix3d m = M.evaluate(t);
      const Eigen::Matrix3d prod = (M * adj).evaluate(t);
      const double s = 1.0 + std::pow(maxAbs(m), 3);
      EXPECT_LT(maxAbs(prod - det(t) * Eigen::Matrix3d::Identity()), 1e-11 * s);
      EXPECT_LT(maxAbs((adj * M).evaluate(t) - det(t) * Eigen::Matrix3d::Identity()), 1e-11 * s);
      if (std::abs(m.determinant()) > 1e-3) {
        // Independent: Eigen's inverse times the determinant.
        EXPECT_LT(maxAbs(adj.evaluate(t) - m.determinant() * m.inverse()), 1e-9 * s);
      }
    }
  }
}

TEST(PolynomialMatrix3, PencilDeterminantMatchesNumericDeterminants) {
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::Matrix3d A = randomMatrix(rng);
    const Eigen::Matrix3d B = randomMatrix(rng);
    const Polynomial f = pencilDeterminant3(A, B);
    ASSERT_EQ(f.degree(), 3);
    EXPECT_NEAR(f.coefficient(3), A.determinant(), 1e-14);
    EXPECT_NEAR(f.coefficient(0), -B.determinant(), 1e-14);
    for (double l : {-3.0, -0.5, 0.0, 0.4, 2.0}) EXPECT_NEAR(f(l), (l * A - B).determinant(), 1e-12 * (1 + std::pow(std::abs(l), 3)));
  }
}

TEST(PolynomialMatrix3, BivariatePencilDeterminantMatchesEvaluation) {
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    const PolynomialMatrix3 A = randomPolynomialMatrix(rng, 1 + trial % 3);
    const PolynomialMatrix3 B = randomPolynomialMatrix(rng, trial % 2);
    const Eigen::MatrixXd P = pencilDeterminant3(A, B);
    ASSERT_EQ(P.rows(), 4);
    EXPECT_EQ(P.cols(), 3 * std::max(A.maxDegree(), B.maxDegree()) + 1);
    for (double t : {-0.7, 0.0, 0.3, 1.0}) {
      for (double l : {-2.0, -0.25, 0.5, 1.5}) {
        double v = 0.0;
        for (int k = 3; k >= 0; --k) {
          double c = 0.0;
          for (Eigen::Index j = P.cols() - 1; j >= 0; --j) c = c * t + P(k, j);
          v = v * l + c;
        }
        const Eigen::Matrix3d Q = l * A.evaluate(t) - B.evaluate(t);
        EXPECT_NEAR(v, Q.determinant(), 1e-10 * (1.0 + std::pow(maxAbs(Q), 3)));
      }
    }
  }
}

TEST(PolynomialMatrix3, BadInputThrowsNamingTheItem) {
  PolynomialMatrix3 M;
  try {
    (void)M(3, 0);
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("outside [0, 2]"), std::string::npos) << e.what();
  }
  Eigen::Matrix3d bad = Eigen::Matrix3d::Identity();
  bad(1, 2) = std::numeric_limits<double>::infinity();
  try {
    PolynomialMatrix3 X(bad);
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("(1, 2)"), std::string::npos) << e.what();
  }
  try {
    (void)PolynomialMatrix3::fromCoefficients({Eigen::Matrix3d::Identity(), bad});
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("M_1"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)pencilDeterminant3(bad, Eigen::Matrix3d::Identity()), std::invalid_argument);
  EXPECT_THROW((void)(M * std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
}

}  // namespace
}  // namespace test_polynomial_matrix3
}  // namespace fcl_quadric
