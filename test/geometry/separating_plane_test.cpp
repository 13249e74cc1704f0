// Separating planes (Choi 2008 Theorems 4.5/4.6) and inter-frame coherence (§4.3, Wang 2004 §4).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "fcl_quadric/geometry/pair_coherence.h"
#include "fcl_quadric/geometry/separating_plane.h"
#include "support/exact_oracle.h"
#include "support/random_ellipsoids.h"

namespace fcl_quadric {
namespace {

/// Points on the surface of e from a Fibonacci lattice on the unit sphere.
std::vector<Eigen::Vector3d> surfaceSamples(const Ellipsoid& e, int n) {
  std::vector<Eigen::Vector3d> pts;
  for (const Eigen::Vector3d& u : test::fibonacciSphere(n))
    pts.push_back(e.center() + e.rotation() * u.cwiseProduct(e.radii()));
  return pts;
}

TEST(SeparatingPlane, SeparatesSampledSurfacesOfRandomDisjointPairs) {
  std::mt19937_64 rng(51);
  int planes = 0, theorem = 0;
  for (int i = 0; i < 3000; ++i) {
    const Ellipsoid a = test::anchorEllipsoid(rng), b = test::anchorEllipsoid(rng);
    const auto sp = separatingPlane(a, b);
    const bool separate = test::exactClassify(a, b) == Separation::Separated;
    ASSERT_EQ(sp.has_value(), separate);
    if (!sp) continue;
    ++planes;
    theorem += sp->from_theorem_4_6;
    ASSERT_TRUE(sp->certified);
    EXPECT_NEAR(sp->plane.normal.norm(), 1.0, 1e-14);
    for (const auto& x : surfaceSamples(a, 200)) ASSERT_LT(sp->plane.signedDistance(x), 0.0);
    for (const auto& x : surfaceSamples(b, 200)) ASSERT_GT(sp->plane.signedDistance(x), 0.0);
    // Theorem 4.6: the tangent points lie on their surfaces and between the solids.
    if (sp->from_theorem_4_6) {
      EXPECT_NEAR(a.implicit(sp->tangent_a), 0.0, 1e-9);
      EXPECT_NEAR(b.implicit(sp->tangent_b), 0.0, 1e-9);
      EXPECT_LE(sp->plane.signedDistance(sp->tangent_a), 0.0);
      EXPECT_GE(sp->plane.signedDistance(sp->tangent_b), 0.0);
    }
  }
  EXPECT_GT(planes, 1000);
  EXPECT_GE(theorem, planes * 99 / 100);  // the fallback is for near-tangent pairs only
}

TEST(SeparatingPlane, CertificateNormalAlwaysGivesASeparatingPlane) {
  // planeWithNormal(): psi(mu) > 0 at the certificate makes the supports along its normal disjoint.
  std::mt19937_64 rng(57);
  int checked = 0;
  for (int i = 0; i < 20000; ++i) {
    const Ellipsoid a = test::anchorEllipsoid(rng), b = test::anchorEllipsoid(rng);
    const SeparationCertificate c = classifyEllipsoids(a, b);
    if (c.status != Separation::Separated) continue;
    ++checked;
    const Plane p = planeWithNormal(c.normal, a, b);
    ASSERT_TRUE(planeSeparates(p, a, b)) << "pair " << i << " stage " << c.precision_stage;
    if (i % 20 == 0) {
      for (const auto& x : surfaceSamples(a, 100)) ASSERT_LT(p.signedDistance(x), 0.0);
      for (const auto& x : surfaceSamples(b, 100)) ASSERT_GT(p.signedDistance(x), 0.0);
    }
  }
  EXPECT_GT(checked, 10000);
}

TEST(SeparatingPlane, TheoremPlaneTangentPointsAreClosestPointsForSpheres) {
  // §4.3: for spheres P_R^A and P_L^B are exactly the closest points.
  const Ellipsoid a = Ellipsoid::sphere(1.0, {0, 0, 0}), b = Ellipsoid::sphere(2.0, {3, 4, 0});
  const auto sp = separatingPlane(a, b);
  ASSERT_TRUE(sp && sp->from_theorem_4_6);
  EXPECT_NEAR((sp->tangent_a - Eigen::Vector3d(0.6, 0.8, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((sp->tangent_b - Eigen::Vector3d(1.8, 2.4, 0)).norm(), 0.0, 1e-12);
}

TEST(SeparatingPlane, NoPlaneCanSeparateOverlappingOrTouchingPairs) {
  std::mt19937_64 rng(53);
  for (int i = 0; i < 2000; ++i) {
    const Ellipsoid a = test::anchorEllipsoid(rng), b = test::anchorEllipsoid(rng);
    if (test::exactClassify(a, b) == Separation::Separated) continue;
    EXPECT_FALSE(separatingPlane(a, b).has_value());
    Plane p;
    p.normal = test::randomUnitVector(rng);
    for (double off = -5; off <= 5; off += 0.5) {
      p.offset = off;
      ASSERT_FALSE(planeSeparates(p, a, b));
    }
  }
}

TEST(SeparatingPlane, PlaneEllipsoidGapIsTheDistanceForUnitNormals) {
  const Ellipsoid e({1, 2, 3}, Eigen::Matrix3d::Identity(), {0, 0, 10});
  Plane p;
  p.normal = Eigen::Vector3d::UnitZ();
  p.offset = 5.0;
  EXPECT_NEAR(planeEllipsoidGap(p, e), 2.0, 1e-15);  // lowest point z = 7
  p.offset = 7.5;
  EXPECT_NEAR(planeEllipsoidGap(p, e), -0.5, 1e-15);
}

/// Support of e along n in long double: n.c + |S R^T n| (independent of the kernels' lanes).
long double supportLong(const Ellipsoid& e, const Eigen::Vector3d& n) {
  long double nc = 0, sq = 0;
  for (int i = 0; i < 3; ++i) nc += static_cast<long double>(n[i]) * e.center()[i];
  for (int j = 0; j < 3; ++j) {
    long double u = 0;
    for (int i = 0; i < 3; ++i) u += static_cast<long double>(e.rotation()(i, j)) * n[i];
    const long double m = u * e.radii()[j];
    sq += m * m;
  }
  return nc + std::sqrt(sq);
}

// The cached-plane kernel exists twice, for the baseline instruction set and in AVX registers
// with fused multiply-adds, reading the poses by rows (chosen at run time). Both must be sound against an independent long double
// evaluation of the supports, agree outside a band of relative width 1e-9 around touching, and
// CachedPlane::separates() and planeSeparates() must run the one cpuHasFma() names.
TEST(SeparatingPlane, GenericAndFmaKernelsAreSoundAndAgreeAwayFromTangency) {
  std::mt19937_64 rng(61);
  const bool fma = detail::cpuHasFma();
  const double ts[] = {-0.1, -1e-12, 0.0, 1e-13, 1e-9, 0.5, 1 - 1e-9, 1 - 1e-13, 1.0, 1 + 1e-12, 1.1};
  int certified = 0, declined = 0, band = 0, disagreements = 0;
  for (int i = 0; i < 20000; ++i) {
    const Ellipsoid a = test::anchorEllipsoid(rng), b = test::anchorEllipsoid(rng);
    // The certificate's normal (slightly perturbed) on separated pairs, else a random direction.
    const SeparationCertificate cert = classifyEllipsoids(a, b);
    Plane p;
    p.normal = cert.status == Separation::Separated
                   ? (cert.normal.normalized() + 1e-3 * test::randomUnitVector(rng)).normalized()
                   : test::randomUnitVector(rng);
    const long double lo = supportLong(a, p.normal);    // a lies in n.x <= lo
    const long double hi = -supportLong(b, -p.normal);  // b lies in n.x >= hi
    const double scale = std::fabs(static_cast<double>(lo)) + std::fabs(static_cast<double>(hi)) +
                         p.normal.lpNorm<1>() * (a.center().lpNorm<Eigen::Infinity>() + b.center().lpNorm<Eigen::Infinity>() +
                                                 a.radii().sum() + b.radii().sum());
    for (double t : ts) {
      p.offset = static_cast<double>(lo + t * (hi - lo));
      const long double margin = std::min(p.offset - lo, hi - p.offset);  // > 0: strictly separates
      const std::optional<CachedPlane> c = CachedPlane::fromPlane(p);
      ASSERT_TRUE(c.has_value());
      const bool generic = detail::cachedPlaneSeparatesGeneric(*c, a, b);
      const bool chosen = c->separates(a, b);
      const bool other = fma ? detail::cachedPlaneSeparatesFma(*c, a, b) : generic;
      ASSERT_EQ(chosen, other) << "pair " << i << " t " << t;  // other is generic without FMA
      ASSERT_EQ(planeSeparates(p, a, b), chosen) << "pair " << i << " t " << t;
      for (bool c : {generic, other}) {
        if (c) {
          ASSERT_GT(margin, 0.0L) << "certified a plane that does not separate: pair " << i << " t " << t;
        }
      }
      if (std::fabs(static_cast<double>(margin)) > 1e-9 * scale) {
        ASSERT_EQ(generic, margin > 0) << "pair " << i << " t " << t << " margin " << static_cast<double>(margin);
        ASSERT_EQ(other, margin > 0) << "pair " << i << " t " << t;
      } else {
        ++band;
        disagreements += generic != other;
      }
      certified += generic;
      declined += !generic;
    }
  }
  EXPECT_GT(certified, 20000);
  EXPECT_GT(declined, 20000);
  EXPECT_GT(band, 40000);  // t = 0, 1 and the 1e-12 / 1e-13 offsets of every separated pair
  EXPECT_LE(disagreements, band / 100);
  if (!fma) GTEST_SKIP() << "no FMA on this CPU (or no dispatch in this build): only the generic kernel was run";
}

// CachedPlane's record: planes that can never be certified are refused, the empty record certifies
// nothing, a stored plane comes back unchanged, and a plane's answer does not depend on the length
// of its normal: (n, off) and (2^k n, 2^k off) bound the same half-spaces, including where the
// normal is so short or so long that fromPlane() rescales it (without the rescaling, |S R^T n|^2
// of a normal of length 2^-600 underflows to 0 and a plane through b would be certified).
TEST(CachedPlane, RefusesUncertifiablePlanesAndAnswersAlikeForEveryNormalLength) {
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  for (const Plane& bad : {Plane{Eigen::Vector3d(nan, 0, 0), 0.0}, Plane{Eigen::Vector3d(1, 0, 0), inf},
                           Plane{Eigen::Vector3d(0, inf, 0), 1.0}, Plane{Eigen::Vector3d::Zero(), 1.0},
                           Plane{Eigen::Vector3d(0x1p-1000, 0, 0), 1e300}}) {
    EXPECT_FALSE(CachedPlane::fromPlane(bad).has_value()) << bad.normal.transpose() << " " << bad.offset;
    EXPECT_FALSE(planeSeparates(bad, Ellipsoid::sphere(1, {-2, 0, 0}), Ellipsoid::sphere(1, {2, 0, 0})));
  }
  const CachedPlane empty;
  EXPECT_TRUE(empty.empty());
  EXPECT_FALSE(empty.separates(Ellipsoid::sphere(1, {-2, 0, 0}), Ellipsoid::sphere(1, {2, 0, 0})));

  std::mt19937_64 rng(67);
  int certified = 0, checked = 0;
  for (int i = 0; i < 3000; ++i) {
    const Ellipsoid a = test::anchorEllipsoid(rng), b = test::anchorEllipsoid(rng);
    const SeparationCertificate cert = classifyEllipsoids(a, b);
    if (cert.status != Separation::Separated) continue;
    Plane p = planeWithNormal(cert.normal, a, b);
    // Slide the plane towards b by a fraction of the gap: some stay certified, some cut b.
    const double gap = -a.support(p.normal) - b.support(-p.normal);
    std::uniform_real_distribution<double> frac(0.0, 1.5);
    p.offset += frac(rng) * gap;
    const std::optional<CachedPlane> c = CachedPlane::fromPlane(p);
    ASSERT_TRUE(c.has_value());
    ASSERT_EQ(c->plane().normal, p.normal);  // a unit normal is stored as it is
    ASSERT_EQ(c->plane().offset, p.offset);
    const bool base = c->separates(a, b);
    const long double margin = std::min(p.offset - supportLong(a, p.normal), -supportLong(b, -p.normal) - p.offset);
    if (base) {
      ASSERT_GT(margin, 0.0L) << "pair " << i;
    }
    certified += base;
    // Scaling by 2^k is exact while the components stay normal numbers (|n_i| > 2^-1000 here).
    if (p.normal.cwiseAbs().minCoeff() < 0x1p-20) continue;
    for (int k : {-1000, -600, -70, 70, 600, 1000}) {
      if (k < 0 && p.offset != 0.0 && std::fabs(p.offset) < 0x1p-20) continue;  // would turn subnormal
      const Plane q{p.normal * std::ldexp(1.0, k), std::ldexp(p.offset, k)};
      ASSERT_TRUE(std::isfinite(q.offset));
      ASSERT_EQ(planeSeparates(q, a, b), base) << "pair " << i << " k " << k;
      ++checked;
    }
  }
  EXPECT_GT(certified, 300);
  EXPECT_GT(checked, 3000);
}

/// Two ellipsoids (3,3,5) 8 apart, rotating about random axes (the separating-planes experiment).
TEST(PairCoherence, AgreesWithTheFullTestFrameByFrameAndUsesItsPlanes) {
  std::mt19937_64 rng(55);
  const Eigen::Vector3d r(3, 3, 5);
  const Eigen::Vector3d axis_a = test::randomUnitVector(rng), axis_b = test::randomUnitVector(rng);
  PairCoherence cache;
  int separated = 0;
  for (int f = 0; f < 3000; ++f) {
    const Eigen::Matrix3d Ra = Eigen::AngleAxisd(0.1 * f, axis_a).toRotationMatrix();
    const Eigen::Matrix3d Rb = Eigen::AngleAxisd(0.1 * f, axis_b).toRotationMatrix();
    const Ellipsoid a(r, Ra, {0, 0, 0}), b(r, Rb, {8, 0, 0});
    const Separation s = cache.query(a, b);
    ASSERT_EQ(s, classifyEllipsoids(a, b).status) << "frame " << f;
    separated += s == Separation::Separated;
  }
  EXPECT_EQ(cache.queries(), 3000u);
  EXPECT_GT(separated, 1000);
  EXPECT_GT(cache.planeHits(), 0.5 * separated);  // coherence pays off at 0.1 rad/frame
}

// The plane the caches keep (certificatePlane()): for a pre-test's certificate it is
// planeWithNormal()'s plane up to rounding, placed from the witness, and it separates the pair
// (judged on long double supports, and certified by planeSeparates()) except within a band of
// relative width 1e-9 around touching; for a pencil certificate it is planeWithNormal()'s plane.
TEST(CertificatePlane, IsThePlaneWithTheCertificatesNormalPlacedMidway) {
  std::mt19937_64 rng(89);
  int pre_tests = 0, pencil = 0, certified = 0;
  for (int i = 0; i < 30000; ++i) {
    const Ellipsoid a = test::anchorEllipsoid(rng), b = test::anchorEllipsoid(rng);
    const SeparationCertificate cert = classifyEllipsoids(a, b);
    if (cert.status != Separation::Separated) continue;
    const Plane p = certificatePlane(cert, a, b);
    const Plane q = planeWithNormal(cert.normal, a, b);
    if (cert.precision_stage != -1) {
      ++pencil;
      ASSERT_EQ(p.normal, q.normal);
      ASSERT_EQ(p.offset, q.offset);
      continue;
    }
    ++pre_tests;
    const double scale = a.center().lpNorm<1>() + b.center().lpNorm<1>() + a.radii().sum() + b.radii().sum();
    ASSERT_LE((p.normal - q.normal).lpNorm<Eigen::Infinity>(), 1e-15) << "pair " << i;
    ASSERT_LE(std::fabs(p.offset - q.offset), 1e-12 * scale) << "pair " << i;
    const long double lo = supportLong(a, p.normal);    // a lies in n.x <= lo
    const long double hi = -supportLong(b, -p.normal);  // b lies in n.x >= hi
    const long double margin = std::min(p.offset - lo, hi - p.offset);
    const bool ok = planeSeparates(p, a, b);
    if (ok) {
      ASSERT_GT(margin, 0.0L) << "certified a plane that does not separate: pair " << i;
    }
    if (margin > 1e-9L * scale) {
      ASSERT_TRUE(ok) << "pair " << i << " margin " << static_cast<double>(margin);
    }
    certified += ok;
  }
  EXPECT_GT(pre_tests, 15000);
  EXPECT_GT(certified, pre_tests - pre_tests / 100);
  RecordProperty("pencil_certificates", pencil);
}

TEST(PairCoherence, StalePlaneNeverHidesACollision) {
  PairCoherence cache;
  const Ellipsoid a = Ellipsoid::sphere(1.0, {0, 0, 0});
  EXPECT_EQ(cache.query(a, Ellipsoid::sphere(1.0, {3, 0, 0})), Separation::Separated);
  ASSERT_TRUE(cache.candidate().has_value());
  EXPECT_EQ(cache.query(a, Ellipsoid::sphere(1.0, {1.5, 0, 0})), Separation::Overlapping);
  EXPECT_FALSE(cache.candidate().has_value());
  EXPECT_EQ(cache.planeHits(), 0u);
}

}  // namespace
}  // namespace fcl_quadric
