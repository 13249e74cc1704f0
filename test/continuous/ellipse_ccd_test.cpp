// Tests of the moving-ellipse CCD (thesis ch.2 CD-DISC, ch.3 CD-DISC3D) against the thesis'
// worked Example 2.2 (with the seed README's erratum) and independent oracles.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "support/expect_invalid.h"
#include "fcl_quadric/continuous/ellipse_ccd.h"
#include "fcl_quadric/geometry/ellipsoid.h"
#include "fcl_quadric/geometry/ellipsoid_separation.h"
#include "fcl_quadric/geometry/signed_distance.h"

namespace fcl_quadric {
namespace {

Polynomial poly(std::vector<double> c) { return Polynomial(std::move(c)); }

/// Example 2.2 motions (thesis §2.5.4) with the erratum: M_A(0,2) = +160t^3 - 240t^2 + 160t - 40.
/// `dy_b` translates disk B by (0, dy_b) in world coordinates (v -> v + dy_b w).
PolynomialMatrix3 example22MotionA() {
  PolynomialMatrix3 M;
  M(0, 0) = poly({4, -16, 0, 32, -16});
  M(0, 1) = poly({0, -16, 48, -32});
  M(0, 2) = poly({-40, 160, -240, 160});
  M(1, 0) = poly({0, 16, -48, 32});
  M(1, 1) = poly({4, -16, 0, 32, -16});
  M(1, 2) = poly({80, -400, 880, -960, 480});
  M(2, 2) = poly({4, -16, 32, -32, 16});
  return M;
}

PolynomialMatrix3 example22MotionB(double dy_b = 0.0) {
  PolynomialMatrix3 M;
  M(0, 0) = poly({4, -16, 0, 32, -16});
  M(0, 1) = poly({0, 16, -48, 32});
  M(0, 2) = poly({-40, 160, -240, 160});
  M(1, 0) = poly({0, -16, 48, -32});
  M(1, 1) = poly({4, -16, 0, 32, -16});
  M(1, 2) = poly({-80, 400, -880, 960, -480});
  M(2, 2) = poly({4, -16, 32, -32, 16});
  M(1, 2) += M(2, 2) * dy_b;
  return M;
}

TEST(EllipseCcdExample22, GeometryAtHalfIsTangentWithBLower) {
  const MovingEllipse2 a(5.0, 10.0, example22MotionA());
  const MovingEllipse2 b(5.0, 10.0, example22MotionB());
  const Eigen::Vector2d ca = a.centerAt(0.5);
  const Eigen::Vector2d cb = b.centerAt(0.5);
  EXPECT_NEAR(ca(0), 0.0, 1e-12);
  EXPECT_NEAR(ca(1), 10.0, 1e-12);
  EXPECT_NEAR(cb(0), 0.0, 1e-12);
  EXPECT_NEAR(cb(1), -10.0, 1e-12);
  EXPECT_LT(cb(1), ca(1));  // B is the lower disk
  const EllipsePairState s = classifyEllipses(a.conicAt(0.5), b.conicAt(0.5));
  EXPECT_EQ(s.status, Separation::Touching);
  ASSERT_TRUE(s.point_valid);
  EXPECT_NEAR(s.point(0), 0.0, 1e-9);
  EXPECT_NEAR(s.point(1), 0.0, 1e-9);
}

TEST(EllipseCcdExample22, AllVariantsReportContactAtHalf) {
  const MovingEllipse2 a(5.0, 10.0, example22MotionA());
  const MovingEllipse2 b(5.0, 10.0, example22MotionB());
  const EllipseCcdResult v1 = collideMovingEllipses(a, b, EllipseCcdQuery::Collide);
  EXPECT_TRUE(v1.collide);
  const EllipseCcdResult v2 = collideMovingEllipses(a, b, EllipseCcdQuery::FirstContact);
  ASSERT_TRUE(v2.collide);
  ASSERT_TRUE(v2.first_contact.has_value());
  EXPECT_NEAR(*v2.first_contact, 0.5, 1e-9);
  ASSERT_TRUE(v2.first_contact_point_valid);
  EXPECT_NEAR(v2.first_contact_point(0), 0.0, 1e-6);
  EXPECT_NEAR(v2.first_contact_point(1), 0.0, 1e-6);
  const EllipseCcdResult v3 = collideMovingEllipses(a, b, EllipseCcdQuery::AllContacts);
  ASSERT_EQ(v3.contacts.size(), 1u);
  EXPECT_NEAR(v3.contacts[0].t, 0.5, 1e-9);
  EXPECT_TRUE(v3.contacts[0].verified);
  ASSERT_EQ(v3.collision_intervals.size(), 1u);
  EXPECT_NEAR(v3.collision_intervals[0].first, 0.5, 1e-9);
  EXPECT_NEAR(v3.collision_intervals[0].second, 0.5, 1e-9);
  std::printf("Example 2.2: Delta degree %d, first contact %.17g\n", v2.discriminant_degree, *v2.first_contact);
}

TEST(EllipseCcdExample22, SeparatedByDIsFreeAndOverlapByDCollides) {
  const MovingEllipse2 a(5.0, 10.0, example22MotionA());
  for (double d : {1e-7, 1e-6, 1e-5, 1e-3, 1e-1}) {
    const MovingEllipse2 down(5.0, 10.0, example22MotionB(-d));
    const MovingEllipse2 up(5.0, 10.0, example22MotionB(d));
    for (EllipseCcdQuery q : {EllipseCcdQuery::Collide, EllipseCcdQuery::FirstContact, EllipseCcdQuery::AllContacts}) {
      const EllipseCcdResult free = collideMovingEllipses(a, down, q);
      EXPECT_FALSE(free.collide) << "d = " << d;
      const EllipseCcdResult hit = collideMovingEllipses(a, up, q);
      EXPECT_TRUE(hit.collide) << "d = " << d;
    }
  }
  // Smallest d (powers of ten) still reported collision-free.
  double smallest = -1.0;
  for (int e = 7; e <= 16; ++e) {
    const double d = std::pow(10.0, -e);
    if (collideMovingEllipses(a, MovingEllipse2(5.0, 10.0, example22MotionB(-d))).collide) break;
    smallest = d;
  }
  std::printf("Example 2.2: smallest separation reported collision-free: %g\n", smallest);
}


/// The thesis' printed g_3 and g_2 (high -> low degree in t); g_1 = -g_2 and g_0 = -g_3.
const std::vector<double> kPrintedG3 = {-4096, 49152, -294912, 1171456, -3446784, 7974912, -15048704, 23721984,
                                       -31756032, 36517888, -36360192, 31509504, -23835904, 15754752, -9090048,
                                       4564736, -1984752, 741312, -235136, 62304, -13464, 2288, -288, 24, -1};
const std::vector<double> kPrintedG2 = {-135168, 1622016, -11304960, 55959552, -206878720, 588967936, -1325514752,
                                       2409461760, -3596409600, 4461631488, -4639457280, 4065807360, -3011391744,
                                       1886084608, -997282816, 443501312, -164884848, 50819520, -12842880, 2624352,
                                       -426168, 53808, -5120, 344, -13};

Polynomial fromHighToLow(std::vector<double> c, double sign) {
  std::reverse(c.begin(), c.end());
  for (double& v : c) v *= sign;
  return Polynomial(std::move(c));
}

/// Row k of P (coefficients of lambda^k) as a polynomial in t.
Polynomial row(const Eigen::MatrixXd& P, int k) {
  std::vector<double> c(static_cast<std::size_t>(P.cols()));
  for (Eigen::Index j = 0; j < P.cols(); ++j) c[static_cast<std::size_t>(j)] = P(k, j);
  return Polynomial(std::move(c)).trimmed();
}

/// Max relative difference of the coefficient vectors of p and q, each normalised by its largest
/// coefficient (so p = c q with c > 0 gives ~0; c < 0 gives ~2).
double normalisedDifference(const Polynomial& p, const Polynomial& q) {
  const double sp = p.maxAbsCoefficient();
  const double sq = q.maxAbsCoefficient();
  double d = 0.0;
  for (int i = 0; i <= std::max(p.degree(), q.degree()); ++i) {
    d = std::max(d, std::abs(p.coefficient(i) / sp - q.coefficient(i) / sq));
  }
  return d;
}

TEST(EllipseCcdExample22, PrintedCharacteristicPolynomialIsReproduced) {
  const std::array<Polynomial, 4> printed = {fromHighToLow(kPrintedG3, -1.0), fromHighToLow(kPrintedG2, -1.0),
                                             fromHighToLow(kPrintedG2, 1.0), fromHighToLow(kPrintedG3, 1.0)};
  // (1) With the inverse motion of the thesis (§2.5.1: the degree-2n matrix proportional to M^-1),
  // here adj(M) / w(t), computed by exact polynomial division.
  auto inverseOf = [](const PolynomialMatrix3& M) {
    const PolynomialMatrix3 adj = M.adjugate();
    PolynomialMatrix3 N;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        const PolynomialDivision q = divide(adj(i, j), M(2, 2));
        EXPECT_TRUE(q.remainder.isZero()) << i << "," << j;
        N(i, j) = q.quotient;
      }
    }
    return N;
  };
  const MovingEllipse2 a = MovingEllipse2::fromInverseMotion(5.0, 10.0, inverseOf(example22MotionA()));
  const MovingEllipse2 b = MovingEllipse2::fromInverseMotion(5.0, 10.0, inverseOf(example22MotionB()));
  const Eigen::MatrixXd P = characteristicPolynomial2(a, b);
  for (int k = 0; k < 4; ++k) {
    const Polynomial g = row(P, k);
    EXPECT_EQ(g.degree(), 24) << "k = " << k;
    EXPECT_LT(normalisedDifference(g, printed[static_cast<std::size_t>(k)]), 1e-12)
        << "k = " << k;
  }
  // (2) With the motions themselves (adjugate): adj(M) = w(t) * (the thesis' inverse), so every
  // g_k is w(t)^6 times the printed one (a positive factor: w >= 1 on [0, 1]).
  const MovingEllipse2 a2(5.0, 10.0, example22MotionA());
  const MovingEllipse2 b2(5.0, 10.0, example22MotionB());
  const Eigen::MatrixXd P2 = characteristicPolynomial2(a2, b2);
  Polynomial w6 = Polynomial::constant(1.0);
  for (int i = 0; i < 6; ++i) w6 *= example22MotionA()(2, 2);
  for (int k = 0; k < 4; ++k) {
    EXPECT_LT(normalisedDifference(row(P2, k), w6 * printed[static_cast<std::size_t>(k)]), 1e-12) << "k = " << k;
  }
}

