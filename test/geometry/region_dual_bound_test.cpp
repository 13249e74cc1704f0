// The duality bound of a linear function over a composite quadric model (dualLinearBound,
// quadric_region.h): against closed forms on posed rings, lenses, caps of paraboloids, cylinders,
// cones and sheets, and boxes (where it is tight); against the region engine on rounded drilled
// blocks (tight to 1e-6) and on random and/or formulas of every quadric kind (where it must only
// be an upper bound); and the boxes regionAabb builds from it against the closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "fcl_quadric/algebra/quadric_matrix.h"
#include "fcl_quadric/geometry/quadric_region.h"

namespace fcl_quadric {
namespace {

using Op = QuadricRegion::Op;

Eigen::Matrix3d randomRotationForDualBound(std::mt19937_64& rng) {
  std::normal_distribution<double> n;
  Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
  q.normalize();
  return q.toRotationMatrix();
}

/// A ring: the ellipsoid of revolution (a, a, c) minus the coaxial bore of radius r < a, posed.
struct DualTestRing {
  double a, c, r;
  Eigen::Matrix3d R;
  Eigen::Vector3d p;
  QuadricRegion region() const {
    return QuadricRegion::combine(Op::Difference, {QuadricRegion::atom(quadric::ellipsoid({a, a, c})),
                                                   QuadricRegion::atom(quadric::ellipticCylinder(r, r))})
        .transformed(R, p);
  }
  /// max e.y in closed form: the ellipsoid's support point if it is outside the bore, else the
  /// best point of the rims x^2 + y^2 = r^2, z = +-c sqrt(1 - r^2 / a^2).
  double maxAlong(const Eigen::Vector3d& e) const {
    const Eigen::Vector3d el = R.transpose() * e;
    const Eigen::Vector3d A2(a * a, a * a, c * c);
    const double h = std::sqrt(el.cwiseProduct(A2).dot(el));
    const Eigen::Vector3d s = el.cwiseProduct(A2) / h;
    const double rim = r * std::hypot(el.x(), el.y()) + std::fabs(el.z()) * c * std::sqrt(1.0 - r * r / (a * a));
    const double local = s.x() * s.x() + s.y() * s.y() >= r * r ? h : rim;
    return local + e.dot(p);
  }
  Box3 outer() const {
    const Eigen::Vector3d ext = (R.cwiseAbs2() * Eigen::Vector3d(a * a, a * a, c * c)).cwiseSqrt() * 1.01;
    return Box3{p - ext, p + ext};
  }
};

/// A lens: the intersection of two balls whose spheres cross.
struct DualTestLens {
  Eigen::Vector3d c1, c2;
  double r1, r2;
  QuadricRegion region() const {
    const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
    return QuadricRegion::combine(Op::Intersection,
                                  {QuadricRegion::atom(quadric::posedEllipsoid(Eigen::Vector3d::Constant(r1), I, c1)),
                                   QuadricRegion::atom(quadric::posedEllipsoid(Eigen::Vector3d::Constant(r2), I, c2))});
  }
  /// max e.y in closed form: a ball's support point if it lies in the other ball, else the best
  /// point of the circle where the spheres cross.
  double maxAlong(const Eigen::Vector3d& e) const {
    const Eigen::Vector3d s1 = c1 + r1 * e, s2 = c2 + r2 * e;
    if ((s1 - c2).norm() <= r2) return e.dot(s1);
    if ((s2 - c1).norm() <= r1) return e.dot(s2);
    const double d = (c2 - c1).norm();
    const Eigen::Vector3d n = (c2 - c1) / d;
    const double h = (d * d + r1 * r1 - r2 * r2) / (2.0 * d);
    const double rho = std::sqrt(r1 * r1 - h * h);
    return e.dot(c1 + h * n) + rho * (e - e.dot(n) * n).norm();
  }
  Box3 outer() const {
    const Eigen::Vector3d ext = Eigen::Vector3d::Constant(1.01 * r1);
    return Box3{c1 - ext, c1 + ext};
  }
};

/// A convex cap of a quadric cut by planes across its axis z, posed:
///  - Paraboloid: x^2/a^2 + y^2/b^2 <= z <= h (the curved atom's null direction is the axis);
///  - Cylinder: the elliptic cylinder (a, b) cut at |z| <= h (likewise);
///  - Cone: the nappe x^2/a^2 + y^2/b^2 <= z^2/c^2, 0 <= z <= h (an indefinite atom);
///  - Sheet: the upper sheet x^2/a^2 + y^2/b^2 - z^2/c^2 <= -1, 0 <= z <= h, h > c (likewise).
struct DualTestCap {
  enum Kind { Paraboloid, Cylinder, Cone, Sheet } kind;
  double a, b, c, h;
  Eigen::Matrix3d R;
  Eigen::Vector3d p;
  QuadricRegion region() const {
    const Eigen::Matrix4d Q = kind == Paraboloid ? quadric::ellipticParaboloid(a, b)
                              : kind == Cylinder ? quadric::ellipticCylinder(a, b)
                              : kind == Cone     ? quadric::ellipticCone(a, b, c)
                                                 : quadric::hyperboloidTwoSheets(a, b, c);
    std::vector<QuadricRegion> parts{QuadricRegion::atom(Q), QuadricRegion::halfspace({0, 0, 1}, h)};
    if (kind != Paraboloid) parts.push_back(QuadricRegion::halfspace({0, 0, -1}, kind == Cylinder ? h : 0.0));
    return QuadricRegion::combine(Op::Intersection, parts).transformed(R, p);
  }
  /// max e.y in closed form, with k = sqrt(a^2 e_x^2 + b^2 e_y^2) in the local frame: the top
  /// rim e_z h + w k (w: the rim's scale, sqrt(h), 1, h / c or sqrt(h^2 / c^2 - 1)), or for
  /// e_z < 0 the bottom: the cylinder's rim -e_z h + k, the cone's apex 0, the paraboloid's
  /// stationary point -k^2 / (4 e_z) if k^2 / (4 e_z^2) <= h, the sheet's -sqrt(c^2 e_z^2 - k^2)
  /// if k < c |e_z| and its height c / sqrt(1 - k^2 / (c^2 e_z^2)) is <= h.
  double maxAlong(const Eigen::Vector3d& e) const {
    const Eigen::Vector3d el = R.transpose() * e;
    const double k = std::sqrt(a * a * el.x() * el.x() + b * b * el.y() * el.y());
    const double ez = el.z();
    double local = 0.0;
    switch (kind) {
      case Cylinder: local = std::fabs(ez) * h + k; break;
      case Paraboloid:
        local = ez * h + std::sqrt(h) * k;
        if (ez < 0.0 && k * k / (4.0 * ez * ez) <= h) local = std::max(local, -k * k / (4.0 * ez));
        break;
      case Cone: local = std::max(0.0, ez * h + h / c * k); break;
      case Sheet:
        local = ez * h + std::sqrt(h * h / (c * c) - 1.0) * k;
        if (ez < 0.0 && k < c * std::fabs(ez) && c / std::sqrt(1.0 - k * k / (c * c * ez * ez)) <= h)
          local = std::max(local, -std::sqrt(c * c * ez * ez - k * k));
        break;
    }
    return local + e.dot(p);
  }
  Box3 outer() const {
    double w = 1.0;  // the cylinder's
    if (kind == Paraboloid) w = std::sqrt(h);
    if (kind == Cone) w = h / c;
    if (kind == Sheet) w = std::sqrt(h * h / (c * c) - 1.0);
    const double z0 = kind == Cylinder ? -h : 0.0;
    const Eigen::Vector3d half(a * w, b * w, 0.5 * (h - z0));
    const Eigen::Vector3d centre = R * Eigen::Vector3d(0, 0, 0.5 * (h + z0)) + p;
    const Eigen::Vector3d ext = R.cwiseAbs() * half * 1.01;
    return Box3{centre - ext, centre + ext};
  }
};

std::vector<DualTestRing> randomRings(std::mt19937_64& rng, int n) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<DualTestRing> out;
  for (int i = 0; i < n; ++i) {
    const double a = 0.8 + 0.6 * u(rng);
    out.push_back({a, 0.3 + 0.7 * u(rng), a * (0.2 + 0.6 * u(rng)), randomRotationForDualBound(rng),
                   Eigen::Vector3d(6.0 * u(rng) - 3.0, 6.0 * u(rng) - 3.0, 6.0 * u(rng) - 3.0)});
  }
  return out;
}

std::vector<DualTestLens> randomLenses(std::mt19937_64& rng, int n) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<DualTestLens> out;
  for (int i = 0; i < n; ++i) {
    const double r1 = 0.5 + u(rng), r2 = 0.5 + u(rng);
    const double lo = std::fabs(r1 - r2), d = lo + (r1 + r2 - lo) * (0.05 + 0.9 * u(rng));
    const Eigen::Vector3d c1(6.0 * u(rng) - 3.0, 6.0 * u(rng) - 3.0, 6.0 * u(rng) - 3.0);
    out.push_back({c1, c1 + d * randomRotationForDualBound(rng).col(0), r1, r2});
  }
  return out;
}

