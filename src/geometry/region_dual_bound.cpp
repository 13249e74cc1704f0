// Weak duality over an and/or formula's atoms (pairs, slab products, the planes' linear program,
// convex parts): a certified upper bound of e.y over a composite quadric model
// (region_dual_bound.h; docs/algorithms.md section 9, "Faces by duality").
#include "geometry/region_dual_bound.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include <Eigen/Eigenvalues>

#include "fcl_quadric/geometry/convex_support.h"
#include "algebra/input_checks.h"
#include "geometry/nonnegative_multipliers.h"

namespace fcl_quadric {
namespace detail {

namespace {

constexpr double kNoBound = std::numeric_limits<double>::infinity();
/// The rounding unit of the bound's terms. Each is a short sum of products (at most 16 terms:
/// gamma_16 < 17 eps), and the symmetric eigenvalue solver's backward error is a few eps ||H||;
/// 64 eps covers both with a factor > 3.
constexpr double kDualBoundRounding = 64.0 * std::numeric_limits<double>::epsilon();
/// The search over multipliers (not the certificate): eigenvalues of the pencil's quadratic part
/// below this fraction of the largest count as zero in its pseudo-inverse, and a smallest
/// eigenvalue below -kMixIndefinite of the largest makes the mix give no bound.
constexpr double kMixPseudoInverseCutoff = 1e-12;
constexpr double kMixIndefinite = 1e-10;
/// The mix t of a pair (multipliers proportional to 1 - t and t): a grid of kMixGrid steps on
/// [0, 1], then golden section around the grid's best point (0.618^40 ~ 4e-9 of the grid step).
constexpr int kMixGrid = 16;
constexpr int kMixGoldenSteps = 40;
/// An and-node whose pairs with a quadratic part (two planes have none) outnumber this tries its
/// inequalities one by one only: pairs grow as the square, 75 us each (28: eight curved atoms).
constexpr int kMaxCurvedPairs = 28;
/// The convex parts take an and-node of at most this many planes (ConvexSupport's enumeration
/// grows with the cube of the planes).
constexpr int kMaxPlanes = 8;
/// The planes' linear program takes an and-node of at most this many planes (696 subsets of one
/// to three, a few microseconds each): a box with four cut corners has ten, and without the
/// program regionAabb's bisection spent 0.4-0.6 s excluding the levels above a turned vertex.
constexpr int kMaxProgramPlanes = 16;

/// An inequality f(y) = Y^T Q Y <= slack that every point y of the and-node's region inside
/// `outer` satisfies: one of its atoms (slack 0), or the product of two opposite planes.
struct DualAtom {
  Eigen::Matrix4d Q;
  double slack = 0.0;
};

/// The bound certified for the multipliers lam[i] >= 0 of the inequalities a[i] (n = 1 to 3) at
/// the expansion point x. For y in the conjunction (f_i(y) <= slack_i) and in `outer`:
///   e.y <= L(y) + sum_i lam_i slack_i,
///   L(y) := e.y - sum_i lam_i f_i(y) = L(x) + g.(y - x) - (y - x)^T H (y - x)
///        <= L(x) + |g| R + nu R^2,
/// with g = grad L(x) = e - sum_i lam_i grad f_i(x), H = sum_i lam_i A_i (A_i the atoms' 3x3
/// parts), nu >= max(0, -lambda_min(H)) and R >= |y - x| over `outer`. Every computed term is
/// taken at its value plus kDualBoundRounding times the magnitude of its evaluation, and the
/// eigenvalue at the computed H's minus the same unit times sum_i lam_i |A_i|_F (Weyl: that covers
/// forming H and the solver's backward error).
double certifiedBound(const DualAtom* const a[], const double lam[], int n, const Eigen::Vector3d& e,
                      const Eigen::Vector3d& x, const Box3& outer) {
  constexpr double u = kDualBoundRounding;
  const Eigen::Vector4d X(x[0], x[1], x[2], 1.0);
  const Eigen::Vector4d Xa = X.cwiseAbs();
  const Eigen::Vector3d xa = x.cwiseAbs();
  double L = e.dot(x);
  double L_mag = e.cwiseAbs().dot(xa);
  double slack = 0.0;
  Eigen::Vector3d g = e;
  Eigen::Vector3d g_mag = e.cwiseAbs();
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  double H_mag = 0.0;
  for (int i = 0; i < n; ++i) {
    const Eigen::Matrix4d& Qi = a[i]->Q;
    slack += lam[i] * a[i]->slack;
    const Eigen::Matrix3d A = Qi.topLeftCorner<3, 3>();
    const Eigen::Vector3d b = Qi.topRightCorner<3, 1>();
    L -= lam[i] * X.dot(Qi * X);
    L_mag += lam[i] * Xa.dot(Qi.cwiseAbs() * Xa);
    g -= lam[i] * (2.0 * (A * x + b));
    g_mag += lam[i] * (2.0 * (A.cwiseAbs() * xa + b.cwiseAbs()));
    H += lam[i] * A;
    H_mag += lam[i] * A.norm();
  }
  // Multipliers or a point that overflow give no bound (and no NaN reaches a comparison).
  if (!allFinite(H) || !std::isfinite(L) || !std::isfinite(L_mag) || !allFinite(g) || !allFinite(g_mag))
    return kNoBound;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(H, Eigen::EigenvaluesOnly);
  if (es.info() != Eigen::Success) return kNoBound;
  const double nu = std::max(0.0, -es.eigenvalues()[0]) + u * H_mag;
  const double L_up = L + u * L_mag + slack * (1.0 + u);
  const double g_up = g.norm() + u * g_mag.norm();
  Eigen::Vector3d reach;
  for (int i = 0; i < 3; ++i) reach[i] = std::max(std::fabs(outer.lo[i] - x[i]), std::fabs(outer.hi[i] - x[i]));
  const double R = reach.norm() * (1.0 + u);
  const double rest = g_up * R + nu * R * R;
  const double bound = L_up + rest + u * (std::fabs(L_up) + rest);
  return std::isfinite(bound) ? bound : kNoBound;
}

/// The bound of the mix t: the pencil W = (1 - t) Q1 + t Q2 (Q1 alone if a2 is null) scaled by
/// the s > 0 that minimises the dual function of the multipliers s (1 - t), s t, and expanded at
/// the maximiser of its Lagrangian. With W's quadratic part A (positive semidefinite), linear
/// part beta and constant gamma, and A^+ its pseudo-inverse, the dual function is
///   P / s - e^T A^+ beta + s Qw,  P = e^T A^+ e / 4, Qw = beta^T A^+ beta - gamma,
/// if e / 2 - s beta has no component in A's null space (else the Lagrangian is unbounded). So a
/// null direction v with v.beta != 0 fixes s = v.e / (2 v.beta) (a paraboloid's axis against a
/// cap, a cylinder's against an end plane); without one s = sqrt(P / Qw) is the least. The
/// Lagrangian's maximiser is A^+ (e / (2 s) - beta). These only choose the multipliers and the
/// point; certifiedBound() certifies what they give.
double mixBound(const DualAtom& a1, const DualAtom* a2, double t, const Eigen::Vector3d& e, const Box3& outer) {
  const Eigen::Matrix4d W = a2 == nullptr ? a1.Q : Eigen::Matrix4d((1.0 - t) * a1.Q + t * a2->Q);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(W.topLeftCorner<3, 3>());
  if (es.info() != Eigen::Success) return kNoBound;
  const Eigen::Vector3d& ev = es.eigenvalues();
  const double ev_max = ev.cwiseAbs().maxCoeff();
  if (!(ev_max > 0.0) || ev[0] < -kMixIndefinite * ev_max) return kNoBound;
  const Eigen::Vector3d beta = W.topRightCorner<3, 1>();
  const Eigen::Vector3d ve = es.eigenvectors().transpose() * e;
  const Eigen::Vector3d vb = es.eigenvectors().transpose() * beta;
  double P = 0.0, Qw = -W(3, 3);
  double s_null = 0.0;    // s fixed by the null directions, if they agree on one
  bool balanced = true;  // some s > 0 leaves e / 2 - s beta without a null component
  for (int k = 0; k < 3; ++k) {
    if (ev[k] > kMixPseudoInverseCutoff * ev_max) {
      P += 0.25 * ve[k] * ve[k] / ev[k];
      Qw += vb[k] * vb[k] / ev[k];
      continue;
    }
    if (std::fabs(vb[k]) <= kMixPseudoInverseCutoff * beta.norm()) {
      if (std::fabs(ve[k]) > kMixPseudoInverseCutoff * e.norm()) balanced = false;  // no s balances it
      continue;
    }
    const double sk = 0.5 * ve[k] / vb[k];
    if (!(sk > 0.0) || (s_null > 0.0 && !(std::fabs(sk - s_null) <= 1e-9 * s_null))) balanced = false;
    s_null = sk;
  }
  if (!balanced) s_null = 0.0;
  if (!std::isfinite(P) || !std::isfinite(Qw)) return kNoBound;  // an atom's scale overflows the mix
  // Where no s makes the Lagrangian bounded, it is still bounded on `outer` (|g| R in the
  // certificate): the s of the range part is tried as well, and the lesser bound kept.
  const DualAtom* const a[2] = {&a1, a2};
  double best = kNoBound;
  for (const double s : {s_null, P > 0.0 && Qw > 0.0 ? std::sqrt(P / Qw) : 0.0}) {
    if (!(s > 0.0) || !std::isfinite(s)) continue;
    Eigen::Vector3d z = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k)
      if (ev[k] > kMixPseudoInverseCutoff * ev_max) z[k] = (0.5 * ve[k] - s * vb[k]) / (s * ev[k]);
    const Eigen::Vector3d x = es.eigenvectors() * z;
    if (!allFinite(x)) continue;
    const double lam[2] = {a2 == nullptr ? s : s * (1.0 - t), s * t};
    best = std::min(best, certifiedBound(a, lam, a2 == nullptr ? 1 : 2, e, x, outer));
  }
  return best;
}

/// The least bound over the mixes of a pair: the grid's best, then golden section between its
/// neighbours. The dual function is convex in the multipliers, so its least value along the rays
/// of mix t is quasi-convex in t (+infinity where the mix is indefinite); the certified values
/// follow it up to rounding, and the least one seen is returned whichever way the search goes.
double pairBound(const DualAtom& a1, const DualAtom& a2, const Eigen::Vector3d& e, const Box3& outer) {
  if (isPlanarAtom(a1.Q) && isPlanarAtom(a2.Q)) return kNoBound;  // no quadratic part to bound e.y
  double best = kNoBound;
  int best_k = 0;
  for (int k = 0; k <= kMixGrid; ++k) {
    const double v = mixBound(a1, &a2, static_cast<double>(k) / kMixGrid, e, outer);
    if (v < best) {
      best = v;
      best_k = k;
    }
  }
  if (best == kNoBound) return kNoBound;
  const double phi = 0.5 * (std::sqrt(5.0) - 1.0);
  double a = static_cast<double>(std::max(best_k - 1, 0)) / kMixGrid;
  double b = static_cast<double>(std::min(best_k + 1, kMixGrid)) / kMixGrid;
  double c = b - phi * (b - a), d = a + phi * (b - a);
  double fc = mixBound(a1, &a2, c, e, outer), fd = mixBound(a1, &a2, d, e, outer);
  for (int it = 0; it < kMixGoldenSteps; ++it) {
    best = std::min({best, fc, fd});
    if (fc <= fd) {
      b = d;
      d = c;
      fd = fc;
      c = b - phi * (b - a);
      fc = mixBound(a1, &a2, c, e, outer);
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + phi * (b - a);
      fd = mixBound(a1, &a2, d, e, outer);
    }
  }
  return std::min({best, fc, fd});
}

double atomBound(const Eigen::Matrix4d& Q, const Eigen::Vector3d& e, const Box3& outer) {
  return mixBound(DualAtom{Q, 0.0}, nullptr, 0.0, e, outer);
}

/// The linear program over the and-node's planes (atoms whose quadratic part is exactly zero,
/// h.y + c <= 0 with h = 2 b): for every one, two or three of them whose normals are independent,
/// the least-squares multipliers of e = sum mu_k h_k, kept when none is negative, certified at the
/// box's centre (the residual e - sum mu_k h_k is rounding; |g| R charges it). A vertex, an edge
/// or a face of a polytope that bounds e.y is found so, as the curved pairs cannot (their planes
/// have no quadratic part). At most kMaxProgramPlanes planes.
double planeBound(const std::vector<DualAtom>& all, const Eigen::Vector3d& e, const Box3& outer) {
  std::vector<const DualAtom*> planes;
  for (const DualAtom& a : all)
    if (a.slack == 0.0 && a.Q.topLeftCorner<3, 3>().isZero(0.0)) planes.push_back(&a);
  const int p = static_cast<int>(planes.size());
  if (p == 0 || p > kMaxProgramPlanes) return kNoBound;
  const Eigen::Vector3d x = outer.center();
  double best = kNoBound;
  forEachNonNegativeCombination(
      p, [&](int i) -> Eigen::Vector3d { return 2.0 * planes[i]->Q.topRightCorner<3, 1>(); }, e,
      [&](const int idx[3], int k, const Eigen::Matrix<double, 3, Eigen::Dynamic>&, const Eigen::VectorXd& mu) {
        const DualAtom* a[3];
        double lam[3];
        for (int j = 0; j < k; ++j) {
          a[j] = planes[idx[j]];
          lam[j] = mu[j];
        }
        best = std::min(best, certifiedBound(a, lam, k, e, x, outer));
      });
  return best;
}

/// Each convex curved atom with all the and-node's planes: a convex superset of the node's region
/// whose support point towards e (ConvexSupport's KKT enumeration, the box clipping) carries
/// multipliers for the curved atom and up to three planes at once, certified by
/// ConvexSupport::dualSupportBound. A face where an ellipsoid meets two planes (a block's edge
/// rounded off by it) is bounded so, as pairs cannot.
double convexPartBound(const Formula& f, const std::vector<int>& atoms, const Eigen::Vector3d& e,
                       const Box3& outer) {
  std::vector<QuadricRegion> planes;
  std::vector<int> curved;
  for (int i : atoms) {
    const Eigen::Matrix3d A = f.atoms[i].topLeftCorner<3, 3>();
    if (A.isZero(0.0)) {
      planes.push_back(QuadricRegion::atom(f.atoms[i]));
      continue;
    }
    // Only a positive semidefinite atom (an ellipsoid, a cylinder, a paraboloid): the certificate
    // (dualSupportBound) refuses the others, whose mixes with a slab pairBound() covers.
    const Eigen::Vector3d ev = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(A, Eigen::EigenvaluesOnly).eigenvalues();
    if (ev[0] >= -1e-14 * ev.cwiseAbs().maxCoeff()) curved.push_back(i);
  }
  if (planes.empty() || curved.empty() || static_cast<int>(planes.size()) > kMaxPlanes) return kNoBound;
  double best = kNoBound;
  for (int i : curved) {
    std::vector<QuadricRegion> parts = planes;
    parts.push_back(QuadricRegion::atom(f.atoms[i]));
    const QuadricRegion part = QuadricRegion::combine(QuadricRegion::Op::Intersection, parts);
    const std::optional<ConvexSupport> support = ConvexSupport::fromRegion(part, outer);
    if (!support || support->kind() != ConvexSupport::Kind::Region) continue;
    // Any point of `outer` gives a valid bound; the support point makes it tight.
    const Eigen::Vector3d x = support->support(e);
    if (const std::optional<double> b = support->dualSupportBound(e, x, outer)) best = std::min(best, *b);
  }
  return best;
}

/// The and-node's inequalities: its atoms, and for every two of its planes p1 = P1.Y <= 0 and
/// p2 = P2.Y <= 0 with opposite normals (a slab: a cone's or a hyperboloid's caps) the product
/// -p1 p2 <= 0, whose quadratic part n n^T can make a mix with an indefinite atom semidefinite.
/// The product's matrix -(P1 P2^T + P2 P1^T) / 2 is rounded, by at most 2 eps |P1| |P2|^T
/// entrywise; its slack over `outer` is kDualBoundRounding (|P1|.Ymax) (|P2|.Ymax), Ymax the
/// largest |y| per coordinate there. Planes are atoms whose quadratic part is exactly zero.
std::vector<DualAtom> andNodeInequalities(const Formula& f, const std::vector<int>& atoms, const Box3& outer) {
  std::vector<DualAtom> out;
  std::vector<Eigen::Vector4d> planes;
  for (int i : atoms) {
    const Eigen::Matrix4d& Q = f.atoms[i];
    out.push_back(DualAtom{Q, 0.0});
    if (Q.topLeftCorner<3, 3>().isZero(0.0))
      planes.emplace_back(2.0 * Q(0, 3), 2.0 * Q(1, 3), 2.0 * Q(2, 3), Q(3, 3));
  }
  const Eigen::Vector4d ymax(std::max(std::fabs(outer.lo[0]), std::fabs(outer.hi[0])),
                             std::max(std::fabs(outer.lo[1]), std::fabs(outer.hi[1])),
                             std::max(std::fabs(outer.lo[2]), std::fabs(outer.hi[2])), 1.0);
  for (std::size_t i = 0; i < planes.size(); ++i)
    for (std::size_t j = i + 1; j < planes.size(); ++j) {
      const Eigen::Vector3d hi = planes[i].head<3>(), hj = planes[j].head<3>();
      if (!(hi.dot(hj) <= -(1.0 - 1e-9) * hi.norm() * hj.norm())) continue;
      const Eigen::Matrix4d P = planes[i] * planes[j].transpose();
      const double slack = kDualBoundRounding * planes[i].cwiseAbs().dot(ymax) * planes[j].cwiseAbs().dot(ymax);
      out.push_back(DualAtom{-0.5 * (P + P.transpose()), slack});
    }
  return out;
}

/// The region of an and-node lies in every pair of its inequalities and in every child's region:
/// the least bound of those. An or-node's region is the union of its members': the largest.
double nodeBound(const Formula& f, int n, const Eigen::Vector3d& e, const Box3& outer) {
  const Formula::Node& node = f.nodes[n];
  if (node.is_and) {
    const std::vector<DualAtom> all = andNodeInequalities(f, node.atoms, outer);
    const int k = static_cast<int>(all.size());
    int planar = 0;
    for (const DualAtom& a : all) planar += isPlanarAtom(a.Q) ? 1 : 0;
    const int curved_pairs = k * (k - 1) / 2 - planar * (planar - 1) / 2;
    double best = kNoBound;
    if (k == 1 || curved_pairs > kMaxCurvedPairs) {
      for (const DualAtom& a : all) best = std::min(best, mixBound(a, nullptr, 0.0, e, outer));
    } else {
      for (int i = 0; i < k; ++i)
        for (int j = i + 1; j < k; ++j) best = std::min(best, pairBound(all[i], all[j], e, outer));
    }
    best = std::min(best, planeBound(all, e, outer));
    best = std::min(best, convexPartBound(f, node.atoms, e, outer));
    for (int m : node.nodes) best = std::min(best, nodeBound(f, m, e, outer));
    return best;
  }
  if (node.atoms.empty() && node.nodes.empty()) return kNoBound;
  double worst = -kNoBound;
  for (int i : node.atoms) {
    worst = std::max(worst, atomBound(f.atoms[i], e, outer));
    if (worst == kNoBound) return kNoBound;
  }
  for (int m : node.nodes) {
    worst = std::max(worst, nodeBound(f, m, e, outer));
    if (worst == kNoBound) return kNoBound;
  }
  return worst;
}

}  // namespace

double dualLinearBound(const Formula& f, const Eigen::Vector3d& e, const Box3& outer) {
  if (f.nodes.empty() || !allFinite(e) || !allFinite(outer.lo) || !allFinite(outer.hi)) return kNoBound;
  return nodeBound(f, f.root, e, outer);
}

}  // namespace detail

double dualLinearBound(const QuadricRegion& region, const Eigen::Vector3d& d, const Box3& box) {
  return detail::dualLinearBound(detail::Formula(region), d, box);
}

}  // namespace fcl_quadric