// ---------------------------------------------------------------------------------------------
// Random motions against an independent oracle: the 2D disk at time t is the affine image
// { (L u + v) / w : |diag(1/a,1/b) u| <= 1 }, embedded as the ellipsoid with a third unit axis
// (two such ellipsoids meet iff their z = 0 sections do) and classified by the certified static
// ellipsoid test (ch.4, a different algorithm and code path).

struct Motion2 {
  PolynomialMatrix3 M;
  double a;
  double b;
};

Ellipsoid oracleBody(const Motion2& m, double t) {
  const Eigen::Matrix3d X = m.M.evaluate(t);
  const double w = X(2, 2);
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
  J.topLeftCorner<2, 2>() = X.topLeftCorner<2, 2>() * Eigen::Vector2d(m.a, m.b).asDiagonal() / w;
  J(2, 2) = 1.0;
  return Ellipsoid::fromAffine(J, Eigen::Vector3d(X(0, 2) / w, X(1, 2) / w, 0.0));
}

bool oracleCollide(const Motion2& p, const Motion2& q, double t) {
  return classifyEllipsoids(oracleBody(p, t), oracleBody(q, t)).status != Separation::Separated;
}

/// Random motion of degree `deg`: rigid (kinematic image, eq. 2.3, plus a polynomial translation)
/// or affine (a deforming linear part), moving roughly from `start` towards `end`.
Motion2 randomMotion(std::mt19937_64& rng, int deg, bool rigid, const Eigen::Vector2d& start,
                     const Eigen::Vector2d& end) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_real_distribution<double> r(0.6, 2.0);
  Motion2 m;
  m.a = r(rng);
  m.b = r(rng);
  // Translation path: start + (end - start) t + random wiggles of degree deg.
  std::vector<Polynomial> v(2);
  for (int i = 0; i < 2; ++i) {
    std::vector<double> c(static_cast<std::size_t>(deg) + 1, 0.0);
    c[0] = start(i);
    c[1] = end(i) - start(i);
    for (int k = 2; k <= deg; ++k) c[static_cast<std::size_t>(k)] = 1.5 * u(rng);
    v[static_cast<std::size_t>(i)] = Polynomial(c);
  }
  Polynomial w = Polynomial::constant(1.0);
  if (rigid) {
    const int dd = deg / 2;  // kinematic image of degree deg/2 gives a rotation of degree 2*dd
    if (dd >= 1) {
      std::vector<double> d2(static_cast<std::size_t>(dd) + 1), d3(static_cast<std::size_t>(dd) + 1);
      for (int k = 0; k <= dd; ++k) {
        d2[static_cast<std::size_t>(k)] = u(rng);
        d3[static_cast<std::size_t>(k)] = u(rng);
      }
      d2[0] += 2.0;  // keeps d2^2 + d3^2 away from zero
      const Polynomial p2(d2), p3(d3);
      w = p2 * p2 + p3 * p3;
      m.M(0, 0) = p2 * p2 - p3 * p3;
      m.M(0, 1) = p2 * p3 * 2.0;
      m.M(1, 0) = p2 * p3 * -2.0;
      m.M(1, 1) = p2 * p2 - p3 * p3;
      // The translation is v / w (rational): scale v by w(0) so that the path starts at `start`.
      v[0] *= w(0.0);
      v[1] *= w(0.0);
    } else {
      const double th = 3.0 * u(rng);
      m.M(0, 0) = Polynomial::constant(std::cos(th));
      m.M(0, 1) = Polynomial::constant(-std::sin(th));
      m.M(1, 0) = Polynomial::constant(std::sin(th));
      m.M(1, 1) = Polynomial::constant(std::cos(th));
    }
  } else {
    const double th = 3.0 * u(rng);
    const Eigen::Matrix2d R = Eigen::Rotation2Dd(th).toRotationMatrix();
    for (int i = 0; i < 2; ++i) {
      for (int j = 0; j < 2; ++j) {
        std::vector<double> c(static_cast<std::size_t>(deg) + 1, 0.0);
        c[0] = R(i, j);
        for (int k = 1; k <= deg; ++k) c[static_cast<std::size_t>(k)] = 0.12 * u(rng);
        m.M(i, j) = Polynomial(c);
      }
    }
    std::vector<double> wc(static_cast<std::size_t>(deg) + 1, 0.0);
    wc[0] = 1.0;
    wc[static_cast<std::size_t>(deg)] = 0.3 * (u(rng) + 1.0);
    w = Polynomial(wc);
  }
  m.M(0, 2) = v[0];
  m.M(1, 2) = v[1];
  m.M(2, 2) = w;
  return m;
}

