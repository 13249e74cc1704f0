// Tests of PolynomialMatrix4 and the pencil determinants against Eigen (numeric determinants,
// generalized eigenvalues) and exact rational determinants (GMP).
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <gtest/gtest.h>

#include "algebra/exact_rational.h"
#include "fcl_quadric/algebra/bivariate_bernstein.h"
#include "fcl_quadric/algebra/polynomial_matrix.h"

namespace fcl_quadric {
namespace {

using algebra_test::Q;
using algebra_test::QPoly;

Eigen::Matrix4d randomMatrix(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  Eigen::Matrix4d M;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) M(i, j) = d(rng);
  }
  return M;
}

Eigen::Matrix4d randomSymmetric(std::mt19937_64& rng) {
  const Eigen::Matrix4d M = randomMatrix(rng);
  return 0.5 * (M + M.transpose());
}

PolynomialMatrix4 randomPolynomialMatrix(std::mt19937_64& rng, int degree) {
  std::vector<Eigen::Matrix4d> coeffs;
  for (int k = 0; k <= degree; ++k) coeffs.push_back(randomMatrix(rng));
  return PolynomialMatrix4::fromCoefficients(coeffs);
}

/// Exact determinant of a rational 4x4 matrix by fraction-free elimination with pivoting.
Q exactDeterminant(std::vector<std::vector<Q>> a) {
  Q det = 1;
  for (int k = 0; k < 4; ++k) {
    int pivot = -1;
    for (int i = k; i < 4; ++i) {
      if (a[static_cast<std::size_t>(i)][static_cast<std::size_t>(k)] != 0) {
        pivot = i;
        break;
      }
    }
    if (pivot < 0) return Q(0);
    if (pivot != k) {
      std::swap(a[static_cast<std::size_t>(pivot)], a[static_cast<std::size_t>(k)]);
      det = -det;
    }
    const Q p = a[static_cast<std::size_t>(k)][static_cast<std::size_t>(k)];
    det *= p;
    for (int i = k + 1; i < 4; ++i) {
      const Q f = a[static_cast<std::size_t>(i)][static_cast<std::size_t>(k)] / p;
      for (int j = k; j < 4; ++j) {
        a[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] -= f * a[static_cast<std::size_t>(k)][static_cast<std::size_t>(j)];
      }
    }
  }
  return det;
}

double maxAbs(const Eigen::Matrix4d& M) { return M.cwiseAbs().maxCoeff(); }

TEST(PolynomialMatrix4, ArithmeticMatchesEigenAtSamplePoints) {
  std::mt19937_64 rng(71);
  std::uniform_real_distribution<double> td(-2.0, 2.0);
  for (int trial = 0; trial < 30; ++trial) {
    const PolynomialMatrix4 A = randomPolynomialMatrix(rng, trial % 4);
    const PolynomialMatrix4 B = randomPolynomialMatrix(rng, (trial + 1) % 3);
    const double s = td(rng);
    const PolynomialMatrix4 prod = A * B;
    const PolynomialMatrix4 sum = A + B;
    const PolynomialMatrix4 diff = A - B;
    const PolynomialMatrix4 scaled = A * s;
    const PolynomialMatrix4 tr = A.transpose();
    const Polynomial q{0.5, -1.0, 2.0};
    const PolynomialMatrix4 by_poly = A * q;
    EXPECT_EQ(prod.maxDegree(), A.maxDegree() + B.maxDegree());
    for (int k = 0; k < 5; ++k) {
      const double t = td(rng);
      const Eigen::Matrix4d a = A.evaluate(t);
      const Eigen::Matrix4d b = B.evaluate(t);
      const double tol = 1e-12 * (1 + maxAbs(a)) * (1 + maxAbs(b)) * std::pow(3.0, A.maxDegree() + B.maxDegree());
      EXPECT_LE(maxAbs(prod.evaluate(t) - a * b), tol);
      EXPECT_LE(maxAbs(sum.evaluate(t) - (a + b)), tol);
      EXPECT_LE(maxAbs(diff.evaluate(t) - (a - b)), tol);
      EXPECT_LE(maxAbs(scaled.evaluate(t) - s * a), tol);
      EXPECT_EQ(tr.evaluate(t), a.transpose());
      EXPECT_LE(maxAbs(by_poly.evaluate(t) - q(t) * a), tol * (1 + std::abs(q(t))));
    }
  }
}

