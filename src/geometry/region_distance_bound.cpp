#include "fcl_quadric/geometry/region_distance_bound.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Eigenvalues>

#include "fcl_quadric/algebra/quadric_matrix.h"
#include "fcl_quadric/geometry/ellipsoid_polytope.h"
#include "fcl_quadric/tolerances.h"
#include "geometry/region_formula.h"

namespace fcl_quadric {

namespace {

void checkBox(const Box3& box, const std::string& what) {
  bool finite = true;
  for (int i = 0; i < 3; ++i) finite = finite && std::isfinite(box.lo[i]) && std::isfinite(box.hi[i]);
  if (!finite || box.empty()) throw std::invalid_argument(what + " is empty or not finite");
}

void checkCap(double cap, const std::string& who) {
  if (std::isnan(cap) || cap < 0.0) {  // isnan first: an ordered comparison with NaN raises FE_INVALID
    throw std::invalid_argument(who + ": cap must be >= 0, got " + std::to_string(cap));
  }
}

/// The largest delta in [lo, hi] for which separated(delta) is certified, lo being a certified
/// bound already; hi itself if separated(hi). From lo = 0 the levels hi / 2, hi / 4, ... are tried
/// first (at most kRegionDistanceDescents), so that the bisection that follows brackets the bound
/// to 2^-kRegionDistanceBisections of itself however small it is (near contact the advancement
/// needs a relative bound, not one to a fraction of the search range); 0 when none separates.
template <class Separated>
double bisectBound(double lo, double hi, Separated&& separated) {
  if (!(hi > lo)) return lo;
  if (separated(hi)) return hi;
  if (lo == 0.0) {
    for (int k = 0; k < tolerance_region::kRegionDistanceDescents && lo == 0.0; ++k) {
      const double mid = 0.5 * hi;
      (separated(mid) ? lo : hi) = mid;
    }
    if (lo == 0.0) return 0.0;
  }
  for (int k = 0; k < tolerance_region::kRegionDistanceBisections; ++k) {
    const double mid = 0.5 * (lo + hi);
    (separated(mid) ? lo : hi) = mid;
  }
  return lo;
}

}  // namespace

double ellipsoidRegionDistanceLowerBound(const Ellipsoid& e, const QuadricRegion& region, const Box3& region_box,
                                         const Eigen::Matrix3d& R, const Eigen::Vector3d& p, double cap) {
  const std::string who = "ellipsoidRegionDistanceLowerBound";
  checkCap(cap, who);
  checkBox(region_box, who + ": the region's box");
  detail::checkFinite(p, "ellipsoidRegionDistanceLowerBound: region translation");
  detail::checkRotation(R, "ellipsoidRegionDistanceLowerBound: region rotation");
  // The region lies in its box: the distance to the box is a lower bound.
  const Eigen::Vector3d half = region_box.halfWidth().cwiseMax(tolerance::kMinRadius);
  const Eigen::Vector3d box_centre = p + R * region_box.center();
  const SignedDistanceResult to_box = signedDistanceEllipsoidBox(e, half, R, box_centre);
  // to_box.distance = phi(n) = min_j n.v_j - n.c - |S R^T n| (a lower bound of the distance for
  // any n) is rounded by up to tau times its absolute evaluation, which includes |n|_1 sum(r)
  // (tolerances.h, "Supports": a long radius magnifies the rounding of R^T n); subtracting that
  // keeps it a lower bound for thin ellipsoids too.
  const Eigen::Vector3d& n = to_box.normal;
  const double phi_rounding =
      tolerance::kCertificateRelativeBoundDouble *
      (std::fabs(to_box.distance) + box_centre.norm() + 2.0 * half.norm() + e.center().norm() +
       n.cwiseAbs().sum() * e.radii().sum());
  const double lo = std::clamp(to_box.distance - phi_rounding, 0.0, cap);
  if (lo >= cap) return cap;
  // The ellipsoid scaled about its centre by s = 1 + delta / r_min, in the region's frame
  // (x_R = R^T (R_e x + c_e - p)), certified separate => the distance is >= delta (file comment).
  const double r_min = e.radii().minCoeff();
  const Eigen::Matrix3d R_RE = R.transpose() * e.rotation();
  const Eigen::Vector3d p_RE = R.transpose() * (e.center() - p);
  auto separated = [&](double delta) {
    const Eigen::Vector3d radii = (1.0 + delta / r_min) * e.radii();
    return collideRegions(region, region_box, QuadricRegion::atom(quadric::ellipsoid(radii)), Box3{-radii, radii},
                          R_RE, p_RE)
               .relation == RegionRelation::Separated;
  };
  if (!separated(0.0)) return lo;  // 0 unless the box already separates
  // Search where the bound matters: a cap far beyond the pair's size is cut to the size (a
  // separated test there still returns a valid, smaller bound); keep the scaled radii within the
  // range Ellipsoid accepts (tolerances.h).
  const double span = 2.0 * (region_box.halfWidth().norm() + e.maxRadius());
  double hi = std::min(cap, lo + span);
  hi = std::min(hi, (tolerance::kMaxLength / e.maxRadius() - 1.0) * r_min);
  return bisectBound(lo, hi, separated);
}

double regionConvexDistanceLowerBound(const QuadricRegion& a, const Box3& a_box, const QuadricRegion& b,
                                      const Box3& b_box, double b_inradius, const Eigen::Matrix3d& R_AB,
                                      const Eigen::Vector3d& p_AB, double cap) {
  const std::string who = "regionConvexDistanceLowerBound";
  checkCap(cap, who);
  if (!std::isfinite(b_inradius) || !(b_inradius > 0.0)) {
    throw std::invalid_argument(who + ": b_inradius must be finite and > 0, got " + std::to_string(b_inradius));
  }
  checkBox(a_box, who + ": a's box");
  checkBox(b_box, who + ": b's box");
  // The ball of radius b_inradius about b's origin lies in b, hence in its box.
  for (int i = 0; i < 3; ++i) {
    if (!(b_box.lo[i] <= -b_inradius && b_box.hi[i] >= b_inradius)) {
      throw std::invalid_argument(who + ": b's box does not contain the ball of radius b_inradius = " +
                                  std::to_string(b_inradius) + " about b's origin");
    }
  }
  detail::checkFinite(p_AB, "regionConvexDistanceLowerBound: translation");
  detail::checkRotation(R_AB, "regionConvexDistanceLowerBound: rotation");
  auto separated = [&](double delta) {
    const double s = 1.0 + delta / b_inradius;
    const QuadricRegion scaled = b.transformedAffine(s * Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
    return collideRegions(a, a_box, scaled, Box3{s * b_box.lo, s * b_box.hi}, R_AB, p_AB).relation ==
           RegionRelation::Separated;
  };
  if (cap == 0.0 || !separated(0.0)) return 0.0;
  // As above: search up to the pair's size, and keep the scaled solid within kMaxLength.
  const double reach = b_box.hi.cwiseAbs().cwiseMax(b_box.lo.cwiseAbs()).norm();
  double hi = std::min(cap, 2.0 * (a_box.halfWidth().norm() + reach));
  hi = std::min(hi, (tolerance::kMaxLength / reach - 1.0) * b_inradius);
  return bisectBound(0.0, hi, separated);
}

OffsetSuperset boxOffsetSuperset(const Eigen::Vector3d& c, const Eigen::Vector3d& h) {
  detail::checkFinite(c, "boxOffsetSuperset: centre");
  detail::checkFinite(h, "boxOffsetSuperset: half widths");
  if ((h.array() < 0.0).any())
    throw std::invalid_argument("boxOffsetSuperset: a half width is negative (" + std::to_string(h.minCoeff()) + ")");
  return [c, h](double delta) {
    const Eigen::Vector3d g = h + Eigen::Vector3d::Constant(delta);
    std::vector<QuadricRegion> planes;
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d e = Eigen::Vector3d::Unit(i);
      planes.push_back(QuadricRegion::halfspace(e, c[i] + g[i]));
      planes.push_back(QuadricRegion::halfspace(-e, -(c[i] - g[i])));
    }
    return std::make_pair(QuadricRegion::combine(QuadricRegion::Op::Intersection, std::move(planes)),
                          Box3{c - g, c + g});
  };
}

std::optional<OffsetSuperset> triangleOffsetSuperset(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                                     const Eigen::Vector3d& p2) {
  if (!p0.allFinite() || !p1.allFinite() || !p2.allFinite()) return std::nullopt;
  const Eigen::Vector3d cross = (p1 - p0).cross(p2 - p0);
  if (!(cross.norm() > 1e-14 * (p1 - p0).norm() * (p2 - p0).norm())) return std::nullopt;
  const Eigen::Vector3d n = cross.normalized();
  const std::array<Eigen::Vector3d, 3> p{p0, p1, p2};
  // Outward in-plane unit normal of edge i (from p[i] to p[i+1]); n points so that p is
  // counter-clockwise about it, hence (p[i+1] - p[i]) x n points out.
  std::array<Eigen::Vector3d, 3> m;
  for (int i = 0; i < 3; ++i) m[i] = (p[(i + 1) % 3] - p[i]).cross(n).normalized();
  return [n, p, m](double delta) {
    std::vector<QuadricRegion> parts{QuadricRegion::halfspace(n, n.dot(p[0]) + delta),
                                     QuadricRegion::halfspace(-n, -n.dot(p[0]) + delta)};
    for (int i = 0; i < 3; ++i) {
      parts.push_back(QuadricRegion::halfspace(m[i], m[i].dot(p[i]) + delta));
      // Chamfers along the edge, k = (m +- n) / sqrt 2: k.t <= k.p_i on the triangle, so
      // k.x <= k.p_i + delta within delta of it. They cut the prism's square edge to an octagon
      // about the edge's delta-cylinder (reach delta / cos 22.5 deg instead of delta sqrt 2).
      for (double s : {-1.0, 1.0}) {
        const Eigen::Vector3d k = (m[i] + s * n) / std::sqrt(2.0);
        parts.push_back(QuadricRegion::halfspace(k, k.dot(p[i]) + delta));
      }
    }
    // Vertex i of the grown triangle: where the pushed edges i-1 and i meet, p[i] + delta (m_a +
    // m_b) / (1 + m_a.m_b); the prism's box holds those points moved by +-delta n, padded.
    Box3 box{Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()),
             Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity())};
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d& ma = m[(i + 2) % 3];
      const Eigen::Vector3d& mb = m[i];
      const Eigen::Vector3d v = p[i] + delta * (ma + mb) / std::max(1.0 + ma.dot(mb), 1e-300);
      for (double s : {-1.0, 1.0}) {
        box.lo = box.lo.cwiseMin(v + s * delta * n);
        box.hi = box.hi.cwiseMax(v + s * delta * n);
      }
    }
    const double pad = 1e-12 * ((box.hi - box.lo).cwiseAbs().maxCoeff() + box.hi.cwiseAbs().maxCoeff());
    box.lo.array() -= pad;
    box.hi.array() += pad;
    return std::make_pair(QuadricRegion::combine(QuadricRegion::Op::Intersection, std::move(parts)), box);
  };
}

