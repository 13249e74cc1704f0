#include "fcl_quadric/geometry/ellipsoid_quadric.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

#include "algebra/input_checks.h"
#include "fcl_quadric/tolerances.h"

namespace fcl_quadric {

const char* toString(QuadricSurfaceType t) {
  switch (t) {
    case QuadricSurfaceType::Ellipsoid: return "ellipsoid";
    case QuadricSurfaceType::HyperboloidOneSheet: return "hyperboloid of one sheet";
    case QuadricSurfaceType::HyperboloidTwoSheets: return "hyperboloid of two sheets";
    case QuadricSurfaceType::EllipticParaboloid: return "elliptic paraboloid";
    case QuadricSurfaceType::HyperbolicParaboloid: return "hyperbolic paraboloid";
    case QuadricSurfaceType::EllipticCylinder: return "elliptic cylinder";
    case QuadricSurfaceType::HyperbolicCylinder: return "hyperbolic cylinder";
    case QuadricSurfaceType::ParabolicCylinder: return "parabolic cylinder";
    case QuadricSurfaceType::ParallelPlanes: return "parallel planes";
    case QuadricSurfaceType::Cone: return "cone";
    case QuadricSurfaceType::IntersectingPlanes: return "intersecting planes";
    case QuadricSurfaceType::Plane: return "plane";
    case QuadricSurfaceType::Other: return "other";
  }
  return "unknown";
}

const char* toString(EllipsoidQuadricRelation r) {
  switch (r) {
    case EllipsoidQuadricRelation::Outside: return "outside";
    case EllipsoidQuadricRelation::Inside: return "inside";
    case EllipsoidQuadricRelation::Transversal: return "transversal";
    case EllipsoidQuadricRelation::Undecided: return "undecided";
  }
  return "unknown";
}

namespace {

/// -1 / 0 / +1 for a value that is (relative to `scale`) negative, zero, positive; 2 when it is
/// in the ambiguous band between kQuadricTypeRelativeZero and kQuadricTypeAmbiguity.
int bandSign(double v, double scale) {
  const double a = std::fabs(v);
  if (a <= kQuadricTypeRelativeZero * scale) return 0;
  if (a <= kQuadricTypeAmbiguity * scale) return 2;
  return v > 0.0 ? 1 : -1;
}

// --- A minimal interval arithmetic with outward widening (enough for the discrimination system,
// whose enclosures only need to be valid, not tight).
struct Iv {
  double lo, hi;
};
constexpr double kWiden = 4.0 * tolerance::kUnitRoundoff;
constexpr double kTiny = 1e-300;
Iv widen(double lo, double hi) {
  return {lo - std::fabs(lo) * kWiden - kTiny, hi + std::fabs(hi) * kWiden + kTiny};
}
Iv point(double v, double err) { return widen(v - err, v + err); }
Iv operator+(Iv a, Iv b) { return widen(a.lo + b.lo, a.hi + b.hi); }
Iv operator-(Iv a, Iv b) { return widen(a.lo - b.hi, a.hi - b.lo); }
Iv operator*(Iv a, Iv b) {
  const double p[4] = {a.lo * b.lo, a.lo * b.hi, a.hi * b.lo, a.hi * b.hi};
  return widen(*std::min_element(p, p + 4), *std::max_element(p, p + 4));
}
Iv operator*(double k, Iv a) { return k >= 0.0 ? widen(k * a.lo, k * a.hi) : widen(k * a.hi, k * a.lo); }
int certifiedSign(Iv a) { return a.lo > 0.0 ? 1 : (a.hi < 0.0 ? -1 : 0); }

/// Sign changes of f's coefficients (low to high) with certified signs: the number of positive
/// roots when every root is real (Descartes). f(0) may be uncertified only for a singular quadric
/// (its root at 0 is then not positive); any other uncertified coefficient gives -1.
int positiveRootsBySignChanges(const std::array<double, 5>& f, const std::array<double, 5>& err,
                               const QuadricSurfaceShape& surface) {
  const bool singular = surface.type == QuadricSurfaceType::EllipticCylinder ||
                        surface.type == QuadricSurfaceType::HyperbolicCylinder ||
                        surface.type == QuadricSurfaceType::ParabolicCylinder ||
                        surface.type == QuadricSurfaceType::ParallelPlanes;
  int changes = 0, last = 0;
  for (int k = 0; k <= 4; ++k) {
    const int sign = f[k] > err[k] ? 1 : (f[k] < -err[k] ? -1 : 0);
    if (sign == 0) {
      if (k == 0 && singular) continue;
      return -1;
    }
    if (last != 0 && sign != last) ++changes;
    last = sign;
  }
  return changes;
}

/// Sum of the k x k principal minors of C (Leibniz expansion), with the sum of |terms| computed
/// from |C| and from |C| + E (E: absolute entry error bounds), for a rigorous error bound.
struct MinorSum {
  double value = 0.0, abs = 0.0, abs_perturbed = 0.0;
};
MinorSum principalMinorSum(const Eigen::Matrix4d& C, const Eigen::Matrix4d& E, int k) {
  MinorSum s;
  for (int mask = 0; mask < 16; ++mask) {
    if (__builtin_popcount(static_cast<unsigned>(mask)) != k) continue;
    int idx[4], n = 0;
    for (int i = 0; i < 4; ++i)
      if (mask & (1 << i)) idx[n++] = i;
    int perm[4] = {0, 1, 2, 3};
    do {
      int inversions = 0;
      for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j) inversions += perm[i] > perm[j];
      double term = inversions % 2 ? -1.0 : 1.0, a = 1.0, ap = 1.0;
      for (int i = 0; i < n; ++i) {
        const double c = C(idx[i], idx[perm[i]]);
        term *= c;
        a *= std::fabs(c);
        ap *= std::fabs(c) + E(idx[i], idx[perm[i]]);
      }
      s.value += term;
      s.abs += a;
      s.abs_perturbed += ap;
    } while (std::next_permutation(perm, perm + n));
  }
  return s;
}

}  // namespace