TEST(PolynomialMatrix4, DeterminantMatchesEigenDeterminantAtSamplePoints) {
  std::mt19937_64 rng(72);
  std::uniform_real_distribution<double> td(-1.5, 1.5);
  for (int trial = 0; trial < 40; ++trial) {
    const PolynomialMatrix4 M = randomPolynomialMatrix(rng, 1 + trial % 3);
    const Polynomial det = M.determinant();
    EXPECT_LE(det.degree(), 4 * M.maxDegree());
    for (int k = 0; k < 6; ++k) {
      const double t = td(rng);
      const Eigen::Matrix4d m = M.evaluate(t);
      // Scale: the permanent-like bound prod of row norms.
      double scale = 1.0;
      for (int i = 0; i < 4; ++i) scale *= m.row(i).cwiseAbs().sum();
      EXPECT_NEAR(det(t), m.determinant(), 1e-12 * std::max(scale, 1.0) * std::pow(2.0, M.maxDegree()));
    }
  }
}

TEST(PolynomialMatrix4, DeterminantIsExactForSmallIntegerEntries) {
  // Integer coefficients in [-3, 3], degree <= 2: every coefficient of the determinant is an
  // integer far below 2^53, so the Laplace expansion must be exact. Checked against exact
  // rational determinants at integer points (a degree-8 polynomial is fixed by 9 values).
  std::mt19937_64 rng(73);
  std::uniform_int_distribution<int> d(-3, 3);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Eigen::Matrix4d> coeffs(3);
    for (Eigen::Matrix4d& C : coeffs) {
      for (int i = 0; i < 4; ++i) {
        for (int j = 0; j < 4; ++j) C(i, j) = d(rng);
      }
    }
    const PolynomialMatrix4 M = PolynomialMatrix4::fromCoefficients(coeffs);
    const QPoly det = algebra_test::toQ(M.determinant().coefficients());
    for (int t = -4; t <= 4; ++t) {
      std::vector<std::vector<Q>> m(4, std::vector<Q>(4));
      for (int i = 0; i < 4; ++i) {
        for (int j = 0; j < 4; ++j) {
          m[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] =
              Q(coeffs[0](i, j)) + Q(coeffs[1](i, j)) * t + Q(coeffs[2](i, j)) * t * t;
        }
      }
      EXPECT_EQ(algebra_test::eval(det, Q(t)), exactDeterminant(m)) << "trial " << trial << " t " << t;
    }
  }
}

TEST(PolynomialMatrix4, PencilDeterminantMatchesDirectDeterminant) {
  std::mt19937_64 rng(74);
  std::uniform_real_distribution<double> ld(-3.0, 3.0);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::Matrix4d A = randomMatrix(rng);
    const Eigen::Matrix4d B = randomMatrix(rng);
    const Polynomial f = pencilDeterminant(A, B);
    ASSERT_EQ(f.degree(), 4);
    EXPECT_NEAR(f.coefficient(4), A.determinant(), 1e-13);
    EXPECT_NEAR(f.coefficient(0), B.determinant(), 1e-13);
    for (int k = 0; k < 6; ++k) {
      const double lambda = ld(rng);
      const Eigen::Matrix4d P = lambda * A - B;
      double scale = 1.0;
      for (int i = 0; i < 4; ++i) scale *= P.row(i).cwiseAbs().sum();
      EXPECT_NEAR(f(lambda), P.determinant(), 1e-13 * std::max(scale, 1.0));
    }
  }
}

TEST(PolynomialMatrix4, PencilDeterminantRootsAreGeneralizedEigenvalues) {
  // Symmetric B and positive definite A: det(lambda A - B) = det(A) prod (lambda - lambda_k)
  // with the real generalized eigenvalues of B v = lambda A v.
  std::mt19937_64 rng(75);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::Matrix4d R = randomMatrix(rng);
    const Eigen::Matrix4d A = R * R.transpose() + 0.5 * Eigen::Matrix4d::Identity();
    const Eigen::Matrix4d B = randomSymmetric(rng);
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix4d> ges(B, A);
    ASSERT_EQ(ges.info(), Eigen::Success);
    std::vector<double> eig(4);
    for (int k = 0; k < 4; ++k) eig[static_cast<std::size_t>(k)] = ges.eigenvalues()(k);
    const Polynomial expected = Polynomial::fromRoots(eig, A.determinant());
    const Polynomial f = pencilDeterminant(A, B);
    const double scale = std::max(1.0, expected.maxAbsCoefficient());
    for (int i = 0; i <= 4; ++i) EXPECT_NEAR(f.coefficient(i), expected.coefficient(i), 1e-10 * scale);
  }
}

