// Signed distance between ellipsoids: optimality conditions, closed forms, independent oracles.
#include <gtest/gtest.h>

#include <random>

#include "fcl_quadric/geometry/signed_distance.h"
#include "fcl_quadric/tolerances.h"
#include "support/exact_oracle.h"
#include "support/random_ellipsoids.h"

namespace fcl_quadric {
namespace {

/// Independent oracle: signed distance from a point to an ellipsoid surface (negative inside),
/// by bisection in long double on the Lagrange multiplier t of the closest point
/// x_i = y_i e_i^2 / (e_i^2 + t) (Eberly's formulation), body frame.
long double pointEllipsoidSignedDistance(const Ellipsoid& e, const Eigen::Vector3d& p) {
  const Eigen::Vector3d yd = e.rotation().transpose() * (p - e.center());
  long double y[3], r[3];
  for (int i = 0; i < 3; ++i) {
    y[i] = yd[i];
    r[i] = e.radii()[i];
  }
  auto g = [&](long double t) {
    long double s = 0;
    for (int i = 0; i < 3; ++i) {
      const long double q = r[i] * y[i] / (r[i] * r[i] + t);
      s += q * q;
    }
    return s - 1;
  };
  long double rmin2 = std::min({r[0] * r[0], r[1] * r[1], r[2] * r[2]});
  long double lo = -rmin2, hi = 1;
  while (g(hi) > 0) hi *= 2;
  for (int it = 0; it < 200; ++it) {
    const long double mid = 0.5L * (lo + hi);
    (g(mid) > 0 ? lo : hi) = mid;
  }
  long double d2 = 0;
  for (int i = 0; i < 3; ++i) {
    const long double x = y[i] * r[i] * r[i] / (r[i] * r[i] + hi);
    d2 += (x - y[i]) * (x - y[i]);
  }
  const long double d = std::sqrt(d2);
  return e.implicit(p) < 0 ? -d : d;
}

TEST(SignedDistance, SphereSphereMatchesClosedForm) {
  std::mt19937_64 rng(61);
  std::uniform_real_distribution<double> u(0.2, 3.0);
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector3d c1 = 3 * test::randomUnitVector(rng) * u(rng), c2 = 3 * test::randomUnitVector(rng) * u(rng);
    const double r1 = u(rng), r2 = u(rng);
    const SignedDistanceResult d = signedDistance(Ellipsoid::sphere(r1, c1), Ellipsoid::sphere(r2, c2));
    const double expected = (c2 - c1).norm() - r1 - r2;
    ASSERT_NEAR(d.distance, expected, 1e-12 * (1 + std::fabs(expected))) << i;
    ASSERT_NEAR(d.normal.dot((c2 - c1).normalized()), 1.0, 1e-10);
  }
}

TEST(SignedDistance, SphereEllipsoidMatchesPointDistanceOracle) {
  std::mt19937_64 rng(63);
  std::uniform_real_distribution<double> u(-4.0, 4.0), ur(0.5, 3.0);
  int overlapping = 0;
  for (int i = 0; i < 3000; ++i) {
    const Ellipsoid e(test::randomRadii(rng, 3.0, 20.0), test::randomRotation(rng), {u(rng), u(rng), u(rng)});
    const Eigen::Vector3d c(u(rng), u(rng), u(rng));
    const double r = ur(rng);
    const double expected = static_cast<double>(pointEllipsoidSignedDistance(e, c) - r);
    const SignedDistanceResult d = signedDistance(e, Ellipsoid::sphere(r, c));
    overlapping += expected < 0;
    ASSERT_NEAR(d.distance, expected, 1e-10 * (1 + std::fabs(expected))) << "case " << i;
  }
  EXPECT_GT(overlapping, 300);
}

TEST(SignedDistance, SeparatedPairsSatisfyTheOptimalityConditions) {
  // For convex bodies these KKT conditions certify the global minimum distance.
  std::mt19937_64 rng(65);
  int separated = 0;
  for (int i = 0; i < 20000 && separated < 5000; ++i) {
    const Ellipsoid a = test::anchorEllipsoid(rng), b = test::anchorEllipsoid(rng);
    const SignedDistanceResult d = signedDistance(a, b);
    if (d.status != Separation::Separated) continue;
    ++separated;
    ASSERT_GT(d.distance, 0.0);
    EXPECT_TRUE(d.converged);
    ASSERT_NEAR(a.implicit(d.point_a), 0.0, 1e-12);
    ASSERT_NEAR(b.implicit(d.point_b), 0.0, 1e-12);
    ASSERT_NEAR((d.point_b - d.point_a).norm(), d.distance, 1e-12 * (1 + d.distance));
    ASSERT_NEAR((d.point_b - d.point_a - d.distance * d.normal).norm(), 0.0, 1e-9);
    ASSERT_NEAR(a.normalAt(d.point_a).dot(d.normal), 1.0, 1e-12);
    ASSERT_NEAR(b.normalAt(d.point_b).dot(-d.normal), 1.0, 1e-12);
  }
  EXPECT_EQ(separated, 5000);
}

/// An ellipsoid from its radii, its rotation's rows and its centre (the audit's printed inputs).
Ellipsoid ellipsoidFromRows(const double* radii, const double* R_rows, const double* p) {
  return Ellipsoid(Eigen::Vector3d(radii[0], radii[1], radii[2]),
                   Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(R_rows), Eigen::Vector3d(p[0], p[1], p[2]));
}

/// Separated pairs of session 38's audit (thin ellipsoids, aspect ratios up to 1e4) where the ascent
/// used to stop at its iteration cap 2.1% and 2.6e-4 short of the distance: its step along the flat
/// direction of a concave Hessian (eigenvalues -1.07e5 and -1.52) was floored to 1/70 of Newton's.
/// The certificate is weak duality, independent of the ascent: phi(n) <= distance <= |y_b - y_a|
/// for any unit n and the support points y_a of a along n and y_b of b along -n, so the gap
/// between the two bounds at the returned normal bounds the error.
TEST(SignedDistance, ThinSeparatedPairsOfTheAuditConvergeToTheDistance) {
  struct Case {
    double ra[3], Ra[9], pa[3], rb[3], Rb[9], pb[3];
  };
  const Case cases[] = {
      {{0.0067798096014706115, 2.3815755572624552e-05, 0.0026265203805485209},
       {0.69388808881683828, 0.014325895909327341, -0.71994033704502958, -0.2987235226337126, -0.90398468572578583,
        -0.30590185517345087, -0.65519735746065211, 0.4273247672200246, -0.62298472380703784},
       {6.793915357221664, -1.9406658490652036, -4.9089663966466439},
       {0.25775670362936653, 182.2501482781808, 0.70569202427681865},
       {-0.23993321204338014, -0.60022788105189717, 0.7629931484400736, -0.95158056989838091, -0.010162286418532229,
        -0.30723142242716739, 0.19216262058584466, -0.79976447704477194, -0.56872691909815876},
       {7.0113877802897155, -2.7092930244979216, -5.9488396289888996}},
      {{0.0087986878636098879, 1.8924533014677516, 0.0022027930235179751},
       {-0.83161627292910079, 0.23355444152176613, 0.5038518606147715, 0.47615430633629091, -0.1670712216341681,
        0.8633448230336892, 0.2858171638598998, 0.95788283717118683, 0.027731193554562328},
       {0.69660640776559268, 1.1406101910011706, 1.0531916482052588},
       {0.057651128872307097, 0.19429391685278621, 0.0022138699862808515},
       {-0.59788241737853065, 0.78074481582247035, 0.18158785079388395, 0.14131774898839833, 0.32565335213249691,
        -0.93486854052627111, -0.7890284588089691, -0.53327987662315257, -0.30503551330679235},
       {0.8509437369314421, 1.2293877566864049, 0.84553316678432711}},
  };
  for (const Case& c : cases) {
    const Ellipsoid a = ellipsoidFromRows(c.ra, c.Ra, c.pa), b = ellipsoidFromRows(c.rb, c.Rb, c.pb);
    for (const bool swap : {false, true}) {
      const Ellipsoid& x = swap ? b : a;
      const Ellipsoid& y = swap ? a : b;
      const SignedDistanceResult d = signedDistance(x, y);
      ASSERT_EQ(d.status, Separation::Separated);
      EXPECT_TRUE(d.converged);
      const Eigen::Vector3d n = d.normal.normalized();
      const double lower = n.dot(y.center() - x.center()) - x.support(n) + x.center().dot(n) - y.support(-n) -
                           y.center().dot(n);
      const double upper = (y.supportPoint(-n) - x.supportPoint(n)).norm();
      const double scale = (y.center() - x.center()).norm() + x.maxRadius() + y.maxRadius();
      EXPECT_LE(upper - lower, 1e-12 * scale) << "duality gap at the returned normal, swap " << swap;
      EXPECT_NEAR(d.distance, lower, 1e-12 * scale);
    }
  }
}

/// A thin ellipsoid (0.5, 5e-4, 6.5e-4) turning by slerp past a sphere it grazes at 5e-9 (the OMPL
/// audit's slow motion, docs/reliability.md finding 33): near tangency phi no longer resolves the
/// gradient, and the ascent ran to its 100-iteration cap on most instants (~25 us each, 97,717 of
/// them per motion check). It must stop at the rounding floor instead, with the duality gap at the
/// returned normal within 1e-10 of the scale (the needle's support point moves ~500 times the
/// normal's error: the 100 iterations reached 1.6e-11 of the scale, 3 stall steps 2e-9).
TEST(SignedDistance, NearTangentThinPairsStopAtTheRoundingFloorNotTheIterationCap) {
  const Eigen::Quaterniond q0(0.39351122477608025, -0.66634236362779009, 0.50942091001436041, -0.37633377054192224);
  const Eigen::Quaterniond q1(0.23200498318672691, 0.59643159657204425, -0.68440564155125072, 0.349330726103316);
  const Eigen::Vector3d p(0.38969137442655716, -0.87153992663187374, -1.2390397949217991);
  Eigen::Isometry3d Xs = Eigen::Isometry3d::Identity();
  Xs.translation() = Eigen::Vector3d(0.27591577925155027, -0.98745790205916347, -1.2439859152365624);
  const Ellipsoid sphere(Eigen::Vector3d::Constant(0.11530835475480349), Xs);
  int capped = 0, total_iterations = 0, frames = 0;
  double closest = 1.0;
  for (double t = 0.50; t < 0.53; t += 3e-4, ++frames) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.linear() = q0.normalized().slerp(t, q1.normalized()).toRotationMatrix();
    X.translation() = p;
    const Ellipsoid needle(Eigen::Vector3d(0.5, 5e-4, 6.5e-4), X);
    const SignedDistanceResult d = signedDistance(needle, sphere);
    ASSERT_EQ(d.status, Separation::Separated) << t;
    closest = std::min(closest, d.distance);
    capped += d.iterations >= tolerance::kMaxDistanceNewtonIterations;
    total_iterations += d.iterations;
    const Eigen::Vector3d n = d.normal.normalized();
    const double lower = n.dot(sphere.center() - needle.center()) - needle.support(n) + needle.center().dot(n) -
                         sphere.support(-n) - sphere.center().dot(n);
    const double upper = (sphere.supportPoint(-n) - needle.supportPoint(n)).norm();
    const double scale = (sphere.center() - needle.center()).norm() + needle.maxRadius() + sphere.maxRadius();
    EXPECT_LE(upper - lower, 1e-10 * scale) << "duality gap at t = " << t;
    EXPECT_NEAR(d.distance, lower, 1e-12 * scale) << t;
  }
  EXPECT_LT(closest, 1e-6);  // the frames pass near tangency
  EXPECT_EQ(capped, 0);      // the code before this test capped 25 of the 101 frames
  EXPECT_LT(total_iterations, 15 * frames);
}