double regionOffsetDistanceLowerBound(const QuadricRegion& a, const Box3& a_box, const OffsetSuperset& grown,
                                      double reach, const Eigen::Matrix3d& R_AB, const Eigen::Vector3d& p_AB,
                                      double cap) {
  const std::string who = "regionOffsetDistanceLowerBound";
  checkCap(cap, who);
  if (!std::isfinite(reach) || reach < 0.0)
    throw std::invalid_argument(who + ": reach must be finite and >= 0, got " + std::to_string(reach));
  checkBox(a_box, who + ": a's box");
  detail::checkFinite(p_AB, "regionOffsetDistanceLowerBound: translation");
  detail::checkRotation(R_AB, "regionOffsetDistanceLowerBound: rotation");
  auto separated = [&](double delta) {
    const auto [region, box] = grown(delta);
    return collideRegions(a, a_box, region, box, R_AB, p_AB).relation == RegionRelation::Separated;
  };
  if (cap == 0.0 || !separated(0.0)) return 0.0;
  const double hi = std::min(cap, 2.0 * (a_box.halfWidth().norm() + reach));
  return bisectBound(0.0, hi, separated);
}

namespace {

/// The atom {X^T Q X <= 0} grown by delta (grownRegion), or none.
std::optional<Eigen::Matrix4d> grownAtom(const Eigen::Matrix4d& Q, double delta) {
  const Eigen::Matrix3d A = Q.topLeftCorner<3, 3>();
  const Eigen::Vector3d b = Q.topRightCorner<3, 1>();
  const double c = Q(3, 3);
  if (detail::isPlanarAtom(Q)) {  // a plane 2 b.x + c <= 0 (or a constant)
    Eigen::Matrix4d G = Q;
    G.topLeftCorner<3, 3>().setZero();
    G(3, 3) = c - 2.0 * delta * b.norm();
    return G;
  }
  // The convex atom f = (x - x0)^T A (x - x0) - k <= 0 (A PSD, b in its range), or its complement
  // -f <= 0 (A NSD).
  const bool complement = A.trace() < 0.0;
  const Eigen::Matrix3d P = complement ? Eigen::Matrix3d(-A) : A;
  const Eigen::Vector3d q = complement ? Eigen::Vector3d(-b) : b;
  const double r = complement ? -c : c;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(P);
  const Eigen::Vector3d lam = es.eigenvalues();
  const double lmax = lam.cwiseAbs().maxCoeff();
  if (lam.minCoeff() < -1e-12 * lmax) return std::nullopt;  // indefinite: hyperboloid, cone
  const Eigen::Vector3d qz = es.eigenvectors().transpose() * q;
  double bAb = 0.0;  // q^T P^+ q
  for (int i = 0; i < 3; ++i) {
    if (lam[i] > 1e-12 * lmax) {
      bAb += qz[i] * qz[i] / lam[i];
    } else if (std::abs(qz[i]) > 1e-12 * (q.norm() + lmax)) {
      return std::nullopt;  // a linear term along a null direction: a paraboloid
    }
  }
  const double k = bAb - r;  // f = (x - x0)^T P (x - x0) - k
  if (!(k > 0.0)) return std::nullopt;  // a point, a line or empty: not a solid to grow
  const double r_min = std::sqrt(k / lam.maxCoeff());
  double s = complement ? 1.0 - delta / r_min : 1.0 + delta / r_min;
  Eigen::Matrix4d G = Eigen::Matrix4d::Zero();
  if (complement && s <= 0.0) {  // the complement grows to the whole space
    G(3, 3) = -1.0;
    return G;
  }
  const double c_new = bAb - s * s * k;  // the same centre and axes, semi-axes times s
  G.topLeftCorner<3, 3>() = P;
  G.topRightCorner<3, 1>() = q;
  G.bottomLeftCorner<1, 3>() = q.transpose();
  G(3, 3) = c_new;
  if (complement) G = -G;
  return G;
}

/// The formula's node n as a region, with its atoms replaced by grown ones; none if one cannot be.
std::optional<QuadricRegion> grownNode(const detail::Formula& f, int n, double delta) {
  const detail::Formula::Node& node = f.nodes[n];
  std::vector<QuadricRegion> parts;
  for (int a : node.atoms) {
    const std::optional<Eigen::Matrix4d> g = grownAtom(f.atoms[a], delta);
    if (!g) return std::nullopt;
    parts.push_back(QuadricRegion::atom(*g));
  }
  for (int m : node.nodes) {
    std::optional<QuadricRegion> g = grownNode(f, m, delta);
    if (!g) return std::nullopt;
    parts.push_back(std::move(*g));
  }
  if (parts.empty()) return std::nullopt;  // (the shapes' constructors reject empty formulas)
  return QuadricRegion::combine(node.is_and ? QuadricRegion::Op::Intersection : QuadricRegion::Op::Union,
                                std::move(parts));
}

}  // namespace

