// Continuous collision in the FCL layer (issue 4): RationalMotion as an fcl::MotionBase,
// fcl_quadric::continuousCollide (exact, certified conservative advancement, delegated) and the
// continuous broad phase, against closed forms, dense-sampling oracles and stock FCL.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <cstdio>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/bv/AABB.h>
#include <fcl/math/bv/RSS.h>
#include <fcl/math/motion/interp_motion.h>
#include <fcl/math/motion/screw_motion.h>
#include <fcl/math/motion/tbv_motion_bound_visitor.h>
#include <fcl/math/motion/translation_motion.h>
#include <fcl/math/motion/triangle_motion_bound_visitor.h>
#include <fcl/narrowphase/continuous_collision.h>

#include "support/expect_invalid.h"
#include "fcl_quadric/continuous/ellipsoid_ccd.h"
#include "fcl_quadric/fcl/continuous_broadphase.h"
#include "fcl_quadric/fcl/continuous_collision.h"
#include "fcl_quadric/fcl/rational_motion.h"
#include "fcl_quadric/geometry/ellipsoid_separation.h"
#include "fcl_quadric/geometry/signed_distance.h"
#include "fcl/fcl_test_support.h"
#include "support/random_ellipsoids.h"

namespace fcl_quadric {
namespace continuous_collision_test {
namespace {

using test::expectInvalid;

using Clock = std::chrono::steady_clock;

double seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

fcl::Transform3d makePose(const Eigen::Matrix3d& R, const Eigen::Vector3d& p) {
  fcl::Transform3d tf = fcl::Transform3d::Identity();
  tf.linear() = R;
  tf.translation() = p;
  return tf;
}

fcl::Transform3d randomPose(std::mt19937_64& rng, double spread) {
  std::uniform_real_distribution<double> u(-spread, spread);
  return makePose(test::randomRotation(rng), Eigen::Vector3d(u(rng), u(rng), u(rng)));
}

// FCL's InterpMotion with the reference point at the body origin (as fcl_quadric builds it for
// CCDM_LINEAR; FCL's (tf1, tf2) constructor leaves the reference point uninitialised).
class OriginInterp : public fcl::InterpMotion<double> {
 public:
  OriginInterp(const fcl::Transform3d& a, const fcl::Transform3d& b) {
    tf1 = a;
    tf2 = b;
    tf = tf1;
    reference_p.setZero();
    computeVelocity();
  }
};

Eigen::Matrix4d poseOf(const fcl::MotionBase<double>& m, double t) {
  m.integrate(t);
  fcl::Transform3d tf;
  m.getCurrentTransform(tf);
  Eigen::Matrix4d X = Eigen::Matrix4d::Identity();
  X.topLeftCorner<3, 3>() = tf.linear();
  X.block<3, 1>(0, 3) = tf.translation();
  return X;
}

Ellipsoid worldEllipsoid(const Eigen::Vector3d& radii, const Eigen::Matrix4d& X) {
  return Ellipsoid(radii, X.topLeftCorner<3, 3>(), X.block<3, 1>(0, 3));
}

std::shared_ptr<fcl::CollisionGeometryd> fclShape(const Eigen::Vector3d& radii, bool sphere) {
  if (sphere) return std::make_shared<fcl::Sphered>(radii[0]);
  return std::make_shared<fcl::Ellipsoidd>(radii);
}

// --- (a) RationalMotion --------------------------------------------------------------------------

TEST(RationalMotion, IntegrateMatchesTheMotionMatrix) {
  std::mt19937_64 rng(101);
  for (int k = 0; k < 30; ++k) {
    const fcl::Transform3d a = randomPose(rng, 4.0), b = randomPose(rng, 4.0);
    const RationalMotion<double> m(a, b);
    const MotionMatrix ref = MotionMatrix::fromPoses(a, b);
    for (double t : {0.0, 0.1, 0.25, 0.5, 0.77, 1.0}) {
      ASSERT_TRUE(m.integrate(t));
      EXPECT_EQ(m.currentTime(), t);
      fcl::Transform3d tf;
      m.getCurrentTransform(tf);
      const Eigen::Matrix4d X = ref.evaluate(t);
      EXPECT_EQ(tf.linear(), Eigen::Matrix3d(X.topLeftCorner<3, 3>()));
      EXPECT_EQ(tf.translation(), Eigen::Vector3d(X.block<3, 1>(0, 3)));
      Eigen::Matrix3d Rr;
      Eigen::Vector3d Tr;
      m.getCurrentTransform(Rr, Tr);  // MotionBase's non-virtual accessors read the same pose
      EXPECT_EQ(Rr, tf.linear());
    }
    fcl::Transform3d t0, t1;
    m.integrate(0.0);
    m.getCurrentTransform(t0);
    m.integrate(1.0);
    m.getCurrentTransform(t1);
    EXPECT_TRUE(t0.matrix().isApprox(a.matrix(), 1e-12));
    EXPECT_TRUE(t1.matrix().isApprox(b.matrix(), 1e-12));
    // Clamping (FCL's motions clamp t > 1) and NaN.
    m.integrate(0.3);
    ASSERT_TRUE(m.integrate(2.5));
    EXPECT_EQ(m.currentTime(), 1.0);
    ASSERT_TRUE(m.integrate(-1.0));
    EXPECT_EQ(m.currentTime(), 0.0);
    m.integrate(0.3);
    EXPECT_FALSE(m.integrate(std::numeric_limits<double>::quiet_NaN()));
    EXPECT_EQ(m.currentTime(), 0.3);
  }
  // Keyframes and an explicit matrix.
  std::vector<double> times{0.0, 0.3, 1.0};
  std::vector<fcl::Transform3d> poses{randomPose(rng, 2.0), randomPose(rng, 2.0), randomPose(rng, 2.0)};
  const RationalMotion<double> key(times, poses);
  std::vector<Eigen::Isometry3d> iso(poses.begin(), poses.end());
  const PiecewiseMotion pm = PiecewiseMotion::fromKeyframes(times, iso);
  for (double t : {0.0, 0.1, 0.3, 0.6, 1.0}) {
    key.integrate(t);
    fcl::Transform3d tf;
    key.getCurrentTransform(tf);
    const Eigen::Matrix4d X = pm.evaluate(t);
    EXPECT_EQ(tf.translation(), Eigen::Vector3d(X.block<3, 1>(0, 3)));
    EXPECT_EQ(key.currentMatrix(), X);
  }
  PolynomialMatrix4 M(Eigen::Matrix4d::Identity());
  M(0, 3) = Polynomial{1.0, 2.0, -1.0};
  M(1, 1) = Polynomial{1.0, 0.5};
  const RationalMotion<double> affine(M);
  EXPECT_FALSE(affine.piecewiseMotion().isRigid());
  affine.integrate(0.5);
  EXPECT_EQ(affine.currentMatrix(), MotionMatrix::fromPolynomialMatrix(M).evaluate(0.5));
  fcl::TMatrix3<double> tm;
  fcl::TVector3<double> tv;
  EXPECT_THROW(affine.getTaylorModel(tm, tv), std::logic_error);
}

// The motion bound: sampled n . dx/dt over the remaining time never exceeds it, and it is not
// wildly loose.
TEST(RationalMotion, MotionBoundsAreCertifiedOnSampledPoints) {
  std::mt19937_64 rng(102);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double worst_ratio = 0.0, worst_excess = 0.0;
  for (int k = 0; k < 20; ++k) {
    const std::vector<double> times{0.0, 0.4, 1.0};
    const std::vector<fcl::Transform3d> poses{randomPose(rng, 3.0), randomPose(rng, 3.0), randomPose(rng, 3.0)};
    const RationalMotion<double> m(times, poses);
    fcl::RSSd rss;
    rss.axis = test::randomRotation(rng);
    rss.To = Eigen::Vector3d(u(rng), u(rng), u(rng)) - Eigen::Vector3d::Constant(0.5);
    rss.l[0] = u(rng);
    rss.l[1] = u(rng);
    rss.r = 0.5 * u(rng);
    const Eigen::Vector3d n = test::randomUnitVector(rng);
    const fcl::Vector3d a = Eigen::Vector3d::Random(), b = Eigen::Vector3d::Random(), c = Eigen::Vector3d::Random();
    for (double t0 : {0.0, 0.35, 0.8}) {
      m.integrate(t0);
      const double bv_bound = m.computeMotionBound(fcl::TBVMotionBoundVisitor<fcl::RSSd>(rss, n));
      const double tri_bound = m.computeMotionBound(fcl::TriangleMotionBoundVisitor<double>(a, b, c, n));
      double bv_max = -1e300, tri_max = -1e300, speed_scale = 0.0;
      const double h = 1e-7;
      for (int s = 0; s <= 400; ++s) {
        const double t = std::min(t0 + (1.0 - t0) * s / 400.0, 1.0 - h);
        const double tt = std::max(t, h);
        const Eigen::Matrix4d D = (m.piecewiseMotion().evaluate(tt + h) - m.piecewiseMotion().evaluate(tt - h)) / (2 * h);
        auto speed = [&](const Eigen::Vector3d& x) { return n.dot(D.topLeftCorner<3, 3>() * x + D.block<3, 1>(0, 3)); };
        for (int i = 0; i < 2; ++i)
          for (int j = 0; j < 2; ++j) {
            const Eigen::Vector3d corner = rss.To + i * rss.l[0] * rss.axis.col(0) + j * rss.l[1] * rss.axis.col(1);
            const Eigen::Vector3d dn = D.topLeftCorner<3, 3>().transpose() * n;
            bv_max = std::max(bv_max, speed(corner) + rss.r * dn.norm());
          }
        tri_max = std::max({tri_max, speed(a), speed(b), speed(c)});
        speed_scale = std::max(speed_scale, (D.topLeftCorner<3, 3>() * rss.To + D.block<3, 1>(0, 3)).norm());
      }
      EXPECT_LE(bv_max, bv_bound + 1e-5) << "t0 = " << t0;
      EXPECT_LE(tri_max, tri_bound + 1e-5) << "t0 = " << t0;
      if (bv_max > 0.1) worst_ratio = std::max(worst_ratio, bv_bound / bv_max);
      worst_excess = std::max(worst_excess, (bv_bound - bv_max) / speed_scale);
    }
  }
  std::printf("[ info ] RationalMotion RSS bound: worst bound / sampled sup %.2f (sup > 0.1), worst excess %.2f of "
              "the speed of the RSS origin\n", worst_ratio, worst_excess);
  EXPECT_LT(worst_excess, 1.0);
}

// FCL's own conservative advancement accepts RationalMotion (through computeMotionBound) and
// agrees with the exact answer on box pairs moving by translation.
TEST(RationalMotion, FclConservativeAdvancementRunsOnIt) {
  test::ScopedNoFpTraps no_traps;
  const auto box = std::make_shared<fcl::Boxd>(1.0, 1.0, 1.0);
  const fcl::Transform3d a0 = makePose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(-3, 0, 0));
  const fcl::Transform3d a1 = makePose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(3, 0, 0));
  const fcl::Transform3d b = makePose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0.2, 0));
  const RationalMotion<double> ma(a0, a1), mb(b, b);
  fcl::ContinuousCollisionRequestd req;
  req.ccd_solver_type = fcl::CCDC_CONSERVATIVE_ADVANCEMENT;
  fcl::ContinuousCollisionResultd res;
  fcl::continuousCollide(box.get(), &ma, box.get(), &mb, req, res);
  EXPECT_TRUE(res.is_collide);
  // Exact: the faces meet when the x-gap 6 t - 3 reaches -1, t = 1/3; CA stops early.
  EXPECT_LE(res.time_of_contact, 1.0 / 3.0 + 1e-9);
  EXPECT_GT(res.time_of_contact, 1.0 / 3.0 - 1e-2);
}