struct OracleResult {
  bool collide = false;
  double first = 2.0;
};

OracleResult sampleOracle(const Motion2& p, const Motion2& q, int samples) {
  OracleResult r;
  if (oracleCollide(p, q, 0.0)) {
    r.collide = true;
    r.first = 0.0;
    return r;
  }
  for (int i = 1; i <= samples; ++i) {
    const double t = static_cast<double>(i) / samples;
    if (oracleCollide(p, q, t)) {
      double lo = static_cast<double>(i - 1) / samples;
      double hi = t;
      for (int k = 0; k < 60 && hi - lo > 1e-15; ++k) {
        const double mid = 0.5 * (lo + hi);
        (oracleCollide(p, q, mid) ? hi : lo) = mid;
      }
      r.collide = true;
      r.first = hi;
      return r;
    }
  }
  return r;
}

double oracleDistance(const Motion2& p, const Motion2& q, double t) {
  return signedDistance(oracleBody(p, t), oracleBody(q, t)).distance;
}

TEST(EllipseCcdRandom, AgreesWithDenseSamplingOracle) {
  std::mt19937_64 rng(20080);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int collisions = 0, free = 0, tight = 0, grazing_between_samples = 0;
  for (int deg = 1; deg <= 4; ++deg) {
    for (int rigid = 0; rigid < 2; ++rigid) {
      for (int trial = 0; trial < 8; ++trial) {
        const Eigen::Vector2d sa(-4.0 + u(rng), 1.5 * u(rng));
        const Eigen::Vector2d sb(4.0 + u(rng), 1.5 * u(rng));
        const Motion2 p = randomMotion(rng, deg, rigid == 1, sa, Eigen::Vector2d(2.0 * u(rng), 2.5 * u(rng)));
        const Motion2 q = randomMotion(rng, deg, rigid == 1, sb, Eigen::Vector2d(2.0 * u(rng), 2.5 * u(rng)));
        const MovingEllipse2 ea(p.a, p.b, p.M);
        const MovingEllipse2 eb(q.a, q.b, q.M);
        const EllipseCcdResult r = collideMovingEllipses(ea, eb, EllipseCcdQuery::FirstContact);
        const EllipseCcdResult r1 = collideMovingEllipses(ea, eb, EllipseCcdQuery::Collide);
        const EllipseCcdResult r3 = collideMovingEllipses(ea, eb, EllipseCcdQuery::AllContacts);
        EXPECT_EQ(r1.collide, r.collide);
        EXPECT_EQ(r3.collide, r.collide);
        if (r.collide && r3.first_contact) {
          EXPECT_NEAR(*r3.first_contact, *r.first_contact, 1e-12);
        }
        const OracleResult o = sampleOracle(p, q, 2000);
        const std::string where = "deg " + std::to_string(deg) + " rigid " + std::to_string(rigid) + " trial " +
                                  std::to_string(trial);
        if (o.collide) {
          ++collisions;
          // Never "no collision" where the oracle finds one, never a later first contact.
          ASSERT_TRUE(r.collide) << where;
          ASSERT_TRUE(r.first_contact.has_value()) << where;
          EXPECT_LE(*r.first_contact, o.first + 1e-8) << where;
          if (*r.first_contact < o.first - 1e-8) {
            // An earlier contact that the samples stepped over: it must be a real (grazing) one.
            ++grazing_between_samples;
            EXPECT_LT(oracleDistance(p, q, *r.first_contact), 1e-7) << where;
          } else {
            ++tight;
            EXPECT_NEAR(*r.first_contact, o.first, 1e-8) << where;
          }
        } else {
          ++free;
          if (r.collide) {
            ++grazing_between_samples;
            EXPECT_LT(oracleDistance(p, q, *r.first_contact), 1e-7) << where;
          }
        }
        // Every reported contact instant is a tangency (independent distance ~ 0).
        for (const EllipseContact& c : r3.contacts) {
          EXPECT_LT(std::abs(oracleDistance(p, q, c.t)), 1e-6) << where << " t = " << c.t;
        }
      }
    }
  }
  std::printf("random: %d colliding (%d first contacts within 1e-8), %d free, %d grazing between samples\n",
              collisions, tight, free, grazing_between_samples);
  EXPECT_GT(collisions, 10);
  EXPECT_GT(free, 10);
}

