// Tests of symmetricEigen (cyclic Jacobi): matrices built as Q D Q^T from known eigenvalues D
// and a random orthogonal Q are the oracle (Weyl: each computed eigenvalue lies within
// ||A - Q D Q^T||_2 of d_i, and that rounding is a few ulps of ||D||).
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "fcl_quadric/algebra/symmetric_eigen.h"

namespace fcl_quadric {
namespace test_symmetric_eigen {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

/// A random orthogonal n x n matrix: a product of 3 n^2 random plane rotations.
Eigen::MatrixXd randomOrthogonal(int n, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  std::uniform_int_distribution<int> index(0, n - 1);
  Eigen::MatrixXd q = Eigen::MatrixXd::Identity(n, n);
  for (int k = 0; k < 3 * n * n && n > 1; ++k) {
    const int p = index(rng);
    int r = index(rng);
    if (r == p) r = (p + 1) % n;
    const double t = angle(rng), c = std::cos(t), s = std::sin(t);
    for (int i = 0; i < n; ++i) {
      const double a = q(i, p), b = q(i, r);
      q(i, p) = c * a - s * b;
      q(i, r) = s * a + c * b;
    }
  }
  return q;
}

void expectDecomposition(const Eigen::MatrixXd& a, const std::vector<double>& expected, double value_tol,
                         const std::string& what) {
  const SymmetricEigenDecomposition e = symmetricEigen(a);
  const int n = static_cast<int>(a.rows());
  ASSERT_EQ(e.values.size(), n) << what;
  std::vector<double> sorted = expected;
  std::sort(sorted.begin(), sorted.end());
  for (int i = 0; i < n; ++i) EXPECT_NEAR(e.values[i], sorted[i], value_tol) << what << " eigenvalue " << i;
  for (int i = 0; i + 1 < n; ++i) EXPECT_LE(e.values[i], e.values[i + 1]) << what;
  const double scale = std::max(a.norm(), std::numeric_limits<double>::min());
  EXPECT_LE((e.vectors.transpose() * e.vectors - Eigen::MatrixXd::Identity(n, n)).norm(), 16 * n * kEps) << what;
  EXPECT_LE((a * e.vectors - e.vectors * e.values.asDiagonal()).norm(), 16 * n * kEps * scale) << what;
  EXPECT_LE(e.sweeps, kJacobiMaxSweeps) << what;
}

TEST(SymmetricEigen, RecoversKnownSpectraOfRandomRotatedDiagonals) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> value(-10.0, 10.0);
  std::uniform_int_distribution<int> pattern(0, 3);
  int max_sweeps = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const int n = 1 + trial % 4;
    std::vector<double> d(n);
    for (double& x : d) x = value(rng);
    // Repeated and zero eigenvalues: the null spaces the callers look for.
    switch (pattern(rng)) {
      case 1: if (n > 1) d[1] = d[0]; break;
      case 2: d[0] = 0.0; if (n > 2) d[2] = 0.0; break;
      case 3: if (n > 1) d[1] = d[0] * (1.0 + 1e-12); break;
      default: break;
    }
    const Eigen::MatrixXd q = randomOrthogonal(n, rng);
    Eigen::VectorXd dv(n);
    for (int i = 0; i < n; ++i) dv[i] = d[i];
    const Eigen::MatrixXd a = q * dv.asDiagonal() * q.transpose();
    const double norm = dv.norm();
    expectDecomposition(a, d, 32 * n * kEps * norm, "trial " + std::to_string(trial));
    max_sweeps = std::max(max_sweeps, symmetricEigen(a).sweeps);
  }
  EXPECT_LE(max_sweeps, 10);  // quadratic convergence: far below the cap
}

TEST(SymmetricEigen, ScaleInvariantFromTinyToHugeEntries) {
  std::mt19937_64 rng(8);
  const std::vector<double> d{-3.0, 0.5, 2.0, 7.0};
  const Eigen::MatrixXd q = randomOrthogonal(4, rng);
  const Eigen::MatrixXd base = q * Eigen::Vector4d(d[0], d[1], d[2], d[3]).asDiagonal() * q.transpose();
  for (double s : {1e-200, 1e-100, 1.0, 1e100, 1e150}) {  // squares stay normal
    std::vector<double> ds;
    for (double x : d) ds.push_back(s * x);
    expectDecomposition(s * base, ds, 128 * kEps * 8 * s, "scale " + std::to_string(s));
  }
}

TEST(SymmetricEigen, ZeroAndDiagonalAndEmptyMatrices) {
  const SymmetricEigenDecomposition z = symmetricEigen(Eigen::MatrixXd::Zero(3, 3));
  EXPECT_EQ(z.values, Eigen::VectorXd::Zero(3));
  EXPECT_EQ(z.vectors, Eigen::MatrixXd::Identity(3, 3));
  Eigen::MatrixXd diag = Eigen::MatrixXd::Zero(3, 3);
  diag.diagonal() << 3.0, -1.0, 2.0;
  const SymmetricEigenDecomposition e = symmetricEigen(diag);
  EXPECT_EQ(e.values, Eigen::Vector3d(-1.0, 2.0, 3.0));  // exact: no rotation is needed
  EXPECT_EQ(e.sweeps, 0);
  EXPECT_EQ(symmetricEigen(Eigen::MatrixXd(0, 0)).values.size(), 0);
}

TEST(SymmetricEigen, UsesTheSymmetricPartOfANonSymmetricInput) {
  Eigen::MatrixXd a(2, 2);
  a << 1.0, 4.0, 0.0, 1.0;  // symmetric part [[1, 2], [2, 1]]: eigenvalues -1, 3
  expectDecomposition(0.5 * (a + a.transpose()), {-1.0, 3.0}, 8 * kEps, "sym part");
  const SymmetricEigenDecomposition e = symmetricEigen(a);
  EXPECT_NEAR(e.values[0], -1.0, 8 * kEps);
  EXPECT_NEAR(e.values[1], 3.0, 8 * kEps);
}

TEST(SymmetricEigen, BadInputThrowsNamingTheValue) {
  try {
    symmetricEigen(Eigen::MatrixXd::Zero(2, 3));
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("2 x 3"), std::string::npos) << e.what();
  }
  Eigen::MatrixXd a = Eigen::MatrixXd::Identity(3, 3);
  a(1, 2) = std::numeric_limits<double>::infinity();
  try {
    symmetricEigen(a);
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("(1, 2) = inf"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace test_symmetric_eigen
}  // namespace fcl_quadric
