#include "fcl_quadric/geometry/ellipsoid_polytope.h"

#include <array>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include "fcl_quadric/geometry/point_ellipsoid.h"
#include "fcl_quadric/geometry/sphere_solid.h"
#include "fcl_quadric/tolerances.h"
#include "algebra/dense_decompositions.h"

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

/// The unit-frame rounding of a box's g = S^-1 R^T (p_WB - c) and G = S^-1 R^T R_WB diag(h).
double boxUnitFrameRounding(const Ellipsoid& e, const Eigen::Vector3d& half_extents, const Eigen::Matrix3d& R_WB,
                            const Eigen::Vector3d& p_WB) {
  return detail::unitFrameRounding(e, (p_WB - e.center()).cwiseAbs().sum() + (R_WB.cwiseAbs() * half_extents).sum());
}

/// The two bands of the certificates on unit-frame points: relative (tau over the magnitude
/// `scale` of the coordinates) plus the absolute transform rounding `eta` of each coordinate (a
/// point of the polytope is a convex combination of vertices, or g + G s with |s_j| <= 1, so its
/// error is bounded by the same eta up to sqrt(3) <= 2).
struct Bands {
  double overlap;   ///< |u|^2 < 1 - overlap certifies u strictly inside the unit ball
  double separate;  ///< every vertex beyond the plane u.n = 1 + separate certifies separation
};
Bands bands(double scale, double eta) {
  const double tau = tolerance::kCertificateRelativeBoundDouble;
  return {tau * (1.0 + scale * scale) + 4.0 * (1.0 + scale) * eta, tau * (1.0 + scale) + 2.0 * eta};
}

/// Certification shared by box and triangle: `vertices` are the polytope's vertices in the unit
/// frame, `best` the computed minimiser, `scale` the magnitude of the unit-frame coordinates and
/// `eta` their absolute transform rounding (detail::unitFrameRounding()).
void certify(const Candidate& best, const Eigen::Vector3d* vertices, int nv, double scale, double eta,
             EllipsoidPolytopeResult* out) {
  const Bands band = bands(scale, eta);
  out->unit_distance2 = best.value;
  if (best.value < 1.0 - band.overlap) {
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
    if (lowest > 1.0 + band.separate) {
      out->status = Separation::Separated;
      return;
    }
  }
  out->status = Separation::Touching;  // within the band: err toward contact
}

}  // namespace

EllipsoidPolytopeResult classifyEllipsoidBox(const Ellipsoid& e, const Eigen::Vector3d& half_extents,
                                             const Eigen::Matrix3d& R_WB, const Eigen::Vector3d& p_WB) {
  for (int i = 0; i < 3; ++i) detail::checkLength(half_extents[i], "box half extent", nullptr, i);
  detail::checkRotation(R_WB, "box rotation");
  detail::checkPosition(p_WB, "box centre");
  // Unit frame: u = g + G s, s in [-1,1]^3.
  const Eigen::Matrix3d SinvRt = e.inverseRadii().asDiagonal() * e.rotation().transpose();
  const Eigen::Vector3d g = SinvRt * (p_WB - e.center());
  const Eigen::Matrix3d G = SinvRt * R_WB * half_extents.asDiagonal();
  EllipsoidPolytopeResult out;
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
  Eigen::Vector3d verts[8];
  for (int i = 0; i < 8; ++i)
    verts[i] = g + G * Eigen::Vector3d((i & 1) ? 1.0 : -1.0, (i & 2) ? 1.0 : -1.0, (i & 4) ? 1.0 : -1.0);
  const double scale = g.cwiseAbs().sum() + G.cwiseAbs().sum();
  certify(best, verts, 8, scale, boxUnitFrameRounding(e, half_extents, R_WB, p_WB), &out);
  out.closest = p_WB + R_WB * half_extents.cwiseProduct(best.s);
  return out;
}