PolynomialMatrix3 reparametrised(const PolynomialMatrix3& M, double alpha, double beta) {
  PolynomialMatrix3 R;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) R(i, j) = M(i, j).composeAffine(alpha, beta);
  }
  return R;
}

TEST(EllipseCcdConsistency, WholeIntervalEqualsUnionOfHalves) {
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int compared = 0;
  for (int trial = 0; trial < 24; ++trial) {
    const int deg = 1 + trial % 4;
    const Motion2 p = randomMotion(rng, deg, trial % 2 == 0, Eigen::Vector2d(-4.0 + u(rng), u(rng)),
                                   Eigen::Vector2d(2.0 * u(rng), 2.0 * u(rng)));
    const Motion2 q = randomMotion(rng, deg, trial % 2 == 0, Eigen::Vector2d(4.0 + u(rng), u(rng)),
                                   Eigen::Vector2d(2.0 * u(rng), 2.0 * u(rng)));
    const EllipseCcdResult whole =
        collideMovingEllipses(MovingEllipse2(p.a, p.b, p.M), MovingEllipse2(q.a, q.b, q.M), EllipseCcdQuery::AllContacts);
    const EllipseCcdResult first = collideMovingEllipses(MovingEllipse2(p.a, p.b, reparametrised(p.M, 0.5, 0.0)),
                                                         MovingEllipse2(q.a, q.b, reparametrised(q.M, 0.5, 0.0)),
                                                         EllipseCcdQuery::AllContacts);
    const EllipseCcdResult second = collideMovingEllipses(MovingEllipse2(p.a, p.b, reparametrised(p.M, 0.5, 0.5)),
                                                          MovingEllipse2(q.a, q.b, reparametrised(q.M, 0.5, 0.5)),
                                                          EllipseCcdQuery::AllContacts);
    ASSERT_EQ(whole.collide, first.collide || second.collide) << "trial " << trial;
    if (!whole.collide) continue;
    ++compared;
    const double split_first = first.collide ? 0.5 * *first.first_contact : 0.5 + 0.5 * *second.first_contact;
    EXPECT_NEAR(*whole.first_contact, split_first, 1e-9) << "trial " << trial;
    // Collision intervals: the union of the halves' intervals (mapped back) equals the whole's.
    std::vector<std::pair<double, double>> merged;
    for (const auto& iv : first.collision_intervals) merged.emplace_back(0.5 * iv.first, 0.5 * iv.second);
    for (const auto& iv : second.collision_intervals) {
      const std::pair<double, double> m(0.5 + 0.5 * iv.first, 0.5 + 0.5 * iv.second);
      if (!merged.empty() && std::abs(merged.back().second - m.first) <= 1e-9) {
        merged.back().second = m.second;
      } else {
        merged.push_back(m);
      }
    }
    ASSERT_EQ(merged.size(), whole.collision_intervals.size()) << "trial " << trial;
    for (std::size_t i = 0; i < merged.size(); ++i) {
      EXPECT_NEAR(merged[i].first, whole.collision_intervals[i].first, 1e-9) << "trial " << trial;
      EXPECT_NEAR(merged[i].second, whole.collision_intervals[i].second, 1e-9) << "trial " << trial;
    }
  }
  EXPECT_GT(compared, 5);
}

