#include "fcl_quadric/geometry/signed_distance.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>


#include <Eigen/Eigenvalues>

#include "fcl_quadric/tolerances.h"
#include "geometry/sphere_directions.h"

namespace fcl_quadric {

namespace {

/// phi(n) = n.d - |P_a n| - |P_b n| = -h_a(n) - h_b(-n) + n.(p_b - p_a) ... with d = p_b - p_a and
/// |P n|^2 = n^T G n, G = R S^2 R^T. phi is concave and positively homogeneous of degree 1.
struct Objective {
  Eigen::Vector3d d;
  Eigen::Matrix3d Ga, Gb;

  double value(const Eigen::Vector3d& n) const {
    return n.dot(d) - std::sqrt(n.dot(Ga * n)) - std::sqrt(n.dot(Gb * n));
  }

  /// Value, gradient and Hessian in R^3.
  double evaluate(const Eigen::Vector3d& n, Eigen::Vector3d* grad, Eigen::Matrix3d* hess) const {
    const Eigen::Vector3d wa = Ga * n, wb = Gb * n;
    const double na = std::sqrt(n.dot(wa)), nb = std::sqrt(n.dot(wb));
    *grad = d - wa / na - wb / nb;
    *hess = -(Ga / na - wa * wa.transpose() / (na * na * na)) - (Gb / nb - wb * wb.transpose() / (nb * nb * nb));
    return n.dot(d) - na - nb;
  }
};

/// kGridDirections directions of a Fibonacci lattice and their antipodes (seeds for the
/// penetration depth). phi_ba(n) = phi_ab(-n), so an antipodally symmetric set searches the same
/// directions in both argument orders.
constexpr int kGridDirections = 96;
const std::array<Eigen::Vector3d, 2 * kGridDirections>& sphereGrid() {
  static const std::array<Eigen::Vector3d, 2 * kGridDirections> grid = [] {
    const std::array<Eigen::Vector3d, kGridDirections> lattice = detail::fibonacciLattice<kGridDirections>();
    std::array<Eigen::Vector3d, 2 * kGridDirections> g;
    for (int i = 0; i < kGridDirections; ++i) {
      g[2 * i] = lattice[i];
      g[2 * i + 1] = -lattice[i];
    }
    return g;
  }();
  return grid;
}

using detail::tangentBasis;

struct LocalMax {
  Eigen::Vector3d n;
  double phi;
  int iterations;
  bool converged;
};

/// Riemannian Newton ascent of phi on the unit sphere from n0, with a modified Hessian where phi is
/// not locally concave and Armijo backtracking; at most tolerance::kMaxDistanceNewtonIterations
/// steps. On reaching the cap the best iterate is returned with converged = false.
LocalMax ascend(const Objective& obj, Eigen::Vector3d n, double scale) {
  n.normalize();
  Eigen::Vector3d grad;
  Eigen::Matrix3d hess;
  double phi = obj.evaluate(n, &grad, &hess);
  const double gtol = tolerance::kDistanceGradientTolerance * scale;
  int stalled = 0;  // accepted steps in a row that gained at most `noise`
  for (int it = 0; it < tolerance::kMaxDistanceNewtonIterations; ++it) {
    Eigen::Vector3d e1, e2;
    tangentBasis(n, &e1, &e2);
    const Eigen::Vector2d g(e1.dot(grad), e2.dot(grad));
    if (g.norm() <= gtol) return {n, phi, it, true};
    // Riemannian Hessian on the sphere: T^T hess T - (n.grad) I, and n.grad = phi (Euler).
    const Eigen::Vector3d he1 = hess * e1, he2 = hess * e2;
    const double h11 = e1.dot(he1) - phi, h22 = e2.dot(he2) - phi, h12 = 0.5 * (e1.dot(he2) + e2.dot(he1));
    // Closed-form eigenvalues of the symmetric 2x2. Negative definite (phi locally concave, which
    // holds wherever phi > 0): the Newton step, however ill-conditioned; the trust region below
    // bounds it. Otherwise make the matrix negative definite (an ascent direction) by mirroring
    // positive eigenvalues and flooring small ones at 1e-3 of the largest. (Until session 38 that
    // floor applied to concave Hessians too: with eigenvalues -1.07e5 and -1.52, a thin pair's
    // step along the flat direction was 1/70 of Newton's, and the ascent stopped at its cap 2%
    // short of the distance.)
    const double hd = 0.5 * (h11 - h22);
    const double mean = 0.5 * (h11 + h22), half = std::sqrt(hd * hd + h12 * h12);
    double l1 = mean - half, l2 = mean + half;  // l1 <= l2
    const double det = h11 * h22 - h12 * h12;
    Eigen::Vector2d xi;
    if (l2 < -1e-12 * std::fabs(l1) && det > 0.0) {  // Newton step -H^-1 g
      xi = Eigen::Vector2d(-(h22 * g[0] - h12 * g[1]) / det, -(-h12 * g[0] + h11 * g[1]) / det);
    } else {
      // eigenvector of l1: (h12, l1 - h11) or (l1 - h22, h12), whichever is better conditioned.
      Eigen::Vector2d v1 = std::fabs(h11 - l1) > std::fabs(h22 - l1) ? Eigen::Vector2d(h12, l1 - h11)
                                                                    : Eigen::Vector2d(l1 - h22, h12);
      if (v1.squaredNorm() == 0.0) v1 = Eigen::Vector2d(1.0, 0.0);
      v1.normalize();
      const Eigen::Vector2d v2(-v1[1], v1[0]);
      const double floor = 1e-3 * std::max(std::fabs(l1), std::fabs(l2)) + 1e-300;
      l1 = -std::max(std::fabs(l1), floor);
      l2 = -std::max(std::fabs(l2), floor);
      xi = -(v1 * (v1.dot(g) / l1) + v2 * (v2.dot(g) / l2));
    }
    // Trust the step only up to a quarter turn.
    const double len = xi.norm();
    if (len > 0.5) xi *= 0.5 / len;
    // Accept by Armijo, or - near the optimum where phi no longer resolves the increase - by a
    // halved Riemannian gradient at a value no worse than phi up to rounding.
    const double noise = 16.0 * tolerance::kUnitRoundoff * scale;
    const double phi_before = phi;
    bool accepted = false;
    for (int bt = 0; bt < 40 && xi.norm() > 1e-17; ++bt, xi *= 0.5) {
      const Eigen::Vector3d cand = (n + xi[0] * e1 + xi[1] * e2).normalized();
      Eigen::Vector3d cgrad;
      Eigen::Matrix3d chess;
      const double phic = obj.evaluate(cand, &cgrad, &chess);
      const double cg = (cgrad - cgrad.dot(cand) * cand).norm();
      if (phic >= phi + 1e-4 * g.dot(xi) || (cg <= 0.5 * g.norm() && phic >= phi - noise)) {
        n = cand;
        phi = phic;
        grad = cgrad;
        hess = chess;
        accepted = true;
        break;
      }
    }
    if (!accepted) return {n, phi, it + 1, g.norm() <= 1e3 * gtol};
    // At the rounding floor phi no longer resolves the gradient: steps are accepted as "no worse up
    // to rounding" and the ascent ran to its cap (near-tangent thin pairs, ~25 us each; finding
    // 33). tolerance::kDistanceStallSteps steps in a row that gain at most `noise` each end it,
    // converged as at a failed backtracking. Measured on the signed distance audit's sets: the
    // same errors, worst times 450-610 us -> 44-88 us.
    stalled = phi - phi_before <= noise ? stalled + 1 : 0;
    if (stalled >= tolerance::kDistanceStallSteps) return {n, phi, it + 1, g.norm() <= 1e3 * gtol};
  }
  return {n, phi, tolerance::kMaxDistanceNewtonIterations, false};
}

}  // namespace

SignedDistanceResult signedDistance(const Ellipsoid& a, const Ellipsoid& b, const Eigen::Vector3d* warm_normal) {
  return signedDistance(a, b, classifyEllipsoids(a, b), warm_normal);
}

SignedDistanceResult signedDistance(const Ellipsoid& a, const Ellipsoid& b, const SeparationCertificate& cert,
                                    const Eigen::Vector3d* warm_normal) {
  SignedDistanceResult res;
  res.status = cert.status;

  Objective obj;
  obj.d = b.center() - a.center();
  obj.Ga = a.rotation() * a.radii().cwiseAbs2().asDiagonal() * a.rotation().transpose();
  obj.Gb = b.rotation() * b.radii().cwiseAbs2().asDiagonal() * b.rotation().transpose();
  const double scale = obj.d.norm() + a.maxRadius() + b.maxRadius();

  // Seeds. The certificate's normal is a separating direction when the pair is separate
  // (separating_plane.cpp), so phi > 0 there and the ascent stays in the region
  // where phi is concave: one start suffices. For overlapping pairs the penetration depth can have
  // several local optima: rank many directions by phi and ascend from the best kDepthStarts that
  // lie ~37 degrees apart. Until session 38 these were 3 starts from 40 grid directions, which an
  // audit found stuck in a local optimum in 1-2 of 3,000 overlapping pairs of aspect ratio up to
  // 100 and ~0.5% of deep overlaps up to 1000 (3% too deep at aspect 5 and 19; the two argument
  // orders disagreed); SignedDistance.PenetrationDepthOfTheAuditsPairsIsTheGlobalOptimum.
  constexpr int kDepthStarts = 6;
  constexpr int kMaxSeeds = 2 * kGridDirections + 24;  // the grid and at most 21 other directions
  std::array<Eigen::Vector3d, kMaxSeeds> seeds;
  int nseeds = 0;
  auto add = [&](const Eigen::Vector3d& v) { seeds[nseeds++] = v; };
  if (warm_normal && warm_normal->squaredNorm() > 0.0 && warm_normal->allFinite()) add(*warm_normal);
  if (cert.normal.allFinite()) add(cert.normal);
  int starts = 1;
  if (cert.status != Separation::Separated) {
    starts = kDepthStarts;
    if (obj.d.squaredNorm() > 0.0) add(obj.d);
    for (const Ellipsoid* e : {&a, &b})
      for (int k = 0; k < 3; ++k) {
        add(e->rotation().col(k));
        add(-e->rotation().col(k));
      }
    // Principal axes of the summed shape G_a + G_b, and a uniform spherical grid.
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(obj.Ga + obj.Gb);
    for (int k = 0; k < 3; ++k) {
      add(es.eigenvectors().col(k));
      add(-es.eigenvectors().col(k));
    }
    for (const Eigen::Vector3d& g : sphereGrid()) add(g);
  }
  if (nseeds == 0) add(Eigen::Vector3d::UnitX());
  // Rank the seeds by phi and ascend from the best `starts` distinct ones (selection, no sort).
  std::array<double, kMaxSeeds> value;
  for (int i = 0; i < nseeds; ++i) {
    seeds[i].normalize();
    value[i] = obj.value(seeds[i]);
  }
  LocalMax best{seeds[0], -std::numeric_limits<double>::infinity(), 0, false};
  // Starts are the best-ranked seeds that are not within ~37 degrees of an earlier start, so that
  // they tend to lie in different basins of phi.
  std::array<int, kDepthStarts> picked{};
  int npicked = 0;
  for (int used = 0; used < starts; ++used) {
    int pick = -1;
    for (int i = 0; i < nseeds; ++i) {
      bool near = false;
      for (int j = 0; j < npicked && !near; ++j) near = seeds[i].dot(seeds[picked[j]]) > 0.8;
      if (!near && (pick < 0 || value[i] > value[pick])) pick = i;
    }
    if (pick < 0) break;
    picked[npicked++] = pick;
    const LocalMax m = ascend(obj, seeds[pick], scale);
    res.iterations += m.iterations;
    if (m.phi > best.phi) best = m;
  }

  const Eigen::Vector3d n = best.n;
  res.normal = n;
  res.converged = best.converged;
  res.point_a = a.supportPoint(n);
  res.point_b = b.supportPoint(-n);
  // The algebraic classification decides the sign (touching band: distance 0).
  switch (cert.status) {
    case Separation::Separated: res.distance = std::max(best.phi, 0.0); break;
    case Separation::Overlapping: res.distance = std::min(best.phi, 0.0); break;
    case Separation::Touching: res.distance = 0.0; break;
  }
  return res;
}

}  // namespace fcl_quadric