Separation ellipsoidBoxStatus(const Ellipsoid& e, const Eigen::Vector3d& half_extents, const Eigen::Matrix3d& R_WB,
                              const Eigen::Vector3d& p_WB) {
  // Cheap certificates first (most OcTree leaves are far away or deep inside): the box centre
  // strictly inside the unit ball (overlap), or every vertex beyond the plane u.n = 1, n = g/|g|
  // (separation; the lowest vertex along n is at n.g - sum_j |n.G_j|). They are the full test's
  // own certificates applied to particular points/planes; otherwise run the full test.
  for (int i = 0; i < 3; ++i)
    if (!std::isfinite(half_extents[i]) || !(half_extents[i] >= 0.0)) return classifyEllipsoidBox(e, half_extents, R_WB, p_WB).status;  // throws
  const Eigen::Matrix3d SinvRt = e.inverseRadii().asDiagonal() * e.rotation().transpose();
  const Eigen::Vector3d g = SinvRt * (p_WB - e.center());
  const Eigen::Matrix3d G = SinvRt * R_WB * half_extents.asDiagonal();
  if (g.allFinite() && G.allFinite()) {
    const double scale = g.cwiseAbs().sum() + G.cwiseAbs().sum();
    const Bands band = bands(scale, boxUnitFrameRounding(e, half_extents, R_WB, p_WB));
    const double g2 = g.squaredNorm();
    if (g2 < 1.0 - band.overlap) return Separation::Overlapping;
    const double glen = std::sqrt(g2);
    if (glen > 0.0) {
      const double lowest = glen - (G.transpose() * (g / glen)).cwiseAbs().sum();
      if (lowest > 1.0 + band.separate) return Separation::Separated;
    }
    // Near the surface (the OcTree leaves that survive FCL's bounding-volume tests): approximate
    // the point of the parallelepiped nearest the centre, u = g + G s, s in [-1,1]^3, by
    // kBoxNearestPointSweeps sweeps of exact coordinate descent on |g + G s|^2 (each step is the
    // clamped 1-D minimiser). Any such u is a point of the box, and the box's lowest point along
    // n = u/|u| bounds it from below, so the same two certificates apply: u strictly inside the
    // unit ball (overlap), or the whole box beyond the plane u.n = 1 (separation). Undecided
    // pairs (within about the descent's error of tangency) go to the full test.
    constexpr int kBoxNearestPointSweeps = 3;
    Eigen::Vector3d sv = Eigen::Vector3d::Zero();
    Eigen::Vector3d u = g;
    for (int sweep = 0; sweep < kBoxNearestPointSweeps; ++sweep) {
      for (int j = 0; j < 3; ++j) {
        const double gj2 = G.col(j).squaredNorm();
        if (!(gj2 > 0.0)) continue;
        const double sj = std::clamp(sv[j] - G.col(j).dot(u) / gj2, -1.0, 1.0);
        u += (sj - sv[j]) * G.col(j);
        sv[j] = sj;
      }
    }
    u = g + G * sv;  // recomputed from s: the point of the box the certificates speak about
    const double u2 = u.squaredNorm();
    if (u2 < 1.0 - band.overlap) return Separation::Overlapping;
    const double ulen = std::sqrt(u2);
    if (ulen > 0.0) {
      const Eigen::Vector3d n = u / ulen;
      const double lowest = n.dot(g) - (G.transpose() * n).cwiseAbs().sum();
      if (lowest > 1.0 + band.separate) return Separation::Separated;
    }
  }
  return classifyEllipsoidBox(e, half_extents, R_WB, p_WB).status;  // validates R_WB, p_WB
}

EllipsoidPolytopeResult classifyEllipsoidTriangle(const Ellipsoid& e, const Eigen::Vector3d& a,
                                                  const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  detail::checkPosition(a, "triangle vertex a");
  detail::checkPosition(b, "triangle vertex b");
  detail::checkPosition(c, "triangle vertex c");
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
  const double eta = detail::unitFrameRounding(
      e, (a - e.center()).cwiseAbs().sum() + (b - e.center()).cwiseAbs().sum() + (c - e.center()).cwiseAbs().sum());
  certify(best, verts, 3, scale, eta, &out);
  out.closest = a + best.s[0] * (b - a) + best.s[1] * (c - a);
  return out;
}