// --- (b) exact: spheres on straight lines against the closed form; stock FCL for the record ----

// First t in [0, 1] with |d0 + t v| = R (0 if already touching); nullopt if none.
std::optional<double> sphereContact(const Eigen::Vector3d& d0, const Eigen::Vector3d& v, double R, double* disc_rel) {
  const double a = v.squaredNorm(), b = 2.0 * d0.dot(v), c = d0.squaredNorm() - R * R;
  *disc_rel = 1.0;
  if (c <= 0.0) return 0.0;
  if (a == 0.0) return std::nullopt;
  const double disc = b * b - 4 * a * c;
  *disc_rel = disc / (b * b);
  if (disc < 0.0) return std::nullopt;
  const double t = (-b - std::sqrt(disc)) / (2 * a);  // the smaller root (c > 0: same sign roots)
  if (t < 0.0 || t > 1.0) return std::nullopt;
  return t;
}

TEST(ContinuousCollide, SpheresUnderTranslationMatchTheClosedForm) {
  std::mt19937_64 rng(202);
  std::uniform_real_distribution<double> ur(0.2, 1.5), uc(-4.0, 4.0);
  int cases = 0, colliding = 0, naive_missed = 0, naive_spurious = 0, ca_missed = 0, ca_spurious = 0;
  double max_err = 0.0, naive_max_lag = 0.0, ca_max_lag = 0.0, ca_max_early = 0.0;
  double t_exact = 0.0, t_naive = 0.0, t_ca = 0.0, t_exact_hit = 0.0;
  long work_hit = 0;
  for (int k = 0; k < 600; ++k) {
    const double ra = ur(rng), rb = ur(rng);
    const Eigen::Vector3d pa0(uc(rng), uc(rng), uc(rng)), pb0(uc(rng), uc(rng), uc(rng));
    // Aim b's end position near a's end position so that about half the pairs meet.
    const Eigen::Vector3d pa1(uc(rng), uc(rng), uc(rng));
    const Eigen::Vector3d pb1 = pa1 + 3.0 * Eigen::Vector3d(uc(rng), uc(rng), uc(rng)) / 4.0;
    double disc_rel = 1.0;
    const std::optional<double> truth = sphereContact(pb0 - pa0, (pb1 - pb0) - (pa1 - pa0), ra + rb, &disc_rel);
    if (disc_rel >= 0.0 && disc_rel < 1e-6) continue;  // grazing: the closed form is ill-conditioned
    ++cases;
    const auto sa = std::make_shared<fcl::Sphered>(ra), sb = std::make_shared<fcl::Sphered>(rb);
    const Eigen::Matrix3d Ra = test::randomRotation(rng), Rb = test::randomRotation(rng);
    const fcl::TranslationMotiond ma(makePose(Ra, pa0), makePose(Ra, pa1)), mb(makePose(Rb, pb0), makePose(Rb, pb1));
    fcl::ContinuousCollisionRequestd req;
    fcl::ContinuousCollisionResultd res;
    auto start = Clock::now();
    const double ret = fcl_quadric::continuousCollide(sa.get(), &ma, sb.get(), &mb, req, res);
    t_exact += seconds(Clock::now() - start);
    if (res.is_collide) {
      t_exact_hit += seconds(Clock::now() - start);
      work_hit += lastContinuousCollideStats().steps;
    }
    EXPECT_EQ(lastContinuousCollideStats().path, ContinuousCollideStats::Path::Exact);
    ASSERT_EQ(res.is_collide, truth.has_value()) << "case " << k;
    EXPECT_EQ(ret, res.time_of_contact);
    if (truth) {
      ++colliding;
      EXPECT_NEAR(res.time_of_contact, *truth, 1e-9) << "case " << k;
      max_err = std::max(max_err, std::abs(res.time_of_contact - *truth));
      EXPECT_TRUE(res.contact_tf1.translation().isApprox(pa0 + res.time_of_contact * (pa1 - pa0), 1e-12));
      EXPECT_TRUE(res.contact_tf2.translation().isApprox(pb0 + res.time_of_contact * (pb1 - pb0), 1e-12));
    } else {
      EXPECT_EQ(res.time_of_contact, 1.0);
    }
    // Fresh motions for each FCL call: FCL's conservative advancement starts from the motions'
    // current state, which the previous calls moved.
    test::ScopedNoFpTraps no_traps;
    const fcl::TranslationMotiond na(makePose(Ra, pa0), makePose(Ra, pa1)), nb(makePose(Rb, pb0), makePose(Rb, pb1));
    const fcl::TranslationMotiond ca_a(makePose(Ra, pa0), makePose(Ra, pa1)), ca_b(makePose(Rb, pb0), makePose(Rb, pb1));
    fcl::ContinuousCollisionResultd naive;
    start = Clock::now();
    fcl::continuousCollide(sa.get(), &na, sb.get(), &nb, req, naive);
    t_naive += seconds(Clock::now() - start);
    if (truth && !naive.is_collide) ++naive_missed;
    if (!truth && naive.is_collide) ++naive_spurious;
    if (truth && naive.is_collide) naive_max_lag = std::max(naive_max_lag, naive.time_of_contact - *truth);
    fcl::ContinuousCollisionRequestd ca_req;
    ca_req.ccd_solver_type = fcl::CCDC_CONSERVATIVE_ADVANCEMENT;
    fcl::ContinuousCollisionResultd ca;
    start = Clock::now();
    fcl::continuousCollide(sa.get(), &ca_a, sb.get(), &ca_b, ca_req, ca);
    t_ca += seconds(Clock::now() - start);
    if (truth && !ca.is_collide) ++ca_missed;
    if (!truth && ca.is_collide) ++ca_spurious;
    if (truth && ca.is_collide) {
      ca_max_lag = std::max(ca_max_lag, ca.time_of_contact - *truth);
      ca_max_early = std::max(ca_max_early, *truth - ca.time_of_contact);
    }
  }
  std::printf(
      "[ info ] spheres, TranslationMotion: %d cases, %d colliding; exact max |t - t*| = %.2e, %.2f us/pair "
      "(colliding pairs: %.1f us, work %.1f)\n"
      "[ info ]   fcl CCDC_NAIVE (10 samples): missed %d, spurious %d, max lag %.3f, %.2f us/pair\n"
      "[ info ]   fcl CCDC_CONSERVATIVE_ADVANCEMENT: missed %d, spurious %d, max lag %.2e, max early %.2e, %.2f us/pair\n",
      cases, colliding, max_err, 1e6 * t_exact / cases, 1e6 * t_exact_hit / colliding,
      static_cast<double>(work_hit) / colliding, naive_missed, naive_spurious, naive_max_lag,
      1e6 * t_naive / cases, ca_missed, ca_spurious, ca_max_lag, ca_max_early, 1e6 * t_ca / cases);
  EXPECT_GT(colliding, cases / 5);
  EXPECT_GT(cases - colliding, cases / 5);
}

