// Tests of the Bernstein root finders. The oracle is an exact rational Sturm sequence of the
// polynomial that the double Bernstein coefficients represent (converted exactly to the power
// basis), so every certificate the library issues is checked exactly.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "algebra/exact_rational.h"
#include "fcl_quadric/algebra/root_isolation.h"

namespace fcl_quadric {
namespace {

using algebra_test::ExactSturm;
using algebra_test::Q;
using algebra_test::QPoly;

/// The Bernstein polynomial on [a, b] of scale * prod (t - r_k) * (optionally) ((t-m)^2 + d),
/// computed exactly and rounded to double coefficients.
BernsteinPolynomial fromRootsRounded(const std::vector<double>& roots, double a, double b, double scale,
                                     bool complex_pair = false) {
  std::vector<Q> qroots;
  for (double r : roots) qroots.emplace_back(r);
  QPoly p = algebra_test::fromRoots(qroots, Q(scale));
  if (complex_pair) {
    const Q m = (Q(a) + Q(b)) / 2;
    const Q d = (Q(b) - Q(a)) * (Q(b) - Q(a)) / 16;
    p = algebra_test::mul(p, QPoly{m * m + d, -2 * m, Q(1)});
  }
  const std::vector<Q> c = algebra_test::powerToBernstein(p, static_cast<int>(p.size()) - 1, Q(a), Q(b));
  std::vector<double> cd;
  for (const Q& v : c) cd.push_back(v.get_d());
  return BernsteinPolynomial(cd, a, b);
}

QPoly exactPower(const BernsteinPolynomial& p) {
  return algebra_test::bernsteinToPower(p.coefficients(), p.lower(), p.upper());
}

/// Random roots in (a, b), pairwise at least min_gap apart; some deliberately close pairs.
std::vector<double> randomRoots(std::mt19937_64& rng, int k, double a, double b, double min_gap, bool with_close_pair) {
  std::uniform_real_distribution<double> rd(a + 0.01 * (b - a), b - 0.01 * (b - a));
  std::vector<double> roots;
  if (with_close_pair && k >= 2) {
    const double r = rd(rng);
    const double r2 = std::min(r + min_gap * 1.5, b - 0.001 * (b - a));
    if (r2 - r >= min_gap) {
      roots.push_back(r);
      roots.push_back(r2);
    }
  }
  while (static_cast<int>(roots.size()) < k) {
    const double r = rd(rng);
    bool ok = true;
    for (double s : roots) ok = ok && std::abs(r - s) >= min_gap;
    if (ok) roots.push_back(r);
  }
  std::sort(roots.begin(), roots.end());
  return roots;
}

/// Checks the contract of a root-finder result against the exact polynomial:
///  - intervals sorted, within [a,b], pairwise disjoint up to shared endpoints (or an overlap of
///    a few ulps where a subdivision point of a non-dyadic [a,b] was rounded outward);
///  - every Single interval with lo < hi holds exactly one exact root in (lo, hi), with nonzero
///    exact values of opposite sign at lo and hi; every Single point is an exact zero;
///  - no exact root lies outside the union of the intervals (nothing dropped);
///  - Unresolved intervals are at most max_width wide.
void checkContract(const BernsteinPolynomial& p, const std::vector<RootInterval>& out, double max_width) {
  const QPoly exact = exactPower(p);
  const ExactSturm sturm(exact);
  double prev_hi = p.lower();
  Q gap_lo = Q(p.lower());
  bool gap_lo_closed = true;  // whether gap_lo itself is uncovered
  for (const RootInterval& r : out) {
    ASSERT_LE(r.lo, r.hi);
    const double ulps = 16.0 * std::numeric_limits<double>::epsilon() * (std::abs(p.lower()) + std::abs(p.upper()));
    ASSERT_GE(r.lo, prev_hi - ulps) << "intervals overlap or are unsorted";
    ASSERT_GE(r.lo, p.lower());
    ASSERT_LE(r.hi, p.upper());
    // Uncovered gap before this interval: [gap_lo or (gap_lo, r.lo).
    if (Q(r.lo) > gap_lo) {
      int uncovered = sturm.countOpen(gap_lo, Q(r.lo));
      if (gap_lo_closed && algebra_test::eval(exact, gap_lo) == 0) ++uncovered;
      EXPECT_EQ(uncovered, 0) << "root dropped before [" << r.lo << ", " << r.hi << "]";
    }
    if (r.kind == RootKind::Single) {
      if (r.lo == r.hi) {
        EXPECT_EQ(algebra_test::eval(exact, Q(r.lo)), 0) << "point " << r.lo;
      } else {
        EXPECT_EQ(sturm.countOpen(Q(r.lo), Q(r.hi)), 1) << "[" << r.lo << ", " << r.hi << "]";
        const int slo = algebra_test::signOf(algebra_test::eval(exact, Q(r.lo)));
        const int shi = algebra_test::signOf(algebra_test::eval(exact, Q(r.hi)));
        EXPECT_EQ(slo * shi, -1) << "[" << r.lo << ", " << r.hi << "]";
      }
    } else {
      EXPECT_LE(r.hi - r.lo, max_width);
    }
    prev_hi = r.hi;
    gap_lo = Q(r.hi);
    gap_lo_closed = false;
  }
  if (Q(p.upper()) > gap_lo) {
    int uncovered = sturm.countClosed(gap_lo, Q(p.upper()));
    if (!gap_lo_closed && algebra_test::eval(exact, gap_lo) == 0) --uncovered;  // gap_lo is covered
    EXPECT_EQ(uncovered, 0) << "root dropped after the last interval";
  } else if (gap_lo_closed && algebra_test::eval(exact, gap_lo) == 0) {
    ADD_FAILURE() << "root at the upper end dropped";
  }
}

std::string describe(const std::vector<RootInterval>& out) {
  std::ostringstream os;
  os.precision(17);
  for (const RootInterval& r : out) {
    os << "[" << r.lo << ", " << r.hi << (r.kind == RootKind::Single ? " S] " : " U] ");
  }
  return os.str();
}

/// Number of intervals (closed) containing x.
int containing(const std::vector<RootInterval>& out, double x, double slack) {
  int n = 0;
  for (const RootInterval& r : out) {
    if (r.lo - slack <= x && x <= r.hi + slack) ++n;
  }
  return n;
}

TEST(RootIsolation, IsolateRootsFindsEveryRootOfRandomProducts) {
  std::mt19937_64 rng(61);
  std::uniform_real_distribution<double> ad(-2.0, 1.0);
  std::uniform_real_distribution<double> wd(0.5, 3.0);
  int all_roots_survived_rounding = 0;
  const int trials = 80;
  for (int trial = 0; trial < trials; ++trial) {
    const double a = trial % 3 == 0 ? 0.0 : ad(rng);
    const double b = trial % 3 == 0 ? 1.0 : a + wd(rng);
    const int k = 1 + trial % 8;
    const std::vector<double> roots = randomRoots(rng, k, a, b, 1e-6 * (b - a), trial % 2 == 0);
    const BernsteinPolynomial p = fromRootsRounded(roots, a, b, trial % 4 == 1 ? -3.0 : 1.0, trial % 5 == 0);
    const double min_width = 1e-12;
    const std::vector<RootInterval> out = isolateRoots(p, min_width);
    checkContract(p, out, min_width);
    // The roots of the rounded polynomial (a close pair may have become complex): one Single
    // interval for each, nothing unresolved.
    const int exact_roots = ExactSturm(exactPower(p)).countClosed(Q(a), Q(b));
    int unresolved = 0;
    for (const RootInterval& r : out) unresolved += r.kind == RootKind::Unresolved;
    EXPECT_EQ(unresolved, 0) << "trial " << trial;
    EXPECT_EQ(static_cast<int>(out.size()), exact_roots) << "trial " << trial;
    if (exact_roots != k) continue;
    ++all_roots_survived_rounding;
    // Each intended root is near an interval (the slack, below half the separation, covers the
    // displacement of close roots by the rounding of the coefficients).
    for (double r : roots) EXPECT_GE(containing(out, r, 4e-7 * (b - a)), 1) << "root " << r << " trial " << trial;
  }
  EXPECT_GE(all_roots_survived_rounding, trials * 9 / 10);
}

TEST(RootIsolation, RootsExactlyAtSubdivisionPointsAreReportedOnce) {
  // Antisymmetric dyadic coefficients with zero ends: exact zeros at a = 0, at the first
  // midpoint 1/2 and at b = 1 (de Casteljau at 1/2 is exact for these values).
  {
    const BernsteinPolynomial p({0.0, 1.0, -1.0, 1.0, -1.0, 0.0});
    const std::vector<RootInterval> out = isolateRoots(p, 1e-12);
    checkContract(p, out, 1e-12);
    for (double x : {0.0, 0.5, 1.0}) {
      int points = 0;
      for (const RootInterval& r : out) points += (r.lo == x && r.hi == x);
      EXPECT_EQ(points, 1) << "x = " << x;
      EXPECT_EQ(containing(out, x, 0.0), 1) << "x = " << x;  // not also inside a neighbour
    }
    const ExactSturm sturm(exactPower(p));
    EXPECT_EQ(static_cast<int>(out.size()), sturm.countClosed(Q(0), Q(1)));
  }
  // Roots at 1, 2, 3 on [0, 4]: the midpoints of the first two subdivision levels.
  {
    const BernsteinPolynomial p = fromRootsRounded({1.0, 2.0, 3.0}, 0.0, 4.0, 1.0);
    const std::vector<RootInterval> out = isolateRoots(p, 1e-12);
    checkContract(p, out, 1e-12);
    EXPECT_EQ(out.size(), 3u);
    for (double x : {1.0, 2.0, 3.0}) EXPECT_EQ(containing(out, x, 1e-12), 1) << "x = " << x;
  }
  // A triple root exactly at the midpoint: (s - 1/2)^3 has Bernstein coefficients
  // (-1/2)^(3-i) (1/2)^i. Reported once, as an Unresolved point.
  {
    const BernsteinPolynomial p({-0.125, 0.125, -0.125, 0.125});
    const std::vector<RootInterval> out = isolateRoots(p, 1e-9);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].lo, 0.5);
    EXPECT_EQ(out[0].hi, 0.5);
    EXPECT_EQ(out[0].kind, RootKind::Unresolved);
  }
}