namespace {

/// Feature candidates of the max-min formulation (see the header).
struct PolytopeData {
  const Eigen::Vector3d* v;
  int nv;
  const int (*edges)[2];
  int ne;
  const Eigen::Vector3d* face_normals;  // outward
  int nf;
};

double phi(const Ellipsoid& e, const PolytopeData& P, const Eigen::Vector3d& n) {
  double m = std::numeric_limits<double>::infinity();
  for (int j = 0; j < P.nv; ++j) m = std::min(m, n.dot(P.v[j]));
  return m - e.support(n);
}

/// Candidate directions for the edge through v with direction u: n orthogonal to u maximising
/// n.v - h_e(n) is the outward normal of the ellipsoid's shadow (on the plane orthogonal to u) at a
/// critical point of the distance from the projected line; all = false keeps only the closest.
int edgeDirections(const Ellipsoid& e, const Eigen::Vector3d& v, const Eigen::Vector3d& u, bool all,
                   Eigen::Vector3d* out) {
  const Eigen::Vector3d helper = std::fabs(u.x()) < 0.6 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d b1 = (helper - helper.dot(u) * u).normalized(), b2 = u.cross(b1);
  Eigen::Matrix<double, 3, 2> B;
  B << b1, b2;
  const Eigen::Matrix3d G = e.rotation() * e.radii().cwiseAbs2().asDiagonal() * e.rotation().transpose();
  const Eigen::Matrix2d G2 = B.transpose() * G * B;  // shadow: support h(m) = sqrt(m^T G2 m)
  const detail::SymmetricEigen2 es = detail::selfAdjointEigen(G2);
  const Eigen::Vector2d radii = es.values.cwiseMax(0.0).cwiseSqrt();
  if (!(radii.minCoeff() > 0.0)) return 0;
  const Eigen::Vector2d y = es.vectors.transpose() * (B.transpose() * (v - e.center()));
  Eigen::Vector2d xs[4];
  int n = 0;
  if (all) {
    n = detail::criticalPointsPrincipal<2>(radii, y, xs, 4);
  } else {
    detail::closestPointPrincipal<2>(radii, y, &xs[0]);
    n = 1;
  }
  int k = 0;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d n2 = xs[i].cwiseQuotient(radii.cwiseAbs2());  // normal of the shadow
    const double len = n2.norm();
    if (len > 0.0) out[k++] = B * (es.vectors * (n2 / len));
  }
  return k;
}

SignedDistanceResult polytopeSignedDistance(const Ellipsoid& e, const PolytopeData& P, Separation status) {
  Eigen::Vector3d best_n = Eigen::Vector3d::UnitX();
  double best = -std::numeric_limits<double>::infinity();
  auto consider = [&](const Eigen::Vector3d& n) {
    if (!n.allFinite() || !(n.squaredNorm() > 0.0)) return;
    const Eigen::Vector3d nn = n.normalized();
    const double f = phi(e, P, nn);
    if (f > best) {
      best = f;
      best_n = nn;
    }
  };
  // Separate pairs: each feature's sub-problem is convex, its global optimum is the candidate.
  // Otherwise (penetration depth) the optimum may be any critical point of a sub-problem.
  const bool all = status != Separation::Separated;
  for (int i = 0; i < P.nf; ++i) consider(-P.face_normals[i]);
  for (int j = 0; j < P.nv; ++j) {
    if (!all) {
      consider(e.normalAt(closestPointOnEllipsoid(e, P.v[j]).closest));
      continue;
    }
    const Eigen::Vector3d y = e.rotation().transpose() * (P.v[j] - e.center());
    Eigen::Vector3d xs[8];
    const int n = detail::criticalPointsPrincipal<3>(e.radii(), y, xs, 8);
    for (int i = 0; i < n; ++i) consider(e.rotation() * xs[i].cwiseQuotient(e.radii().cwiseAbs2()));
  }
  for (int k = 0; k < P.ne; ++k) {
    const Eigen::Vector3d& v = P.v[P.edges[k][0]];
    const Eigen::Vector3d d = P.v[P.edges[k][1]] - v;
    if (!(d.squaredNorm() > 0.0)) continue;
    Eigen::Vector3d dirs[4];
    const int n = edgeDirections(e, v, d.normalized(), all, dirs);
    for (int i = 0; i < n; ++i) consider(dirs[i]);
  }
  SignedDistanceResult r;
  r.status = status;
  r.normal = best_n;
  r.converged = true;
  r.point_a = e.supportPoint(best_n);
  switch (status) {
    case Separation::Separated: r.distance = std::max(best, 0.0); break;
    case Separation::Overlapping: r.distance = std::min(best, 0.0); break;
    case Separation::Touching: r.distance = 0.0; break;
  }
  r.point_b = r.point_a + best * best_n;
  return r;
}

}  // namespace

