#include "fcl_quadric/geometry/signed_distance.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Dense>

#include "fcl_quadric/tolerances.h"

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

/// An orthonormal basis of the plane orthogonal to the unit vector n.
void tangentBasis(const Eigen::Vector3d& n, Eigen::Vector3d* e1, Eigen::Vector3d* e2) {
  const Eigen::Vector3d helper = std::fabs(n.x()) < 0.6 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  *e1 = (helper - helper.dot(n) * n).normalized();
  *e2 = n.cross(*e1);
}

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
  for (int it = 0; it < tolerance::kMaxDistanceNewtonIterations; ++it) {
    Eigen::Vector3d e1, e2;
    tangentBasis(n, &e1, &e2);
    const Eigen::Vector2d g(e1.dot(grad), e2.dot(grad));
    if (g.norm() <= gtol) return {n, phi, it, true};
    // Riemannian Hessian on the sphere: T^T hess T - (n.grad) I, and n.grad = phi (Euler).
    Eigen::Matrix2d H;
    H << e1.dot(hess * e1) - phi, e1.dot(hess * e2), e2.dot(hess * e1), e2.dot(hess * e2) - phi;
    H = 0.5 * (H + H.transpose());
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(H);
    // Make it negative definite (ascent direction), keeping curvature information.
    Eigen::Vector2d ev = es.eigenvalues();
    const double floor = 1e-3 * std::max(std::fabs(ev[0]), std::fabs(ev[1])) + 1e-300;
    for (int k = 0; k < 2; ++k) ev[k] = -std::max(std::fabs(ev[k]), floor);
    const Eigen::Matrix2d Hneg = es.eigenvectors() * ev.asDiagonal() * es.eigenvectors().transpose();
    Eigen::Vector2d xi = -Hneg.inverse() * g;
    // Trust the step only up to a quarter turn.
    const double len = xi.norm();
    if (len > 0.5) xi *= 0.5 / len;
    // Accept by Armijo, or - near the optimum where phi no longer resolves the increase - by a
    // halved Riemannian gradient at a value no worse than phi up to rounding.
    const double noise = 16.0 * tolerance::kUnitRoundoff * scale;
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
  }
  return {n, phi, tolerance::kMaxDistanceNewtonIterations, false};
}

}  // namespace

SignedDistanceResult signedDistance(const Ellipsoid& a, const Ellipsoid& b, const Eigen::Vector3d* warm_normal) {
  SignedDistanceResult res;
  const SeparationCertificate cert = classifyEllipsoids(a, b);
  res.status = cert.status;

  Objective obj;
  obj.d = b.center() - a.center();
  obj.Ga = a.rotation() * a.radii().cwiseAbs2().asDiagonal() * a.rotation().transpose();
  obj.Gb = b.rotation() * b.radii().cwiseAbs2().asDiagonal() * b.rotation().transpose();
  const double scale = obj.d.norm() + a.maxRadius() + b.maxRadius();

  // Seeds. The certificate's normal is a separating direction when the pair is separate
  // (separating_plane.cpp), so phi > 0 there and the ascent stays in the region
  // where phi is concave: one start suffices. For overlapping pairs the penetration depth can have
  // several local optima: rank many directions by phi and ascend from the best three.
  std::vector<Eigen::Vector3d> seeds;
  if (warm_normal && warm_normal->squaredNorm() > 0.0 && warm_normal->allFinite()) seeds.push_back(*warm_normal);
  if (cert.normal.allFinite()) seeds.push_back(cert.normal);
  int starts = 1;
  if (cert.status != Separation::Separated) {
    starts = 3;
    if (obj.d.squaredNorm() > 0.0) seeds.push_back(obj.d);
    for (const Ellipsoid* e : {&a, &b})
      for (int k = 0; k < 3; ++k) {
        seeds.push_back(e->rotation().col(k));
        seeds.push_back(-e->rotation().col(k));
      }
    for (int sx = -1; sx <= 1; sx += 2)
      for (int sy = -1; sy <= 1; sy += 2)
        for (int sz = -1; sz <= 1; sz += 2) seeds.push_back(Eigen::Vector3d(sx, sy, sz));
  }
  if (seeds.empty()) seeds.push_back(Eigen::Vector3d::UnitX());
  std::vector<std::pair<double, Eigen::Vector3d>> ranked;
  for (const auto& s : seeds) {
    const Eigen::Vector3d n = s.normalized();
    ranked.emplace_back(obj.value(n), n);
  }
  std::stable_sort(ranked.begin(), ranked.end(), [](const auto& x, const auto& y) { return x.first > y.first; });

  LocalMax best{ranked.front().second, -std::numeric_limits<double>::infinity(), 0, false};
  int used = 0;
  for (size_t i = 0; i < ranked.size() && used < starts; ++i) {
    bool duplicate = false;
    for (size_t j = 0; j < i; ++j) duplicate |= ranked[j].second.dot(ranked[i].second) > 1.0 - 1e-9;
    if (duplicate) continue;
    ++used;
    const LocalMax m = ascend(obj, ranked[i].second, scale);
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