TEST(EllipseCcdConsistency, ReportedContactsAreTouchingAndIntervalsAreOverlapping) {
  const MovingEllipse2 a(5.0, 10.0, example22MotionA());
  const MovingEllipse2 b(5.0, 10.0, example22MotionB(0.5));  // overlap around t = 0.5
  const EllipseCcdResult r = collideMovingEllipses(a, b, EllipseCcdQuery::AllContacts);
  ASSERT_TRUE(r.collide);
  ASSERT_EQ(r.collision_intervals.size(), 1u);
  const auto iv = r.collision_intervals[0];
  EXPECT_LT(iv.first, 0.5);
  EXPECT_GT(iv.second, 0.5);
  EXPECT_NEAR(iv.first + iv.second, 1.0, 1e-9);  // the example is symmetric in t -> 1 - t
  ASSERT_EQ(r.contacts.size(), 2u);
  for (const EllipseContact& c : r.contacts) {
    const EllipsePairState s = classifyEllipses(a.conicAt(c.t), b.conicAt(c.t));
    EXPECT_EQ(s.status, Separation::Touching) << c.t;
    EXPECT_TRUE(c.verified);
    ASSERT_TRUE(c.point_valid);
    // The contact point lies on both boundaries.
    const Eigen::Vector3d X(c.point(0), c.point(1), 1.0);
    const Eigen::Matrix3d A = a.conicAt(c.t) / a.conicAt(c.t).norm();
    const Eigen::Matrix3d B = b.conicAt(c.t) / b.conicAt(c.t).norm();
    EXPECT_NEAR(X.dot(A * X), 0.0, 1e-8);
    EXPECT_NEAR(X.dot(B * X), 0.0, 1e-8);
  }
  EXPECT_NEAR(r.contacts[0].t, iv.first, 1e-12);
  EXPECT_NEAR(r.contacts[1].t, iv.second, 1e-12);
  const EllipsePairState mid = classifyEllipses(a.conicAt(0.5), b.conicAt(0.5));
  EXPECT_EQ(mid.status, Separation::Overlapping);
}