SignedDistanceResult signedDistanceEllipsoidBox(const Ellipsoid& e, const Eigen::Vector3d& half_extents,
                                                const Eigen::Matrix3d& R_WB, const Eigen::Vector3d& p_WB) {
  if (isSphere(e)) return signedDistanceSphereBox(e.center(), e.radii()[0], half_extents, R_WB, p_WB);
  const EllipsoidPolytopeResult c = classifyEllipsoidBox(e, half_extents, R_WB, p_WB);  // validates
  Eigen::Vector3d v[8];
  for (int i = 0; i < 8; ++i)
    v[i] = p_WB + R_WB * Eigen::Vector3d((i & 1) ? half_extents[0] : -half_extents[0],
                                         (i & 2) ? half_extents[1] : -half_extents[1],
                                         (i & 4) ? half_extents[2] : -half_extents[2]);
  static const int edges[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3},
                                   {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  const Eigen::Vector3d normals[6] = {R_WB.col(0), -R_WB.col(0), R_WB.col(1), -R_WB.col(1), R_WB.col(2), -R_WB.col(2)};
  return polytopeSignedDistance(e, {v, 8, edges, 12, normals, 6}, c.status);
}

SignedDistanceResult signedDistanceEllipsoidTriangle(const Ellipsoid& e, const Eigen::Vector3d& a,
                                                     const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  if (isSphere(e)) return signedDistanceSphereTriangle(e.center(), e.radii()[0], a, b, c);
  const EllipsoidPolytopeResult cl = classifyEllipsoidTriangle(e, a, b, c);  // validates
  const Eigen::Vector3d v[3] = {a, b, c};
  static const int edges[3][2] = {{0, 1}, {1, 2}, {2, 0}};
  const Eigen::Vector3d nrm = (b - a).cross(c - a);
  Eigen::Vector3d normals[2];
  int nf = 0;
  if (nrm.squaredNorm() > 0.0) {
    normals[nf++] = nrm.normalized();
    normals[nf++] = -nrm.normalized();
  }
  return polytopeSignedDistance(e, {v, 3, edges, 3, normals, nf}, cl.status);
}

namespace {

/// The validated polytope's outward face normals (a degenerate face's is zero) and its edges
/// (each pair of consecutive face vertices once).
struct ConvexFeatures {
  std::vector<Eigen::Vector3d> normals;
  std::vector<std::array<int, 2>> edges;
  double scale = 0.0;  ///< max |v|_inf over the vertices: the plane tests' rounding scale
};

/// P's face normals and (want_edges) its edges, validating P. The edges' set is what a sphere's
/// closed form does not need (it cost more than its answer).
ConvexFeatures convexFeatures(const ConvexPolytope& P, bool want_edges = true) {
  if (P.vertices.empty()) throw std::invalid_argument("convex polytope has no vertices");
  const int nv = static_cast<int>(P.vertices.size());
  ConvexFeatures f;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& v : P.vertices) {
    detail::checkPosition(v, "convex polytope vertex");
    mean += v;
    f.scale = std::max(f.scale, v.cwiseAbs().maxCoeff());
  }
  mean /= nv;  // strictly inside a solid convex polytope (the mean of its vertices)
  f.normals.reserve(P.faces.size());
  std::set<std::pair<int, int>> seen;
  for (std::size_t k = 0; k < P.faces.size(); ++k) {
    const std::vector<int>& face = P.faces[k];
    if (face.size() < 3) {
      std::ostringstream os;
      os << "convex polytope face " << k << " has " << face.size() << " vertices (at least 3 needed)";
      throw std::invalid_argument(os.str());
    }
    for (int i : face)
      if (i < 0 || i >= nv) {
        std::ostringstream os;
        os << "convex polytope face " << k << " has vertex index " << i << ", outside [0, " << nv << ")";
        throw std::invalid_argument(os.str());
      }
    // Newell's normal of the polygon, turned outward (away from the vertices' mean).
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < face.size(); ++i) {
      const Eigen::Vector3d& a = P.vertices[face[i]];
      const Eigen::Vector3d& b = P.vertices[face[(i + 1) % face.size()]];
      n += (a - mean).cross(b - mean);
      const int lo = std::min(face[i], face[(i + 1) % face.size()]), hi = std::max(face[i], face[(i + 1) % face.size()]);
      if (want_edges && lo != hi && seen.insert({lo, hi}).second) f.edges.push_back({lo, hi});
    }
    // |n| of a polytope of 1e78 overflowed and of 1e-90 underflowed with norm() (session 36, an
    // audit): stableNorm() then, which is slower, only when the squares leave the normal range.
    const double n2 = n.squaredNorm();
    const double len = n2 > 1e-290 && n2 < 1e290 ? std::sqrt(n2) : n.stableNorm();
    if (len > 0.0) {
      n /= len;
      if (n.dot(P.vertices[face[0]] - mean) < 0.0) n = -n;
    }
    f.normals.push_back(n);
  }
  return f;
}