Eigen::Vector3d randomDirectionForDualBound(std::mt19937_64& rng) {
  std::normal_distribution<double> n;
  return Eigen::Vector3d(n(rng), n(rng), n(rng)).normalized();
}

// Both kinds have a duality gap of zero over their two atoms: the bound is the maximum up to
// rounding, from above. Their maxima lie on the rims (a circle of maximisers for the ring's
// axis) for most directions, where a bisection needs the most boxes.
TEST(DualLinearBound, RingsAndLensesAreBoundedTightlyFromAboveAtEveryPoseAndDirection) {
  std::mt19937_64 rng(20261201);
  int on_rim = 0;
  for (const DualTestRing& ring : randomRings(rng, 300)) {
    const QuadricRegion region = ring.region();
    for (const Eigen::Vector3d& e : {randomDirectionForDualBound(rng), Eigen::Vector3d(ring.R.col(2))}) {
      const double exact = ring.maxAlong(e);
      const double bound = dualLinearBound(region, e, ring.outer());
      ASSERT_GE(bound, exact - 1e-12) << "ring a " << ring.a << " c " << ring.c << " r " << ring.r;
      ASSERT_LE(bound, exact + 1e-9) << "ring a " << ring.a << " c " << ring.c << " r " << ring.r;
      const Eigen::Vector3d el = ring.R.transpose() * e;
      if (std::hypot(el.x() * ring.a * ring.a, el.y() * ring.a * ring.a) < ring.r * std::sqrt(el.cwiseProduct(
              Eigen::Vector3d(ring.a * ring.a, ring.a * ring.a, ring.c * ring.c)).dot(el)))
        ++on_rim;
    }
  }
  EXPECT_GE(on_rim, 300);  // every axis direction, and some of the random ones
  for (const DualTestLens& lens : randomLenses(rng, 300)) {
    const Eigen::Vector3d e = randomDirectionForDualBound(rng);
    const double exact = lens.maxAlong(e);
    const double bound = dualLinearBound(lens.region(), e, lens.outer());
    ASSERT_GE(bound, exact - 1e-12);
    ASSERT_LE(bound, exact + 1e-9);
  }
}