/// Overlapping pairs of the same audit where the ascent stopped in a local optimum of the support
/// gap, 0.46-12% too deep, and the two argument orders disagreed (aspect ratios 4.9 and 19 in the
/// first). The audit's certified global search found a cheaper direction n_ref for each: the depth
/// is at most the support gap h_a(n_ref) + h_b(-n_ref) - n_ref.(p_b - p_a). The returned depth must
/// not exceed that, must be the support gap at its own normal, and moving b by it along the normal
/// must take the pair (classified exactly) from overlapping to separated.
TEST(SignedDistance, PenetrationDepthOfTheAuditsPairsIsTheGlobalOptimum) {
  struct Case {
    double a[15], b[15], n_ref[3];  // radii, R (row-major), centre; a direction the audit certified
  };
  const Case cases[] = {
      {{20.684078939010313, 4.2064910336881685, 5.863261463153651, -0.9851390438313534, 0.16757880659469626,
        -0.037661756455908066, 0.16686913649025925, 0.8818552791152858, -0.44100562126065546, -0.04069097696101652,
        -0.4407364408314779, -0.896713797215789, 3.6688490107385743, 3.4236877820608433, -0.26149684485585534},
       {6.181706988411291, 0.31835259426609464, 5.881065581657784, 0.0017586260919051355, 0.42516481991355676,
        0.9051142376198387, -0.9959769437876673, 0.08183649237956547, -0.03650638243358684, -0.08959260392268353,
        -0.9014087110866426, 0.4235982777343068, -6.9639961852756365, 1.7146493628383401, -2.353104825882505},
       {-0.052025405471922581, -0.055418464453904817, -0.99710689045009282}},
      {{0.001811524966531302, 1.3192719984396e-05, 0.006508267520253443, -0.3513870400799488, 0.5331145055122325,
        -0.7696207326185418, -0.8318948684248314, 0.19933283696512916, 0.5178970438184274, 0.429509110441543,
        0.8222258473922366, 0.37345224584655157, -0.0, -0.0, -0.0},
       {2.7974366985621613e-05, 0.00015543531699873468, 0.002071712425398915, -0.6374987170210575, -0.09154109270175481,
        0.764993865428654, 0.41036772264133836, -0.880695179716793, 0.2365889529072865, 0.652068798525636,
        0.46475394433030187, 0.5990075568962048, -0.0023440071729624694, 0.001494770692297146, 0.0011666330599205495},
       {-0.31710244939580118, -0.65315220817404984, 0.68763233602307128}},
      {{6.416677145128656, 0.948638360877737, 601.3908599513773, -0.3815868513312759, 0.581478379384648,
        -0.7185223512176127, 0.06314098109072852, -0.7591280678546395, -0.6478717412437298, -0.9221738943377129,
        -0.292587543999203, 0.25295817381245334, -173.3563318256896, -131.8514401501418, -244.53126898055874},
       {3191.450240897717, 392.7099080374514, 46.30619022480186, -0.9891363956999935, -0.12962400489917594,
        -0.06933114780187304, -0.14695624026088452, 0.8603569731268658, 0.4880468647992351, -0.0036130527275326507,
        0.49293356159413215, -0.8700594518216056, -175.78699909553652, -133.37991256559513, -243.17073529771287},
       {-0.053821154528594664, 0.40516573899353725, 0.91265766159663064}},
      {{0.0006991230459151231, 0.003857959342187766, 0.02175412177448404, 0.7925871925256291, 0.41777102816398376,
        -0.44415415147350495, -0.5035036856677938, 0.03754937378033785, -0.8631767391720261, -0.3439325235613648,
        0.9077760806253447, 0.2401104051914429, -0.044348651380974095, -0.11152765427484775, -0.09687964877104814},
       {6.259070440138214e-05, 9.890985110211787e-05, 0.008395469183536359, 0.6411589406119873, -0.7606322055604572,
        0.1017539224676296, -0.36443359491498917, -0.18510180435402113, 0.9126475096784208, -0.6753542535370985,
        -0.622234658219164, -0.3958796058655061, -0.044348651380974095, -0.11152765427484775, -0.09687964877104814},
       {-0.45563140429191146, 0.4129007553189884, 0.7886146014879446}},
  };
  auto make = [](const double* v) { return ellipsoidFromRows(v, v + 3, v + 12); };
  for (const Case& c : cases) {
    const Ellipsoid a = make(c.a), b = make(c.b);
    const double scale = (b.center() - a.center()).norm() + a.maxRadius() + b.maxRadius();
    double depths[2];
    for (const bool swap : {false, true}) {
      const Ellipsoid& x = swap ? b : a;
      const Ellipsoid& y = swap ? a : b;
      // The support gap of (x, y) along n: h_x(n) + h_y(-n) - n.(p_y - p_x), centred supports.
      auto gap = [&](const Eigen::Vector3d& n) {
        return (x.support(n) - x.center().dot(n)) + (y.support(-n) + y.center().dot(n)) - n.dot(y.center() - x.center());
      };
      const Eigen::Vector3d n_ref = (swap ? -1.0 : 1.0) * Eigen::Vector3d(c.n_ref[0], c.n_ref[1], c.n_ref[2]).normalized();
      const SignedDistanceResult d = signedDistance(x, y);
      ASSERT_EQ(d.status, Separation::Overlapping);
      const double depth = -d.distance;
      depths[swap] = depth;
      EXPECT_LE(depth, gap(n_ref) + 1e-12 * scale) << "a local optimum, swap " << swap;
      EXPECT_NEAR(gap(d.normal.normalized()), depth, 1e-12 * scale);
      const Ellipsoid out(y.radii(), y.rotation(), y.center() + depth * (1.0 + 1e-6) * d.normal);
      const Ellipsoid in(y.radii(), y.rotation(), y.center() + depth * (1.0 - 1e-6) * d.normal);
      EXPECT_EQ(test::exactClassify(x, out), Separation::Separated);
      EXPECT_EQ(test::exactClassify(x, in), Separation::Overlapping);
    }
    EXPECT_NEAR(depths[0], depths[1], 1e-12 * scale);
  }
}

