#include "fcl_quadric/geometry/ellipsoid_polytope.h"

#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <Eigen/Dense>

#include "fcl_quadric/tolerances.h"

namespace fcl_quadric {

namespace {

/// Least squares on the free coordinates: minimise |r + G_F s_F| (G_F = the columns in `free`).
/// Returns false if the reduced normal matrix is singular (a degenerate face).
template <int N>
bool reducedLeastSquares(const Eigen::Matrix<double, 3, N>& G, const Eigen::Vector3d& r, const std::array<bool, N>& free,
                         Eigen::Matrix<double, N, 1>* s) {
  int idx[N];
  int k = 0;
  for (int j = 0; j < N; ++j)
    if (free[j]) idx[k++] = j;
  if (k == 0) return true;
  Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, N> GF(3, k);
  for (int j = 0; j < k; ++j) GF.col(j) = G.col(idx[j]);
  const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, N, N> M = GF.transpose() * GF;
  Eigen::LDLT<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, N, N>> ldlt(M);
  if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().cwiseAbs().minCoeff() > 1e-300)) return false;
  const Eigen::Matrix<double, Eigen::Dynamic, 1, 0, N, 1> sol = ldlt.solve(-GF.transpose() * r);
  for (int j = 0; j < k; ++j) (*s)[idx[j]] = sol[j];
  return sol.allFinite();
}

struct Candidate {
  double value = std::numeric_limits<double>::infinity();
  Eigen::Vector3d u = Eigen::Vector3d::Zero();  // g + G s, unit frame
  Eigen::Vector3d s = Eigen::Vector3d::Zero();  // parameters (unused components 0)
};

/// Certification shared by box and triangle: `vertices` are the polytope's vertices in the unit
/// frame, `best` the computed minimiser, `scale` the magnitude of the unit-frame coordinates.
void certify(const Candidate& best, const Eigen::Vector3d* vertices, int nv, double scale, EllipsoidPolytopeResult* out) {
  const double tau = tolerance::kCertificateRelativeBoundDouble;
  out->unit_distance2 = best.value;
  if (best.value < 1.0 - tau * (1.0 + scale * scale)) {
    out->status = Separation::Overlapping;  // a polytope point strictly inside the ball
    return;
  }
  const double len = best.u.norm();
  if (len > 1.0) {
    // Separating plane u.n = (1 + len)/2... any level in (1, min vertex projection) works; check
    // that every vertex lies strictly beyond the unit ball along n = u*/|u*|.
    const Eigen::Vector3d n = best.u / len;
    double lowest = std::numeric_limits<double>::infinity();
    for (int i = 0; i < nv; ++i) lowest = std::min(lowest, n.dot(vertices[i]));
    if (lowest > 1.0 + tau * (1.0 + scale)) {
      out->status = Separation::Separated;
      return;
    }
  }
  out->status = Separation::Touching;  // within the band: err toward contact
}

void checkFiniteVector(const Eigen::Vector3d& v, const char* what) {
  if (!v.allFinite()) {
    std::ostringstream os;
    os << what << " must be finite, got [" << v.transpose() << "]";
    throw std::invalid_argument(os.str());
  }
}

}  // namespace