TEST(EllipseCcdConsistency, OverlapAtStartStartsAnIntervalAtZero) {
  // Disk A fixed at the origin, B translating along x from (1, 0) to (5, 0); both have semi-axis
  // 1 along x, so they are tangent when the centres are 2 apart: t = 1/4.
  PolynomialMatrix3 ma(Eigen::Matrix3d::Identity());
  PolynomialMatrix3 mb(Eigen::Matrix3d::Identity());
  mb(0, 2) = Polynomial{1.0, 4.0};
  const MovingEllipse2 a(1.0, 2.0, ma);
  const MovingEllipse2 b(1.0, 1.5, mb);
  const EllipseCcdResult r2 = collideMovingEllipses(a, b, EllipseCcdQuery::FirstContact);
  EXPECT_TRUE(r2.collide);
  EXPECT_FALSE(r2.separate_at_start);
  ASSERT_TRUE(r2.first_contact.has_value());
  EXPECT_EQ(*r2.first_contact, 0.0);
  EXPECT_FALSE(r2.first_contact_point_valid);
  const EllipseCcdResult r3 = collideMovingEllipses(a, b, EllipseCcdQuery::AllContacts);
  ASSERT_EQ(r3.collision_intervals.size(), 1u);
  EXPECT_EQ(r3.collision_intervals[0].first, 0.0);
  EXPECT_NEAR(r3.collision_intervals[0].second, 0.25, 1e-12);
  ASSERT_EQ(r3.contacts.size(), 1u);
  EXPECT_NEAR(r3.contacts[0].t, 0.25, 1e-12);
  ASSERT_TRUE(r3.contacts[0].point_valid);
  EXPECT_NEAR(r3.contacts[0].point(0), 1.0, 1e-9);
  EXPECT_NEAR(r3.contacts[0].point(1), 0.0, 1e-9);
}

TEST(EllipseCcdBadInput, EachDocumentedErrorThrowsNamingTheItem) {
  const PolynomialMatrix3 id(Eigen::Matrix3d::Identity());
  test::expectInvalid([&] { MovingEllipse2(0.0, 1.0, id); }, "radius a");
  test::expectInvalid([&] { MovingEllipse2(1.0, std::nan(""), id); }, "radius b");
  test::expectInvalid([&] { MovingEllipse2(1.0, -2.0, id); }, "radius b");
  PolynomialMatrix3 m = id;
  m(2, 0) = Polynomial{0.0, 1.0};
  test::expectInvalid([&] { MovingEllipse2(1.0, 1.0, m); }, "last row");
  m = id;
  m(2, 2) = Polynomial{1.0, -2.0};  // w(1/2) = 0
  test::expectInvalid([&] { MovingEllipse2(1.0, 1.0, m); }, "w(t)");
  m = id;
  m(0, 0) = Polynomial{1.0, -1.0};  // det L = 1 - t vanishes at t = 1
  test::expectInvalid([&] { MovingEllipse2(1.0, 1.0, m); }, "det of the linear 2x2 part");
  m = id;
  m(0, 2) = Polynomial::monomial(kMaxEllipseMotionDegree + 1, 1.0);
  test::expectInvalid([&] { MovingEllipse2(1.0, 1.0, m); }, "kMaxEllipseMotionDegree");
  m = id;
  m(2, 2) = Polynomial{0.5, -1.0};  // inverse motion with w' vanishing at 1/2
  test::expectInvalid([&] { (void)MovingEllipse2::fromInverseMotion(1.0, 1.0, m); }, "inverse motion N(t)");
  const Eigen::Matrix3d good = ellipseMatrix(1.0, 2.0, 0.3, Eigen::Vector2d(0.0, 0.0));
  test::expectInvalid([&] { (void)classifyEllipses(good, Eigen::Matrix3d::Identity()); }, "B is not an ellipse");
  Eigen::Matrix3d nan = good;
  nan(0, 1) = std::nan("");
  test::expectInvalid([&] { (void)classifyEllipses(nan, good); }, "non-finite entry (0, 1) of A");
  test::expectInvalid([&] { (void)ellipseMatrix(-1.0, 2.0, 0.0, Eigen::Vector2d::Zero()); }, "radius a");
}