/// -distance = min over unit n of h_a(n) + h_b(-n) (support function of the Minkowski difference).
/// Dense sampling of 20,000 directions gives an upper bound of the true minimum: the library's
/// value must not exceed it (else it stopped in a worse local optimum), and must be attained at its
/// own normal. `aspect` = largest axis ratio of the random ellipsoids.
void checkPenetrationDepth(int wanted, std::uint64_t seed, double aspect) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uc(-2.0, 2.0);
  const std::vector<Eigen::Vector3d> dirs = test::fibonacciSphere(20000);
  int overlapping = 0, worse = 0;
  for (int i = 0; i < 50 * wanted && overlapping < wanted; ++i) {
    auto make = [&] {
      return aspect <= 6.0 ? test::anchorEllipsoid(rng)
                           : Ellipsoid(test::randomRadii(rng, 2.0, aspect), test::randomRotation(rng),
                                       Eigen::Vector3d(uc(rng), uc(rng), uc(rng)));
    };
    const Ellipsoid a = make(), b = make();
    const SignedDistanceResult d = signedDistance(a, b);
    if (d.status != Separation::Overlapping) continue;
    ++overlapping;
    auto hK = [&](const Eigen::Vector3d& n) { return a.support(n) + b.support(-n); };
    double sampled = std::numeric_limits<double>::infinity();
    for (const auto& n : dirs) sampled = std::min(sampled, hK(n));
    ASSERT_LT(d.distance, 0.0);
    if (-d.distance > sampled + 1e-12) {
      ++worse;
      ADD_FAILURE() << "case " << i << ": depth " << -d.distance << " but direction sampling finds " << sampled;
    }
    ASSERT_NEAR(hK(d.normal), -d.distance, 1e-12 * (1 - d.distance));
    // Translating b by -distance * normal makes the pair touch.
    const Ellipsoid moved(b.radii(), b.rotation(), b.center() - d.distance * d.normal);
    EXPECT_LT(std::fabs(classifyEllipsoids(a, moved).psi), 1e-8);
  }
  EXPECT_EQ(overlapping, wanted);
  EXPECT_EQ(worse, 0);
}