// Ellipsoid pairs under translation: exact against FCL's naive sampler (for the record) and
// RationalMotion pairs against continuousCollideEllipsoids directly.
TEST(ContinuousCollide, EllipsoidsUnderRationalMotionsAreTheCoreSolver) {
  std::mt19937_64 rng(203);
  std::uniform_real_distribution<double> ur(0.3, 1.5);
  int colliding = 0, naive_missed = 0, naive1000_missed = 0;
  double t_exact = 0.0, t_naive = 0.0, t_naive1000 = 0.0, t_exact_hit = 0.0;
  long work_hit = 0;
  const int n = 200;
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector3d ra(ur(rng), ur(rng), ur(rng)), rb(ur(rng), ur(rng), ur(rng));
    const fcl::Transform3d a0 = randomPose(rng, 3.0), a1 = randomPose(rng, 3.0);
    const fcl::Transform3d b0 = randomPose(rng, 3.0), b1 = randomPose(rng, 3.0);
    const auto ga = fclShape(ra, false), gb = fclShape(rb, false);
    const RationalMotion<double> ma(a0, a1), mb(b0, b1);
    fcl::ContinuousCollisionRequestd req;
    fcl::ContinuousCollisionResultd res;
    auto start = Clock::now();
    fcl_quadric::continuousCollide(ga.get(), &ma, gb.get(), &mb, req, res);
    t_exact += seconds(Clock::now() - start);
    if (res.is_collide) {
      t_exact_hit += seconds(Clock::now() - start);
      work_hit += lastContinuousCollideStats().steps;
    }
    CcdOptions opt;
    opt.all_intervals = false;
    const EllipsoidCcdResult core = continuousCollideEllipsoids(
        MovingEllipsoid{Ellipsoid(ra, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()), ma.piecewiseMotion()},
        MovingEllipsoid{Ellipsoid(rb, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()), mb.piecewiseMotion()}, opt);
    ASSERT_EQ(res.is_collide, core.collide);
    if (core.collide) {
      ++colliding;
      EXPECT_EQ(res.time_of_contact, *core.first_contact_time);
      const Eigen::Matrix4d X = ma.piecewiseMotion().evaluate(res.time_of_contact);
      EXPECT_EQ(res.contact_tf1.translation(), Eigen::Vector3d(X.block<3, 1>(0, 3)));
    }
    // Stock FCL on the same rational motions (its naive sampler evaluates them).
    test::ScopedNoFpTraps no_traps;
    fcl::ContinuousCollisionResultd naive;
    start = Clock::now();
    fcl::continuousCollide(ga.get(), &ma, gb.get(), &mb, req, naive);
    t_naive += seconds(Clock::now() - start);
    if (core.collide && !naive.is_collide) ++naive_missed;
    fcl::ContinuousCollisionRequestd req1000(1000, 1e-4);
    fcl::ContinuousCollisionResultd naive1000;
    start = Clock::now();
    fcl::continuousCollide(ga.get(), &ma, gb.get(), &mb, req1000, naive1000);
    t_naive1000 += seconds(Clock::now() - start);
    if (core.collide && !naive1000.is_collide) ++naive1000_missed;
  }
  std::printf(
      "[ info ] ellipsoids, RationalMotion (fromPoses): %d pairs, %d colliding; exact %.1f us/pair (colliding pairs: "
      "%.1f us, work %.1f)\n"
      "[ info ]   fcl CCDC_NAIVE 10 samples: missed %d, %.1f us/pair; 1000 samples: missed %d, %.1f us/pair\n"
      "[ info ]   (fcl CCDC_CONSERVATIVE_ADVANCEMENT has no ellipsoid entry: warning and -1)\n",
      n, colliding, 1e6 * t_exact / n, 1e6 * t_exact_hit / colliding, static_cast<double>(work_hit) / colliding,
      naive_missed, 1e6 * t_naive / n, naive1000_missed, 1e6 * t_naive1000 / n);
  // For the record: FCL's conservative advancement table has no ellipsoid entry.
  const auto e = fclShape(Eigen::Vector3d(1.0, 0.5, 0.7), false);
  const RationalMotion<double> m0(fcl::Transform3d::Identity(), fcl::Transform3d::Identity());
  fcl::ContinuousCollisionRequestd ca_req;
  ca_req.ccd_solver_type = fcl::CCDC_CONSERVATIVE_ADVANCEMENT;
  fcl::ContinuousCollisionResultd ca;
  test::ScopedNoFpTraps no_traps;
  EXPECT_EQ(fcl::continuousCollide(e.get(), &m0, e.get(), &m0, ca_req, ca), -1.0);
  EXPECT_FALSE(ca.is_collide);
}