QuadricSurfaceShape classifyQuadricSurface(const Eigen::Matrix4d& Q_in) {
  detail::checkQuadricMatrix(Q_in);
  QuadricSurfaceShape out;
  const double s = Q_in.cwiseAbs().maxCoeff();
  if (!(s > 0.0)) return out;
  const Eigen::Matrix4d Q = Q_in / s;
  const Eigen::Matrix3d Q3 = 0.5 * (Q.topLeftCorner<3, 3>() + Q.topLeftCorner<3, 3>().transpose());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(Q3);
  const Eigen::Vector3d mu = eig.eigenvalues();
  const Eigen::Vector3d l = eig.eigenvectors().transpose() * Q.topRightCorner<3, 1>();
  const double q0 = Q(3, 3);
  const double mu_max = mu.cwiseAbs().maxCoeff();
  if (!(mu_max > kQuadricTypeAmbiguity)) {  // (nearly) no quadratic part
    if (mu_max <= kQuadricTypeRelativeZero && l.norm() > 0.0) out.type = QuadricSurfaceType::Plane;
    return out;
  }
  // Non-zero eigen-directions N (squares completed), zero ones Z (linear term beta).
  int N[3], nN = 0, Z[3], nZ = 0;
  for (int i = 0; i < 3; ++i) {
    const int b = bandSign(mu[i], mu_max);
    if (b == 2) return out;  // too close to a type change
    (b == 0 ? Z[nZ++] : N[nN++]) = i;
  }
  double k = q0, k_scale = std::fabs(q0);
  for (int j = 0; j < nN; ++j) {
    k -= l[N[j]] * l[N[j]] / mu[N[j]];
    k_scale += l[N[j]] * l[N[j]] / std::fabs(mu[N[j]]);
  }
  double beta = 0.0;
  for (int j = 0; j < nZ; ++j) beta += l[Z[j]] * l[Z[j]];
  beta = std::sqrt(beta);
  // beta is compared with sqrt(mu_max |k|) (scale-free: a cylinder of radius r has mu ~ 1/r^2,
  // k ~ -1); k with the magnitude of the terms it was formed from.
  const int k_sign = bandSign(k, k_scale);
  const int beta_band = nZ == 0 ? 0 : bandSign(beta, std::sqrt(mu_max * std::max(std::fabs(k), 0.0)));
  if (beta_band == 2) return out;
  const bool parabolic = nZ > 0 && beta_band != 0;
  if (k_sign == 2 && !parabolic) return out;  // (a paraboloid's k only moves its vertex)
  // Inertia (Sylvester) from the completed squares: each non-zero mu_i, then the constant k, or
  // for a paraboloid the block [[0, beta], [beta, k]] (determinant -beta^2: one of each sign).
  out.positive_eigenvalues = parabolic ? 1 : (k_sign > 0 ? 1 : 0);
  for (int j = 0; j < nN; ++j) out.positive_eigenvalues += mu[N[j]] > 0.0;

  if (nN == 3) {
    if (k_sign == 0) {
      const bool mixed = (mu.minCoeff() < 0.0) && (mu.maxCoeff() > 0.0);
      out.type = mixed ? QuadricSurfaceType::Cone : QuadricSurfaceType::Other;
      return out;
    }
    // sum nu_i y_i^2 = 1 with nu = mu / (-k).
    Eigen::Vector3d nu = mu / (-k);
    std::vector<double> pos, neg;
    for (int i = 0; i < 3; ++i) (nu[i] > 0.0 ? pos : neg).push_back(1.0 / std::sqrt(std::fabs(nu[i])));
    std::sort(pos.begin(), pos.end());
    std::sort(neg.begin(), neg.end());
    if (pos.size() == 3) {  // semi-axes b3 <= b2 <= b1
      out.type = QuadricSurfaceType::Ellipsoid;
      out.max_curvature = pos[2] / (pos[0] * pos[0]);
    } else if (pos.size() == 2) {  // x^2/b1^2 + y^2/b2^2 - z^2/b3^2 = 1: vertices (0, b_max, 0)
      out.type = QuadricSurfaceType::HyperboloidOneSheet;
      out.max_curvature = std::max(pos[1] / (pos[0] * pos[0]), pos[1] / (neg[0] * neg[0]));
    } else if (pos.size() == 1) {  // x^2/b1^2 - y^2/b2^2 - z^2/b3^2 = 1: vertices (+-b1, 0, 0)
      out.type = QuadricSurfaceType::HyperboloidTwoSheets;
      out.max_curvature = pos[0] / (neg[0] * neg[0]);
      out.min_gap = 2.0 * pos[0];
    }
    return out;
  }
  if (nN == 2) {
    const bool same = mu[N[0]] * mu[N[1]] > 0.0;
    if (parabolic) {  // z = -(mu_1 y_1^2 + mu_2 y_2^2 + k) / (2 beta): vertex curvatures |mu_i| / beta
      out.type = same ? QuadricSurfaceType::EllipticParaboloid : QuadricSurfaceType::HyperbolicParaboloid;
      out.max_curvature = std::max(std::fabs(mu[N[0]]), std::fabs(mu[N[1]])) / beta;
      return out;
    }
    if (k_sign == 0) {
      out.type = same ? QuadricSurfaceType::Other : QuadricSurfaceType::IntersectingPlanes;
      return out;
    }
    const double nu0 = mu[N[0]] / (-k), nu1 = mu[N[1]] / (-k);
    if (nu0 > 0.0 && nu1 > 0.0) {
      const double b1 = std::max(1.0 / std::sqrt(nu0), 1.0 / std::sqrt(nu1));
      const double b2 = std::min(1.0 / std::sqrt(nu0), 1.0 / std::sqrt(nu1));
      out.type = QuadricSurfaceType::EllipticCylinder;
      out.max_curvature = b1 / (b2 * b2);
    } else if (nu0 * nu1 < 0.0) {  // x^2/b1^2 - y^2/b2^2 = 1
      const double b1 = 1.0 / std::sqrt(std::max(nu0, nu1)), b2 = 1.0 / std::sqrt(-std::min(nu0, nu1));
      out.type = QuadricSurfaceType::HyperbolicCylinder;
      out.max_curvature = b1 / (b2 * b2);
      out.min_gap = 2.0 * b1;
    }
    return out;
  }
  // nN == 1
  if (parabolic) {
    out.type = QuadricSurfaceType::ParabolicCylinder;
    out.max_curvature = std::fabs(mu[N[0]]) / beta;
    return out;
  }
  const double nu = k_sign == 0 ? 0.0 : mu[N[0]] / (-k);
  if (nu > 0.0) {
    out.type = QuadricSurfaceType::ParallelPlanes;
    out.max_curvature = 0.0;
    out.min_gap = 2.0 / std::sqrt(nu);
  }
  return out;
}