// A curved atom with a null direction (a paraboloid's or cylinder's axis) bounds e.y only with a
// plane across that axis, whose multiplier the null direction fixes; an indefinite one (a cone, a
// hyperboloid of two sheets) only with the product of its two caps' planes. All four caps are
// convex: the bound is their maximum, from above, except for a cone or sheet along directions
// down its axis (there it is checked to be an upper bound only).
TEST(DualLinearBound, CapsOfParaboloidsCylindersConesAndSheetsAreBoundedTightlyFromAbove) {
  std::mt19937_64 rng(4401);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const char* names[] = {"paraboloid", "cylinder", "cone", "sheet"};
  int tight = 0, loose_allowed = 0;
  for (int i = 0; i < 800; ++i) {
    const DualTestCap::Kind kind = static_cast<DualTestCap::Kind>(i % 4);
    const double c = 0.3 + u(rng);
    const double h = kind == DualTestCap::Sheet ? c * (1.2 + 2.0 * u(rng)) : 0.3 + u(rng);
    const DualTestCap cap{kind, 0.3 + u(rng), 0.3 + u(rng), c, h, randomRotationForDualBound(rng),
                          Eigen::Vector3d(6.0 * u(rng) - 3.0, 6.0 * u(rng) - 3.0, 6.0 * u(rng) - 3.0)};
    const Eigen::Vector3d e = randomDirectionForDualBound(rng);
    const double exact = cap.maxAlong(e);
    const double bound = dualLinearBound(cap.region(), e, cap.outer());
    ASSERT_GE(bound, exact - 1e-12) << names[kind] << " case " << i;
    // A cone's or sheet's maximum along a direction down its axis (on the rim, or at the apex)
    // has multipliers that leave the Lagrangian indefinite: only the upper bound is asserted.
    const bool indefinite = cap.kind == DualTestCap::Cone || cap.kind == DualTestCap::Sheet;
    if (indefinite && (cap.R.transpose() * e).z() < 0.0) {
      ++loose_allowed;
      continue;
    }
    ASSERT_LE(bound, exact + 1e-9) << names[kind] << " case " << i;
    ++tight;
  }
  EXPECT_GE(tight, 550);
  EXPECT_GE(loose_allowed, 150);
}