// --- (c) conservative advancement under InterpMotion / ScrewMotion vs a dense oracle ------------

struct OracleResult {
  bool collide = false;
  double t = 1.0;  // bisected first contact
};

// classifyEllipsoids at `samples` + 1 equally spaced times, then bisection of the first change.
template <typename MakeMotion>
OracleResult denseOracle(const Eigen::Vector3d& ra, const Eigen::Vector3d& rb, MakeMotion make_a, MakeMotion make_b,
                         int samples) {
  const auto ma = make_a(), mb = make_b();
  auto collides = [&](double t) {
    return classifyEllipsoids(worldEllipsoid(ra, poseOf(*ma, t)), worldEllipsoid(rb, poseOf(*mb, t))).status !=
           Separation::Separated;
  };
  OracleResult o;
  if (collides(0.0)) return {true, 0.0};
  for (int s = 1; s <= samples; ++s) {
    const double t = static_cast<double>(s) / samples;
    if (!collides(t)) continue;
    double lo = static_cast<double>(s - 1) / samples, hi = t;
    for (int it = 0; it < 60; ++it) {
      const double mid = 0.5 * (lo + hi);
      (collides(mid) ? hi : lo) = mid;
    }
    return {true, hi};
  }
  return o;
}

TEST(ContinuousCollide, ConservativeAdvancementIsNeverLateAgainstADenseOracle) {
  std::mt19937_64 rng(303);
  std::uniform_real_distribution<double> ur(0.3, 1.5);
  int pairs = 0, colliding = 0, ca_only = 0, step_caps = 0, total_steps = 0;
  double max_gap = 0.0, t_ca = 0.0;
  for (int kind = 0; kind < 3; ++kind) {  // 0: InterpMotion, 1: ScrewMotion, 2: SplineMotion
    for (int k = 0; k < 40; ++k) {
      const Eigen::Vector3d ra(ur(rng), ur(rng), ur(rng)), rb(ur(rng), ur(rng), ur(rng));
      const fcl::Transform3d a0 = randomPose(rng, 3.0), a1 = randomPose(rng, 3.0);
      const fcl::Transform3d b0 = randomPose(rng, 3.0), b1 = randomPose(rng, 3.0);
      using Ptr = std::shared_ptr<fcl::MotionBase<double>>;
      auto make = [&](const fcl::Transform3d& x0, const fcl::Transform3d& x1) {
        return [=]() -> Ptr {
          if (kind == 0) return std::make_shared<OriginInterp>(x0, x1);
          if (kind == 1) return std::make_shared<fcl::ScrewMotion<double>>(x0, x1);
          // A cubic B-spline from x0 to x1 (control points doubled at the ends), rotation as a
          // rotation vector.
          const Eigen::AngleAxisd r0(x0.linear()), r1(x1.linear());
          const Eigen::Vector3d w0 = r0.angle() * r0.axis(), w1 = r1.angle() * r1.axis();
          return std::make_shared<fcl::SplineMotion<double>>(x0.translation(), x0.translation(), x1.translation(),
                                                             x1.translation(), w0, w0, w1, w1);
        };
      };
      const auto make_a = make(a0, a1), make_b = make(b0, b1);
      const Ptr ma = make_a(), mb = make_b();
      const auto ga = fclShape(ra, false), gb = fclShape(rb, false);
      fcl::ContinuousCollisionRequestd req;
      fcl::ContinuousCollisionResultd res;
      const auto start = Clock::now();
      fcl_quadric::continuousCollide(ga.get(), ma.get(), gb.get(), mb.get(), req, res);
      t_ca += seconds(Clock::now() - start);
      ++pairs;
      const ContinuousCollideStats stats = lastContinuousCollideStats();
      ASSERT_EQ(stats.path, ContinuousCollideStats::Path::ConservativeAdvancement);
      total_steps += stats.steps;
      if (stats.step_cap) ++step_caps;
      const OracleResult oracle = denseOracle(ra, rb, make_a, make_b, 2000);
      if (oracle.collide) {
        ++colliding;
        ASSERT_TRUE(res.is_collide) << "missed a collision, pair " << k << " kind " << kind;
        EXPECT_LE(res.time_of_contact, oracle.t + 1e-12) << "late, pair " << k << " kind " << kind;
        max_gap = std::max(max_gap, oracle.t - res.time_of_contact);
      } else if (res.is_collide) {
        ++ca_only;  // the oracle's samples can step over a brief contact or a near miss
      }
      if (res.is_collide) {
        // The documented tolerance: at the reported time the pair is within
        // kAdvancementDistanceRelative (r_a + r_b) of contact, or not separate.
        const Ellipsoid ea = worldEllipsoid(ra, poseOf(*make_a(), res.time_of_contact));
        const Ellipsoid eb = worldEllipsoid(rb, poseOf(*make_b(), res.time_of_contact));
        const SignedDistanceResult sd = signedDistance(ea, eb);
        const double tol = kAdvancementDistanceRelative * (ra.maxCoeff() + rb.maxCoeff());
        EXPECT_LE(sd.distance, tol * (1.0 + 1e-6) + 1e-12) << "pair " << k << " kind " << kind;
        EXPECT_TRUE(res.contact_tf1.isApprox(fcl::Transform3d(poseOf(*make_a(), res.time_of_contact)), 1e-12));
      }
    }
  }
  std::printf(
      "[ info ] conservative advancement (InterpMotion, ScrewMotion, SplineMotion): %d pairs, %d colliding by the oracle, %d "
      "more reported (near misses), max (t* - t) = %.2e, %.1f steps/pair, %d step caps, %.1f us/pair\n",
      pairs, colliding, ca_only, max_gap, static_cast<double>(total_steps) / pairs, step_caps, 1e6 * t_ca / pairs);
  EXPECT_GT(colliding, 10);
  EXPECT_EQ(step_caps, 0);
}