TEST(EllipseCcdStatic, ClassifyEllipsesAgreesWithEllipsoidOracleOnRandomPairs) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_real_distribution<double> r(0.3, 3.0);
  int counts[3] = {0, 0, 0};
  for (int i = 0; i < 2000; ++i) {
    const double a1 = r(rng), b1 = r(rng), a2 = r(rng), b2 = r(rng);
    const double th1 = 3.0 * u(rng), th2 = 3.0 * u(rng);
    const Eigen::Vector2d c1(0.0, 0.0), c2(4.0 * u(rng), 4.0 * u(rng));
    const EllipsePairState s =
        classifyEllipses(ellipseMatrix(a1, b1, th1, c1), ellipseMatrix(a2, b2, th2, c2));
    auto body = [](double a, double b, double th, const Eigen::Vector2d& c) {
      Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
      R.topLeftCorner<2, 2>() = Eigen::Rotation2Dd(th).toRotationMatrix();
      return Ellipsoid(Eigen::Vector3d(a, b, 1.0), R, Eigen::Vector3d(c(0), c(1), 0.0));
    };
    const Separation o = classifyEllipsoids(body(a1, b1, th1, c1), body(a2, b2, th2, c2)).status;
    if (o != Separation::Touching) {
      EXPECT_EQ(s.status, o) << i;
    }
    ++counts[static_cast<int>(s.status)];
  }
  EXPECT_GT(counts[0], 100);
  EXPECT_GT(counts[2], 100);
}

// ---------------------------------------------------------------------------------------------
// Chapter 3: ellipses moving in 3D.

/// 4x4 motion from a 2D one, in the plane z = z0.
PolynomialMatrix4 lift(const PolynomialMatrix3& m, double z0) {
  PolynomialMatrix4 M;
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) M(i, j) = m(i, j);
    M(i, 3) = m(i, 2);
  }
  M(2, 2) = m(2, 2);
  M(2, 3) = m(2, 2) * z0;
  M(3, 3) = m(2, 2);
  return M;
}

TEST(Ellipse3Ccd, CoplanarCaseAgreesWithTheTwoDimensionalAlgorithm) {
  std::mt19937_64 rng(33);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int collided = 0;
  for (int trial = 0; trial < 12; ++trial) {
    const int deg = 1 + trial % 3;
    const Motion2 p = randomMotion(rng, deg, trial % 2 == 0, Eigen::Vector2d(-4.0 + u(rng), u(rng)),
                                   Eigen::Vector2d(2.0 * u(rng), 2.0 * u(rng)));
    const Motion2 q = randomMotion(rng, deg, trial % 2 == 0, Eigen::Vector2d(4.0 + u(rng), u(rng)),
                                   Eigen::Vector2d(2.0 * u(rng), 2.0 * u(rng)));
    const EllipseCcdResult r2 = collideMovingEllipses(MovingEllipse2(p.a, p.b, p.M), MovingEllipse2(q.a, q.b, q.M));
    const Ellipse3CcdResult r3 =
        collideMovingEllipses3(MovingEllipse3(p.a, p.b, lift(p.M, 0.75)), MovingEllipse3(q.a, q.b, lift(q.M, 0.75)));
    EXPECT_TRUE(r3.coplanar) << trial;
    ASSERT_EQ(r3.collide, r2.collide) << trial;
    if (r2.collide) {
      ++collided;
      EXPECT_NEAR(*r3.first_contact, *r2.first_contact, 1e-9) << trial;
    }
  }
  EXPECT_GT(collided, 2);
}