// Planes bound e.y together: a posed box alone (its vertex, by the linear program over its
// planes) against its closed-form support, and a posed block whose corners an ellipsoid rounds
// off, drilled along its axis (the maximum where the ellipsoid meets one or two planes, by the
// ellipsoid with every plane at once), against the engine: nothing beyond the bound, and the
// level 1e-6 below it not empty.
TEST(DualLinearBound, BoxesAndRoundedBlocksAreBoundedTightlyByTheirPlanes) {
  std::mt19937_64 rng(4402);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int found_below = 0;
  for (int i = 0; i < 60; ++i) {
    const Eigen::Vector3d h(0.3 + u(rng), 0.3 + u(rng), 0.3 + u(rng));
    const Eigen::Matrix3d R = randomRotationForDualBound(rng);
    const Eigen::Vector3d p(6.0 * u(rng) - 3.0, 6.0 * u(rng) - 3.0, 6.0 * u(rng) - 3.0);
    std::vector<QuadricRegion> planes;
    for (int k = 0; k < 3; ++k) {
      planes.push_back(QuadricRegion::halfspace(Eigen::Vector3d::Unit(k), h[k]));
      planes.push_back(QuadricRegion::halfspace(-Eigen::Vector3d::Unit(k), h[k]));
    }
    const Eigen::Vector3d ext = R.cwiseAbs() * h * 1.01;
    const Box3 outer{p - ext, p + ext};
    const Eigen::Vector3d e = randomDirectionForDualBound(rng);
    // The box: max e.y = e.p + sum_k h_k |e.R_k|.
    const QuadricRegion box = QuadricRegion::combine(Op::Intersection, planes).transformed(R, p);
    const double exact = e.dot(p) + h.dot((R.transpose() * e).cwiseAbs());
    const double bound = dualLinearBound(box, e, outer);
    ASSERT_GE(bound, exact - 1e-12) << "box " << i;
    ASSERT_LE(bound, exact + 1e-9) << "box " << i;
    // The rounded block, drilled: an ellipsoid through the box's edges (its semi-axes 1.2 h
    // leave the corners out), minus a bore of a fifth of the smaller half-width along z.
    std::vector<QuadricRegion> parts = planes;
    parts.push_back(QuadricRegion::atom(quadric::ellipsoid(1.2 * h)));
    const QuadricRegion rounded = QuadricRegion::combine(Op::Intersection, parts);
    const double r = 0.2 * std::min(h.x(), h.y());
    const QuadricRegion block =
        QuadricRegion::combine(Op::Difference, {rounded, QuadricRegion::atom(quadric::ellipticCylinder(r, r))})
            .transformed(R, p);
    const double b = dualLinearBound(block, e, outer);
    ASSERT_TRUE(std::isfinite(b)) << "block " << i;
    const double size = 2.0 * h.maxCoeff();
    auto above = [&](double level) {  // the block's points with e.y >= level
      return QuadricRegion::combine(Op::Intersection, {block, QuadricRegion::halfspace(-e, -level)});
    };
    ASSERT_NE(findPoint(above(b + 1e-9 * size), outer).status, PointSearch::Found) << "block " << i;
    const PointSearchResult below = findPoint(above(b - 1e-6 * size), outer);
    ASSERT_NE(below.status, PointSearch::Empty) << "block " << i << ": the bound is loose";
    found_below += below.status == PointSearch::Found ? 1 : 0;
  }
  EXPECT_GE(found_below, 30);
}