// --- (d) the three overloads agree ----------------------------------------------------------------

TEST(ContinuousCollide, TheThreeOverloadsAgree) {
  std::mt19937_64 rng(404);
  std::uniform_real_distribution<double> ur(0.3, 1.5);
  int collisions = 0;
  for (fcl::CCDMotionType type : {fcl::CCDM_TRANS, fcl::CCDM_LINEAR, fcl::CCDM_SCREW}) {
    for (int k = 0; k < 25; ++k) {
      const bool sphere_a = k % 5 == 0;
      const Eigen::Vector3d ra = sphere_a ? Eigen::Vector3d::Constant(ur(rng)) : Eigen::Vector3d(ur(rng), ur(rng), ur(rng));
      const Eigen::Vector3d rb(ur(rng), ur(rng), ur(rng));
      const fcl::Transform3d a0 = randomPose(rng, 3.0), a1 = randomPose(rng, 3.0);
      const fcl::Transform3d b0 = randomPose(rng, 3.0), b1 = randomPose(rng, 3.0);
      const auto ga = fclShape(ra, sphere_a), gb = fclShape(rb, false);
      fcl::ContinuousCollisionRequestd req;
      req.ccd_motion_type = type;
      fcl::ContinuousCollisionResultd r_tf, r_motion, r_obj;
      const double v_tf = fcl_quadric::continuousCollide(ga.get(), a0, a1, gb.get(), b0, b1, req, r_tf);
      // shared_ptr (allocator-based): FCL's motions must not be deleted through a pointer from
      // this C++17 code's `new` (their EIGEN_MAKE_ALIGNED_OPERATOR_NEW differs in libfcl).
      std::shared_ptr<fcl::MotionBase<double>> ma, mb;
      if (type == fcl::CCDM_TRANS) {
        ma = std::make_shared<fcl::TranslationMotiond>(a0, a1);
        mb = std::make_shared<fcl::TranslationMotiond>(b0, b1);
      } else if (type == fcl::CCDM_LINEAR) {
        ma = std::make_shared<OriginInterp>(a0, a1);
        mb = std::make_shared<OriginInterp>(b0, b1);
      } else {
        ma = std::make_shared<fcl::ScrewMotion<double>>(a0, a1);
        mb = std::make_shared<fcl::ScrewMotion<double>>(b0, b1);
      }
      const double v_motion = fcl_quadric::continuousCollide(ga.get(), ma.get(), gb.get(), mb.get(), req, r_motion);
      const fcl::CollisionObjectd oa(ga, a0), ob(gb, b0);
      const double v_obj = fcl_quadric::continuousCollide(&oa, a1, &ob, b1, req, r_obj);
      ASSERT_EQ(r_tf.is_collide, r_motion.is_collide);
      ASSERT_EQ(r_tf.is_collide, r_obj.is_collide);
      EXPECT_EQ(v_tf, v_motion);
      EXPECT_EQ(v_tf, v_obj);
      EXPECT_EQ(r_tf.time_of_contact, r_motion.time_of_contact);
      EXPECT_EQ(r_tf.time_of_contact, r_obj.time_of_contact);
      if (r_tf.is_collide) {
        ++collisions;
        EXPECT_EQ(r_tf.contact_tf1.matrix(), r_motion.contact_tf1.matrix());
        EXPECT_EQ(r_tf.contact_tf2.matrix(), r_obj.contact_tf2.matrix());
      }
    }
  }
  EXPECT_GT(collisions, 10);
}

// --- (e) non-ellipsoid pairs are FCL's answer ------------------------------------------------------