/// classifyEllipsoidConvex() on P's validated features.
EllipsoidPolytopeResult classifyConvex(const Ellipsoid& e, const ConvexPolytope& P, const ConvexFeatures& f) {
  // The centre strictly inside every face plane (by more than the rounding of n.(c - v), a few
  // eps of |n||c - v|: 2^-40 of the coordinates' scale, as the triangles' band).
  const Eigen::Vector3d c = e.center();
  const double band = std::ldexp(1.0, -40) * (f.scale + c.cwiseAbs().maxCoeff());
  bool inside = !P.faces.empty();
  for (std::size_t k = 0; k < P.faces.size() && inside; ++k)
    inside = f.normals[k].squaredNorm() > 0.0 && f.normals[k].dot(c - P.vertices[P.faces[k][0]]) < -band;
  if (inside) return EllipsoidPolytopeResult{Separation::Overlapping, 0.0, c};
  EllipsoidPolytopeResult best{Separation::Separated, std::numeric_limits<double>::infinity(), P.vertices.front()};
  bool touching = false;
  for (const std::vector<int>& face : P.faces)
    for (std::size_t i = 1; i + 1 < face.size(); ++i) {
      const EllipsoidPolytopeResult r =
          classifyEllipsoidTriangle(e, P.vertices[face[0]], P.vertices[face[i]], P.vertices[face[i + 1]]);
      if (r.status == Separation::Overlapping) return r;
      touching = touching || r.status == Separation::Touching;
      if (r.unit_distance2 < best.unit_distance2) best = r;
    }
  if (P.faces.empty()) {  // no boundary given: the vertices alone (points of P)
    for (const Eigen::Vector3d& v : P.vertices) {
      const EllipsoidPolytopeResult r = classifyEllipsoidTriangle(e, v, v, v);
      if (r.status == Separation::Overlapping) return r;
      touching = touching || r.status == Separation::Touching;
      if (r.unit_distance2 < best.unit_distance2) best = r;
    }
  }
  best.status = touching ? Separation::Touching : Separation::Separated;
  return best;
}