EllipsoidPolytopeResult classifyEllipsoidBox(const Ellipsoid& e, const Eigen::Vector3d& half_extents,
                                             const Eigen::Matrix3d& R_WB, const Eigen::Vector3d& p_WB) {
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(half_extents[i]) || !(half_extents[i] >= 0.0)) {
      std::ostringstream os;
      os << "box half extent " << i << " must be finite and >= 0, got " << half_extents[i];
      throw std::invalid_argument(os.str());
    }
  }
  detail::checkRotation(R_WB, "box rotation");
  checkFiniteVector(p_WB, "box centre");
  // Unit frame: u = g + G s, s in [-1,1]^3.
  const Eigen::Matrix3d SinvRt = e.inverseRadii().asDiagonal() * e.rotation().transpose();
  const Eigen::Vector3d g = SinvRt * (p_WB - e.center());
  const Eigen::Matrix3d G = SinvRt * R_WB * half_extents.asDiagonal();
  Candidate best;
  // Enumerate the 27 faces of the cube (each coordinate free, -1 or +1).
  for (int code = 0; code < 27; ++code) {
    std::array<bool, 3> free;
    Eigen::Vector3d s = Eigen::Vector3d::Zero();
    int c = code;
    for (int j = 0; j < 3; ++j, c /= 3) {
      free[j] = (c % 3 == 0) && half_extents[j] > 0.0;
      s[j] = (c % 3 == 1) ? -1.0 : (c % 3 == 2 ? 1.0 : 0.0);
      if (half_extents[j] == 0.0) s[j] = 0.0;  // a flat box: that coordinate is irrelevant
    }
    Eigen::Vector3d fixed = s;
    for (int j = 0; j < 3; ++j)
      if (free[j]) fixed[j] = 0.0;
    Eigen::Vector3d sf = fixed;
    if (!reducedLeastSquares<3>(G, g + G * fixed, free, &sf)) continue;
    if ((sf.array().abs() > 1.0).any()) continue;  // not in this face
    const Eigen::Vector3d u = g + G * sf;
    const double v = u.squaredNorm();
    if (v < best.value) best = {v, u, sf};
  }
  EllipsoidPolytopeResult out;
  Eigen::Vector3d verts[8];
  for (int i = 0; i < 8; ++i)
    verts[i] = g + G * Eigen::Vector3d((i & 1) ? 1.0 : -1.0, (i & 2) ? 1.0 : -1.0, (i & 4) ? 1.0 : -1.0);
  const double scale = g.cwiseAbs().sum() + G.cwiseAbs().sum();
  certify(best, verts, 8, scale, &out);
  out.closest = p_WB + R_WB * half_extents.cwiseProduct(best.s);
  return out;
}

EllipsoidPolytopeResult classifyEllipsoidTriangle(const Ellipsoid& e, const Eigen::Vector3d& a,
                                                  const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  checkFiniteVector(a, "triangle vertex a");
  checkFiniteVector(b, "triangle vertex b");
  checkFiniteVector(c, "triangle vertex c");
  const Eigen::Matrix3d SinvRt = e.inverseRadii().asDiagonal() * e.rotation().transpose();
  const Eigen::Vector3d ua = SinvRt * (a - e.center()), ub = SinvRt * (b - e.center()), uc = SinvRt * (c - e.center());
  Eigen::Matrix<double, 3, 2> G;
  G.col(0) = ub - ua;
  G.col(1) = uc - ua;
  Candidate best;
  auto consider = [&](const Eigen::Vector2d& s) {
    const Eigen::Vector3d u = ua + G * s;
    const double v = u.squaredNorm();
    if (v < best.value) best = {v, u, Eigen::Vector3d(s[0], s[1], 0.0)};
  };
  // Vertices.
  consider({0.0, 0.0});
  consider({1.0, 0.0});
  consider({0.0, 1.0});
  // Edges: minimise |p + t q| over t in [0,1].
  auto edge = [&](const Eigen::Vector2d& s0, const Eigen::Vector2d& s1) {
    const Eigen::Vector3d p = ua + G * s0, q = G * (s1 - s0);
    const double qq = q.squaredNorm();
    if (!(qq > 0.0)) return;
    const double t = -p.dot(q) / qq;
    if (t > 0.0 && t < 1.0) consider(s0 + t * (s1 - s0));
  };
  edge({0.0, 0.0}, {1.0, 0.0});
  edge({0.0, 0.0}, {0.0, 1.0});
  edge({1.0, 0.0}, {0.0, 1.0});
  // Interior.
  Eigen::Vector2d s;
  if (reducedLeastSquares<2>(G, ua, {true, true}, &s) && s[0] > 0.0 && s[1] > 0.0 && s[0] + s[1] < 1.0) consider(s);
  EllipsoidPolytopeResult out;
  const Eigen::Vector3d verts[3] = {ua, ub, uc};
  const double scale = ua.cwiseAbs().sum() + ub.cwiseAbs().sum() + uc.cwiseAbs().sum();
  certify(best, verts, 3, scale, &out);
  out.closest = a + best.s[0] * (b - a) + best.s[1] * (c - a);
  return out;
}

}  // namespace fcl_quadric
