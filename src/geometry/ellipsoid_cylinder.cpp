#include "fcl_quadric/geometry/ellipsoid_cylinder.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include <Eigen/Eigenvalues>

#include "fcl_quadric/geometry/point_ellipsoid.h"
#include "fcl_quadric/geometry/sphere_solid.h"
#include "fcl_quadric/tolerances.h"
#include "algebra/dense_decompositions.h"
#include "geometry/sphere_directions.h"

namespace fcl_quadric {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = 3.14159265358979323846;
/// Newton on a disk term stops within this angle of the axis (see ascend).
constexpr double kPoleAngle = 1e-7;

/// K = conv(D0 u D1): coaxial disks with centres q_i (stored relative to the ellipsoid centre c)
/// and radii r_i. Disk 0 is at local z = -L/2, disk 1 at +L/2.
struct RoundSolid {
  Eigen::Vector3d a, u, v;  // axis and two radial unit vectors (columns of R)
  Eigen::Vector3d dp;       // p - c
  Eigen::Vector3d dq[2];    // q_i - c
  double r[2] = {0.0, 0.0};
  double L = 0.0;
};

struct Problem {
  const Ellipsoid* e = nullptr;
  Eigen::Matrix3d G;  // R S^2 R^T: |S R^T n|^2 = n^T G n
  RoundSolid k;
  double scale = 0.0;  // |p - c| + L + max r_i + largest ellipsoid radius
};

double halfWidth(const Ellipsoid& e, const Eigen::Vector3d& n) {
  return (e.rotation().transpose() * n).cwiseProduct(e.radii()).norm();
}

double radialNorm(const Eigen::Vector3d& a, const Eigen::Vector3d& n) { return (n - n.dot(a) * a).norm(); }

/// phi_i(n) = n.(q_i - c) - |S R^T n| - r_i |Pi n|: minus the supports of E at n and of D_i at -n.
double phiDisk(const Problem& P, int i, const Eigen::Vector3d& n) {
  return n.dot(P.k.dq[i]) - halfWidth(*P.e, n) - P.k.r[i] * radialNorm(P.k.a, n);
}

/// phi(n) = -h_E(n) - h_K(-n) = min(phi_0, phi_1) (h_K = max of the disks' supports).
double phi(const Problem& P, const Eigen::Vector3d& n) { return std::min(phiDisk(P, 0, n), phiDisk(P, 1, n)); }

struct Best {
  double phi = -kInf;
  Eigen::Vector3d n = Eigen::Vector3d::UnitX();
  bool converged = false;
  int iterations = 0;
};

void consider(const Problem& P, const Eigen::Vector3d& n, bool converged, Best* b) {
  if (!n.allFinite()) return;
  const double l = n.norm();
  if (!(l > 0.0)) return;
  const Eigen::Vector3d nn = n / l;
  const double f = phi(P, nn);
  if (f > b->phi) {
    b->phi = f;
    b->n = nn;
    b->converged = converged;
  }
}

/// The smooth function phi_i with its gradient and Hessian in R^3; false at its kink (n parallel
/// to the axis, where a flat cap supports the disk: the pole candidates cover it).
struct DiskObjective {
  const Problem* P;
  int i;