/// A random atom of every kind the models use, posed: ellipsoid, cylinder, cone, paraboloid,
/// hyperboloids of one and two sheets, hyperbolic paraboloid, plane; negated half the time (the
/// subtracted operand of a difference).
Eigen::Matrix4d randomAtomForDualBound(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double a = 0.3 + u(rng), b = 0.3 + u(rng), c = 0.3 + u(rng);
  Eigen::Matrix4d Q;
  switch (static_cast<int>(u(rng) * 8.0)) {
    case 0: Q = quadric::ellipsoid({a, b, c}); break;
    case 1: Q = quadric::ellipticCylinder(a, b); break;
    case 2: Q = quadric::ellipticCone(a, b, c); break;
    case 3: Q = quadric::ellipticParaboloid(a, b); break;
    case 4: Q = quadric::hyperboloidOneSheet(a, b, c); break;
    case 5: Q = quadric::hyperboloidTwoSheets(a, b, c); break;
    case 6: Q = quadric::hyperbolicParaboloid(a, b); break;
    default: Q = QuadricRegion::halfspace(randomDirectionForDualBound(rng), u(rng) - 0.5).matrix(); break;
  }
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = randomRotationForDualBound(rng);
  T.topRightCorner<3, 1>() = Eigen::Vector3d(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
  Q = quadric::transform(Q, T);
  return u(rng) < 0.5 ? Q : Eigen::Matrix4d(-Q);
}

// Wherever the duality gap is not zero the bound is looser, never lower: no point of the region
// lies beyond it. Checked on random intersections, differences and unions of two to four atoms
// inside a box (half of them with a slab of two opposite planes as well), by the engine's
// certified search beyond the bound (findPoint Found would be a certified interior point there)
// and on 2,000 sampled certified interior points each.
TEST(DualLinearBound, NoCertifiedPointOfRandomModelsLiesBeyondIt) {
  std::mt19937_64 rng(44);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Box3 box{Eigen::Vector3d::Constant(-1.5), Eigen::Vector3d::Constant(1.5)};
  int finite = 0, sampled = 0;
  for (int model = 0; model < 400; ++model) {
    const int n_atoms = 2 + static_cast<int>(u(rng) * 3.0);
    std::vector<QuadricRegion> atoms;
    for (int i = 0; i < n_atoms; ++i) atoms.push_back(QuadricRegion::atom(randomAtomForDualBound(rng)));
    if (u(rng) < 0.5) {  // a slab: two opposite planes, whose product the bound also uses
      const Eigen::Vector3d n = randomDirectionForDualBound(rng);
      const double d1 = 0.2 + u(rng), d2 = 0.2 + u(rng);
      atoms.insert(atoms.begin() + 1, {QuadricRegion::halfspace(n, d1), QuadricRegion::halfspace(-n, d2)});
    }
    const double kind = u(rng);
    QuadricRegion region = atoms[0];
    if (kind < 0.5) {
      region = QuadricRegion::combine(Op::Intersection, atoms);
    } else if (kind < 0.8) {
      region = QuadricRegion::combine(Op::Difference, atoms);
    } else {
      const QuadricRegion pair = QuadricRegion::combine(Op::Intersection, {atoms[0], atoms[1]});
      std::vector<QuadricRegion> rest(atoms.begin() + 1, atoms.end());
      region = QuadricRegion::combine(Op::Union, {pair, QuadricRegion::combine(Op::Intersection, rest)});
    }
    const Eigen::Vector3d e = randomDirectionForDualBound(rng);
    const double bound = dualLinearBound(region, e, box);
    if (!std::isfinite(bound)) continue;
    ++finite;
    const double beyond = bound + 1e-9;
    if (beyond < e.cwiseAbs().dot(box.halfWidth())) {
      const PointSearchResult s =
          findPoint(QuadricRegion::combine(Op::Intersection, {region, QuadricRegion::halfspace(-e, -beyond)}), box);
      ASSERT_NE(s.status, PointSearch::Found) << "model " << model << ": bound " << bound << ", found e.x "
                                               << e.dot(s.point);
    }
    for (int k = 0; k < 2000; ++k) {
      const Eigen::Vector3d x(3.0 * u(rng) - 1.5, 3.0 * u(rng) - 1.5, 3.0 * u(rng) - 1.5);
      if (region.classifyPoint(x) <= 0) continue;
      ++sampled;
      ASSERT_LE(e.dot(x), bound) << "model " << model;
    }
  }
  EXPECT_GE(finite, 150);
  EXPECT_GE(sampled, 10000);
}

// The boxes regionAabb builds for posed rings and lenses, whose faces now start from the bound:
// they contain the closed-form extents and exceed them by at most the documented 1e-6 of the
// extent (kRegionAabbRelative per stage).
TEST(DualLinearBound, RegionAabbOfPosedRingsAndLensesMatchesClosedForms) {
  std::mt19937_64 rng(1201);
  auto check = [](const QuadricRegion& region, const auto& maxAlong) {
    const Box3 box = regionAabb(region);
    const double size = (box.hi - box.lo).maxCoeff();
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d e = Eigen::Vector3d::Unit(i);
      const double hi = maxAlong(e), lo = -maxAlong(-e);
      EXPECT_GE(box.hi[i], hi - 1e-12 * size);
      EXPECT_LE(box.hi[i], hi + 1e-6 * size);
      EXPECT_LE(box.lo[i], lo + 1e-12 * size);
      EXPECT_GE(box.lo[i], lo - 1e-6 * size);
    }
  };
  for (const DualTestRing& ring : randomRings(rng, 8))
    check(ring.region(), [&](const Eigen::Vector3d& e) { return ring.maxAlong(e); });
  for (const DualTestLens& lens : randomLenses(rng, 8))
    check(lens.region(), [&](const Eigen::Vector3d& e) { return lens.maxAlong(e); });
}