/// Ellipse B in the vertical plane y = 0 (body x -> world x, body y -> world z), centre
/// (cx(t), 0, cz(t)) with cx = 3 - 2t, cz = 1.5 - 2t, radii (1, 1); ellipse A fixed in z = 0,
/// radii (2, 1) at the origin. The planes meet in the x axis; A's chord there is [-2, 2] and B's is
/// cx -+ sqrt(1 - cz^2) while |cz| <= 1.
MovingEllipse3 transversalB(double shift_y) {
  PolynomialMatrix4 M;
  M(0, 0) = Polynomial::constant(1.0);  // body x -> world x
  M(2, 1) = Polynomial::constant(1.0);  // body y -> world z
  M(1, 2) = Polynomial::constant(1.0);  // body z -> world y (unused direction, keeps L invertible)
  M(0, 3) = Polynomial{3.0, -2.0};
  M(1, 3) = Polynomial::constant(shift_y);
  M(2, 3) = Polynomial{1.5, -2.0};
  M(3, 3) = Polynomial::constant(1.0);
  return MovingEllipse3(1.0, 1.0, M);
}

TEST(Ellipse3Ccd, TransversalPassageMatchesIndependentChordSampling) {
  const MovingEllipse3 a(2.0, 1.0, PolynomialMatrix4(Eigen::Matrix4d::Identity()));
  const MovingEllipse3 b = transversalB(0.0);
  // Independent first contact: dense sampling + bisection of the chord overlap.
  auto overlap = [](double t) {
    const double cx = 3.0 - 2.0 * t, cz = 1.5 - 2.0 * t;
    if (std::abs(cz) > 1.0) return false;
    return cx - std::sqrt(1.0 - cz * cz) <= 2.0;
  };
  double lo = 0.0, hi = -1.0;
  for (int i = 1; i <= 20000; ++i) {
    if (overlap(i / 20000.0)) {
      lo = (i - 1) / 20000.0;
      hi = i / 20000.0;
      break;
    }
  }
  ASSERT_GT(hi, 0.0);
  for (int k = 0; k < 60; ++k) {
    const double m = 0.5 * (lo + hi);
    (overlap(m) ? hi : lo) = m;
  }
  const Ellipse3CcdResult r = collideMovingEllipses3(a, b);
  EXPECT_FALSE(r.coplanar);
  ASSERT_TRUE(r.collide);
  ASSERT_TRUE(r.first_contact.has_value());
  EXPECT_NEAR(*r.first_contact, hi, 1e-8);
  EXPECT_EQ(classifyEllipses3(a, b, *r.first_contact), Separation::Touching);
  std::printf("3D transversal: first contact %.15g (oracle %.15g), Delta_f degree %d\n", *r.first_contact, hi,
              r.discriminant_degree);
  // Shifted off A's plane line by y = 5 (B's plane y = 5 misses A's chord region): free.
  const Ellipse3CcdResult miss = collideMovingEllipses3(a, transversalB(5.0));
  EXPECT_FALSE(miss.collide);
}

TEST(Ellipse3Ccd, ParallelDistinctPlanesNeverCollide) {
  const MovingEllipse3 a(2.0, 1.0, PolynomialMatrix4(Eigen::Matrix4d::Identity()));
  PolynomialMatrix4 M(Eigen::Matrix4d::Identity());
  M(0, 3) = Polynomial{-3.0, 6.0};  // sweeps over A, but in the plane z = 0.5
  M(2, 3) = Polynomial::constant(0.5);
  const Ellipse3CcdResult r = collideMovingEllipses3(a, MovingEllipse3(1.0, 1.0, M));
  EXPECT_FALSE(r.coplanar);
  EXPECT_FALSE(r.collide);
  // The same sweep in A's plane collides (coplanar reduction): centres 3 apart at t = 0 with
  // semi-axes 2 + 1 along x, so the first contact is t = 0 (touching).
  M(2, 3) = Polynomial::constant(0.0);
  const Ellipse3CcdResult c = collideMovingEllipses3(a, MovingEllipse3(1.0, 1.0, M));
  EXPECT_TRUE(c.coplanar);
  ASSERT_TRUE(c.collide);
  EXPECT_NEAR(*c.first_contact, 0.0, 1e-12);
}

TEST(Ellipse3Ccd, BadInputThrowsNamingTheItem) {
  PolynomialMatrix4 M(Eigen::Matrix4d::Identity());
  test::expectInvalid([&] { MovingEllipse3(0.0, 1.0, M); }, "radius a");
  M(3, 1) = Polynomial{0.0, 1.0};
  test::expectInvalid([&] { MovingEllipse3(1.0, 1.0, M); }, "last row");
  M = PolynomialMatrix4(Eigen::Matrix4d::Identity());
  M(3, 3) = Polynomial{1.0, -1.5};
  test::expectInvalid([&] { MovingEllipse3(1.0, 1.0, M); }, "w(t)");
  M = PolynomialMatrix4(Eigen::Matrix4d::Identity());
  M(2, 2) = Polynomial{-0.5, 1.0};
  test::expectInvalid([&] { MovingEllipse3(1.0, 1.0, M); }, "det of the linear 3x3 part");
}

}  // namespace
}  // namespace fcl_quadric