/// A sphere (centre c, radius r) against P in closed form (docs/algorithms.md §12d): the centre's
/// signed distance to P minus r. Inside every face plane, the nearest face plane (for a convex
/// polytope, the distance of an interior point to its boundary); otherwise the nearest of the fan
/// triangles of the faces that see the centre (signedDistanceSphereTriangle), or of the vertices
/// when no face is given. (The nearest point q of a convex polytope to an outside centre c lies
/// on a face whose plane has c strictly outside: c - q is a non-negative combination of the
/// normals of the faces through q, and (c - q).(c - q) > 0 makes one of their n.(c - q) positive.)
SignedDistanceResult sphereConvex(const Eigen::Vector3d& c, double r, const ConvexPolytope& P, const ConvexFeatures& f) {
  bool inside = !P.faces.empty();
  double reach = 0.0;  // max |c - v| over the faces' first vertices: the plane tests' rounding scale
  int nearest_face = -1;
  double depth = -std::numeric_limits<double>::infinity();
  std::vector<char> sees(P.faces.size(), 1);  // the face's plane has the centre outside (or nearly)
  for (std::size_t k = 0; k < P.faces.size(); ++k) {
    const Eigen::Vector3d w = c - P.vertices[P.faces[k][0]];
    const double s = f.normals[k].dot(w);
    const double w_max = w.cwiseAbs().maxCoeff();
    reach = std::max(reach, w_max);
    const bool oriented = f.normals[k].squaredNorm() > 0.0;
    // (A margin far above the rounding of n.w, a few eps of 3 |w|_inf, so no face that may hold
    // the nearest point is skipped.)
    sees[k] = !oriented || s > -tolerance::kCertificateRelativeBoundDouble * (3.0 * w_max + r);
    inside = inside && oriented && s <= 0.0;
    if (inside && s > depth) {
      depth = s;
      nearest_face = static_cast<int>(k);
    }
  }
  SignedDistanceResult best;
  best.converged = true;
  if (inside) {
    const Eigen::Vector3d& n = f.normals[nearest_face];  // outward, unit
    best.normal = -n;                                     // toward the nearest face, from inside
    best.point_a = c + r * best.normal;
    best.point_b = c - depth * n;
    // The plane tests' rounding: that of n.(c - v), relative to |c - v| (each difference exact to
    // one rounding of itself), not to the coordinates' magnitude (a cube of 1e-6 at 1e6 was all
    // "touching" with that: session 36, an audit); plus the radius.
    const double band = tolerance::kCertificateRelativeBoundDouble * (reach + r);
    best.distance = depth - r;
    best.status = best.distance < -band ? Separation::Overlapping : Separation::Touching;
    if (best.status == Separation::Touching) best.distance = 0.0;
    return best;
  }
  // The nearest triangle by the centre's distance (the answers' own distances are zeroed in the
  // touching band, so they cannot rank).
  double nearest = std::numeric_limits<double>::infinity();
  const auto consider = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& t) {
    const SignedDistanceResult d = signedDistanceSphereTriangle(c, r, a, b, t);
    const double to_centre = (d.point_b - c).norm();
    if (to_centre < nearest) {
      nearest = to_centre;
      best = d;
    }
  };
  for (std::size_t k = 0; k < P.faces.size(); ++k) {
    if (!sees[k]) continue;
    const std::vector<int>& face = P.faces[k];
    for (std::size_t i = 1; i + 1 < face.size(); ++i)
      consider(P.vertices[face[0]], P.vertices[face[i]], P.vertices[face[i + 1]]);
  }
  if (P.faces.empty())
    for (const Eigen::Vector3d& v : P.vertices) consider(v, v, v);
  return best;
}

}  // namespace

EllipsoidPolytopeResult classifyEllipsoidConvex(const Ellipsoid& e, const ConvexPolytope& P) {
  return classifyConvex(e, P, convexFeatures(P));  // (convexFeatures validates)
}

SignedDistanceResult signedDistanceEllipsoidConvex(const Ellipsoid& e, const ConvexPolytope& P) {
  if (isSphere(e)) return sphereConvex(e.center(), e.radii()[0], P, convexFeatures(P, false));  // (validates)
  const ConvexFeatures f = convexFeatures(P);  // validates
  const EllipsoidPolytopeResult c = classifyConvex(e, P, f);
  const std::unique_ptr<int[][2]> edges(new int[f.edges.size() + 1][2]);
  for (std::size_t k = 0; k < f.edges.size(); ++k) {
    edges[k][0] = f.edges[k][0];
    edges[k][1] = f.edges[k][1];
  }
  std::vector<Eigen::Vector3d> normals;
  for (const Eigen::Vector3d& n : f.normals)
    if (n.squaredNorm() > 0.0) normals.push_back(n);
  return polytopeSignedDistance(e,
                                {P.vertices.data(), static_cast<int>(P.vertices.size()), edges.get(),
                                 static_cast<int>(f.edges.size()), normals.data(), static_cast<int>(normals.size())},
                                c.status);
}

}  // namespace fcl_quadric