TEST(PolynomialMatrix4, BivariatePencilMatchesDirectDeterminant) {
  std::mt19937_64 rng(76);
  std::uniform_real_distribution<double> xd(-1.5, 1.5);
  for (int trial = 0; trial < 20; ++trial) {
    const PolynomialMatrix4 A = randomPolynomialMatrix(rng, 1 + trial % 2);
    const PolynomialMatrix4 B = randomPolynomialMatrix(rng, 1);
    const Eigen::MatrixXd P = pencilDeterminant(A, B);
    ASSERT_EQ(P.rows(), 5);
    for (int k = 0; k < 6; ++k) {
      const double lambda = xd(rng);
      const double t = xd(rng);
      double value = 0.0;
      for (int i = P.rows() - 1; i >= 0; --i) {
        double row = 0.0;
        for (int j = P.cols() - 1; j >= 0; --j) row = row * t + P(i, j);
        value = value * lambda + row;
      }
      const Eigen::Matrix4d M = lambda * A.evaluate(t) - B.evaluate(t);
      double scale = 1.0;
      for (int i = 0; i < 4; ++i) scale *= M.row(i).cwiseAbs().sum();
      EXPECT_NEAR(value, M.determinant(), 1e-11 * std::max(scale, 1.0));
    }
  }
}

TEST(PolynomialMatrix4, CollisionFunctionOnUnitSquareMatchesDirectDeterminant) {
  // F(u,t) = det((u-1) A(t) - u B(t)) = det(u (A - B)(t) - A(t)), as the continuous-collision
  // layer builds it, in the Bernstein basis of [0,1]^2.
  std::mt19937_64 rng(77);
  for (int trial = 0; trial < 10; ++trial) {
    const PolynomialMatrix4 A = randomPolynomialMatrix(rng, 2);
    const PolynomialMatrix4 B = randomPolynomialMatrix(rng, 2);
    const BivariateBernstein F = BivariateBernstein::fromPower(pencilDeterminant(A - B, A));
    EXPECT_EQ(F.degreeU(), 4);
    EXPECT_EQ(F.degreeT(), 8);
    std::uniform_real_distribution<double> ud(0.0, 1.0);
    for (int k = 0; k < 8; ++k) {
      const double u = ud(rng);
      const double t = ud(rng);
      const Eigen::Matrix4d M = (u - 1.0) * A.evaluate(t) - u * B.evaluate(t);
      double scale = 1.0;
      for (int i = 0; i < 4; ++i) scale *= M.row(i).cwiseAbs().sum();
      EXPECT_NEAR(F.evaluate(u, t), M.determinant(), 1e-11 * std::max(scale, 1.0));
    }
  }
}

TEST(PolynomialMatrix4, RejectsBadInput) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Eigen::Matrix4d M = Eigen::Matrix4d::Identity();
  PolynomialMatrix4 P(M);
  EXPECT_THROW(P(4, 0), std::invalid_argument);
  EXPECT_THROW(P(0, -1), std::invalid_argument);
  EXPECT_THROW(P * nan, std::invalid_argument);
  EXPECT_THROW(P.evaluate(nan), std::invalid_argument);
  M(2, 3) = nan;
  EXPECT_THROW(PolynomialMatrix4{M}, std::invalid_argument);
  EXPECT_THROW(pencilDeterminant(M, Eigen::Matrix4d::Identity()), std::invalid_argument);
  EXPECT_THROW(pencilDeterminant(Eigen::Matrix4d::Identity(), M), std::invalid_argument);
  EXPECT_THROW(PolynomialMatrix4::linear(Eigen::Matrix4d::Zero(), M), std::invalid_argument);
}

}  // namespace
}  // namespace fcl_quadric