TEST(SignedDistance, PenetrationDepthIsAtLeastAsGoodAsDenseSampling) { checkPenetrationDepth(2000, 67, 6.0); }
TEST(SignedDistance, PenetrationDepthOfElongatedPairsIsAtLeastAsGoodAsDenseSampling) {
  checkPenetrationDepth(500, 68, 20.0);
}
TEST(SignedDistance, LongPenetrationDepthSweep) {
  checkPenetrationDepth(20000, 69, 6.0);
  checkPenetrationDepth(5000, 70, 20.0);
}

TEST(SignedDistance, SignAgreesWithTheExactClassificationAndIsSymmetric) {
  std::mt19937_64 rng(69);
  for (int i = 0; i < 5000; ++i) {
    const Ellipsoid a = test::anchorEllipsoid(rng), b = test::anchorEllipsoid(rng);
    const SignedDistanceResult ab = signedDistance(a, b), ba = signedDistance(b, a);
    const Separation truth = test::exactClassify(a, b);
    ASSERT_EQ(ab.status, truth);
    ASSERT_EQ(ab.distance > 0, truth == Separation::Separated);
    ASSERT_NEAR(ab.distance, ba.distance, 1e-10 * (1 + std::fabs(ab.distance)));
    ASSERT_NEAR(ab.normal.dot(ba.normal), -1.0, 1e-6);
  }
}

