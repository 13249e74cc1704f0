// Tests of SturmSequence: known roots, and an exact rational Sturm sequence (GMP) as oracle.
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "algebra/exact_rational.h"
#include "fcl_quadric/algebra/sturm_sequence.h"

namespace fcl_quadric {
namespace {

using algebra_test::ExactSturm;
using algebra_test::Q;
using algebra_test::QPoly;

/// Distinct values of `roots` in (a, b].
template <typename T>
int countInHalfOpen(std::vector<T> roots, const T& a, const T& b) {
  std::sort(roots.begin(), roots.end());
  roots.erase(std::unique(roots.begin(), roots.end()), roots.end());
  int n = 0;
  for (const T& r : roots) {
    if (a < r && r <= b) ++n;
  }
  return n;
}

TEST(SturmSequence, ExactRationalOracleCountsKnownRootsIncludingMultipleAndClustered) {
  std::mt19937_64 rng(51);
  std::uniform_int_distribution<int> num(-40, 40);
  std::uniform_int_distribution<int> den(1, 7);
  std::uniform_int_distribution<int> mult(1, 3);
  const Q cluster_gap = Q(1, 1000000000) / 1000;  // 1e-12
  for (int trial = 0; trial < 60; ++trial) {
    std::vector<Q> roots;
    std::vector<Q> distinct;
    const int k = 1 + trial % 5;
    for (int i = 0; i < k; ++i) {
      Q r(num(rng), den(rng));
      r.canonicalize();
      const int m = mult(rng);
      for (int j = 0; j < m; ++j) roots.push_back(r);
      distinct.push_back(r);
      if (i == 0 && trial % 2 == 0) {  // a cluster: r and r + 1e-12
        roots.push_back(r + cluster_gap);
        distinct.push_back(r + cluster_gap);
      }
    }
    const ExactSturm sturm(algebra_test::fromRoots(roots, Q(trial % 3 == 0 ? -2 : 3)));
    EXPECT_EQ(sturm.countAll(), countInHalfOpen<Q>(distinct, Q(-1000), Q(1000)));
    for (int q = 0; q < 20; ++q) {
      Q a(num(rng), den(rng));
      Q b(num(rng), den(rng));
      a.canonicalize();
      b.canonicalize();
      if (q % 4 == 0) a = distinct[static_cast<std::size_t>(q) % distinct.size()];  // endpoint at a root
      if (q % 4 == 1) b = distinct[static_cast<std::size_t>(q) % distinct.size()];
      if (a == b) continue;
      if (b < a) std::swap(a, b);
      EXPECT_EQ(sturm.count(a, b), countInHalfOpen<Q>(distinct, a, b)) << "trial " << trial;
    }
  }
}

TEST(SturmSequence, CountsDistinctRootsOfKnownProducts) {
  // Roots are multiples of 1/4 in [-3, 3] (pairwise >= 1/4 apart) with multiplicity 1 or 2, so
  // fromRoots is exact and the only rounding is inside the Sturm sequence.
  std::mt19937_64 rng(52);
  std::uniform_int_distribution<int> quarter(-12, 12);
  std::uniform_int_distribution<int> mult(1, 2);
  std::uniform_real_distribution<double> ends(-4.0, 4.0);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<double> distinct;
    std::vector<double> roots;
    const int k = 1 + trial % 5;
    while (static_cast<int>(distinct.size()) < k) {
      const double r = quarter(rng) / 4.0;
      if (std::find(distinct.begin(), distinct.end(), r) != distinct.end()) continue;
      distinct.push_back(r);
      const int m = mult(rng);
      for (int j = 0; j < m; ++j) roots.push_back(r);
    }
    const Polynomial p = Polynomial::fromRoots(roots, trial % 2 == 0 ? 1.0 : -0.5);
    const SturmSequence sturm(p);
    const double inf = std::numeric_limits<double>::infinity();
    EXPECT_EQ(sturm.countAllDistinctRoots(), k) << "trial " << trial;
    EXPECT_EQ(sturm.countDistinctRoots(-inf, inf), k);
    for (int q = 0; q < 20; ++q) {
      double a = ends(rng);
      double b = ends(rng);
      if (q % 4 == 0) a = distinct[static_cast<std::size_t>(q) % distinct.size()];
      if (q % 4 == 1) b = distinct[static_cast<std::size_t>(q) % distinct.size()];
      if (a == b) continue;
      if (b < a) std::swap(a, b);
      EXPECT_EQ(sturm.countDistinctRoots(a, b), countInHalfOpen(distinct, a, b))
          << "trial " << trial << " interval (" << a << ", " << b << "]";
    }
  }
}

TEST(SturmSequence, AgreesWithExactSturmOnWellSeparatedRandomRoots) {
  std::mt19937_64 rng(53);
  std::uniform_real_distribution<double> rd(-3.0, 3.0);
  std::uniform_real_distribution<double> ends(-4.0, 4.0);
  for (int trial = 0; trial < 100; ++trial) {
    std::vector<double> roots;
    const int k = 1 + trial % 7;
    while (static_cast<int>(roots.size()) < k) {
      const double r = rd(rng);
      bool ok = true;
      for (double s : roots) ok = ok && std::abs(r - s) >= 0.05;
      if (ok) roots.push_back(r);
    }
    // The double coefficients are the polynomial under test; the oracle uses them exactly.
    const Polynomial p = Polynomial::fromRoots(roots);
    const SturmSequence sturm(p);
    const ExactSturm exact(algebra_test::toQ(p.coefficients()));
    EXPECT_EQ(sturm.countAllDistinctRoots(), exact.countAll());
    EXPECT_EQ(exact.countAll(), k);  // separation >> rounding: the roots survive rounding
    for (int q = 0; q < 20; ++q) {
      double a = ends(rng);
      double b = ends(rng);
      if (b < a) std::swap(a, b);
      bool near_root = false;
      for (double r : roots) near_root = near_root || std::abs(r - a) < 1e-6 || std::abs(r - b) < 1e-6;
      if (a == b || near_root) continue;
      EXPECT_EQ(sturm.countDistinctRoots(a, b), exact.count(Q(a), Q(b))) << "trial " << trial;
    }
  }
}

TEST(SturmSequence, SeparatesModeratelyClusteredRootsAndNeverInventsRoots) {
  // Roots 1 and 1 + 2^-10 (~1e-3 apart, exact dyadics) plus far roots: the double sequence
  // is well conditioned enough to count both.
  const double gap = std::ldexp(1.0, -10);
  const Polynomial p = Polynomial::fromRoots({1.0, 1.0 + gap, -2.0, 3.0});
  const SturmSequence sturm(p);
  EXPECT_EQ(sturm.countDistinctRoots(0.5, 1.5), 2);
  EXPECT_EQ(sturm.countDistinctRoots(0.5, 1.0 + gap / 2), 1);
  EXPECT_EQ(sturm.countAllDistinctRoots(), 4);
  // A tight cluster (2^-30 ~ 1e-9): the exact sequence sees two roots; the double sequence
  // may merge them (documented) but must report the cluster, and no more than two roots.
  const double tight = std::ldexp(1.0, -30);
  const Polynomial pc = Polynomial::fromRoots({1.0, 1.0 + tight, -2.0});
  const ExactSturm exact(algebra_test::toQ(pc.coefficients()));
  EXPECT_EQ(exact.count(Q(0.5), Q(1.5)), 2);
  const int c = SturmSequence(pc).countDistinctRoots(0.5, 1.5);
  EXPECT_GE(c, 1);
  EXPECT_LE(c, 2);
  EXPECT_EQ(SturmSequence(pc).countDistinctRoots(-3.0, 0.0), 1);
}

TEST(SturmSequence, VariationsAtInfinityMatchVariationsBeyondAllRoots) {
  std::mt19937_64 rng(54);
  std::uniform_real_distribution<double> c(-1.0, 1.0);
  for (int trial = 0; trial < 100; ++trial) {
    std::vector<double> coeffs(static_cast<std::size_t>(trial % 9) + 1);
    for (double& v : coeffs) v = c(rng);
    const SturmSequence sturm{Polynomial(coeffs)};
    // Cauchy bound over every member: beyond R no member changes sign.
    double R = 1.0;
    for (const Polynomial& q : sturm.polynomials()) {
      double m = 0.0;
      for (int i = 0; i < q.degree(); ++i) m = std::max(m, std::abs(q.coefficient(i) / q.leadingCoefficient()));
      R = std::max(R, 1.0 + m);
    }
    EXPECT_EQ(sturm.variationsAt(std::numeric_limits<double>::infinity()), sturm.variationsAt(2 * R));
    EXPECT_EQ(sturm.variationsAt(-std::numeric_limits<double>::infinity()), sturm.variationsAt(-2 * R));
    EXPECT_EQ(sturm.variationsAtPositiveInfinity(), sturm.variationsAt(2 * R));
    // The number of real roots of a polynomial never exceeds its degree.
    EXPECT_LE(sturm.countAllDistinctRoots(), Polynomial(coeffs).effectiveDegree());
    EXPECT_GE(sturm.countAllDistinctRoots(), 0);
  }
}

TEST(SturmSequence, RejectsBadInput) {
  EXPECT_THROW(SturmSequence(Polynomial{0.0, 0.0}), std::invalid_argument);
  const SturmSequence s(Polynomial{-1.0, 0.0, 1.0});
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(s.variationsAt(nan), std::invalid_argument);
  EXPECT_THROW(s.countDistinctRoots(1.0, 1.0), std::invalid_argument);
  EXPECT_THROW(s.countDistinctRoots(2.0, 1.0), std::invalid_argument);
  EXPECT_THROW(s.countDistinctRoots(nan, 1.0), std::invalid_argument);
  // A nonzero constant has no roots.
  EXPECT_EQ(SturmSequence(Polynomial{3.0}).countAllDistinctRoots(), 0);
}

TEST(SturmSequence, HandlesSubnormalAndHugeCoefficientsWithoutFloatingPointExceptions) {
  // Normalising by a subnormal maximum must not overflow a reciprocal (the test main traps
  // invalid operations): 1e-310 x (x - 1) has the roots 0 and 1.
  const SturmSequence tiny(Polynomial{0.0, -1e-310, 1e-310});
  EXPECT_EQ(tiny.countAllDistinctRoots(), 2);
  EXPECT_EQ(tiny.countDistinctRoots(-0.5, 0.5), 1);
  const SturmSequence huge(Polynomial{-1e300, 0.0, 1e300});  // roots -1, 1
  EXPECT_EQ(huge.countAllDistinctRoots(), 2);
  EXPECT_EQ(huge.countDistinctRoots(0.0, 2.0), 1);
}

}  // namespace
}  // namespace fcl_quadric