TEST(ContinuousCollide, OtherPairsAreStockFcl) {
  test::ScopedNoFpTraps no_traps;
  std::mt19937_64 rng(505);
  std::uniform_real_distribution<double> us(0.5, 2.0);
  int collisions = 0, cases = 0;
  for (fcl::CCDSolverType solver : {fcl::CCDC_NAIVE, fcl::CCDC_CONSERVATIVE_ADVANCEMENT}) {
    for (fcl::CCDMotionType type : {fcl::CCDM_TRANS, fcl::CCDM_SCREW}) {
      for (int k = 0; k < 30; ++k) {
        std::shared_ptr<fcl::CollisionGeometryd> g1 = std::make_shared<fcl::Boxd>(us(rng), us(rng), us(rng));
        std::shared_ptr<fcl::CollisionGeometryd> g2 = std::make_shared<fcl::Boxd>(us(rng), us(rng), us(rng));
        if (k % 3 == 1) g2 = std::make_shared<fcl::Sphered>(us(rng));
        if (k % 3 == 2 && solver == fcl::CCDC_NAIVE) g2 = std::make_shared<fcl::Ellipsoidd>(us(rng), us(rng), us(rng));
        const fcl::Transform3d a0 = randomPose(rng, 3.0), a1 = randomPose(rng, 3.0);
        const fcl::Transform3d b0 = randomPose(rng, 3.0), b1 = randomPose(rng, 3.0);
        fcl::ContinuousCollisionRequestd req(20, 1e-4, type, fcl::GST_LIBCCD, solver);
        fcl::ContinuousCollisionResultd ours, stock;
        const double v_ours = fcl_quadric::continuousCollide(g1.get(), a0, a1, g2.get(), b0, b1, req, ours);
        EXPECT_EQ(lastContinuousCollideStats().path, ContinuousCollideStats::Path::Delegated);
        const double v_stock = fcl::continuousCollide(g1.get(), a0, a1, g2.get(), b0, b1, req, stock);
        ++cases;
        EXPECT_EQ(v_ours, v_stock);
        ASSERT_EQ(ours.is_collide, stock.is_collide);
        EXPECT_EQ(ours.time_of_contact, stock.time_of_contact);
        if (stock.is_collide) {
          ++collisions;
          EXPECT_EQ(ours.contact_tf1.matrix(), stock.contact_tf1.matrix());
          EXPECT_EQ(ours.contact_tf2.matrix(), stock.contact_tf2.matrix());
        }
        // The motion overload with FCL's motions is the same call. Fresh motions for each call:
        // FCL's conservative advancement starts from the motions' current time.
        const fcl::TranslationMotiond ta(a0, a1), tb(b0, b1), tc(a0, a1), td(b0, b1);
        fcl::ContinuousCollisionResultd ours_m, stock_m;
        req.ccd_motion_type = fcl::CCDM_TRANS;
        fcl_quadric::continuousCollide(g1.get(), &ta, g2.get(), &tb, req, ours_m);
        fcl::continuousCollide(g1.get(), &tc, g2.get(), &td, req, stock_m);
        EXPECT_EQ(ours_m.is_collide, stock_m.is_collide);
        EXPECT_EQ(ours_m.time_of_contact, stock_m.time_of_contact);
      }
    }
  }
  std::printf("[ info ] delegated box/sphere/ellipsoid-box pairs: %d cases, %d colliding, all equal to stock FCL\n",
              cases, collisions);
  EXPECT_GT(collisions, 5);
}

// --- (f) continuous broad phase -------------------------------------------------------------------

struct Scene {
  std::vector<std::unique_ptr<SweptCollisionObject>> objects;
  std::vector<Eigen::Vector3d> radii;
};

Scene movingScene(std::mt19937_64& rng, int n) {
  Scene s;
  std::uniform_real_distribution<double> ur(0.2, 0.8), u(0.0, 1.0);
  for (int i = 0; i < n; ++i) {
    const bool sphere = i % 4 == 0;
    const Eigen::Vector3d r = sphere ? Eigen::Vector3d::Constant(ur(rng)) : Eigen::Vector3d(ur(rng), ur(rng), ur(rng));
    PiecewiseMotion motion;
    for (bool placed = false; !placed;) {  // start poses pairwise separate, so that t-bar > 0
      if (i % 3 == 0) {  // three keyframes
        const double tm = 0.2 + 0.6 * u(rng);
        std::vector<Eigen::Isometry3d> poses{randomPose(rng, 6.0), randomPose(rng, 6.0), randomPose(rng, 6.0)};
        motion = PiecewiseMotion::fromKeyframes({0.0, tm, 1.0}, poses);
      } else {
        motion = PiecewiseMotion(MotionMatrix::fromPoses(randomPose(rng, 6.0), randomPose(rng, 6.0)));
      }
      const MovingEllipsoid me{Ellipsoid(r, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()), motion};
      placed = true;
      for (std::size_t j = 0; j < s.objects.size() && placed; ++j) {
        const MovingEllipsoid other{Ellipsoid(s.radii[j], Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()),
                                    s.objects[j]->motion()};
        placed = classifyEllipsoids(ellipsoidAt(me, 0.0), ellipsoidAt(other, 0.0)).status == Separation::Separated;
      }
    }
    s.objects.push_back(std::make_unique<SweptCollisionObject>(fclShape(r, sphere), motion));
    s.radii.push_back(r);
  }
  return s;
}

TEST(ContinuousBroadPhase, EveryPairAndTheEarliestMatchPairwiseCcd) {
  std::mt19937_64 rng(606);
  const int n = 60;
  Scene scene = movingScene(rng, n);
  std::vector<SweptCollisionObject*> raw;
  for (auto& o : scene.objects) raw.push_back(o.get());
  const MotionMap motions = motionMap(raw);

  // The swept AABBs contain the world AABB of every sampled pose.
  for (int i = 0; i < n; ++i) {
    const fcl::AABBd& box = scene.objects[i]->getAABB();
    const MovingEllipsoid m{Ellipsoid(scene.radii[i], Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()),
                            scene.objects[i]->motion()};
    for (int s = 0; s <= 200; ++s) {
      const Ellipsoid e = ellipsoidAt(m, s / 200.0);
      const Eigen::Matrix3d A = e.rotation() * e.radii().asDiagonal();
      for (int ax = 0; ax < 3; ++ax) {
        const double h = A.row(ax).norm();
        EXPECT_LE(box.min_[ax], e.center()[ax] - h + 1e-12);
        EXPECT_GE(box.max_[ax], e.center()[ax] + h - 1e-12);
      }
    }
  }

  // Brute force: every pair through the exact CCD.
  std::map<std::pair<int, int>, double> truth;
  const auto bf_start = Clock::now();
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      CcdOptions opt;
      opt.all_intervals = false;
      const EllipsoidCcdResult r = continuousCollideEllipsoids(
          MovingEllipsoid{Ellipsoid(scene.radii[i], Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()),
                          scene.objects[i]->motion()},
          MovingEllipsoid{Ellipsoid(scene.radii[j], Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()),
                          scene.objects[j]->motion()},
          opt);
      if (r.collide) truth[{i, j}] = *r.first_contact_time;
    }
  }
  const double bf_time = seconds(Clock::now() - bf_start);
  ASSERT_GT(truth.size(), 5u);
  ASSERT_GT(std::min_element(truth.begin(), truth.end(), [](const auto& x, const auto& y) { return x.second < y.second; })->second, 0.0);
  double global_min = 1.0;
  for (const auto& kv : truth) global_min = std::min(global_min, kv.second);

  fcl::DynamicAABBTreeCollisionManagerd manager;
  std::vector<fcl::CollisionObjectd*> base(raw.begin(), raw.end());
  manager.registerObjects(base);
  manager.setup();
  std::map<const fcl::CollisionObjectd*, int> index;
  for (int i = 0; i < n; ++i) index[raw[i]] = i;

  ContinuousBroadPhaseRequest req;
  ContinuousBroadPhaseResult all;
  auto start = Clock::now();
  continuousCollideBroadPhase(&manager, motions, req, all);
  const double all_time = seconds(Clock::now() - start);
  ASSERT_EQ(all.contacts.size(), truth.size());
  for (const ContinuousContactPair& c : all.contacts) {
    int i = index.at(c.o1), j = index.at(c.o2);
    if (i > j) std::swap(i, j);
    ASSERT_EQ(truth.count({i, j}), 1u) << i << " " << j;
    EXPECT_NEAR(c.time_of_contact, truth.at({i, j}), 1e-9) << i << " " << j;
    EXPECT_TRUE(c.exact);
  }
  EXPECT_TRUE(std::is_sorted(all.contacts.begin(), all.contacts.end(),
                             [](const auto& x, const auto& y) { return x.time_of_contact < y.time_of_contact; }));
  EXPECT_NEAR(all.earliestTime(), global_min, 1e-9);

  req.earliest_only = true;
  ContinuousBroadPhaseResult first;
  start = Clock::now();
  continuousCollideBroadPhase(&manager, motions, req, first);
  const double first_time = seconds(Clock::now() - start);
  ASSERT_EQ(first.contacts.size(), 1u);
  EXPECT_NEAR(first.earliestTime(), global_min, 1e-9);
  std::printf(
      "[ info ] broad phase, %d moving ellipsoids: %zu colliding pairs of %d; candidates %zu (every pair: %zu exact "
      "solves, %zu culled, %.1f ms; earliest only: %zu candidates, %zu solves, %zu culled, %.1f ms); brute force %d pairs %.1f ms\n",
      n, truth.size(), n * (n - 1) / 2, all.candidate_pairs, all.exact_solves, all.culled, 1e3 * all_time,
      first.candidate_pairs, first.exact_solves, first.culled, 1e3 * first_time, n * (n - 1) / 2, 1e3 * bf_time);
}