  bool evaluate(const Eigen::Vector3d& n, double* f, Eigen::Vector3d* grad, Eigen::Matrix3d* hess) const {
    const Eigen::Vector3d w = P->G * n;
    const double s = std::sqrt(std::max(n.dot(w), 0.0));
    if (!(s > 0.0)) return false;
    double val = n.dot(P->k.dq[i]) - s;
    *grad = P->k.dq[i] - w / s;
    *hess = -(P->G / s - w * w.transpose() / (s * s * s));
    const double r = P->k.r[i];
    if (r > 0.0) {
      const Eigen::Vector3d& a = P->k.a;
      const Eigen::Vector3d m = n - n.dot(a) * a;
      const double t = m.norm();
      if (!(t > 1e-12 * n.norm())) return false;
      val -= r * t;
      *grad -= (r / t) * m;
      *hess -= r * ((Eigen::Matrix3d::Identity() - a * a.transpose()) / t - m * m.transpose() / (t * t * t));
    }
    *f = val;
    return true;
  }
};

using detail::tangentBasis;

struct DiskLocalMax {
  Eigen::Vector3d n;
  int iterations = 0;
  bool converged = false;
};

/// Riemannian Newton ascent of phi_i on the unit sphere (the iteration of signed_distance.cpp:
/// modified Hessian where phi_i is not locally concave, steps capped at a quarter turn, Armijo
/// backtracking). At most round_solid::kMaxNewtonIterations steps; the best iterate is returned.
DiskLocalMax ascend(const DiskObjective& obj, Eigen::Vector3d n, double scale) {
  n.normalize();
  double f;
  Eigen::Vector3d grad;
  Eigen::Matrix3d hess;
  if (!obj.evaluate(n, &f, &grad, &hess)) return {n, 0, false};
  const double gtol = tolerance::kDistanceGradientTolerance * scale;
  const double noise = 16.0 * tolerance::kUnitRoundoff * scale;
  for (int it = 0; it < round_solid::kMaxNewtonIterations; ++it) {
    Eigen::Vector3d e1, e2;
    tangentBasis(n, &e1, &e2);
    const Eigen::Vector2d g(e1.dot(grad), e2.dot(grad));
    if (g.norm() <= gtol) return {n, it, true};
    // Drawn into the cap's kink: the pole candidate is exact there, and an optimum this close to
    // the pole (angle < kPoleAngle) is worth less than kPoleAngle^2 relative over the pole.
    if (obj.P->k.r[obj.i] > 0.0 && radialNorm(obj.P->k.a, n) < kPoleAngle) return {n, it, false};
    const Eigen::Vector3d he1 = hess * e1, he2 = hess * e2;
    const double h11 = e1.dot(he1) - f, h22 = e2.dot(he2) - f, h12 = 0.5 * (e1.dot(he2) + e2.dot(he1));
    const double hd = 0.5 * (h11 - h22);
    const double mean = 0.5 * (h11 + h22), half = std::sqrt(hd * hd + h12 * h12);
    double l1 = mean - half, l2 = mean + half;
    const double floor = 1e-3 * std::max(std::fabs(l1), std::fabs(l2)) + 1e-300;
    Eigen::Vector2d xi;
    if (l2 < -floor) {
      const double det = h11 * h22 - h12 * h12;
      xi = Eigen::Vector2d(-(h22 * g[0] - h12 * g[1]) / det, -(-h12 * g[0] + h11 * g[1]) / det);
    } else {
      Eigen::Vector2d v1 = std::fabs(h11 - l1) > std::fabs(h22 - l1) ? Eigen::Vector2d(h12, l1 - h11)
                                                                    : Eigen::Vector2d(l1 - h22, h12);
      if (!(v1.squaredNorm() > 0.0)) v1 = Eigen::Vector2d(1.0, 0.0);
      v1.normalize();
      const Eigen::Vector2d v2(-v1[1], v1[0]);
      l1 = -std::max(std::fabs(l1), floor);
      l2 = -std::max(std::fabs(l2), floor);
      xi = -(v1 * (v1.dot(g) / l1) + v2 * (v2.dot(g) / l2));
    }
    if (!xi.allFinite()) return {n, it + 1, false};
    const double len = xi.norm();
    if (len > 0.5) xi *= 0.5 / len;
    bool accepted = false;
    for (int bt = 0; bt < 40 && xi.norm() > 1e-17; ++bt, xi *= 0.5) {
      const Eigen::Vector3d cand = (n + xi[0] * e1 + xi[1] * e2).normalized();
      double fc;
      Eigen::Vector3d cgrad;
      Eigen::Matrix3d chess;
      if (!obj.evaluate(cand, &fc, &cgrad, &chess)) continue;
      const double cg = (cgrad - cgrad.dot(cand) * cand).norm();
      if (fc >= f + 1e-4 * g.dot(xi) || (cg <= 0.5 * g.norm() && fc >= f - noise)) {
        n = cand;
        f = fc;
        grad = cgrad;
        hess = chess;
        accepted = true;
        break;
      }
    }
    if (!accepted) return {n, it + 1, g.norm() <= 1e3 * gtol};
  }
  return {n, round_solid::kMaxNewtonIterations, false};
}

/// Seed directions of the penetration-depth ascent: 40 of a Fibonacci lattice.
const std::array<Eigen::Vector3d, 40>& diskSeedDirections() {
  static const std::array<Eigen::Vector3d, 40> grid = detail::fibonacciLattice<40>();
  return grid;
}

void sideCandidatesCone(const Problem& P, Best* best);

/// Cylinder side (r0 = r1): for n orthogonal to the axis phi = n.(p - c) - |S R^T n| - r, the
/// point-ellipse problem of the projected axis against the ellipsoid's shadow on the plane
/// orthogonal to a.
void sideCandidatesCylinder(const Problem& P, Best* best) {
  const RoundSolid& k = P.k;
  Eigen::Matrix<double, 3, 2> B;
  B << k.u, k.v;
  const Eigen::Matrix2d G2 = B.transpose() * P.G * B;
  const detail::SymmetricEigen2 es = detail::selfAdjointEigen(G2);
  const Eigen::Vector2d radii = es.values.cwiseMax(0.0).cwiseSqrt();
  if (!(radii.minCoeff() > 0.0)) return;
  const Eigen::Vector2d y = es.vectors.transpose() * (B.transpose() * k.dp);
  // Restricted to this circle phi is the 2D signed distance minus r, whose maximum is attained at
  // the closest point of the shadow's boundary (inside or outside): one candidate suffices.
  Eigen::Vector2d x;
  detail::closestPointPrincipal<2>(radii, y, &x);
  consider(P, B * (es.vectors * x.cwiseQuotient(radii.cwiseAbs2())), true, best);
}

/// Cone (frustum) side (r0 != r1): both disks support K at -n exactly on the circle of directions
/// n(t) = sb w(t) + cb a, w(t) = cos t u + sin t v, cb = (r1 - r0)/hyp, sb = L/hyp; there
/// phi = F(t) = n.(q0 - c) - |S R^T n| - r0 sb. Local maxima of F: sign changes (+ to -) of F' on
/// kConeSideSamples samples, refined by safeguarded Newton.
void sideCandidatesCone(const Problem& P, Best* best) {
  const RoundSolid& k = P.k;
  const double hyp = std::hypot(k.L, k.r[1] - k.r[0]);
  const double sb = k.L / hyp, cb = (k.r[1] - k.r[0]) / hyp;
  auto dir = [&](double t) { return Eigen::Vector3d(sb * (std::cos(t) * k.u + std::sin(t) * k.v) + cb * k.a); };
  // F'(t) and F''(t).
  auto derivs = [&](double t, double* d2) {
    const double ct = std::cos(t), st = std::sin(t);
    const Eigen::Vector3d w = ct * k.u + st * k.v, wp = -st * k.u + ct * k.v;
    const Eigen::Vector3d n = sb * w + cb * k.a, n1 = sb * wp, n2 = -sb * w;
    const Eigen::Vector3d Gn = P.G * n;
    const double s = std::sqrt(std::max(n.dot(Gn), 1e-300));
    const double g1 = n1.dot(Gn);
    *d2 = n2.dot(k.dq[0]) - (n2.dot(Gn) + n1.dot(P.G * n1)) / s + g1 * g1 / (s * s * s);
    return n1.dot(k.dq[0]) - g1 / s;
  };
  constexpr int K = round_solid::kConeSideSamples;
  double dval[K + 1];
  double dummy;
  for (int j = 0; j <= K; ++j) dval[j] = derivs(2.0 * kPi * j / K, &dummy);
  for (int j = 0; j < K; ++j) {
    if (!(dval[j] >= 0.0 && dval[j + 1] <= 0.0)) continue;  // a sample may sit on the maximum
    double lo = 2.0 * kPi * j / K, hi = 2.0 * kPi * (j + 1) / K;  // F'(lo) > 0 >= F'(hi)
    double t = 0.5 * (lo + hi);
    for (int it = 0; it < round_solid::kMaxConeSideIterations && hi - lo > 1e-15; ++it) {
      double d2;
      const double d1 = derivs(t, &d2);
      if (d1 == 0.0) break;
      if (d1 > 0.0) lo = t; else hi = t;
      double next = d2 < 0.0 ? t - d1 / d2 : 0.5 * (lo + hi);
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
      if (std::fabs(next - t) <= 1e-16) break;
      t = next;
    }
    consider(P, dir(t), true, best);
  }
}

/// Every critical point of phi_i for a disk of radius 0 (a point q): the normals at the critical
/// points of the distance from q to the ellipsoid's surface (point_ellipsoid.h).
void pointCandidates(const Problem& P, const Eigen::Vector3d& dq, Best* best) {
  const Ellipsoid& e = *P.e;
  const Eigen::Vector3d y = e.rotation().transpose() * dq;
  Eigen::Vector3d xs[8];
  const int n = detail::criticalPointsPrincipal<3>(e.radii(), y, xs, 8);
  for (int i = 0; i < n; ++i) consider(P, e.rotation() * xs[i].cwiseQuotient(e.radii().cwiseAbs2()), true, best);
}

/// Newton on phi_i (for a point, r_i = 0, it backs up the exact candidates), from the `starts` best distinct seeds that lie in
/// the region where disk i supports K (phi_i <= phi_j).
void newtonCandidates(const Problem& P, int starts, Best* best) {
  const RoundSolid& k = P.k;
  std::array<Eigen::Vector3d, 72> seeds;  // at most 65 used
  int ns = 0;
  auto add = [&](const Eigen::Vector3d& s) {
    if (ns >= static_cast<int>(seeds.size()) || !s.allFinite()) return;
    const double l = s.norm();
    if (l > 0.0) seeds[ns++] = s / l;
  };
  add(best->n);
  add(k.dp);
  add(k.dq[0]);
  add(k.dq[1]);
  const Eigen::Vector3d rad = k.dp - k.dp.dot(k.a) * k.a;
  if (rad.norm() > 1e-9 * P.scale) {
    const Eigen::Vector3d rn = rad.normalized();
    add(rn);
    add(rn + k.a);
    add(rn - k.a);
    add(rn + 0.1 * k.a);
    add(rn - 0.1 * k.a);
  }
  add(k.a + 0.1 * k.u);
  add(-k.a + 0.1 * k.u);
  for (int j = 0; j < 3; ++j) {
    add(P.e->rotation().col(j));
    add(-P.e->rotation().col(j));
  }
  if (starts > 2)
    for (const Eigen::Vector3d& g : diskSeedDirections()) add(g);  // penetration depth: more basins
  const bool same_disk = k.L == 0.0 && k.r[0] == k.r[1];
  const int base_seeds = ns;
  for (int i = 0; i < 2; ++i) {
    if (same_disk && i == 1) continue;
    const DiskObjective obj{&P, i};
    // Escape seeds: off each pole along the tangential gradient of phi_i's smooth part. Newton
    // started on the wrong side of a pole is drawn into the kink (where the cap candidate is exact
    // but the true optimum may lie just off it).
    ns = base_seeds;
    for (double sg : {1.0, -1.0}) {
      const Eigen::Vector3d n0 = sg * k.a, w = P.G * n0;
      const Eigen::Vector3d gs = k.dq[i] - w / std::sqrt(n0.dot(w));
      const Eigen::Vector3d gt = gs - gs.dot(k.a) * k.a;
      const double gn = gt.norm();
      if (!(gn > 0.0)) continue;
      for (double tau : {1e-3, 0.02, 0.2, 0.7}) add(n0 + (tau / gn) * gt);
    }
    std::array<double, 72> value;
    for (int s = 0; s < ns; ++s) {
      const double fi = phiDisk(P, i, seeds[s]), fj = phiDisk(P, 1 - i, seeds[s]);
      // Seeds where disk i supports K, off its kink (a pole is a start Newton cannot leave).
      const bool kink = k.r[i] > 0.0 && radialNorm(k.a, seeds[s]) <= 1e-9;
      value[s] = (fi <= fj || same_disk) && !kink ? fi : -kInf;
    }
    std::array<int, 8> picked{};
    int npicked = 0;
    for (int used = 0; used < starts; ++used) {
      int pick = -1;
      for (int s = 0; s < ns; ++s) {
        if (value[s] == -kInf) continue;
        bool near = false;
        for (int j = 0; j < npicked && !near; ++j) near = seeds[s].dot(seeds[picked[j]]) > 0.8;
        if (!near && (pick < 0 || value[s] > value[pick])) pick = s;
      }
      if (pick < 0) break;
      picked[npicked++] = pick;
      const DiskLocalMax m = ascend(obj, seeds[pick], P.scale);
      best->iterations += m.iterations;
      consider(P, m.n, m.converged, best);
    }
  }
}

/// min over K of |S^-1 R^T (y - c)|^2 (convex): golden section on the axial parameter t in [0, 1]
/// of the trust-region problem on the disk section at t (radius r0 + (r1 - r0) t).
struct Witness {
  double f = kInf;       // the minimum found (unit-frame squared norm)
  double bound = 0.0;    // certified rounding bound of f
  Eigen::Vector3d y_rel = Eigen::Vector3d::Zero();  // the point minus c
  int iterations = 0;
};

Witness ellipsoidMinimumOverSolid(const Problem& P) {
  const Ellipsoid& e = *P.e;
  const RoundSolid& k = P.k;
  const Eigen::Matrix3d M = e.inverseRadii().asDiagonal() * e.rotation().transpose();
  const Eigen::Vector3d g = M * k.dp, b = M * k.a;
  Eigen::Matrix<double, 3, 2> A;
  A << M * k.u, M * k.v;
  const detail::SymmetricEigen2 es = detail::selfAdjointEigen(A.transpose() * A);
  const Eigen::Vector2d h = es.values;
  const Eigen::Matrix2d Q = es.vectors;
  Witness W;
  auto section = [&](double t, Eigen::Vector2d* xi) {
    const double z = k.L * (t - 0.5);
    const double rho = std::max(0.0, k.r[0] + (k.r[1] - k.r[0]) * t);
    const Eigen::Vector3d w = g + z * b;
    const Eigen::Vector2d c = Q.transpose() * (A.transpose() * w);
    Eigen::Vector2d x(-c[0] / h[0], -c[1] / h[1]);  // unconstrained minimiser, eigenbasis
    double xn = x.norm();
    if (!(rho > 0.0)) {
      x.setZero();
    } else if (xn > rho) {
      // Secular equation |x(lambda)| = rho, x(lambda) = -(h + lambda)^-1 c (More-Sorensen Newton on
      // 1/|x| - 1/rho, monotone from lambda = 0).
      double lam = 0.0;
      for (int it = 0; it < round_solid::kMaxWitnessRadialIterations; ++it) {
        ++W.iterations;
        const double d0 = h[0] + lam, d1 = h[1] + lam;
        const double q2 = c[0] * c[0] / (d0 * d0 * d0) + c[1] * c[1] / (d1 * d1 * d1);
        if (std::fabs(xn - rho) <= 4.0 * tolerance::kUnitRoundoff * rho || !(q2 > 0.0)) break;
        const double step = (xn / rho - 1.0) * xn * xn / q2;
        if (!(step > 0.0) || !std::isfinite(step)) break;
        lam += step;
        x = Eigen::Vector2d(-c[0] / (h[0] + lam), -c[1] / (h[1] + lam));
        xn = x.norm();
      }
      if (xn > 0.0) x *= (rho / xn) * (1.0 - 4.0 * tolerance::kUnitRoundoff);  // on or inside the disk
    }
    *xi = Q * x;
    return (w + A * *xi).squaredNorm();
  };
  double best_t = 0.0;
  Eigen::Vector2d best_xi = Eigen::Vector2d::Zero();
  auto eval = [&](double t) {
    Eigen::Vector2d xi;
    const double f = section(t, &xi);
    if (f < W.f) {
      W.f = f;
      best_t = t;
      best_xi = xi;
    }
    return f;
  };
  eval(0.0);
  eval(1.0);
  if (k.L > 0.0 || k.r[0] != k.r[1]) {
    const double ratio = 0.6180339887498949;
    double lo = 0.0, hi = 1.0;
    double x1 = hi - ratio * (hi - lo), x2 = lo + ratio * (hi - lo);
    double f1 = eval(x1), f2 = eval(x2);
    for (int it = 0; it < round_solid::kMaxWitnessAxialIterations && hi - lo > 1e-17; ++it) {
      if (f1 <= f2) {
        hi = x2;
        x2 = x1;
        f2 = f1;
        x1 = hi - ratio * (hi - lo);
        f1 = eval(x1);
      } else {
        lo = x1;
        x1 = x2;
        f1 = f2;
        x2 = lo + ratio * (hi - lo);
        f2 = eval(x2);
      }
    }
  }
  W.y_rel = k.dp + k.L * (best_t - 0.5) * k.a + best_xi[0] * k.u + best_xi[1] * k.v;
  // Rounding bound: every quantity is a few operations on unit-frame magnitudes <= s_u, plus the
  // absolute rounding eta of the unit-frame map M = S^-1 R^T of the world vectors dp, z a, xi u,
  // xi v (~6u |.|_1 / r_j, which a thin ellipsoid's small radius magnifies and s_u does not
  // bound; tolerances.h, kUnitFrameRoundingBound): f = |y|^2 moves by at most 2 |y| sqrt(3) eta.
  const double s_u = g.norm() + std::sqrt(h.cwiseAbs().sum()) * std::max(k.r[0], k.r[1]) + b.norm() * 0.5 * k.L;
  const double world_l1 = k.dp.cwiseAbs().sum() + 0.5 * k.L * k.a.cwiseAbs().sum() +
                          std::max(k.r[0], k.r[1]) * (k.u.cwiseAbs().sum() + k.v.cwiseAbs().sum());
  const double eta = detail::unitFrameRounding(e, world_l1);
  W.bound = tolerance::kCertificateRelativeBoundDouble * (1.0 + s_u) * (1.0 + s_u) + 4.0 * (1.0 + s_u) * eta;
  return W;
}

void runCandidates(const Problem& P, int starts, Best* best) {
  const RoundSolid& k = P.k;
  consider(P, k.a, true, best);
  consider(P, -k.a, true, best);
  if (k.L > 0.0) {
    if (k.r[0] == k.r[1]) sideCandidatesCylinder(P, best);
    else sideCandidatesCone(P, best);
  }
  for (int i = 0; i < 2; ++i)
    if (!(k.r[i] > 0.0)) pointCandidates(P, k.dq[i], best);
  newtonCandidates(P, starts, best);
}

SignedDistanceResult solve(const Ellipsoid& e, const RoundSolid& k) {
  Problem P;
  P.e = &e;
  P.G = e.rotation() * e.radii().cwiseAbs2().asDiagonal() * e.rotation().transpose();
  P.k = k;
  P.scale = k.dp.norm() + k.L + std::max(k.r[0], k.r[1]) + e.maxRadius();
  const double band = tolerance::kCertificateRelativeBoundDouble * P.scale;

  Best best;
  runCandidates(P, 2, &best);
  Separation status = Separation::Touching;
  if (best.phi > band) {
    status = Separation::Separated;  // certified: phi(n) > its rounding bound
  } else {
    const Witness W = ellipsoidMinimumOverSolid(P);
    best.iterations += W.iterations;
    if (W.f < 1.0 - W.bound) status = Separation::Overlapping;  // a point of K strictly inside E
    // Penetration depth (or an uncertain pair): several starts per disk, keep the best.
    runCandidates(P, round_solid::kPenetrationStarts, &best);
    if (status != Separation::Overlapping && best.phi > band) status = Separation::Separated;
  }

  SignedDistanceResult res;
  res.status = status;
  res.normal = best.n;
  res.iterations = best.iterations;
  res.converged = best.converged;
  res.point_a = e.supportPoint(best.n);
  const double f = std::isfinite(best.phi) ? best.phi : 0.0;
  switch (status) {
    case Separation::Separated: res.distance = f; break;
    case Separation::Overlapping: res.distance = std::min(f, 0.0); break;
    case Separation::Touching: res.distance = 0.0; break;
  }
  res.point_b = res.point_a + f * best.n;
  return res;
}

RoundSolid validated(const char* what, const Ellipsoid& e, double radius, double length, const Eigen::Matrix3d& R,
                     const Eigen::Vector3d& p) {
  const std::string w(what);
  detail::checkLength(radius, what, "radius");
  detail::checkLength(length, what, "length");
  // As for Ellipsoid: the supports r |n - (n.a) a| treat (u, v, a) as orthonormal and the witness
  // parametrises the solid by them, so both describe the stored rotation.
  const Eigen::Matrix3d Rs = detail::storedRotation(R, (w + " rotation").c_str());
  detail::checkPosition(p, (w + " centre").c_str());
  RoundSolid k;
  k.u = Rs.col(0);
  k.v = Rs.col(1);
  k.a = Rs.col(2);
  k.dp = p - e.center();
  k.L = length;
  k.dq[0] = k.dp - (0.5 * length) * k.a;
  k.dq[1] = k.dp + (0.5 * length) * k.a;
  return k;
}

}  // namespace

SignedDistanceResult signedDistanceEllipsoidCylinder(const Ellipsoid& e, double radius, double length,
                                                     const Eigen::Matrix3d& R_WC, const Eigen::Vector3d& p_WC) {
  if (isSphere(e)) return signedDistanceSphereCylinder(e.center(), e.radii()[0], radius, length, R_WC, p_WC);
  RoundSolid k = validated("cylinder", e, radius, length, R_WC, p_WC);
  k.r[0] = k.r[1] = radius;
  return solve(e, k);
}

SignedDistanceResult signedDistanceEllipsoidCone(const Ellipsoid& e, double radius, double length,
                                                 const Eigen::Matrix3d& R_WC, const Eigen::Vector3d& p_WC) {
  if (isSphere(e)) return signedDistanceSphereCone(e.center(), e.radii()[0], radius, length, R_WC, p_WC);
  RoundSolid k = validated("cone", e, radius, length, R_WC, p_WC);
  k.r[0] = radius;  // base at z = -L/2
  k.r[1] = 0.0;     // apex at z = +L/2
  return solve(e, k);
}

}  // namespace fcl_quadric