TEST(RootIsolation, MultipleRootsAndClustersAreNeverDropped) {
  std::mt19937_64 rng(62);
  std::uniform_real_distribution<double> rd(0.05, 0.95);
  for (int trial = 0; trial < 40; ++trial) {
    const double r = rd(rng);
    std::vector<double> roots{r, r};  // double root
    if (trial % 2 == 0) roots.push_back(r + 1e-13);  // plus a clustered third root
    if (trial % 3 == 0) roots.push_back(rd(rng));
    const BernsteinPolynomial p = fromRootsRounded(roots, 0.0, 1.0, 1.0);
    const double min_width = 1e-8;
    const std::vector<RootInterval> out = isolateRoots(p, min_width);
    checkContract(p, out, min_width);
    // The rounded polynomial's cluster near r has real roots whenever the exact oracle says so;
    // then some interval lies within the cluster's neighbourhood.
    const ExactSturm sturm(exactPower(p));
    if (sturm.countClosed(Q(r - 1e-6), Q(r + 1e-6)) > 0) {
      EXPECT_GE(containing(out, r, 1e-6), 1) << "trial " << trial;
    }
  }
  // Exactly representable double root at a non-dyadic position is impossible, so also check a
  // cluster with the ends of the interval: roots 0, 0 and 1e-13 on [0, 1].
  const BernsteinPolynomial p = fromRootsRounded({0.0, 0.0, 1e-13, 0.5}, 0.0, 1.0, 1.0);
  const std::vector<RootInterval> out = isolateRoots(p, 1e-9);
  checkContract(p, out, 1e-9);
  ASSERT_FALSE(out.empty());
  EXPECT_EQ(out.front().lo, 0.0);
}