std::optional<QuadricRegion> grownRegion(const QuadricRegion& region, double delta) {
  if (!std::isfinite(delta) || delta < 0.0) return std::nullopt;
  const detail::Formula f(region);
  return grownNode(f, f.root, delta);
}

double regionPairDistanceLowerBound(const QuadricRegion& a, const Box3& a_box, const QuadricRegion& b,
                                    const Box3& b_box, const Eigen::Matrix3d& R_AB, const Eigen::Vector3d& p_AB,
                                    double cap) {
  const std::string who = "regionPairDistanceLowerBound";
  checkCap(cap, who);
  checkBox(a_box, who + ": a's box");
  checkBox(b_box, who + ": b's box");
  detail::checkFinite(p_AB, "regionPairDistanceLowerBound: translation");
  detail::checkRotation(R_AB, "regionPairDistanceLowerBound: rotation");
  // Grow b if its atoms allow it, else a (in b's frame: the inverse pose).
  const bool grow_b = grownRegion(b, 0.0).has_value();
  if (!grow_b && !grownRegion(a, 0.0)) return 0.0;
  const QuadricRegion& fixed = grow_b ? a : b;
  const QuadricRegion& moving = grow_b ? b : a;
  const Box3& fixed_box = grow_b ? a_box : b_box;
  const Box3& moving_box = grow_b ? b_box : a_box;
  const Eigen::Matrix3d R = grow_b ? R_AB : Eigen::Matrix3d(R_AB.transpose());
  const Eigen::Vector3d p = grow_b ? p_AB : Eigen::Vector3d(-(R_AB.transpose() * p_AB));
  auto separated = [&](double delta) {
    const std::optional<QuadricRegion> g = grownRegion(moving, delta);
    if (!g) return false;
    const Eigen::Vector3d d = Eigen::Vector3d::Constant(delta);
    return collideRegions(fixed, fixed_box, *g, Box3{moving_box.lo - d, moving_box.hi + d}, R, p).relation ==
           RegionRelation::Separated;
  };
  if (cap == 0.0 || !separated(0.0)) return 0.0;
  const double hi = std::min(cap, 2.0 * (a_box.halfWidth().norm() + b_box.halfWidth().norm()) +
                                      (a_box.center() - (R_AB * b_box.center() + p_AB)).norm());
  return bisectBound(0.0, hi, separated);
}

}  // namespace fcl_quadric