TEST(SignedDistance, IsInvariantUnderRigidMotion) {
  std::mt19937_64 rng(71);
  std::uniform_real_distribution<double> u(-100.0, 100.0);
  for (int i = 0; i < 2000; ++i) {
    const Ellipsoid a = test::anchorEllipsoid(rng), b = test::anchorEllipsoid(rng);
    const Eigen::Matrix3d R = test::randomRotation(rng);
    const Eigen::Vector3d t(u(rng), u(rng), u(rng));
    auto move = [&](const Ellipsoid& e) { return Ellipsoid(e.radii(), R * e.rotation(), R * e.center() + t); };
    const SignedDistanceResult d1 = signedDistance(a, b), d2 = signedDistance(move(a), move(b));
    ASSERT_NEAR(d1.distance, d2.distance, 1e-9 * (1 + std::fabs(d1.distance))) << i;
  }
}

TEST(SignedDistance, NearTangentDistanceIsTinyWithTheRightSign) {
  std::mt19937_64 rng(73);
  for (int k = 0; k < 200; ++k) {
    const Ellipsoid a(test::randomRadii(rng, 1.0, 10.0), test::randomRotation(rng), Eigen::Vector3d::Zero());
    const Eigen::Vector3d rb = test::randomRadii(rng, 1.0, 10.0);
    const Eigen::Matrix3d Rb = test::randomRotation(rng);
    const Eigen::Vector3d dir = test::randomUnitVector(rng);
    double lo = 0, hi = 40;
    for (int it = 0; it < 100; ++it) {
      const double mid = 0.5 * (lo + hi);
      (test::exactClassify(a, Ellipsoid(rb, Rb, mid * dir)) == Separation::Separated ? hi : lo) = mid;
    }
    for (double gap : {1e-6, 1e-9}) {
      const SignedDistanceResult out = signedDistance(a, Ellipsoid(rb, Rb, hi * (1 + gap) * dir));
      const SignedDistanceResult in = signedDistance(a, Ellipsoid(rb, Rb, lo * (1 - gap) * dir));
      ASSERT_GT(out.distance, 0.0);
      ASSERT_LT(in.distance, 0.0);
      // The distance along dir is at most the offset moved.
      ASSERT_LE(out.distance, hi * gap * 1.0000001 + 1e-15);
      ASSERT_LE(-in.distance, lo * gap * 1.0000001 + 1e-15);
    }
  }
}

}  // namespace
}  // namespace fcl_quadric