TEST(RootIsolation, DescartesBoundOfZeroOrOneIsExactOnSubintervals) {
  std::mt19937_64 rng(63);
  std::uniform_real_distribution<double> c(-1.0, 1.0);
  std::uniform_real_distribution<double> s(0.0, 1.0);
  int zero = 0;
  int one = 0;
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<double> coeffs(static_cast<std::size_t>(1 + trial % 7) + 1);
    for (double& v : coeffs) v = c(rng);
    double lo = s(rng);
    double hi = s(rng);
    if (lo > hi) std::swap(lo, hi);
    if (!(lo < hi)) continue;
    const BernsteinPolynomial piece = BernsteinPolynomial(coeffs).restrict(lo, hi);
    const int v = descartesBound(piece);
    const ExactSturm sturm(exactPower(piece));
    const int roots = sturm.countOpen(Q(lo), Q(hi));
    EXPECT_LE(roots, v);
    if (v == 0) {
      EXPECT_EQ(roots, 0);
      ++zero;
    }
    if (v == 1) {
      EXPECT_EQ(roots, 1);
      ++one;
    }
  }
  EXPECT_GT(zero, 20);
  EXPECT_GT(one, 20);
}

TEST(RootIsolation, BezierClipAgreesWithIsolateRoots) {
  std::mt19937_64 rng(64);
  for (int trial = 0; trial < 60; ++trial) {
    const double a = trial % 2 == 0 ? 0.0 : -1.0;
    const double b = trial % 2 == 0 ? 1.0 : 2.0;
    const int k = 1 + trial % 7;
    const std::vector<double> roots = randomRoots(rng, k, a, b, 1e-3, trial % 3 == 0);
    const BernsteinPolynomial p = fromRootsRounded(roots, a, b, 2.0, trial % 4 == 0);
    const double tol = 1e-12;
    const std::vector<RootInterval> clip = bezierClip(p, tol);
    const std::vector<RootInterval> iso = isolateRoots(p, tol);
    checkContract(p, clip, tol);
    ASSERT_EQ(clip.size(), iso.size()) << "trial " << trial << ": " << describe(clip) << " vs " << describe(iso);
    for (std::size_t i = 0; i < clip.size(); ++i) {
      EXPECT_EQ(clip[i].kind, RootKind::Single);
      EXPECT_LE(clip[i].hi - clip[i].lo, tol);
      // The clipped interval lies in the isolating interval of the same root.
      EXPECT_GE(clip[i].lo, iso[i].lo);
      EXPECT_LE(clip[i].hi, iso[i].hi);
    }
  }
  // Endpoint and midpoint zeros are reported once as well.
  const BernsteinPolynomial p({0.0, 1.0, -1.0, 1.0, -1.0, 0.0});
  const std::vector<RootInterval> clip = bezierClip(p, 1e-12);
  checkContract(p, clip, 1e-12);
  for (double x : {0.0, 0.5, 1.0}) EXPECT_EQ(containing(clip, x, 0.0), 1) << "x = " << x;
}

