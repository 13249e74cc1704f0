// Continuous collision of composite quadric models (region_ccd.h) against independent oracles:
// analytic first-contact times (a ball against the side, cap and rim of a capped cylinder; a box
// face against a cylinder cap), the closed-form distance from a point to a capped cylinder along
// random rational motions (ball vs capped cylinder: never miss, first contact within 1e-7), the
// static engine sampled densely in time for cylinder pairs and CSG pairs, and bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "fcl_quadric/algebra/quadric_matrix.h"
#include "fcl_quadric/continuous/region_ccd.h"

namespace fcl_quadric {
namespace region_ccd_test {
namespace {

using Op = QuadricRegion::Op;

QuadricRegion cappedCylinder(double a, double b, double L) {
  return QuadricRegion::combine(Op::Intersection, {QuadricRegion::atom(quadric::ellipticCylinder(a, b)),
                                                   QuadricRegion::halfspace({0, 0, 1}, 0.5 * L),
                                                   QuadricRegion::halfspace({0, 0, -1}, 0.5 * L)});
}
Box3 centredBox(const Eigen::Vector3d& h) { return Box3{-h, h}; }
QuadricRegion ball(double r) { return QuadricRegion::atom(quadric::ellipsoid(Eigen::Vector3d::Constant(r))); }

PiecewiseMotion still() { return PiecewiseMotion(MotionMatrix()); }
PiecewiseMotion translation(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1) {
  return PiecewiseMotion(MotionMatrix::fromPoses(Eigen::Matrix3d::Identity(), p0, Eigen::Matrix3d::Identity(), p1));
}

// Exact distance from p (cylinder frame) to the capped circular cylinder of radius R, half-length
// h; negative inside (minus the distance to the boundary).
double cylinderDistance(const Eigen::Vector3d& p, double R, double h) {
  const double dr = std::hypot(p[0], p[1]) - R, dz = std::fabs(p[2]) - h;
  if (dr <= 0.0 && dz <= 0.0) return std::max(dr, dz);
  return std::hypot(std::max(dr, 0.0), std::max(dz, 0.0));
}

TEST(RegionCcd, BallAgainstTheSideCapAndRimOfACylinderAtTheAnalyticTime) {
  const double R = 1.0, h = 1.0, r = 0.5;
  const MovingRegion cyl{cappedCylinder(R, R, 2 * h), centredBox({R, R, h}), still()};
  struct Case {
    Eigen::Vector3d p0, p1;
    double expected;
  };
  // Side: centre x from 5 to -5 at z = 0.3: contact at x = R + r. Cap: z from 4 to -4 on the
  // axis: contact at z = h + r. Rim: x = 1.2 from z = 4 down: contact when |(0.2, z - h)| = r.
  const Case cases[] = {
      {{5, 0, 0.3}, {-5, 0, 0.3}, (5.0 - (R + r)) / 10.0},
      {{0.1, 0.2, 4}, {0.1, 0.2, -4}, (4.0 - (h + r)) / 8.0},
      {{1.2, 0, 4}, {1.2, 0, -4}, (4.0 - (h + std::sqrt(r * r - 0.2 * 0.2))) / 8.0},
  };
  for (const Case& c : cases) {
    const MovingRegion b{ball(r), centredBox(Eigen::Vector3d::Constant(r)), translation(c.p0, c.p1)};
    for (bool swap : {false, true}) {
      const RegionCcdResult res = swap ? continuousCollideRegions(b, cyl) : continuousCollideRegions(cyl, b);
      ASSERT_TRUE(res.collide);
      EXPECT_LE(res.time, c.expected + 1e-12);
      EXPECT_NEAR(res.time, c.expected, 1e-7) << "boxes " << res.boxes;
      // The contact point lies on both surfaces.
      const Eigen::Vector3d centre = c.p0 + res.time * (c.p1 - c.p0);
      EXPECT_NEAR((res.point - centre).norm(), r, 1e-6);
      EXPECT_NEAR(cylinderDistance(res.point, R, h), 0.0, 1e-6);
    }
  }
}

TEST(RegionCcd, NearMissesAreCertifiedFree) {
  const double R = 1.0, h = 1.0, r = 0.5;
  const MovingRegion cyl{cappedCylinder(R, R, 2 * h), centredBox({R, R, h}), still()};
  for (double gap : {1e-2, 1e-4, 1e-6}) {
    const MovingRegion b{ball(r), centredBox(Eigen::Vector3d::Constant(r)),
                         translation({5, 0, h + r + gap}, {-5, 0, h + r + gap})};
    const RegionCcdResult res = continuousCollideRegions(cyl, b);
    EXPECT_FALSE(res.collide) << "gap " << gap << " time " << res.time << " boxes " << res.boxes;
  }
}

// The query's work limits (RegionCcdLimits) hold for each piece of the motion, so that a
// keyframed motion is answered as its pieces would be one by one. A ball sweeps back and forth
// past the rim of a capped cylinder at a gap of 1e-6 (four keyframed pieces, thousands of boxes
// each: a slow-closing gap); the oracle is the closed-form distance of its centre to the cylinder,
// positive along the sweep, so the pair never touches. Limits above what one piece uses change
// nothing, even when the query as a whole uses more; lower ones stop the first piece with a
// conservative (capped) contact, within one box of the limit; limits below 1 are refused, naming
// the value.
TEST(RegionCcd, WorkLimitsHoldPerPieceCapConservativelyAndBadLimitsThrow) {
  const double R = 1.0, h = 1.0, r = 0.5, gap = 1e-6;
  const MovingRegion cyl{cappedCylinder(R, R, 2 * h), centredBox({R, R, h}), still()};
  const double o = (r + gap) / std::sqrt(2.0);  // the centre passes the rim's point (R, 0, h) at r + gap
  std::vector<double> times;
  std::vector<Eigen::Isometry3d> poses;
  for (int k = 0; k <= 4; ++k) {
    times.push_back(k / 4.0);
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.translation() = Eigen::Vector3d(R + o, k % 2 == 0 ? 2.0 : -2.0, h + o);
    poses.push_back(X);
  }
  double min_gap = 1.0;
  for (int i = 0; i <= 2000; ++i) {  // one sweep, y from 2 to -2 (the others retrace it)
    const Eigen::Vector3d centre(R + o, 2.0 - 4.0 * i / 2000.0, h + o);
    min_gap = std::min(min_gap, cylinderDistance(centre, R, h) - r);
  }
  ASSERT_GT(min_gap, 0.5 * gap);
  const MovingRegion b{ball(r), centredBox(Eigen::Vector3d::Constant(r)), PiecewiseMotion::fromKeyframes(times, poses)};
  const RegionCcdResult free = continuousCollideRegions(cyl, b);
  ASSERT_FALSE(free.collide);
  ASSERT_GT(free.boxes, 1000);
  ASSERT_GT(free.pencil_evaluations, 10000);
  RecordProperty("boxes", free.boxes);

  // Half the query's total is about twice one piece's share: every piece still fits.
  RegionCcdLimits per_piece;
  per_piece.max_boxes = free.boxes / 2;
  per_piece.max_pencil_evaluations = free.pencil_evaluations / 2;
  const RegionCcdResult same = continuousCollideRegions(cyl, b, per_piece);
  EXPECT_FALSE(same.collide);
  EXPECT_EQ(same.boxes, free.boxes);
  EXPECT_EQ(same.pencil_evaluations, free.pencil_evaluations);

  RegionCcdLimits few_boxes;
  few_boxes.max_boxes = free.boxes / 16;
  const RegionCcdResult by_boxes = continuousCollideRegions(cyl, b, few_boxes);
  EXPECT_TRUE(by_boxes.collide && by_boxes.capped);
  EXPECT_LT(by_boxes.time, 0.25);  // in the first piece
  EXPECT_EQ(by_boxes.boxes, few_boxes.max_boxes);

  RegionCcdLimits few_evaluations;
  few_evaluations.max_pencil_evaluations = free.pencil_evaluations / 16;
  const RegionCcdResult by_evaluations = continuousCollideRegions(cyl, b, few_evaluations);
  EXPECT_TRUE(by_evaluations.collide && by_evaluations.capped);
  EXPECT_LT(by_evaluations.time, 0.25);
  EXPECT_GE(by_evaluations.pencil_evaluations, few_evaluations.max_pencil_evaluations);
  // Checked before each box: one box's pencil search beyond the limit at most (a ball against a
  // capped cylinder has four atoms, so at most a few hundred evaluations per box).
  EXPECT_LE(by_evaluations.pencil_evaluations, few_evaluations.max_pencil_evaluations + 1000);

  for (int bad : {0, -3}) {
    RegionCcdLimits limits;
    limits.max_boxes = bad;
    try {
      continuousCollideRegions(cyl, b, limits);
      ADD_FAILURE() << "max_boxes = " << bad << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("max_boxes = " + std::to_string(bad)), std::string::npos) << e.what();
    }
    limits = RegionCcdLimits();
    limits.max_pencil_evaluations = bad;
    EXPECT_THROW(continuousCollideRegions(cyl, b, limits), std::invalid_argument);
  }
}

TEST(RegionCcd, ContactElementsAreLabelledAndBadInputThrows) {
  // A ball falling onto the top cap of a capped cylinder at its centre touches face "cap"; onto
  // the rim it touches the edge between the side and the cap.
  const double R = 1.0, h = 1.0, r = 0.5;
  const QuadricRegion cyl = cappedCylinder(R, R, 2 * h);
  const Box3 box = centredBox({R, R, h});
  const BoundaryElements elements = boundaryElements(cyl, box);
  const MovingRegion still_cyl{cyl, box, still()};
  const MovingRegion on_cap{ball(r), centredBox(Eigen::Vector3d::Constant(r)), translation({0.2, 0, 4}, {0.2, 0, -4})};
  RegionCcdResult res = continuousCollideRegions(still_cyl, on_cap);
  ASSERT_TRUE(res.collide);
  ASSERT_EQ(res.active_a.size(), 1u);
  EXPECT_EQ(res.active_a[0], 1) << "the atom z <= h";
  EXPECT_EQ(boundaryElementLabel(elements, res.active_a), "F1");
  EXPECT_EQ(boundaryElementLabel(boundaryElements(ball(r), centredBox(Eigen::Vector3d::Constant(r))), res.active_b), "F0");
  const MovingRegion on_rim{ball(r), centredBox(Eigen::Vector3d::Constant(r)), translation({1.2, 0, 4}, {1.2, 0, -4})};
  res = continuousCollideRegions(still_cyl, on_rim);
  ASSERT_TRUE(res.collide);
  const std::string rim = boundaryElementLabel(elements, res.active_a);
  ASSERT_EQ(rim.substr(0, 1), "E") << rim;
  const BoundaryEdge& edge = elements.edges[std::stoi(rim.substr(1))];
  EXPECT_EQ(std::min(edge.face0, edge.face1), 0);
  EXPECT_EQ(std::max(edge.face0, edge.face1), 1);
  EXPECT_EQ(boundaryElementLabel(elements, {}), "");

  const MovingRegion plane_a{QuadricRegion::halfspace({0, 0, 1}, 0.0), std::nullopt, still()};
  const MovingRegion plane_b{QuadricRegion::halfspace({1, 0, 0}, 0.0), std::nullopt, still()};
  EXPECT_THROW(continuousCollideRegions(plane_a, plane_b), std::invalid_argument);
  // A half-space against a bounded solid is fine: the ball falls onto the floor z <= 0.
  res = continuousCollideRegions(plane_a, on_cap);
  ASSERT_TRUE(res.collide);
  EXPECT_NEAR(res.time, (4.0 - r) / 8.0, 1e-7);
}

// Degenerate configurations with closed-form times: parallel cylinder axes (a line contact),
// coplanar caps (a surface contact), crossed axes (the two side surfaces meet at a point), and a
// ball that touches a cap exactly at t = 1 or leaves it from a touch at t = 0 (both contacts).
TEST(RegionCcd, DegenerateContactsAreFoundAtTheirClosedFormTimes) {
  const MovingRegion c1{cappedCylinder(0.5, 0.5, 2.0), centredBox({0.5, 0.5, 1.0}), still()};
  const MovingRegion c2{cappedCylinder(0.5, 0.5, 1.0), centredBox({0.5, 0.5, 0.5}), still()};
  const Eigen::Matrix3d Ry = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Box3 ball_box = centredBox(Eigen::Vector3d::Constant(0.3));
  struct Case {
    const char* name;
    MovingRegion a, b;
    double expected;
  };
  const Case cases[] = {
      {"parallel axes", c1, {cappedCylinder(0.5, 0.5, 2.0), centredBox({0.5, 0.5, 1.0}), translation({3, 0, 0.3}, {-1, 0, 0.3})}, 0.5},
      {"coplanar caps", c2, {cappedCylinder(0.5, 0.5, 1.0), centredBox({0.5, 0.5, 0.5}), translation({0.2, 0, 3}, {0.2, 0, -1})}, 0.5},
      {"crossed axes", c1,
       {cappedCylinder(0.5, 0.5, 2.0), centredBox({0.5, 0.5, 1.0}),
        PiecewiseMotion(MotionMatrix::fromPoses(Ry, {0, 0, 4}, Ry, {0, 0, 0}))},
       (4.0 - 1.5) / 4.0},
      {"touch at t = 1", c2, {ball(0.3), ball_box, translation({0, 0, 3}, {0, 0, 0.8})}, 1.0},
      {"touch at t = 0", c2, {ball(0.3), ball_box, translation({0, 0, 0.8}, {0, 0, 3})}, 0.0},
  };
  for (const Case& c : cases) {
    const RegionCcdResult res = continuousCollideRegions(c.a, c.b);
    ASSERT_TRUE(res.collide) << c.name;
    EXPECT_LE(res.time, c.expected + 1e-12) << c.name;
    EXPECT_NEAR(res.time, c.expected, 1e-7) << c.name << " boxes " << res.boxes;
  }
}

// The first t in [0, 1] with gap(t) <= 0: gap sampled at n + 1 instants, the first sign change
// bisected 60 times; none if every sample is positive.
constexpr int kOracleSamples = 4000;
template <class Gap>
std::optional<double> firstContact(const Gap& gap) {
  if (gap(0.0) <= 0.0) return 0.0;
  for (int i = 1; i <= kOracleSamples; ++i) {
    double hi = static_cast<double>(i) / kOracleSamples;
    if (gap(hi) > 0.0) continue;
    double lo = static_cast<double>(i - 1) / kOracleSamples;
    for (int k = 0; k < 60; ++k) {
      const double mid = 0.5 * (lo + hi);
      (gap(mid) <= 0.0 ? hi : lo) = mid;
    }
    return hi;
  }
  return std::nullopt;
}

Eigen::Matrix3d randomRotation(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
}

// Random rational motions (from two random poses) of a ball and a capped cylinder against the
// closed-form point-to-cylinder distance sampled at 4,001 instants and refined by bisection:
// never a missed contact, every reported contact real (distance <= 1e-6 at the reported time) and
// no contact in the oracle more than 1e-7 before it.
TEST(RegionCcd, BallAndCylinderUnderRandomRationalMotionsMatchTheDistanceOracle) {
  std::mt19937 rng(20261122);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  int collisions = 0, tangent = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const double R = 0.3 + 0.7 * U(rng), h = 0.3 + 0.7 * U(rng), r = 0.2 + 0.4 * U(rng);
    auto point = [&](double s) { return Eigen::Vector3d(s * (2 * U(rng) - 1), s * (2 * U(rng) - 1), s * (2 * U(rng) - 1)); };
    const MotionMatrix mc = MotionMatrix::fromPoses(randomRotation(rng), point(1.0), randomRotation(rng), point(1.0));
    const MotionMatrix mb = MotionMatrix::fromPoses(randomRotation(rng), point(2.2), randomRotation(rng), point(2.2));
    const MovingRegion cyl{cappedCylinder(R, R, 2 * h), centredBox({R, R, h}), PiecewiseMotion(mc)};
    const MovingRegion b{ball(r), centredBox(Eigen::Vector3d::Constant(r)), PiecewiseMotion(mb)};
    auto gap = [&](double t) {
      const Eigen::Matrix4d Xc = mc.evaluate(t), Xb = mb.evaluate(t);
      const Eigen::Vector3d centre = Xb.block<3, 1>(0, 3);
      const Eigen::Vector3d local = Xc.topLeftCorner<3, 3>().transpose() * (centre - Xc.block<3, 1>(0, 3));
      return cylinderDistance(local, R, h) - r;
    };
    const std::optional<double> oracle = firstContact(gap);
    const RegionCcdResult res = continuousCollideRegions(trial % 2 ? cyl : b, trial % 2 ? b : cyl);
    if (oracle) {
      ASSERT_TRUE(res.collide) << "trial " << trial << ": missed the contact at " << *oracle;
      EXPECT_LE(res.time, *oracle + 1e-9) << "trial " << trial;
    }
    if (res.collide) {
      ++collisions;
      tangent += res.near_tangent;
      EXPECT_LE(gap(res.time), 1e-6) << "trial " << trial << " time " << res.time;
      // No sampled contact more than 1e-7 before the reported time.
      for (int i = 0; i <= kOracleSamples; ++i) {
        const double t = res.time - 1e-7 - (res.time - 1e-7) * i / kOracleSamples;
        if (t < 0.0) break;
        ASSERT_GT(gap(t), 0.0) << "trial " << trial << ": contact at " << t << " before the reported " << res.time;
      }
    }
  }
  EXPECT_GT(collisions, 15);
  EXPECT_LT(collisions, 55);
  RecordProperty("collisions", collisions);
  RecordProperty("near_tangent", tangent);
}

// The same pairs 1000 sizes from the world origin: the engine shifts both motions next to the
// origin (kRegionCcdShiftRelative), so it decides them as near the origin: never capped, every
// contact of the oracle found no later than it and no earlier than 1e-7 before. Unshifted, half of
// an audit's pairs at that distance reached the box cap (docs/reliability.md finding 48).
TEST(RegionCcd, FarFromTheOriginTheEngineMatchesTheDistanceOracleWithoutReachingItsCap) {
  std::mt19937 rng(48);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  const Eigen::Vector3d far(600.0, -480.0, 640.0);
  int collisions = 0;
  for (int trial = 0; trial < 16; ++trial) {
    const double R = 0.3 + 0.7 * U(rng), h = 0.3 + 0.7 * U(rng), r = 0.2 + 0.4 * U(rng);
    auto point = [&](double s) { return Eigen::Vector3d(s * (2 * U(rng) - 1), s * (2 * U(rng) - 1), s * (2 * U(rng) - 1)); };
    const Eigen::Matrix3d Rc0 = randomRotation(rng), Rc1 = randomRotation(rng);
    const Eigen::Vector3d c0 = point(1.0), c1 = point(1.0);
    const Eigen::Matrix3d Rb0 = randomRotation(rng), Rb1 = randomRotation(rng);
    const Eigen::Vector3d b0 = point(2.2), b1 = point(2.2);
    // The oracle on the motions near the origin; the engine on the far ones (the same relative motion).
    const MotionMatrix mc = MotionMatrix::fromPoses(Rc0, c0, Rc1, c1), mb = MotionMatrix::fromPoses(Rb0, b0, Rb1, b1);
    const MovingRegion cyl{cappedCylinder(R, R, 2 * h), centredBox({R, R, h}),
                           PiecewiseMotion(MotionMatrix::fromPoses(Rc0, c0 + far, Rc1, c1 + far))};
    const MovingRegion b{ball(r), centredBox(Eigen::Vector3d::Constant(r)),
                         PiecewiseMotion(MotionMatrix::fromPoses(Rb0, b0 + far, Rb1, b1 + far))};
    auto gap = [&](double t) {
      const Eigen::Matrix4d Xc = mc.evaluate(t), Xb = mb.evaluate(t);
      const Eigen::Vector3d local = Xc.topLeftCorner<3, 3>().transpose() * (Xb.block<3, 1>(0, 3) - Xc.block<3, 1>(0, 3));
      return cylinderDistance(local, R, h) - r;
    };
    const std::optional<double> oracle = firstContact(gap);
    const RegionCcdResult res = continuousCollideRegions(trial % 2 ? cyl : b, trial % 2 ? b : cyl);
    EXPECT_FALSE(res.capped) << "trial " << trial;
    if (oracle) {
      ++collisions;
      ASSERT_TRUE(res.collide) << "trial " << trial << ": missed the contact at " << *oracle;
      EXPECT_LE(res.time, *oracle + 1e-9) << "trial " << trial;
      EXPECT_GE(res.time, *oracle - 1e-7) << "trial " << trial;
      // The contact point, shifted back, is at the ball's surface near the cylinder.
      const Eigen::Vector3d centre = mb.evaluate(res.time).block<3, 1>(0, 3) + far;
      EXPECT_NEAR((res.point - centre).norm(), r, 1e-6) << "trial " << trial;
    } else {
      EXPECT_TRUE(!res.collide || res.near_tangent) << "trial " << trial << " time " << res.time;
    }
  }
  EXPECT_GE(collisions, 4);
  EXPECT_LE(collisions, 12);
}

// Two balls that both turn (random rotations at both ends: the relative motion has degree 5, the
// moving atoms degree 10) against the closed-form first contact of their centres, which move on
// segments. In the power basis the moving atoms' coefficient magnitudes were 10^3-10^4 times their
// values, and so were the sign pads: on 100 such pairs half the contacts came back near-tangent,
// two capped and up to 4e-8 early (docs/reliability.md finding 49). In the Bernstein basis: never
// capped, and every clear contact (the balls overlap by 1% of their size at the closest approach)
// within kRegionCcdTimeTolerance before the closed form and never after it.
TEST(RegionCcd, TwoTurningBallsMeetAtTheClosedFormTimeWithinTheTimeTolerance) {
  std::mt19937 rng(49);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  int contacts = 0, misses = 0, tangent = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const double ra = 0.6 + 0.4 * U(rng), rb = 0.6 + 0.4 * U(rng);
    const Eigen::Vector3d pa0(U(rng), U(rng), U(rng)), pa1(U(rng), U(rng), U(rng));
    const Eigen::Vector3d pb0 = pa0 + 3.0 * Eigen::Vector3d(U(rng), U(rng), U(rng)).normalized();
    const Eigen::Vector3d pb1 = pa1 + 1.2 * (ra + rb) * Eigen::Vector3d(U(rng), U(rng), U(rng));
    const MovingRegion a{ball(ra), centredBox(Eigen::Vector3d::Constant(ra)),
                         PiecewiseMotion(MotionMatrix::fromPoses(randomRotation(rng), pa0, randomRotation(rng), pa1))};
    const MovingRegion b{ball(rb), centredBox(Eigen::Vector3d::Constant(rb)),
                         PiecewiseMotion(MotionMatrix::fromPoses(randomRotation(rng), pb0, randomRotation(rng), pb1))};
    // |D(t)|^2 = (ra + rb)^2 with D(t) = D0 + t (D1 - D0): its first root in [0, 1], and the
    // closest approach of the centres on [0, 1].
    const Eigen::Vector3d D0 = pb0 - pa0, dD = (pb1 - pa1) - D0;
    const double sum = ra + rb, qa = dD.squaredNorm(), qb = D0.dot(dD), qc = D0.squaredNorm() - sum * sum;
    ASSERT_GT(qc, 0.0) << "trial " << trial << ": the balls start apart";
    const double t_closest = std::clamp(-qb / qa, 0.0, 1.0);
    const double closest = (D0 + t_closest * dD).norm() - sum;
    const RegionCcdResult res = continuousCollideRegions(trial % 2 ? a : b, trial % 2 ? b : a);
    EXPECT_FALSE(res.capped) << "trial " << trial;
    if (closest < -0.01 * sum) {
      ++contacts;
      const double toi = (-qb - std::sqrt(qb * qb - qa * qc)) / qa;
      ASSERT_TRUE(res.collide) << "trial " << trial << ": missed the contact at " << toi;
      EXPECT_LE(res.time, toi + 1e-12) << "trial " << trial;
      EXPECT_GE(res.time, toi - tolerance_region::kRegionCcdTimeTolerance - 1e-12) << "trial " << trial;
      tangent += res.near_tangent;
    } else if (closest > 0.01 * sum) {
      ++misses;
      EXPECT_FALSE(res.collide) << "trial " << trial << " time " << res.time;
    }
  }
  EXPECT_GE(contacts, 10);
  EXPECT_GE(misses, 5);
  RecordProperty("near_tangent", tangent);
}

}  // namespace
}  // namespace region_ccd_test
}  // namespace fcl_quadric
