// Tests of lowDegreeRoots: polynomials built from known roots (exactly representable
// coefficients) are the oracle; random cubics are checked by backward error (each root is an
// exact root of a polynomial within a few ulps of the input) and by Vieta's relations.
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "fcl_quadric/algebra/low_degree_roots.h"

namespace fcl_quadric {
namespace {

using Complex = std::complex<double>;
constexpr double kEps = std::numeric_limits<double>::epsilon();

/// Matches computed to expected roots (as multisets, greedily nearest) within tol.
void expectRoots(const std::vector<double>& c, std::vector<Complex> expected, double tol, const std::string& what) {
  std::vector<Complex> got = lowDegreeRoots(c);
  ASSERT_EQ(got.size(), expected.size()) << what;
  for (const Complex& z : got) {
    auto best = std::min_element(expected.begin(), expected.end(),
                                 [&z](const Complex& a, const Complex& b) { return std::abs(a - z) < std::abs(b - z); });
    EXPECT_LE(std::abs(*best - z), tol * std::max(1.0, std::abs(*best))) << what << ": root " << z << " vs " << *best;
    expected.erase(best);
  }
}

TEST(LowDegreeRoots, KnownRootsWithExactCoefficients) {
  expectRoots({-6.0, 3.0}, {{2.0, 0.0}}, 0.0, "linear");
  expectRoots({6.0, -5.0, 1.0}, {{2.0, 0.0}, {3.0, 0.0}}, 2 * kEps, "two real");
  expectRoots({5.0, -2.0, 1.0}, {{1.0, 2.0}, {1.0, -2.0}}, 2 * kEps, "complex pair");
  expectRoots({-6.0, 11.0, -6.0, 1.0}, {{1.0, 0.0}, {2.0, 0.0}, {3.0, 0.0}}, 8 * kEps, "three real");
  expectRoots({5.0, 3.0, -1.0, 1.0}, {{-1.0, 0.0}, {1.0, 2.0}, {1.0, -2.0}}, 8 * kEps, "real + pair");
  expectRoots({0.0, 0.0, 1.0, 2.0}, {{0.0, 0.0}, {0.0, 0.0}, {-0.5, 0.0}}, 0.0, "double root at 0");
  // (x - 2)^2 (x + 1): a double root is only determined to ~sqrt(eps) by its coefficients.
  expectRoots({4.0, 0.0, -3.0, 1.0}, {{2.0, 0.0}, {2.0, 0.0}, {-1.0, 0.0}}, 4 * std::sqrt(kEps), "double root");
  // (x - 1)^3: ~cbrt(eps).
  expectRoots({-1.0, 3.0, -3.0, 1.0}, {{1.0, 0.0}, {1.0, 0.0}, {1.0, 0.0}}, 4 * std::cbrt(kEps), "triple root");
  // Trailing zeros lower the degree; a constant has no roots.
  expectRoots({-6.0, 3.0, 0.0, 0.0}, {{2.0, 0.0}}, 0.0, "trailing zeros");
  EXPECT_TRUE(lowDegreeRoots({4.0}).empty());
  EXPECT_TRUE(lowDegreeRoots({}).empty());
}

TEST(LowDegreeRoots, RealRootsHaveZeroImaginaryPartAndPairsAreConjugate) {
  for (const Complex& z : lowDegreeRoots({-6.0, 11.0, -6.0, 1.0})) EXPECT_EQ(z.imag(), 0.0);
  const std::vector<Complex> r = lowDegreeRoots({5.0, 3.0, -1.0, 1.0});
  EXPECT_EQ(r[0].imag(), 0.0);
  EXPECT_EQ(r[1], std::conj(r[2]));
}

TEST(LowDegreeRoots, WidelySpreadMagnitudesNeitherOverflowNorLoseTheSmallRoot) {
  // Roots 1e100, 1, -1e-100 (coefficients rounded from the exact ones): scaled (the root bound
  // is beyond 2^300), and the small root's constant term stays normal.
  const double big = 1e100, small = -1e-100;
  const std::vector<double> c{-(big * small), big + big * small + small, -(big + 1.0 + small), 1.0};
  expectRoots(c, {{big, 0.0}, {1.0, 0.0}, {small, 0.0}}, 8 * kEps, "spread");
  const std::vector<Complex> r = lowDegreeRoots(c);
  const auto smallest = std::min_element(r.begin(), r.end(), [](Complex a, Complex b) { return std::abs(a) < std::abs(b); });
  EXPECT_NEAR(smallest->real(), small, 8 * kEps * 1e-100);
  // A leading coefficient far below the others: roots near +-1e300 stay finite.
  for (const Complex& z : lowDegreeRoots({1e300, 0.0, -1e-300})) {
    EXPECT_TRUE(std::isfinite(z.real()) && std::isfinite(z.imag())) << z;
    EXPECT_NEAR(std::fabs(z.real()), 1e300, 1e300 * 8 * kEps);
  }
}

TEST(LowDegreeRoots, RandomCubicsAreBackwardStableAndSatisfyVieta) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> coef(-1.0, 1.0);
  std::uniform_int_distribution<int> expo(-20, 20);
  for (int trial = 0; trial < 20000; ++trial) {
    std::vector<double> c(4);
    for (double& x : c) x = std::ldexp(coef(rng), expo(rng));
    const std::vector<Complex> r = lowDegreeRoots(c);
    ASSERT_EQ(r.size(), 3u);
    for (const Complex& z : r) {
      // |p(z)| <= k eps sum |c_i| |z|^i: z is a root of a polynomial with coefficients within k
      // relative ulps of c.
      Complex v = 0.0;
      double mag = 0.0;
      for (int i = 3; i >= 0; --i) {
        v = v * z + c[i];
        mag = mag * std::abs(z) + std::fabs(c[i]);
      }
      EXPECT_LE(std::abs(v), 32 * kEps * mag) << "trial " << trial << " root " << z;
    }
    // Vieta: sum of roots = -c2 / c3 (up to the roots' own size).
    const Complex sum = r[0] + r[1] + r[2];
    const double size = std::abs(r[0]) + std::abs(r[1]) + std::abs(r[2]);
    EXPECT_LE(std::abs(sum + c[2] / c[3]), 1e-6 * size + 64 * kEps * std::fabs(c[2] / c[3])) << "trial " << trial;
    EXPECT_EQ(r[1].imag() == 0.0, r[2].imag() == 0.0) << "trial " << trial;
  }
}

TEST(LowDegreeRoots, BadInputThrowsNamingTheValue) {
  try {
    lowDegreeRoots({1.0, 2.0, 3.0, 4.0, 5.0});
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("degree 4"), std::string::npos) << e.what();
  }
  try {
    lowDegreeRoots({1.0, std::numeric_limits<double>::quiet_NaN()});
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("c[1]"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace fcl_quadric