TEST(RootIsolation, RefineRootReachesRequestedAccuracy) {
  std::mt19937_64 rng(65);
  const double tol = 1e-14;
  for (int trial = 0; trial < 60; ++trial) {
    const int k = 1 + trial % 6;
    const std::vector<double> roots = randomRoots(rng, k, 0.0, 1.0, 0.02, false);
    const BernsteinPolynomial p = fromRootsRounded(roots, 0.0, 1.0, 1.0, trial % 3 == 0);
    const ExactSturm sturm(exactPower(p));
    for (const RootInterval& iv : isolateRoots(p, 1e-12)) {
      ASSERT_EQ(iv.kind, RootKind::Single);
      if (iv.lo == iv.hi) continue;
      const double x = refineRoot(p, iv.lo, iv.hi, tol);
      EXPECT_GE(sturm.countClosed(Q(x) - Q(tol), Q(x) + Q(tol)), 1) << "x = " << x << " trial " << trial;
      const RootInterval br = refineRootBracket(p, iv.lo, iv.hi, tol);
      EXPECT_LE(br.hi - br.lo, tol);
      EXPECT_EQ(sturm.countClosed(Q(br.lo), Q(br.hi)), 1);
    }
  }
  // A bracket with an exact zero at an end returns that end.
  const BernsteinPolynomial p({-1.0, 1.0}, 0.0, 2.0);  // root at t = 1
  EXPECT_EQ(refineRoot(p, 0.0, 1.0, 1e-3), 1.0);
  EXPECT_EQ(refineRoot(p, 0.5, 1.5, 0.0), 1.0);
}

