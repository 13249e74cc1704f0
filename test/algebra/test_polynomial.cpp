// Tests of Polynomial against exact rational arithmetic (GMP).
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "algebra/exact_rational.h"
#include "fcl_quadric/algebra/polynomial.h"

namespace fcl_quadric {
namespace {

using algebra_test::Q;
using algebra_test::QPoly;

std::vector<double> randomCoefficients(std::mt19937_64& rng, int degree, double lo, double hi) {
  std::uniform_real_distribution<double> d(lo, hi);
  std::vector<double> c(static_cast<std::size_t>(degree) + 1);
  for (double& v : c) v = d(rng);
  return c;
}

std::vector<double> randomIntegers(std::mt19937_64& rng, int degree, int bound) {
  std::uniform_int_distribution<int> d(-bound, bound);
  std::vector<double> c(static_cast<std::size_t>(degree) + 1);
  for (double& v : c) v = d(rng);
  return c;
}

/// Exact equality of a double polynomial with a rational one (trailing zeros ignored).
bool equalsExactly(const Polynomial& p, QPoly q) {
  algebra_test::trim(&q);
  QPoly pq = algebra_test::toQ(p.trimmed().coefficients());
  algebra_test::trim(&pq);
  return pq == q;
}

TEST(Polynomial, HornerValueLiesWithinRunningErrorBoundOfExactValue) {
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<int> deg(0, 12);
  std::uniform_real_distribution<double> xd(-2.0, 2.0);
  int nonzero_errors = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const Polynomial p(randomCoefficients(rng, deg(rng), -1.0, 1.0));
    const double x = xd(rng);
    double bound = -1.0;
    const double y = p.evaluateWithBound(x, &bound);
    EXPECT_EQ(y, p(x));
    const Q exact = algebra_test::eval(algebra_test::toQ(p.coefficients()), Q(x));
    const Q err = abs(Q(y) - exact);
    EXPECT_LE(err, Q(bound)) << "trial " << trial;
    if (err > 0) ++nonzero_errors;
    // The running bound is never looser than the a-priori bound gamma_2n * sum |c_i| |x|^i.
    const int n = p.degree();
    double abs_sum = 0.0;
    for (int i = n; i >= 0; --i) abs_sum = abs_sum * std::abs(x) + std::abs(p.coefficient(i));
    const double u = std::numeric_limits<double>::epsilon() / 2;
    const double gamma = 2 * n * u / (1 - 2 * n * u);
    EXPECT_LE(bound, 1.01 * gamma * abs_sum + 1e-300) << "trial " << trial;
  }
  EXPECT_GT(nonzero_errors, 50);  // the test exercises actual rounding
}

TEST(Polynomial, RunningErrorBoundHoldsNearClusteredRootsOfWilkinsonProduct) {
  std::vector<double> roots;
  for (int k = 1; k <= 12; ++k) roots.push_back(k);
  const Polynomial p = Polynomial::fromRoots(roots);
  // Coefficients of prod (x - k), k <= 12, are integers below 2^53: fromRoots is exact.
  std::vector<Q> qroots;
  for (double r : roots) qroots.emplace_back(r);
  const QPoly exact_p = algebra_test::fromRoots(qroots);
  ASSERT_TRUE(equalsExactly(p, exact_p));
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> off(-1e-3, 1e-3);
  for (int trial = 0; trial < 200; ++trial) {
    const double x = 1 + trial % 12 + off(rng);
    double bound = 0.0;
    const double y = p.evaluateWithBound(x, &bound);
    const Q err = abs(Q(y) - algebra_test::eval(exact_p, Q(x)));
    EXPECT_LE(err, Q(bound)) << "x = " << x;
  }
}

TEST(Polynomial, ArithmeticMatchesExactRationalArithmetic) {
  std::mt19937_64 rng(13);
  std::uniform_int_distribution<int> deg(0, 8);
  for (int trial = 0; trial < 200; ++trial) {
    // Small integers: every result is an integer below 2^53, so double arithmetic is exact.
    const Polynomial a(randomIntegers(rng, deg(rng), 100));
    const Polynomial b(randomIntegers(rng, deg(rng), 100));
    const QPoly qa = algebra_test::toQ(a.coefficients());
    const QPoly qb = algebra_test::toQ(b.coefficients());
    EXPECT_TRUE(equalsExactly(a + b, algebra_test::add(qa, qb)));
    EXPECT_TRUE(equalsExactly(a - b, algebra_test::sub(qa, qb)));
    EXPECT_TRUE(equalsExactly(a * b, algebra_test::mul(qa, qb)));
    EXPECT_TRUE(equalsExactly(a * 3.0, algebra_test::scale(qa, Q(3))));
    EXPECT_TRUE(equalsExactly(-2.0 * a, algebra_test::scale(qa, Q(-2))));
    EXPECT_TRUE(equalsExactly(-a, algebra_test::scale(qa, Q(-1))));
    EXPECT_EQ((a * b).degree(), a.degree() + b.degree());
    EXPECT_EQ((a + b).degree(), std::max(a.degree(), b.degree()));
  }
}

TEST(Polynomial, DerivativeMatchesExactDerivative) {
  std::mt19937_64 rng(14);
  for (int trial = 0; trial < 100; ++trial) {
    const Polynomial p(randomIntegers(rng, trial % 10, 1000));
    EXPECT_TRUE(equalsExactly(p.derivative(), algebra_test::derivative(algebra_test::toQ(p.coefficients()))));
    EXPECT_EQ(p.derivative().degree(), std::max(p.degree() - 1, 0));
  }
  EXPECT_TRUE(Polynomial::constant(5.0).derivative().isZero());
}

TEST(Polynomial, ComposeAffineMatchesExactComposition) {
  std::mt19937_64 rng(15);
  std::uniform_int_distribution<int> quarter(-16, 16);
  for (int trial = 0; trial < 100; ++trial) {
    // Dyadic alpha, beta and integer coefficients of degree <= 6: every intermediate is a dyadic
    // rational with few significant bits, so the result must be exact.
    const Polynomial p(randomIntegers(rng, trial % 7, 50));
    const double alpha = quarter(rng) / 4.0;
    const double beta = quarter(rng) / 4.0;
    QPoly exact{Q(0)};
    const QPoly lin{Q(beta), Q(alpha)};
    const QPoly qp = algebra_test::toQ(p.coefficients());
    for (std::size_t i = 0; i < qp.size(); ++i) {
      exact = algebra_test::add(exact, algebra_test::scale(algebra_test::power(lin, static_cast<int>(i)), qp[i]));
    }
    EXPECT_TRUE(equalsExactly(p.composeAffine(alpha, beta), exact)) << "trial " << trial;
  }
  // Generic doubles: agreement to rounding, relative to the coefficient scale.
  for (int trial = 0; trial < 100; ++trial) {
    const Polynomial p(randomCoefficients(rng, 1 + trial % 8, -1.0, 1.0));
    std::uniform_real_distribution<double> d(-1.5, 1.5);
    const double alpha = d(rng);
    const double beta = d(rng);
    const Polynomial q = p.composeAffine(alpha, beta);
    std::uniform_real_distribution<double> td(-1.0, 1.0);
    for (int k = 0; k < 5; ++k) {
      const double t = td(rng);
      const Q exact = algebra_test::eval(algebra_test::toQ(p.coefficients()), Q(alpha) * Q(t) + Q(beta));
      EXPECT_NEAR(q(t), exact.get_d(), 1e-12 * std::pow(4.0, p.degree()));
    }
  }
}

TEST(Polynomial, FromRootsMatchesExactExpansion) {
  std::mt19937_64 rng(16);
  std::uniform_real_distribution<double> rd(-3.0, 3.0);
  for (int trial = 0; trial < 100; ++trial) {
    std::vector<double> roots(static_cast<std::size_t>(trial % 9));
    std::vector<Q> qroots;
    for (double& r : roots) {
      r = rd(rng);
      qroots.emplace_back(r);
    }
    const double lead = 0.5 + trial % 3;
    const Polynomial p = Polynomial::fromRoots(roots, lead);
    const QPoly exact = algebra_test::fromRoots(qroots, Q(lead));
    ASSERT_EQ(p.degree(), static_cast<int>(roots.size()));
    EXPECT_EQ(p.leadingCoefficient(), lead);
    for (int i = 0; i <= p.degree(); ++i) {
      EXPECT_NEAR(p.coefficient(i), exact[static_cast<std::size_t>(i)].get_d(), 1e-13 * std::pow(4.0, p.degree()) * lead);
    }
  }
}

TEST(Polynomial, DivideReconstructsNumeratorAndMatchesExactRemainder) {
  std::mt19937_64 rng(17);
  std::uniform_int_distribution<int> deg(0, 8);
  for (int trial = 0; trial < 200; ++trial) {
    const Polynomial n(randomIntegers(rng, deg(rng), 20));
    // Monic integer divisor: long division stays in the integers, hence exact.
    std::vector<double> dc = randomIntegers(rng, deg(rng), 5);
    dc.back() = 1.0;
    const Polynomial d(dc);
    const PolynomialDivision qr = divide(n, d);
    EXPECT_TRUE(equalsExactly(qr.remainder, algebra_test::rem(algebra_test::toQ(n.coefficients()), algebra_test::toQ(dc))));
    EXPECT_TRUE(qr.quotient * d + qr.remainder == n.trimmed()) << "trial " << trial;
    EXPECT_LT(qr.remainder.effectiveDegree(), d.effectiveDegree());
  }
  // Non-integer case: reconstruction to rounding.
  for (int trial = 0; trial < 100; ++trial) {
    const Polynomial n(randomCoefficients(rng, 3 + trial % 6, -1.0, 1.0));
    const Polynomial d(randomCoefficients(rng, 1 + trial % 3, 0.5, 1.0));
    const PolynomialDivision qr = divide(n, d);
    const Polynomial back = qr.quotient * d + qr.remainder;
    for (int i = 0; i <= n.degree(); ++i) EXPECT_NEAR(back.coefficient(i), n.coefficient(i), 1e-9);
  }
}

TEST(Polynomial, RunningErrorBoundIsInfiniteWhenEvaluationOverflows) {
  const Polynomial p{1e300, 1e300, 1e300};
  double bound = 0.0;
  const double y = p.evaluateWithBound(1e200, &bound);
  EXPECT_TRUE(std::isinf(y));
  EXPECT_TRUE(std::isinf(bound));
  // Without overflow the bound is finite and holds.
  const double z = p.evaluateWithBound(0.5, &bound);
  EXPECT_TRUE(std::isfinite(bound));
  const Q exact = algebra_test::eval(algebra_test::toQ(p.coefficients()), Q(0.5));
  EXPECT_LE(abs(Q(z) - exact), Q(bound));
}

TEST(Polynomial, TrimmedDropsOnlyExactZeroLeadingCoefficients) {
  const Polynomial p{1.0, 0.0, 2.0, 0.0, 0.0};
  EXPECT_EQ(p.degree(), 4);
  EXPECT_EQ(p.effectiveDegree(), 2);
  EXPECT_EQ(p.trimmed().degree(), 2);
  EXPECT_EQ(p.trimmed().coefficient(1), 0.0);
  const Polynomial tiny{1.0, 1e-300};
  EXPECT_EQ(tiny.trimmed().degree(), 1);
  EXPECT_EQ((Polynomial{0.0, 0.0}.trimmed().degree()), 0);
  EXPECT_EQ((Polynomial{0.0, 0.0}.effectiveDegree()), -1);
  EXPECT_TRUE(Polynomial().isZero());
  EXPECT_EQ(p.coefficient(10), 0.0);
}

TEST(Polynomial, RejectsNonFiniteAndInvalidInput) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(Polynomial({1.0, nan}), std::invalid_argument);
  EXPECT_THROW(Polynomial({inf}), std::invalid_argument);
  EXPECT_THROW(Polynomial::constant(-inf), std::invalid_argument);
  EXPECT_THROW(Polynomial::monomial(-1), std::invalid_argument);
  EXPECT_THROW(Polynomial::fromRoots({1.0, nan}), std::invalid_argument);
  const Polynomial p{1.0, 2.0};
  EXPECT_THROW(p(nan), std::invalid_argument);
  EXPECT_THROW(p.evaluateWithBound(inf, nullptr), std::invalid_argument);
  EXPECT_THROW(p.composeAffine(nan, 0.0), std::invalid_argument);
  EXPECT_THROW(p * inf, std::invalid_argument);
  EXPECT_THROW(p.coefficient(-1), std::invalid_argument);
  Polynomial q = p;
  EXPECT_THROW(q.setCoefficient(0, nan), std::invalid_argument);
  EXPECT_THROW(divide(p, Polynomial{0.0, 0.0}), std::invalid_argument);
  try {
    Polynomial({1.0, 2.0, inf});
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("c[2]"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace fcl_quadric
