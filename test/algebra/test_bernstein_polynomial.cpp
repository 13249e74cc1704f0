// Tests of BernsteinPolynomial against exact rational conversions (GMP) built from the
// definitions of the Bernstein basis and of blossoming.
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "algebra/exact_rational.h"
#include "fcl_quadric/algebra/bernstein_polynomial.h"

namespace fcl_quadric {
namespace {

using algebra_test::Q;
using algebra_test::QPoly;

struct RandomBernstein {
  std::mt19937_64 rng;
  explicit RandomBernstein(unsigned seed) : rng(seed) {}
  BernsteinPolynomial next(int degree) {
    std::uniform_real_distribution<double> c(-1.0, 1.0);
    std::uniform_real_distribution<double> ad(-2.0, 2.0);
    std::uniform_real_distribution<double> wd(0.25, 3.0);
    std::vector<double> coeffs(static_cast<std::size_t>(degree) + 1);
    for (double& v : coeffs) v = c(rng);
    const double a = ad(rng);
    return BernsteinPolynomial(coeffs, a, a + wd(rng));
  }
};

Q exactValue(const BernsteinPolynomial& p, double t) {
  return algebra_test::eval(algebra_test::bernsteinToPower(p.coefficients(), p.lower(), p.upper()), Q(t));
}

double maxAbs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

TEST(BernsteinPolynomial, ToPowerMatchesExactRationalExpansion) {
  RandomBernstein gen(21);
  for (int trial = 0; trial < 150; ++trial) {
    const BernsteinPolynomial p = gen.next(trial % 9);
    const Polynomial power = p.toPower();
    const QPoly exact = algebra_test::bernsteinToPower(p.coefficients(), p.lower(), p.upper());
    ASSERT_EQ(power.degree() + 1, static_cast<int>(exact.size()));
    double scale = 1.0;
    for (const Q& v : exact) scale = std::max(scale, std::abs(v.get_d()));
    for (std::size_t i = 0; i < exact.size(); ++i) {
      EXPECT_NEAR(power.coefficient(static_cast<int>(i)), exact[i].get_d(), 1e-12 * scale) << "trial " << trial;
    }
  }
}

TEST(BernsteinPolynomial, FromPowerMatchesExactBlossomValues) {
  std::mt19937_64 rng(22);
  std::uniform_real_distribution<double> c(-1.0, 1.0);
  std::uniform_real_distribution<double> ad(-1.0, 1.0);
  for (int trial = 0; trial < 150; ++trial) {
    const int deg = trial % 9;
    std::vector<double> pc(static_cast<std::size_t>(deg) + 1);
    for (double& v : pc) v = c(rng);
    const double a = ad(rng);
    const double b = a + 0.5 + std::abs(ad(rng));
    const int target = deg + trial % 3;  // also degree-elevated representations
    const BernsteinPolynomial p = BernsteinPolynomial::fromPower(Polynomial(pc), a, b, target);
    const std::vector<Q> exact = algebra_test::powerToBernstein(algebra_test::toQ(pc), target, Q(a), Q(b));
    ASSERT_EQ(p.degree(), target);
    for (int i = 0; i <= target; ++i) {
      EXPECT_NEAR(p.coefficient(i), exact[static_cast<std::size_t>(i)].get_d(), 1e-12 * std::pow(3.0, deg))
          << "trial " << trial << " i " << i;
    }
  }
}

TEST(BernsteinPolynomial, PowerBernsteinRoundTripIsExactOnDyadicUnitInterval) {
  // On [0,1] with degree 2 all binomials are powers of two; integer power coefficients must
  // come back bit for bit (an exactness property of both conversions).
  std::mt19937_64 rng(23);
  std::uniform_int_distribution<int> d(-1000, 1000);
  for (int trial = 0; trial < 50; ++trial) {
    const Polynomial p{static_cast<double>(d(rng)), static_cast<double>(d(rng)), static_cast<double>(d(rng))};
    EXPECT_TRUE(BernsteinPolynomial::fromPower(p).toPower() == p);
  }
  // General degrees on intervals of moderate size near the origin (where the power basis is
  // well conditioned): agreement to rounding.
  std::uniform_real_distribution<double> c(-1.0, 1.0);
  std::uniform_real_distribution<double> ad(-0.5, 0.5);
  std::uniform_real_distribution<double> wd(0.5, 1.5);
  for (int trial = 0; trial < 100; ++trial) {
    std::vector<double> coeffs(static_cast<std::size_t>(trial % 8) + 1);
    for (double& v : coeffs) v = c(rng);
    const double a = ad(rng);
    const BernsteinPolynomial p(coeffs, a, a + wd(rng));
    const BernsteinPolynomial back = BernsteinPolynomial::fromPower(p.toPower(), p.lower(), p.upper());
    ASSERT_EQ(back.degree(), p.degree());
    // The power basis on such intervals has a condition number growing like ~6^n.
    const double tol = 1e-15 * std::pow(6.0, p.degree());
    for (int i = 0; i <= p.degree(); ++i) EXPECT_NEAR(back.coefficient(i), p.coefficient(i), tol);
  }
}

// Up to kMaxBernsteinDegree the conversion stays finite; above it, it throws instead of dividing
// overflowed binomial coefficients (inf / inf = NaN; session 34: such NaN coefficients passed a
// sign test of the CCD). p(t) = 1 + t^n has Bernstein coefficients 1, ..., 1, 2 on [0, 1].
TEST(BernsteinPolynomial, ConversionsUpToTheDegreeLimitAreFiniteAndAboveItThrow) {
  for (int n : {200, 600, kMaxBernsteinDegree}) {
    std::vector<double> q(static_cast<std::size_t>(n) + 1, 0.0);
    q.front() = 1.0;
    q.back() = 1.0;
    const BernsteinPolynomial b = BernsteinPolynomial::fromPower(Polynomial(q));
    ASSERT_EQ(b.degree(), n);
    for (int i = 0; i < n; ++i) ASSERT_EQ(b.coefficient(i), 1.0) << "n = " << n << ", i = " << i;
    EXPECT_EQ(b.coefficient(n), 2.0);
    EXPECT_NEAR(b.evaluate(0.5), 1.0, 1e-15);
  }
  std::vector<double> q(static_cast<std::size_t>(kMaxBernsteinDegree) + 2, 0.0);
  q.back() = 1.0;
  try {
    BernsteinPolynomial::fromPower(Polynomial(q));
    FAIL() << "degree " << kMaxBernsteinDegree + 1 << " accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(std::to_string(kMaxBernsteinDegree + 1)), std::string::npos) << e.what();
  }
}

TEST(BernsteinPolynomial, ScaledFormMatchesDefinition) {
  RandomBernstein gen(25);
  std::mt19937_64 rng(26);
  for (int trial = 0; trial < 100; ++trial) {
    const BernsteinPolynomial p = gen.next(trial % 10);
    const std::vector<double> scaled = p.toScaled();
    const int n = p.degree();
    // p(t) = sum d_i (1-s)^(n-i) s^i, evaluated exactly.
    std::uniform_real_distribution<double> td(p.lower(), p.upper());
    const double t = td(rng);
    const Q s = (Q(t) - Q(p.lower())) / (Q(p.upper()) - Q(p.lower()));
    Q value = 0;
    for (int i = 0; i <= n; ++i) {
      Q term = Q(scaled[static_cast<std::size_t>(i)]);
      for (int k = 0; k < i; ++k) term *= s;
      for (int k = 0; k < n - i; ++k) term *= (1 - s);
      value += term;
    }
    EXPECT_NEAR(value.get_d(), exactValue(p, t).get_d(), 1e-13 * std::pow(2.0, n));
    const BernsteinPolynomial back = BernsteinPolynomial::fromScaled(scaled, p.lower(), p.upper());
    for (int i = 0; i <= n; ++i) EXPECT_NEAR(back.coefficient(i), p.coefficient(i), 1e-15);
  }
}

TEST(BernsteinPolynomial, DeCasteljauEvaluationMatchesExactValue) {
  RandomBernstein gen(27);
  std::mt19937_64 rng(28);
  for (int trial = 0; trial < 200; ++trial) {
    const BernsteinPolynomial p = gen.next(trial % 12);
    std::uniform_real_distribution<double> td(p.lower(), p.upper());
    const double t = td(rng);
    // de Casteljau is backward stable with error <= 2n u max|c| on the interval.
    EXPECT_NEAR(p.evaluate(t), exactValue(p, t).get_d(), 1e-15 * (2 * p.degree() + 2) * maxAbs(p.coefficients()));
    EXPECT_EQ(p.evaluate(p.lower()), p.coefficients().front());
    EXPECT_EQ(p.evaluate(p.upper()), p.coefficients().back());
  }
}

TEST(BernsteinPolynomial, SubdivisionHalvesEvaluateEqualToWhole) {
  RandomBernstein gen(29);
  std::mt19937_64 rng(30);
  for (int trial = 0; trial < 200; ++trial) {
    const BernsteinPolynomial p = gen.next(1 + trial % 10);
    std::uniform_real_distribution<double> td(p.lower(), p.upper());
    const double t = td(rng);
    const auto halves = p.subdivide(t);
    EXPECT_EQ(halves.first.lower(), p.lower());
    EXPECT_EQ(halves.first.upper(), t);
    EXPECT_EQ(halves.second.lower(), t);
    EXPECT_EQ(halves.second.upper(), p.upper());
    EXPECT_EQ(halves.first.coefficients().back(), halves.second.coefficients().front());
    const double tol = 1e-14 * (p.degree() + 1);
    const QPoly exact = algebra_test::bernsteinToPower(p.coefficients(), p.lower(), p.upper());
    for (int k = 0; k < 5; ++k) {
      std::uniform_real_distribution<double> l(p.lower(), t);
      std::uniform_real_distribution<double> r(t, p.upper());
      const double x = l(rng);
      const double y = r(rng);
      EXPECT_NEAR(halves.first.evaluate(x), algebra_test::eval(exact, Q(x)).get_d(), tol);
      EXPECT_NEAR(halves.second.evaluate(y), algebra_test::eval(exact, Q(y)).get_d(), tol);
    }
  }
}

TEST(BernsteinPolynomial, RestrictMatchesExactCoefficientsOnSubinterval) {
  RandomBernstein gen(31);
  std::mt19937_64 rng(32);
  for (int trial = 0; trial < 150; ++trial) {
    const BernsteinPolynomial p = gen.next(trial % 9);
    std::uniform_real_distribution<double> td(p.lower(), p.upper());
    double c = td(rng);
    double d = td(rng);
    if (c > d) std::swap(c, d);
    if (!(c < d)) continue;
    const BernsteinPolynomial r = p.restrict(c, d);
    const QPoly exact_power = algebra_test::bernsteinToPower(p.coefficients(), p.lower(), p.upper());
    const std::vector<Q> exact = algebra_test::powerToBernstein(exact_power, p.degree(), Q(c), Q(d));
    EXPECT_EQ(r.lower(), c);
    EXPECT_EQ(r.upper(), d);
    for (int i = 0; i <= p.degree(); ++i) {
      EXPECT_NEAR(r.coefficient(i), exact[static_cast<std::size_t>(i)].get_d(), 1e-13 * (p.degree() + 1));
    }
    // Consistency with subdivide and the identity restriction.
    const auto halves = p.subdivide(d);
    EXPECT_EQ(p.restrict(p.lower(), d).coefficients(), halves.first.coefficients());
    EXPECT_EQ(p.restrict(p.lower(), p.upper()).coefficients(), p.coefficients());
  }
}

// detail::restrictInPlace (the bivariate restriction's rows and columns) against the two de
// Casteljau splits it stands for, computed here with deCasteljauSplit: the same doubles, for every
// placement of [lo, hi] (inside, sharing an end, overhanging one end, left of [a, b] touching it),
// for one to three interleaved polynomials (lanes) along a stride, and the entries off the lanes
// untouched. The results are also checked against the exact coefficients (beyond [a, b], a
// moderate extrapolation, with a looser tolerance).
TEST(BernsteinPolynomial, RestrictInPlaceAlongAStrideGivesTheSplitsDoublesAndTheExactCoefficients) {
  RandomBernstein gen(35);
  std::mt19937_64 rng(36);
  std::uniform_real_distribution<double> unit(0.05, 0.95);
  const auto reference = [](std::vector<double> c, double a, double b, double lo, double hi) {
    if (lo == a && hi == b) return c;
    if (hi != a) {
      if (hi != b) detail::deCasteljauSplit(c, (hi - a) / (b - a), &c, nullptr);
      if (lo != a) detail::deCasteljauSplit(c, (lo - a) / (hi - a), nullptr, &c);
    } else {
      detail::deCasteljauSplit(c, (lo - a) / (b - a), nullptr, &c);
      detail::deCasteljauSplit(c, (hi - lo) / (b - lo), &c, nullptr);
    }
    return c;
  };
  int outside = 0;
  for (int trial = 0; trial < 180; ++trial) {
    const BernsteinPolynomial p = gen.next(trial % 12);
    const double a = p.lower(), b = p.upper(), w = b - a;
    double lo = a + unit(rng) * w, hi = a + unit(rng) * w;
    if (lo > hi) std::swap(lo, hi);
    // Overhangs of at most a quarter of [a, b]: each extrapolating split multiplies the rounding
    // by up to 1.5^n (|1 - s| + |s|), so the exact comparison keeps a tolerance near the inside one.
    const double overhang = 0.25 * unit(rng) * w;
    switch (trial % 6) {
      case 0: break;                                    // inside
      case 1: lo = a; break;                            // sharing the lower end
      case 2: hi = b; break;                            // sharing the upper end
      case 3: hi = a; lo = a - overhang; break;         // left of [a, b], touching it
      case 4: hi = b + overhang; break;                 // overhanging the upper end
      default: lo = a - overhang; break;                // overhanging the lower end
    }
    if (!(lo < hi)) continue;
    // Lane 0 is p; the other lanes other polynomials of its degree on [a, b].
    const std::size_t lanes = 1 + static_cast<std::size_t>(trial / 6 % 3), n1 = p.coefficients().size();
    std::vector<std::vector<double>> polys{p.coefficients()};
    std::uniform_real_distribution<double> coefficient(-1.0, 1.0);
    while (polys.size() < lanes) {
      polys.emplace_back(n1);
      for (double& v : polys.back()) v = coefficient(rng);
    }
    const std::size_t stride = lanes + static_cast<std::size_t>(trial % 4);
    const double sentinel = -12345.5;
    std::vector<double> buffer(n1 * stride, sentinel);
    for (std::size_t l = 0; l < lanes; ++l)
      for (std::size_t i = 0; i < n1; ++i) buffer[i * stride + l] = polys[l][i];
    detail::restrictInPlace(buffer.data(), n1, static_cast<std::ptrdiff_t>(stride), lanes, a, b, lo, hi);
    const bool beyond = lo < a || hi > b;
    outside += beyond;
    for (std::size_t l = 0; l < lanes; ++l) {
      const std::vector<double> expected = reference(polys[l], a, b, lo, hi);
      const QPoly exact_power = algebra_test::bernsteinToPower(polys[l], a, b);
      const std::vector<Q> exact = algebra_test::powerToBernstein(exact_power, p.degree(), Q(lo), Q(hi));
      for (std::size_t k = 0; k < n1; ++k) {
        const double v = buffer[k * stride + l];
        EXPECT_EQ(v, expected[k]) << "trial " << trial << ", lane " << l << ", coefficient " << k;
        EXPECT_NEAR(v, exact[k].get_d(), (beyond ? 1e-11 : 1e-13) * (p.degree() + 1))
            << "trial " << trial << ", lane " << l << ", coefficient " << k;
      }
      if (l == 0) {
        EXPECT_EQ(p.restrict(lo, hi).coefficients(), expected) << "trial " << trial;
      }
    }
    for (std::size_t i = 0; i < buffer.size(); ++i) {
      if (i % stride >= lanes) {
        EXPECT_EQ(buffer[i], sentinel) << "trial " << trial << ": entry " << i << " off the lanes";
      }
    }
  }
  EXPECT_GE(outside, 80);
}
TEST(BernsteinPolynomial, DerivativeMatchesExactDerivative) {
  RandomBernstein gen(33);
  std::mt19937_64 rng(34);
  for (int trial = 0; trial < 150; ++trial) {
    const BernsteinPolynomial p = gen.next(trial % 10);
    const BernsteinPolynomial dp = p.derivative();
    EXPECT_EQ(dp.degree(), std::max(p.degree() - 1, 0));
    const QPoly exact = algebra_test::derivative(algebra_test::bernsteinToPower(p.coefficients(), p.lower(), p.upper()));
    std::uniform_real_distribution<double> td(p.lower(), p.upper());
    for (int k = 0; k < 4; ++k) {
      const double t = td(rng);
      const double scale = (p.degree() + 1) * maxAbs(p.coefficients()) / p.width();
      EXPECT_NEAR(dp.evaluate(t), algebra_test::eval(exact, Q(t)).get_d(), 1e-14 * (p.degree() + 1) * scale);
    }
  }
}

TEST(BernsteinPolynomial, ElevationPreservesThePolynomial) {
  RandomBernstein gen(35);
  std::mt19937_64 rng(135);
  for (int trial = 0; trial < 100; ++trial) {
    const BernsteinPolynomial p = gen.next(trial % 8);
    const BernsteinPolynomial e = p.elevateTo(p.degree() + 1 + trial % 3);
    ASSERT_EQ(e.degree(), p.degree() + 1 + trial % 3);
    // Compare the exact power forms of both double representations at sample points.
    const QPoly a = algebra_test::bernsteinToPower(p.coefficients(), p.lower(), p.upper());
    const QPoly b = algebra_test::bernsteinToPower(e.coefficients(), e.lower(), e.upper());
    std::uniform_real_distribution<double> td(p.lower(), p.upper());
    for (int k = 0; k < 5; ++k) {
      const Q t(td(rng));
      EXPECT_NEAR(algebra_test::eval(b, t).get_d(), algebra_test::eval(a, t).get_d(),
                  1e-15 * (e.degree() + 2) * maxAbs(p.coefficients()));
    }
  }
}

TEST(BernsteinPolynomial, ProductMatchesExactProduct) {
  RandomBernstein gen(36);
  std::mt19937_64 rng(37);
  for (int trial = 0; trial < 100; ++trial) {
    const BernsteinPolynomial p = gen.next(trial % 6);
    const BernsteinPolynomial q0 = gen.next(trial % 5);
    const BernsteinPolynomial q(q0.coefficients(), p.lower(), p.upper());
    const BernsteinPolynomial pq = p * q;
    EXPECT_EQ(pq.degree(), p.degree() + q.degree());
    const QPoly exact = algebra_test::mul(algebra_test::bernsteinToPower(p.coefficients(), p.lower(), p.upper()),
                                          algebra_test::bernsteinToPower(q.coefficients(), q.lower(), q.upper()));
    std::uniform_real_distribution<double> td(p.lower(), p.upper());
    for (int k = 0; k < 4; ++k) {
      const double t = td(rng);
      EXPECT_NEAR(pq.evaluate(t), algebra_test::eval(exact, Q(t)).get_d(), 1e-13);
    }
  }
}

TEST(BernsteinPolynomial, CoefficientRangeBoundsValuesOnInterval) {
  RandomBernstein gen(38);
  std::mt19937_64 rng(39);
  for (int trial = 0; trial < 100; ++trial) {
    const BernsteinPolynomial p = gen.next(trial % 10);
    const QPoly exact = algebra_test::bernsteinToPower(p.coefficients(), p.lower(), p.upper());
    std::uniform_real_distribution<double> td(p.lower(), p.upper());
    for (int k = 0; k < 10; ++k) {
      const Q v = algebra_test::eval(exact, Q(td(rng)));
      EXPECT_LE(Q(p.minCoefficient()), v);
      EXPECT_GE(Q(p.maxCoefficient()), v);
    }
  }
}

TEST(BernsteinPolynomial, SignVariationsIgnoreZerosAndBoundRootsInOpenInterval) {
  // By definition: sign sequence + - + (zeros skipped) -> 2 variations, etc.
  EXPECT_EQ(BernsteinPolynomial({1.0, 0.0, -1.0, 0.0, 0.0, 2.0}).signVariations(), 2);
  EXPECT_EQ(BernsteinPolynomial({0.0, 0.0, 0.0}).signVariations(), 0);
  EXPECT_EQ(BernsteinPolynomial({-1.0, -2.0, 0.0, -3.0}).signVariations(), 0);
  EXPECT_EQ(BernsteinPolynomial({0.0, 1.0, -1.0, 1.0, -1.0, 0.0}).signVariations(), 3);
  // Descartes: V bounds the number of distinct roots in (a,b), with the same parity counting
  // multiplicity; checked against exact Sturm counts.
  RandomBernstein gen(40);
  for (int trial = 0; trial < 200; ++trial) {
    const BernsteinPolynomial p = gen.next(1 + trial % 8);
    const algebra_test::ExactSturm sturm(algebra_test::bernsteinToPower(p.coefficients(), p.lower(), p.upper()));
    const int roots = sturm.countOpen(Q(p.lower()), Q(p.upper()));
    EXPECT_LE(roots, p.signVariations());
    if (p.signVariations() <= 1) {
      EXPECT_EQ(roots, p.signVariations());
    }
  }
}

TEST(BernsteinPolynomial, RejectsBadInput) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(BernsteinPolynomial({}, 0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(BernsteinPolynomial({1.0, nan}, 0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(BernsteinPolynomial({1.0}, 1.0, 1.0), std::invalid_argument);
  EXPECT_THROW(BernsteinPolynomial({1.0}, 2.0, 1.0), std::invalid_argument);
  EXPECT_THROW(BernsteinPolynomial({1.0}, 0.0, inf), std::invalid_argument);
  const BernsteinPolynomial p({1.0, -1.0, 2.0}, 0.0, 2.0);
  EXPECT_THROW(p.subdivide(0.0), std::invalid_argument);
  EXPECT_THROW(p.subdivide(2.0), std::invalid_argument);
  EXPECT_THROW(p.subdivide(nan), std::invalid_argument);
  EXPECT_THROW(p.restrict(1.0, 1.0), std::invalid_argument);
  EXPECT_THROW(p.restrict(1.5, 0.5), std::invalid_argument);
  EXPECT_THROW(p.evaluate(nan), std::invalid_argument);
  EXPECT_THROW(p.coefficient(3), std::invalid_argument);
  EXPECT_THROW(p * BernsteinPolynomial({1.0}, 0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(p + BernsteinPolynomial({1.0, 2.0}, 0.0, 2.0), std::invalid_argument);
  EXPECT_THROW(p + BernsteinPolynomial({1.0, 2.0, 3.0}, 0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(p.elevateTo(1), std::invalid_argument);
  EXPECT_THROW(BernsteinPolynomial::fromPower(Polynomial{1.0, 2.0, 3.0}, 0.0, 1.0, 1), std::invalid_argument);
  EXPECT_THROW(BernsteinPolynomial::fromPower(Polynomial{1.0}, 1.0, 0.0), std::invalid_argument);
  EXPECT_THROW(BernsteinPolynomial::fromScaled({1.0, inf}), std::invalid_argument);
}

}  // namespace
}  // namespace fcl_quadric