TEST(RootIsolation, FirstRootIsNeverLaterThanTheSmallestRoot) {
  std::mt19937_64 rng(66);
  for (int trial = 0; trial < 80; ++trial) {
    const int k = 1 + trial % 6;
    const std::vector<double> roots = randomRoots(rng, k, 0.0, 1.0, 1e-4, trial % 2 == 0);
    std::vector<double> with_mult = roots;
    if (trial % 5 == 0) with_mult.push_back(roots.front());  // double first root
    const BernsteinPolynomial p = fromRootsRounded(with_mult, 0.0, 1.0, trial % 2 == 0 ? 1.0 : -1.0);
    const double tol = trial % 3 == 0 ? 1e-6 : 1e-13;
    const std::optional<double> x = firstRoot(p, tol);
    const QPoly exact = exactPower(p);
    const ExactSturm sturm(exact);
    if (!x) {
      EXPECT_EQ(sturm.countClosed(Q(0), Q(1)), 0);
      continue;
    }
    // No exact root in [0, x) and a root within [x, x + tol], or x is the left end of an
    // Unresolved cluster (only possible with a double root).
    const int before = sturm.countClosed(Q(0), Q(*x)) - (algebra_test::eval(exact, Q(*x)) == 0 ? 1 : 0);
    EXPECT_EQ(before, 0) << "trial " << trial;
    if (trial % 5 != 0) {
      EXPECT_GE(sturm.countClosed(Q(*x), Q(*x) + Q(tol)), 1) << "trial " << trial;
      EXPECT_NEAR(*x, roots.front(), tol + 1e-9);
    } else if (sturm.countClosed(Q(roots.front() - 1e-6), Q(roots.front() + 1e-6)) > 0) {
      // The rounded double root stayed real (it may also have become a complex pair, which the
      // exact oracle detects; then the first root is legitimately a later one).
      EXPECT_NEAR(*x, roots.front(), 1e-6) << "trial " << trial;
    }
  }
  // No root: nullopt.
  EXPECT_FALSE(firstRoot(BernsteinPolynomial({1.0, -0.2, 0.5}), 1e-12).has_value());
  EXPECT_FALSE(firstRoot(BernsteinPolynomial({1.0, 2.0, 0.5}), 1e-12).has_value());
  // Root at the lower end.
  EXPECT_EQ(firstRoot(BernsteinPolynomial({0.0, 1.0, 2.0}, 3.0, 4.0), 1e-12), 3.0);
}

TEST(RootIsolation, IdenticallyZeroPolynomialIsReportedAsOneUnresolvedInterval) {
  const BernsteinPolynomial zero({0.0, 0.0, 0.0}, -1.0, 2.0);
  for (const std::vector<RootInterval>& out : {isolateRoots(zero, 1e-6), bezierClip(zero, 1e-6)}) {
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].lo, -1.0);
    EXPECT_EQ(out[0].hi, 2.0);
    EXPECT_EQ(out[0].kind, RootKind::Unresolved);
  }
  EXPECT_EQ(firstRoot(zero, 1e-6), -1.0);
}

TEST(RootIsolation, RejectsBadInput) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const BernsteinPolynomial p({-1.0, 0.5, 1.0});
  EXPECT_THROW(isolateRoots(p, -1.0), std::invalid_argument);
  EXPECT_THROW(isolateRoots(p, nan), std::invalid_argument);
  EXPECT_THROW(bezierClip(p, 0.0), std::invalid_argument);
  EXPECT_THROW(bezierClip(p, inf), std::invalid_argument);
  EXPECT_THROW(firstRoot(p, 0.0), std::invalid_argument);
  EXPECT_THROW(refineRoot(p, 0.6, 0.4, 1e-9), std::invalid_argument);   // inverted
  EXPECT_THROW(refineRoot(p, -0.5, 0.5, 1e-9), std::invalid_argument);  // outside [a, b]
  EXPECT_THROW(refineRoot(p, 0.0, 0.1, 1e-9), std::invalid_argument);   // no sign change
  EXPECT_THROW(refineRoot(p, 0.0, 1.0, -1.0), std::invalid_argument);
  EXPECT_THROW(refineRootBracket(p, nan, 1.0, 1e-9), std::invalid_argument);
}

}  // namespace
}  // namespace fcl_quadric