TEST(ContinuousBroadPhase, StaticAndNonEllipsoidObjectsAreHandled) {
  std::mt19937_64 rng(607);
  Scene scene = movingScene(rng, 12);
  // A static box across the middle (no motion in the map) and a static sphere.
  fcl::CollisionObjectd wall(std::make_shared<fcl::Boxd>(0.5, 12.0, 12.0), makePose(Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()));
  fcl::CollisionObjectd ball(std::make_shared<fcl::Sphered>(1.0), makePose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(3, 3, 3)));
  std::vector<SweptCollisionObject*> raw;
  for (auto& o : scene.objects) raw.push_back(o.get());
  const MotionMap motions = motionMap(raw);
  fcl::DynamicAABBTreeCollisionManagerd manager;
  for (auto* o : raw) manager.registerObject(o);
  manager.registerObject(&wall);
  manager.registerObject(&ball);
  manager.setup();
  ContinuousBroadPhaseRequest req;
  req.delegated_request.num_max_iterations = 200;
  ContinuousBroadPhaseResult res;
  {
    test::ScopedNoFpTraps no_traps;  // the box pairs go to libccd
    continuousCollideBroadPhase(&manager, motions, req, res);
  }
  EXPECT_GT(res.delegated, 0u);
  int ball_pairs = 0;
  for (const auto& c : res.contacts) {
    if (c.o1 == &ball || c.o2 == &ball) {
      ++ball_pairs;
      EXPECT_TRUE(c.exact);  // a static sphere is an exact pair
    }
    if (c.o1 == &wall || c.o2 == &wall) {
      EXPECT_FALSE(c.exact);
    }
  }
  // Every moving object crossing x = 0 hits the wall.
  for (std::size_t i = 0; i < raw.size(); ++i) {
    const double x0 = raw[i]->motion().evaluate(0.0)(0, 3), x1 = raw[i]->motion().evaluate(1.0)(0, 3);
    if (x0 * x1 < 0.0 && std::abs(x0) > 1.5 && std::abs(x1) > 1.5) {
      bool found = false;
      for (const auto& c : res.contacts)
        found = found || ((c.o1 == raw[i] || c.o2 == raw[i]) && (c.o1 == &wall || c.o2 == &wall));
      EXPECT_TRUE(found) << "object " << i;
    }
  }
  std::printf("[ info ] mixed scene: %zu contacts, %zu delegated pair tests, %d with the static sphere\n",
              res.contacts.size(), res.delegated, ball_pairs);
}

// --- (g) bad input ----------------------------------------------------------------------------------

// Conservative advancement bounds the relative velocity of the two solids, not the sum of their
// speeds: two balls translated alike side by side (CCDM_LINEAR, 1000 units at a gap of 1e-2, or 10
// units at 1e-4) never approach each other. With the sum, an audit found both at the step cap and
// reported colliding at t = 0.05 (session 35). Moving towards each other they still collide at the
// closed-form time, never later.
TEST(ContinuousCollide, AdvancementBoundsTheRelativeVelocity) {
  const auto ball = std::make_shared<fcl::Sphered>(1.0);
  fcl::ContinuousCollisionRequestd req;
  req.ccd_motion_type = fcl::CCDM_LINEAR;
  for (const auto& [length, gap] : {std::pair(1000.0, 1e-2), std::pair(10.0, 1e-4), std::pair(1000.0, 1e-4)}) {
    fcl::Transform3d a0 = fcl::Transform3d::Identity(), a1 = a0, b0 = a0, b1 = a0;
    a1.translation() = Eigen::Vector3d(length, 0, 0);
    b0.translation() = Eigen::Vector3d(0, 2.0 + gap, 0);
    b1.translation() = Eigen::Vector3d(length, 2.0 + gap, 0);
    fcl::ContinuousCollisionResultd res;
    fcl_quadric::continuousCollide(ball.get(), a0, a1, ball.get(), b0, b1, req, res);
    EXPECT_FALSE(res.is_collide) << "length " << length << ", gap " << gap << ", toc " << res.time_of_contact;
    EXPECT_FALSE(lastContinuousCollideStats().step_cap);
    // b drifts towards a by 2 gap over the motion: contact at t = 1/2 exactly.
    b1.translation().y() = 2.0 - gap;
    fcl_quadric::continuousCollide(ball.get(), a0, a1, ball.get(), b0, b1, req, res);
    EXPECT_TRUE(res.is_collide);
    EXPECT_LE(res.time_of_contact, 0.5);
    // Contact is reported once the distance is within kAdvancementDistanceRelative (r_a + r_b) = 2e-6,
    // which the distance gap (1 - 2t) reaches at t = 1/2 - 1e-6 / gap.
    EXPECT_GE(res.time_of_contact, 0.5 - kAdvancementDistanceRelative * 2.0 / (2.0 * gap) - 1e-12)
        << "length " << length << ", gap " << gap;
  }
}