bool isSmall(const Ellipsoid& e, const QuadricSurfaceShape& q) {
  switch (q.type) {
    case QuadricSurfaceType::Cone:
    case QuadricSurfaceType::IntersectingPlanes:
    case QuadricSurfaceType::Plane:
    case QuadricSurfaceType::Other: return false;
    default: break;
  }
  const double a1 = e.radii().maxCoeff(), a3 = e.radii().minCoeff();
  const double kappa_min = a3 / (a1 * a1);  // Lemma 3: the ellipsoid's least normal curvature
  const double m = 1.0 + kSmallnessRelativeMargin;
  return q.max_curvature * m <= kappa_min && 2.0 * a1 * m <= q.min_gap;
}

EllipsoidQuadricResult classifyEllipsoidQuadric(const Ellipsoid& e, const Eigen::Matrix4d& Q_in) {
  EllipsoidQuadricResult r;
  r.surface = classifyQuadricSurface(Q_in);
  r.small = isSmall(e, r.surface);
  constexpr double u = tolerance::kUnitRoundoff;

  // B = M^T Q M in the ellipsoid's unit frame (M = [R S, p; 0 1]), normalised to max |B_ij| = 1.
  const double s = Q_in.cwiseAbs().maxCoeff();
  if (!(s > 0.0)) return r;
  const Eigen::Matrix4d Q = Q_in / s;
  Eigen::Matrix4d M = Eigen::Matrix4d::Identity();
  M.topLeftCorner<3, 3>() = e.rotation() * e.radii().asDiagonal();
  M.topRightCorner<3, 1>() = e.center();
  Eigen::Matrix4d B = M.transpose() * Q * M;
  B = 0.5 * (B + B.transpose());
  const Eigen::Matrix4d absM = M.cwiseAbs(), absQ = Q.cwiseAbs();
  Eigen::Matrix4d E = 24.0 * u * (absM.transpose() * absQ * absM);
  // The solid is { p + R^-T S y : |y| <= 1 }, and the stored R is orthogonal only to
  // delta = kStoredRotationDefect (2^-48, tolerances.h), above 24 u: R^-T - R = R^-T (I - R^T R)
  // has entries below sqrt(3) (1 + delta) delta (the rows of R^-T have 1-norm <= sqrt(3) (1 +
  // delta)), so the solid's map differs from M by |Delta| <= 2 delta N with N_ij = r_j for
  // i, j < 3 (0 elsewhere), a bound that does not vanish where |M| does (R = I). Then
  // |B_solid - B| <= |Delta|^T |Q| |M| + |M|^T |Q| |Delta| + |Delta|^T |Q| |Delta|.
  Eigen::Matrix4d N = Eigen::Matrix4d::Zero();
  N.topLeftCorner<3, 3>().rowwise() = e.radii().transpose();
  const double delta = 2.0 * tolerance::kStoredRotationDefect;
  const Eigen::Matrix4d QN = absQ * N;
  E += delta * (N.transpose() * absQ * absM + absM.transpose() * QN) + (delta * delta) * (N.transpose() * QN);
  const double sb = B.cwiseAbs().maxCoeff();
  if (!(sb > 0.0) || !std::isfinite(sb)) return r;
  B /= sb;
  E = E / sb + u * B.cwiseAbs();

  // det(lambda J - B) = -det(lambda I - C), C = J B: coefficients from the principal minor sums
  // e_k of C (c0 = -e4, c1 = e3, c2 = -e2, c3 = e1, c4 = -1).
  Eigen::Matrix4d C = B, CE = E;
  C.row(3) *= -1.0;
  for (int k = 1; k <= 4; ++k) {
    const MinorSum m = principalMinorSum(C, CE, k);
    const double err = (m.abs_perturbed - m.abs) + (k + 24) * u * m.abs_perturbed;
    const double sign = (k % 2 == 1) ? 1.0 : -1.0;  // e1 -> +c3, e2 -> -c2, e3 -> +c1, e4 -> -c0
    r.f[4 - k] = sign * m.value;
    r.f_error[4 - k] = 2.0 * err;  // factor 2: slack for the first-order perturbation bound
  }
  r.f[4] = -1.0;
  r.f_error[4] = 0.0;

  // Complete discrimination system of a x^4 + b x^3 + c x^2 + d x + e.
  const Iv a = point(r.f[4], r.f_error[4]), b = point(r.f[3], r.f_error[3]), c = point(r.f[2], r.f_error[2]),
           d = point(r.f[1], r.f_error[1]), ee = point(r.f[0], r.f_error[0]);
  const Iv a2 = a * a, a3 = a2 * a, b2 = b * b, b3 = b2 * b, b4 = b2 * b2, c2 = c * c, c3 = c2 * c, c4 = c2 * c2,
           d2 = d * d, d3 = d2 * d, d4 = d2 * d2, e2 = ee * ee, e3 = e2 * ee;
  const Iv disc = 256.0 * (a3 * e3) - 192.0 * (a2 * b * d * e2) - 128.0 * (a2 * c2 * e2) + 144.0 * (a2 * c * d2 * ee) -
                  27.0 * (a2 * d4) + 144.0 * (a * b2 * c * e2) - 6.0 * (a * b2 * d2 * ee) - 80.0 * (a * b * c2 * d * ee) +
                  18.0 * (a * b * c * d3) + 16.0 * (a * c4 * ee) - 4.0 * (a * c3 * d2) - 27.0 * (b4 * e2) +
                  18.0 * (b3 * c * d * ee) - 4.0 * (b3 * d3) - 4.0 * (b2 * c3 * ee) + b2 * c2 * d2;
  const Iv P = 8.0 * (a * c) - 3.0 * b2;
  const Iv D = 64.0 * (a3 * ee) - 16.0 * (a2 * c2) + 16.0 * (a * b2 * c) - 16.0 * (a2 * b * d) - 3.0 * b4;
  r.discriminant_lo = disc.lo;
  r.discriminant_hi = disc.hi;
  const int sd = certifiedSign(disc), sp = certifiedSign(P), sD = certifiedSign(D);
  if (sd < 0) {  // two simple real roots and a non-real pair
    r.relation = EllipsoidQuadricRelation::Transversal;
    return r;
  }
  if (sd > 0 && (sp > 0 || sD > 0)) {  // two non-real pairs (Remark 8: transversal for any pair)
    r.relation = EllipsoidQuadricRelation::Transversal;
    return r;
  }
  if (!(sd > 0 && sp < 0 && sD < 0) || !r.small) return r;
  // Four simple real roots and a small ellipsoid: no contact at all (Theorem 2, Table 3), so the
  // ellipsoid is on one side. Theorem 12 (Table 4, rebuilt in docs/algorithms.md section 11):
  // with every root real, Descartes' rule is exact, so the sign changes of f's coefficients count
  // its positive roots, and that count is n+(Q) + 1 on the side X^T Q X < 0 and n+(Q) - 1 on the
  // other (n+(Q): positive eigenvalues of Q). A coefficient whose sign is not certified is
  // skipped only where it is f(0) of a singular Q (a cylinder's or plane pair's root at 0).
  r.positive_roots = positiveRootsBySignChanges(r.f, r.f_error, r.surface);
  const int n_plus = r.surface.positive_eigenvalues;
  EllipsoidQuadricRelation by_coefficients = EllipsoidQuadricRelation::Undecided;
  if (r.positive_roots >= 0 && n_plus >= 0) {
    if (r.positive_roots == n_plus + 1) by_coefficients = EllipsoidQuadricRelation::Inside;
    else if (r.positive_roots == n_plus - 1) by_coefficients = EllipsoidQuadricRelation::Outside;
  }
  // The centre (0,0,0,1) in the unit frame is on the same side: its certified sign must agree
  // (a disagreement, which only rounding beyond the bounds could cause, is left Undecided).
  const double centre = B(3, 3);
  const EllipsoidQuadricRelation by_centre = centre > E(3, 3)    ? EllipsoidQuadricRelation::Outside
                                             : centre < -E(3, 3) ? EllipsoidQuadricRelation::Inside
                                                                 : EllipsoidQuadricRelation::Undecided;
  if (by_coefficients == by_centre) r.relation = by_coefficients;
  return r;
}

}  // namespace fcl_quadric