// Regions no tree box bounds (no ellipsoid atom) and that are not convex start from the duality
// bounds over the +-1e6 search cube: a one-sheet hyperboloid and a double cone cut at |z| <= 1,
// posed. Their hulls are those of their rim ellipses at z = +-1 (radii scaled by w =
// sqrt(1 + 1/c^2) for the tower, 1/c for the hourglass), so max e.y is, in the local frame,
// |e_z| + w sqrt(a^2 e_x^2 + b^2 e_y^2). The boxes contain those extents and exceed them by at
// most 1e-6 of the size.
TEST(DualLinearBound, RegionAabbWithoutAHintOfPosedTowersAndHourglassesMatchesClosedForms) {
  std::mt19937_64 rng(4403);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 12; ++i) {
    const bool tower = i % 2 == 0;
    const double a = 0.3 + u(rng), b = 0.3 + u(rng), c = 0.5 + u(rng);
    const Eigen::Matrix3d R = randomRotationForDualBound(rng);
    const Eigen::Vector3d p(6.0 * u(rng) - 3.0, 6.0 * u(rng) - 3.0, 6.0 * u(rng) - 3.0);
    const Eigen::Matrix4d Q = tower ? quadric::hyperboloidOneSheet(a, b, c) : quadric::ellipticCone(a, b, c);
    const QuadricRegion region =
        QuadricRegion::combine(Op::Intersection, {QuadricRegion::atom(Q), QuadricRegion::halfspace({0, 0, 1}, 1.0),
                                                  QuadricRegion::halfspace({0, 0, -1}, 1.0)})
            .transformed(R, p);
    const double w = tower ? std::sqrt(1.0 + 1.0 / (c * c)) : 1.0 / c;
    auto maxAlong = [&](const Eigen::Vector3d& e) {
      const Eigen::Vector3d el = R.transpose() * e;
      return e.dot(p) + std::fabs(el.z()) + w * std::sqrt(a * a * el.x() * el.x() + b * b * el.y() * el.y());
    };
    const Box3 box = regionAabb(region);
    const double size = (box.hi - box.lo).maxCoeff();
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d e = Eigen::Vector3d::Unit(k);
      SCOPED_TRACE(testing::Message() << (tower ? "tower " : "hourglass ") << i << ", axis " << k);
      EXPECT_GE(box.hi[k], maxAlong(e) - 1e-12 * size);
      EXPECT_LE(box.hi[k], maxAlong(e) + 1e-6 * size);
      EXPECT_LE(box.lo[k], -maxAlong(-e) + 1e-12 * size);
      EXPECT_GE(box.lo[k], -maxAlong(-e) - 1e-6 * size);
    }
  }
}

}  // namespace
}  // namespace fcl_quadric