TEST(ContinuousCollide, BadInputThrowsNamingTheArgument) {
  const auto e = std::make_shared<fcl::Ellipsoidd>(1.0, 0.5, 0.7);
  const auto box = std::make_shared<fcl::Boxd>(1.0, 1.0, 1.0);
  const fcl::Transform3d I = fcl::Transform3d::Identity();
  fcl::Transform3d bad = I;
  bad.translation().x() = std::numeric_limits<double>::quiet_NaN();
  const RationalMotion<double> m(I, I);
  fcl::ContinuousCollisionRequestd req;
  fcl::ContinuousCollisionResultd res;
  expectInvalid([&] { fcl_quadric::continuousCollide<double>(nullptr, &m, e.get(), &m, req, res); }, "o1");
  expectInvalid([&] { fcl_quadric::continuousCollide<double>(e.get(), &m, nullptr, &m, req, res); }, "o2");
  expectInvalid([&] { fcl_quadric::continuousCollide<double>(e.get(), nullptr, e.get(), &m, req, res); }, "motion1");
  expectInvalid([&] { fcl_quadric::continuousCollide<double>(e.get(), &m, e.get(), nullptr, req, res); }, "motion2");
  expectInvalid([&] { fcl_quadric::continuousCollide<double>(nullptr, I, I, e.get(), I, I, req, res); }, "o1");
  expectInvalid([&] { fcl_quadric::continuousCollide(e.get(), bad, I, e.get(), I, I, req, res); }, "tf1_beg");
  expectInvalid([&] { fcl_quadric::continuousCollide(e.get(), I, bad, e.get(), I, I, req, res); }, "tf1_end");
  expectInvalid([&] { fcl_quadric::continuousCollide(e.get(), I, I, e.get(), bad, I, req, res); }, "tf2_beg");
  expectInvalid([&] { fcl_quadric::continuousCollide(e.get(), I, I, box.get(), I, bad, req, res); }, "tf2_end");
  const fcl::CollisionObjectd oe(e, I);
  expectInvalid([&] { fcl_quadric::continuousCollide<double>(nullptr, I, &oe, I, req, res); }, "o1");
  expectInvalid([&] { fcl_quadric::continuousCollide<double>(&oe, I, nullptr, I, req, res); }, "o2");
  expectInvalid([&] { fcl_quadric::continuousCollide(&oe, bad, &oe, I, req, res); }, "tf1_end");
  // A non-rigid RationalMotion on a delegated pair.
  PolynomialMatrix4 M(Eigen::Matrix4d::Identity());
  M(1, 1) = Polynomial{1.0, 0.5};
  const RationalMotion<double> affine(M);
  expectInvalid([&] { fcl_quadric::continuousCollide<double>(box.get(), &affine, box.get(), &m, req, res); }, "motion1");
  // ...which ellipsoid pairs accept (exact).
  EXPECT_NO_THROW(fcl_quadric::continuousCollide<double>(e.get(), &affine, e.get(), &m, req, res));
  // Bad motions and radii.
  expectInvalid([&] { (void)RationalMotion<double>(bad, I); }, "tf_beg");
  expectInvalid([&] { (void)RationalMotion<double>(std::vector<double>{0.0, 1.0}, std::vector<fcl::Transform3d>{I, bad}); },
                "poses[1]");
  expectInvalid([&] { fcl_quadric::continuousCollide<double>(std::make_shared<fcl::Ellipsoidd>(1.0, -1.0, 1.0).get(), &m,
                                                             e.get(), &m, req, res); },
                "o1");
  // (An out-of-range CCDMotionType cannot be tested: FCL's unscoped enum has the value range 0..3,
  // so storing 17 is already undefined behaviour, which UBSan reports at the first load.)
  // FCL 0.7's SplineMotion(tf1, tf2) leaves its control points uninitialised: refused.
  fcl::ContinuousCollisionRequestd spline;
  spline.ccd_motion_type = fcl::CCDM_SPLINE;
  expectInvalid([&] { fcl_quadric::continuousCollide(e.get(), I, I, e.get(), I, I, spline, res); }, "CCDM_SPLINE");
  expectInvalid([&] { m.speedBound(Eigen::Vector3d::Zero(), 1.0, 1.5); }, "t0");
  // Visitors whose bounding volume RationalMotion cannot read, and Taylor models.
  fcl::AABBd aabb(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones());
  EXPECT_THROW(m.computeMotionBound(fcl::TBVMotionBoundVisitor<fcl::AABBd>(aabb, Eigen::Vector3d::UnitX())),
               std::logic_error);
  // Session 35, an audit: non-rigid transforms were read as rotations, and FCL's naive solver
  // with one iteration answered NaN (t = 0 / 0) with is_collide set.
  fcl::Transform3d scaled = I;
  scaled.linear() = 2.0 * Eigen::Matrix3d::Identity();
  fcl::Transform3d far = I;
  far.translation().x() = 1e200;
  for (const fcl::CCDMotionType type : {fcl::CCDM_TRANS, fcl::CCDM_LINEAR, fcl::CCDM_SCREW}) {
    fcl::ContinuousCollisionRequestd r;
    r.ccd_motion_type = type;
    expectInvalid([&] { fcl_quadric::continuousCollide(e.get(), scaled, I, e.get(), I, I, r, res); }, "tf1_beg rotation");
    expectInvalid([&] { fcl_quadric::continuousCollide(e.get(), I, I, box.get(), I, scaled, r, res); }, "tf2_end rotation");
    expectInvalid([&] { fcl_quadric::continuousCollide(e.get(), I, far, e.get(), I, I, r, res); },
                  "tf1_end translation coordinates must be within");
  }
  fcl::ContinuousCollisionRequestd one;
  one.ccd_solver_type = fcl::CCDC_NAIVE;
  one.num_max_iterations = 1;
  expectInvalid([&] { fcl_quadric::continuousCollide(box.get(), I, I, box.get(), I, I, one, res); }, "num_max_iterations");
  const fcl::TranslationMotion<double> still(I, I);
  expectInvalid([&] { fcl_quadric::continuousCollide<double>(box.get(), &still, box.get(), &still, one, res); },
                "num_max_iterations");
  // Broad phase.
  ContinuousBroadPhaseResult bres;
  expectInvalid([&] { continuousCollideBroadPhase(nullptr, MotionMap(), ContinuousBroadPhaseRequest(), bres); },
                "manager");
  expectInvalid([&] { (void)SweptCollisionObject(nullptr, PiecewiseMotion()); }, "geometry");
}

}  // namespace
}  // namespace continuous_collision_test
}  // namespace fcl_quadric
