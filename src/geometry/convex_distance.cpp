// GJK and EPA on support mappings (docs/algorithms.md section 12).
#include "fcl_quadric/geometry/convex_distance.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <utility>
#include <stdexcept>
#include <type_traits>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "algebra/dense_decompositions.h"

namespace fcl_quadric {

namespace {

/// A point w = a - b of the Minkowski difference with its two support points (world frame).
struct Vertex {
  Eigen::Vector3d w, a, b;
};

/// GJK's simplex: at most four vertices, stored in place (GJK runs per triangle in the mesh
/// traversals, and a heap allocation per step cost as much as the step's arithmetic).
class Simplex {
 public:
  Simplex() = default;
  explicit Simplex(const Vertex& v) { push_back(v); }
  std::size_t size() const { return n_; }
  const Vertex& operator[](std::size_t i) const { return v_[i]; }
  void push_back(const Vertex& v) { v_[n_++] = v; }  // callers keep n_ <= 4
  void pop_back() { --n_; }                           // callers keep n_ >= 1
  /// Keeps the vertices of `mask` (bit i: vertex i), in order.
  void keep(int mask) {
    std::size_t m = 0;
    for (std::size_t i = 0; i < n_; ++i)
      if (mask & (1 << i)) v_[m++] = v_[i];
    n_ = m;
  }
  const Vertex* begin() const { return v_.data(); }
  const Vertex* end() const { return v_.data() + n_; }

 private:
  std::array<Vertex, 4> v_;
  std::size_t n_ = 0;
};

struct Minkowski {
  const ConvexSupport& A;
  const Eigen::Matrix3d& Ra;
  const Eigen::Vector3d& pa;
  const ConvexSupport& B;
  const Eigen::Matrix3d& Rb;
  const Eigen::Vector3d& pb;
  /// The point of D = A - B maximising d.x: s_A(d) - s_B(-d), on the cores
  /// (ConvexSupport::coreSupport(): a sphere's centre, a capsule's segment; the solid itself for
  /// every other kind). gjkEpa() adds the radii.
  Vertex support(const Eigen::Vector3d& d) const {
    Vertex v;
    v.a = Ra * A.coreSupport(Ra.transpose() * d) + pa;
    v.b = Rb * B.coreSupport(-(Rb.transpose() * d)) + pb;
    v.w = v.a - v.b;
    return v;
  }
};

/// The barycentric coordinates l of the origin in the tetrahedron W[0..3]: Cramer's rule on the
/// triple products. False (l unset) if the tetrahedron is degenerate: unless its volume is above
/// 1e-12 of the product of its edge lengths. (The Gram matrix's LDLT squares the conditioning:
/// four coplanar support points of a face-to-face pair passed its pivot test on rounding noise and
/// made GJK report the origin inside a flat tetrahedron.) l[i] < 0 exactly when the origin lies
/// beyond the face opposite W[i], up to rounding.
bool tetrahedronCoordinates(const Simplex& W, std::array<double, 4>* l) {
  const Eigen::Vector3d& w0 = W[0].w;
  const Eigen::Vector3d e0 = W[1].w - w0, e1 = W[2].w - w0, e2 = W[3].w - w0;
  const Eigen::Vector3d c12 = e1.cross(e2), c20 = e2.cross(e0), c01 = e0.cross(e1);
  const double det = e0.dot(c12);
  if (!(std::abs(det) > 1e-12 * e0.norm() * e1.norm() * e2.norm())) return false;
  const double k = 1.0 / det;
  (*l)[1] = -w0.dot(c12) * k;
  (*l)[2] = -w0.dot(c20) * k;
  (*l)[3] = -w0.dot(c01) * k;
  (*l)[0] = 1.0 - ((*l)[1] + (*l)[2] + (*l)[3]);
  return true;
}

/// Affine projection of the origin on the hull of the s points W[idx[0..s-1]] (s = 2, 3):
/// barycentric coordinates l (all > 0 required) and the point p. Fixed-size arithmetic (no
/// allocation: this runs several times per GJK step). False for an affinely degenerate subset or
/// a coordinate <= 0. Inlined into closestPoint()'s subsets, whose indices are constants there.
template <int K>
__attribute__((always_inline)) inline bool affineProjectionK(const Simplex& W, const int* idx,
                                                             std::array<double, 4>* l, Eigen::Vector3d* p) {
  const Eigen::Vector3d& w0 = W[idx[0]].w;
  Eigen::Matrix<double, 3, K> E;
  for (int i = 0; i < K; ++i) E.col(i) = W[idx[i + 1]].w - w0;
  static_assert(K == 1 || K == 2, "the tetrahedron is tetrahedronCoordinates()");
  // The segment and the triangle: the Gram system G mu = -E^T w0 solved by G's pivoted LDL^T
  // (larger diagonal entry first; Cramer's rule lost GJK its 1e-10 lower bound on a face
  // parallel to a large triangle), in closed form. Degenerate unless every pivot exceeds 1e-13
  // of the largest diagonal entry.
  const Eigen::Matrix<double, K, K> G = E.transpose() * E;
  const Eigen::Matrix<double, K, 1> rhs = -(E.transpose() * w0);
  Eigen::Matrix<double, K, 1> mu;
  if constexpr (K == 1) {
    if (!(G(0, 0) > 0.0)) return false;
    mu[0] = rhs[0] / G(0, 0);
  } else {
    const int i = G(0, 0) >= G(1, 1) ? 0 : 1, j = 1 - i;  // pivot i first
    if (!(G(i, i) > 0.0)) return false;
    // One division on the chain to mu: 1 / G(i, i) is ready when G is (GJK's steps are a chain of
    // dependent latencies, and three divisions in a row were the step's longest link).
    const double inv_ii = 1.0 / G(i, i);
    const double f = G(j, i) * inv_ii;
    const double d2 = G(j, j) - f * G(j, i);
    if (!(d2 > 1e-13 * G(i, i))) return false;
    mu[j] = (rhs[j] - f * rhs[i]) / d2;
    mu[i] = (rhs[i] - G(i, j) * mu[j]) * inv_ii;
  }
  double sum = 0.0;
  for (int i = 0; i < K; ++i) {
    if (!(mu[i] > 0.0)) return false;
    (*l)[i + 1] = mu[i];
    sum += mu[i];
  }
  (*l)[0] = 1.0 - sum;
  if (!((*l)[0] > 0.0)) return false;
  *p = w0 + E * mu;
  return true;
}

/// A subset of GJK's simplex as a compile-time bit mask (bit i: W[i]), for closestPoint().
template <int N>
using SubsetMask = std::integral_constant<int, N>;

/// Closest point to the origin of the convex hull of W (1..4 vertices): among the subsets that
/// contain the newest point, the affine projection of the origin whose barycentric coordinates are
/// all > 0 and which is nearest. Every such projection is a point of the hull and the true closest
/// point is one of them, so the minimum is exact up to rounding (affinely degenerate subsets are
/// skipped). A subset is not tried when a larger one that contains it has a valid projection:
/// that projection is the nearest point of the larger subset's affine hull, so no point of the
/// smaller one is nearer (Johnson's sub-algorithm, pruned: the same minimum; the distance of two
/// capped cylinders took 13% less time in session 30, with the same steps). Returns the subset
/// as a mask (bit i: W[i]; Simplex::keep() reduces W to it), with lambda its coordinates in order
/// and v the point; W itself is unchanged, so that a caller can still drop the newest point
/// (gjkEpa: a step that does not descend). 0 if no subset qualifies (only possible for a fully
/// degenerate W).
int closestPoint(const Simplex& W, std::array<double, 4>* lambda, Eigen::Vector3d* v) {
  const int k = static_cast<int>(W.size());
  double best = std::numeric_limits<double>::infinity();
  int best_mask = 0;
  std::array<double, 4> best_l{};
  // Tries the subset `mask` (it holds the newest point, W's last): true if its projection is
  // valid, and then it is kept if nearest so far. The mask is a compile-time constant, so each
  // call is specialised to its subset (its indices and size folded; before session 32 one
  // out-of-line lambda walked the mask's bits at run time: ~19% of a cylinder-box distance).
  auto consider = [&](auto mask_constant) {
    constexpr int mask = decltype(mask_constant)::value;
    constexpr int s = (mask & 1) + ((mask >> 1) & 1) + ((mask >> 2) & 1) + ((mask >> 3) & 1);
    int idx[4] = {0, 0, 0, 0};
    for (int i = 0, j = 0; i < 4; ++i)
      if (mask & (1 << i)) idx[j++] = i;
    std::array<double, 4> l{};
    Eigen::Vector3d p;
    if constexpr (s == 1) {
      l[0] = 1.0;
      p = W[idx[0]].w;
    } else if (!affineProjectionK<s - 1>(W, idx, &l, &p)) {
      return false;
    }
    const double d = p.squaredNorm();
    if (d < best) {
      best = d;
      best_mask = mask;
      best_l = l;
      *v = p;
    }
    return true;
  };
  // The subsets as compile-time masks (bit i: W[i]; the newest point is bit k - 1).
  switch (k) {
    case 1: consider(SubsetMask<1>{}); break;
    case 2:
      if (!consider(SubsetMask<3>{})) consider(SubsetMask<2>{});
      break;
    case 3:
      if (!consider(SubsetMask<7>{})) {
        const bool e0 = consider(SubsetMask<5>{}), e1 = consider(SubsetMask<6>{});
        if (!e0 && !e1) consider(SubsetMask<4>{});
      }
      break;
    default: {
      // The tetrahedron: the origin inside it (all coordinates > 0) is the answer.
      std::array<double, 4> l{};
      if (tetrahedronCoordinates(W, &l) && l[0] > 0.0 && l[1] > 0.0 && l[2] > 0.0 && l[3] > 0.0) {
        best_mask = 15;
        best_l = l;
        *v = Eigen::Vector3d::Zero();
        break;
      }
      // The faces {0,1,3}, {0,2,3}, {1,2,3}. Edge {i,3} lies in the two faces that hold i: it is
      // tried when neither has a valid projection.
      const bool f01 = consider(SubsetMask<11>{}), f02 = consider(SubsetMask<13>{});
      const bool f12 = consider(SubsetMask<14>{});
      bool any = f01 || f02 || f12;
      if (!f01 && !f02) any = consider(SubsetMask<9>{}) || any;
      if (!f01 && !f12) any = consider(SubsetMask<10>{}) || any;
      if (!f02 && !f12) any = consider(SubsetMask<12>{}) || any;
      if (!any) consider(SubsetMask<8>{});
    }
  }
  if (best_mask != 0) *lambda = best_l;
  return best_mask;
}

/// Distance of p from the affine hull of W (1..3 points).
double distanceToHull(const Simplex& W, const Eigen::Vector3d& p) {
  const Eigen::Vector3d d = p - W[0].w;
  if (W.size() == 1) return d.norm();
  if (W.size() == 2) {
    const Eigen::Vector3d e = (W[1].w - W[0].w).normalized();
    return (d - d.dot(e) * e).norm();
  }
  const Eigen::Vector3d n = (W[1].w - W[0].w).cross(W[2].w - W[0].w).normalized();
  return std::abs(d.dot(n));
}

struct Face {
  int v[3];
  Eigen::Vector3d n;
  double d;
  bool alive;
};

/// A common point of the two solids from EPA's polytope (whose vertices are points of D = A - B)
/// when it holds the origin: the tetrahedra from vertex 0 to the faces without it tile the convex
/// polytope; in the one that holds the origin (barycentric coordinates >= -1e-12, for rounding on
/// a shared face), those coordinates applied to the support points of a and of b give the point
/// (the same point up to rounding). False if no tetrahedron qualifies (a degenerate polytope).
bool originInStar(const std::vector<Vertex>& verts, const std::vector<Face>& faces, Eigen::Vector3d* point_a,
                  Eigen::Vector3d* point_b) {
  const Vertex& v0 = verts[0];
  for (const Face& g : faces) {
    if (!g.alive || g.v[0] == 0 || g.v[1] == 0 || g.v[2] == 0) continue;
    const Vertex &v1 = verts[g.v[0]], &v2 = verts[g.v[1]], &v3 = verts[g.v[2]];
    Eigen::Matrix3d E;
    E << v1.w - v0.w, v2.w - v0.w, v3.w - v0.w;
    Eigen::Vector3d mu;
    if (!detail::fullPivLuSolve(E, Eigen::Vector3d(-v0.w), &mu)) continue;
    const double l0 = 1.0 - mu.sum();
    if (!(mu.minCoeff() >= -1e-12 && l0 >= -1e-12)) continue;
    *point_a = l0 * v0.a + mu[0] * v1.a + mu[1] * v2.a + mu[2] * v3.a;
    *point_b = l0 * v0.b + mu[0] * v1.b + mu[1] * v2.b + mu[2] * v3.b;
    return true;
  }
  return false;
}

/// convexSignedDistance() with one more way for GJK to stop: as soon as its lower bound exceeds
/// `stop_above` (screenConvexPair(); +infinity: never), with converged = false and distance the
/// upper bound |v| at that step.
///
/// GJK and EPA run on the cores of the solids (ConvexSupport::radius()): with r = r_a + r_b the
/// sum of the radii the cores are grown by (0 for solids that are their own cores), the distance
/// of the solids is the cores' less r when the cores are apart, and minus (the cores' depth + r)
/// when they overlap (Minkowski sums with balls: the standard "swept sphere" reduction, as Coal
/// does for spheres and capsules). GJK's |v| (a point of the cores' difference) bounds the cores'
/// distance from above and v.w / |v| from below, so
///  - separated when v.w / |v| - r exceeds the margin,
///  - overlapping when |v| < r - margin: the point of the segment between the cores' points that
///    splits it in the ratio r_a : r_b is within r_a of a's core and r_b of b's, a common point;
///    with want_depth = false GJK stops there, without EPA, often at its first step for a sphere;
///  - with want_depth, the depth r - |v| once GJK has converged on the cores' distance to
///    kConvexDistanceRelative of |distance| (r - v.w / |v|, an overestimate, if it has not);
///  - cores that overlap: EPA's depth of the cores plus r; cores that meet in a flat set (two
///    crossing segments, concentric spheres) have depth 0, so the solids' depth is r.
/// The witnesses are the cores' points moved by their radii along the normal.
SignedDistanceResult gjkEpa(const ConvexSupport& a, const Eigen::Matrix3d& R_a, const Eigen::Vector3d& p_a,
                            const ConvexSupport& b, const Eigen::Matrix3d& R_b, const Eigen::Vector3d& p_b,
                            bool want_depth, double* lower_bound, double stop_above, const char* where) {
  if (!R_a.allFinite() || !p_a.allFinite() || !R_b.allFinite() || !p_b.allFinite())
    throw std::invalid_argument(std::string(where) + ": a pose is not finite");
  using namespace tolerance_convex;
  const Minkowski D{a, R_a, p_a, b, R_b, p_b};
  const Eigen::Vector3d ca = R_a * a.center() + p_a, cb = R_b * b.center() + p_b;
  const double scale = a.size() + b.size() + (ca - cb).norm();
  const double margin = kConvexSeparationRelative * scale;
  const double tiny = 1e-14 * scale;
  const double ra = a.radius(), rb = b.radius(), r = ra + rb;  // the cores' radii (function comment)
  // GJK's stopping accuracy: relative to the solids' distance |v| - r (|v| when r = 0).
  auto accuracy = [&](double vn) { return kConvexDistanceRelative * std::abs(vn - r) + tiny; };

  SignedDistanceResult out;
  if (lower_bound) *lower_bound = 0.0;
  // --- GJK ---------------------------------------------------------------------------------------
  Eigen::Vector3d dir = ca - cb;
  if (!(dir.norm() > tiny)) dir = Eigen::Vector3d::UnitX();
  Simplex W(D.support(-dir));
  std::array<double, 4> lambda{1.0, 0.0, 0.0, 0.0};
  Eigen::Vector3d v = W[0].w;
  double lower = 0.0;
  bool origin_in_hull = false;
  int it = 0;
  for (; it < kMaxGjkIterations; ++it) {
    const double vn = v.norm();
    if (!want_depth && vn < r - margin) break;  // the grown solids overlap (certified below)
    if (!(vn > tiny)) {
      origin_in_hull = true;
      break;
    }
    const Vertex w = D.support(-v);
    lower = std::max(lower, v.dot(w.w) / vn);
    if (lower - r > stop_above) break;  // the screening's certificate (not converged)
    if (vn - lower <= accuracy(vn)) {
      out.converged = true;
      break;
    }
    bool repeat = false;
    for (const Vertex& x : W) repeat = repeat || (x.w - w.w).norm() <= tiny;
    if (repeat) {  // no new support point: v is as close as this arithmetic gets
      out.converged = vn - lower <= accuracy(vn);
      break;
    }
    // The next simplex is committed only with its point v_new: a step that fails or does not
    // descend drops w again and leaves lambda, so the witnesses below (lambda's combination of
    // W's points) are always v's. (Before session 41 a stalled step kept v but not its simplex: a
    // cone's apex 3e-5 from a parallel box face got witnesses 0.2-0.4 apart.)
    W.push_back(w);
    std::array<double, 4> lambda_next{};
    Eigen::Vector3d v_new = Eigen::Vector3d::Zero();
    const int mask = closestPoint(W, &lambda_next, &v_new);
    const bool descends = mask != 0 && (mask == 15 || v_new.norm() < vn);
    if (!descends) {
      W.pop_back();
      if (mask != 0) out.converged = vn - lower <= accuracy(vn);  // rounding stalled the descent
      break;
    }
    W.keep(mask);
    lambda = lambda_next;
    v = v_new;
    if (mask == 15) {  // the tetrahedron holds the origin
      origin_in_hull = true;
      break;
    }
  }
  out.iterations = it;

  // The cores' nearest points found (pa - pb = v), of the simplex's points by its coordinates.
  Eigen::Vector3d pa = Eigen::Vector3d::Zero(), pb = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < W.size(); ++i) {
    pa += lambda[i] * W[i].a;
    pb += lambda[i] * W[i].b;
  }
  const double vn = v.norm();
  const Eigen::Vector3d normal = vn > 0.0 ? Eigen::Vector3d(-v / vn) : Eigen::Vector3d::UnitX();  // from a to b
  if (!want_depth && vn < r - margin) {
    // The cores are closer than r: the point splitting [pa, pb] in the ratio r_a : r_b is within
    // r_a |v| / r < r_a of pa and r_b |v| / r < r_b of pb, hence in both grown solids.
    out.status = Separation::Overlapping;
    out.distance = 0.0;
    out.point_a = out.point_b = pa + (ra / r) * (pb - pa);
    out.normal = normal;
    out.converged = true;
    return out;
  }
  if (!origin_in_hull) {
    out.normal = normal;
    out.point_a = pa + ra * normal;
    out.point_b = pb - rb * normal;
    if (lower - r > margin) {
      out.status = Separation::Separated;
      out.distance = vn - r;  // the upper bound: within the stopping gap of the distance
      if (lower_bound) *lower_bound = lower - r;
    } else if (vn - r < -margin) {
      // The grown solids overlap (the cores do not): depth r - |v| once converged, else the
      // overestimate r - v.w / |v| (errs toward contact).
      out.status = Separation::Overlapping;
      out.distance = out.converged ? vn - r : lower - r;
    } else {
      out.status = Separation::Touching;
      out.distance = 0.0;
    }
    return out;
  }

  // --- The origin is in D (or within rounding of it): a tetrahedron containing it -------------------
  // A lower-dimensional simplex containing the origin is grown by support points off its hull; if
  // D is flat in every direction tried (no interior) the pair is touching with depth 0 (grown
  // cores: overlapping by r).
  {
    const Eigen::Vector3d axes[3] = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ()};
    while (W.size() < 4) {
      std::vector<Eigen::Vector3d> dirs;
      if (W.size() == 1) {
        // Grown cores that meet in a point (a sphere's centre on the other core): the centres'
        // direction first, the normal if nothing grows (concentric spheres).
        const Eigen::Vector3d d = cb - ca;
        if (r > margin && d.norm() > tiny) dirs.push_back(d.normalized());
        for (const auto& e : axes) {
          dirs.push_back(e);
          dirs.push_back(-e);
        }
      } else if (W.size() == 2) {
        const Eigen::Vector3d e = W[1].w - W[0].w;
        int k = 0;
        e.cwiseAbs().minCoeff(&k);
        const Eigen::Vector3d d1 = e.cross(axes[k]).normalized(), d2 = e.cross(d1).normalized();
        for (const auto& d : {d1, d2}) {
          dirs.push_back(d);
          dirs.push_back(-d);
        }
      } else {
        const Eigen::Vector3d nrm = (W[1].w - W[0].w).cross(W[2].w - W[0].w).normalized();
        dirs.push_back(nrm);
        dirs.push_back(-nrm);
      }
      bool grown = false;
      for (const auto& d : dirs) {
        const Vertex w = D.support(d);
        if (distanceToHull(W, w.w) > 1e-12 * scale) {
          W.push_back(w);
          grown = true;
          break;
        }
      }
      if (!grown) {
        if (r > margin) {
          // Cores meeting in a flat set (depth 0): the grown solids overlap by r, along the
          // direction the set is flat in (the first one tried), from the cores' common point.
          out.status = Separation::Overlapping;
          out.distance = -r;
          out.normal = dirs.front();
          out.point_a = pa + ra * out.normal;
          out.point_b = pa - rb * out.normal;
          out.converged = true;
          return out;
        }
        out.status = Separation::Touching;
        out.distance = 0.0;
        out.point_a = W[0].a;
        out.point_b = W[0].b;
        return out;
      }
    }
  }
  if (!want_depth) {
    // Only the sign is wanted: certified by the tetrahedron's margin when it has one; otherwise
    // (the origin on or near a face, as for concentric solids) EPA below decides.
    const Eigen::Vector3d c = 0.25 * (W[0].w + W[1].w + W[2].w + W[3].w);
    double dmin = std::numeric_limits<double>::infinity();
    static const int fidx[4][3] = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
    for (const auto& f : fidx) {
      Eigen::Vector3d n = (W[f[1]].w - W[f[0]].w).cross(W[f[2]].w - W[f[0]].w);
      if (n.dot(W[f[0]].w - c) < 0) n = -n;
      const double len = n.norm();
      dmin = len > 0 ? std::min(dmin, n.dot(W[f[0]].w) / len) : -1.0;
    }
    if (dmin > margin) {
      out.status = Separation::Overlapping;
      out.distance = 0.0;
      // A common point: the origin's barycentric coordinates in the tetrahedron applied to the
      // support points of a (and of b: the same point up to rounding).
      Eigen::Matrix3d E;
      E << W[1].w - W[0].w, W[2].w - W[0].w, W[3].w - W[0].w;
      Eigen::Vector3d mu;
      detail::fullPivLuSolve(E, Eigen::Vector3d(-W[0].w), &mu);
      const double l0 = 1.0 - mu.sum();
      out.point_a = l0 * W[0].a + mu[0] * W[1].a + mu[1] * W[2].a + mu[2] * W[3].a;
      out.point_b = l0 * W[0].b + mu[0] * W[1].b + mu[1] * W[2].b + mu[2] * W[3].b;
      out.converged = true;
      return out;
    }
  }

  // --- EPA ---------------------------------------------------------------------------------------
  std::vector<Vertex> verts(W.begin(), W.end());
  std::vector<Face> faces;
  std::map<std::pair<int, int>, int> edge_face;  // directed edge (i, j) -> the face that has it
  auto addFace = [&](int i, int j, int k) {
    Face f{{i, j, k}, Eigen::Vector3d::Zero(), 0.0, true};
    Eigen::Vector3d n = (verts[j].w - verts[i].w).cross(verts[k].w - verts[i].w);
    const double len = n.norm();
    f.n = len > 0.0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::UnitX();
    f.d = f.n.dot(verts[i].w);
    const int id = static_cast<int>(faces.size());
    for (int e = 0; e < 3; ++e) edge_face[{f.v[e], f.v[(e + 1) % 3]}] = id;
    faces.push_back(f);
  };
  // The initial tetrahedron, each face counter-clockwise seen from outside.
  {
    const bool positive = (verts[1].w - verts[0].w).cross(verts[2].w - verts[0].w).dot(verts[3].w - verts[0].w) < 0.0;
    const int i0 = 0, i1 = positive ? 1 : 2, i2 = positive ? 2 : 1, i3 = 3;
    addFace(i0, i1, i2);
    addFace(i0, i3, i1);
    addFace(i1, i3, i2);
    addFace(i2, i3, i0);
  }
  double best_up = std::numeric_limits<double>::infinity();
  int face_at_stop = -1;
  bool epa_converged = false;
  int eit = 0;
  for (; eit < kMaxEpaIterations && faces.size() < kMaxEpaFaces; ++eit) {
    int fi = -1;
    for (int i = 0; i < static_cast<int>(faces.size()); ++i)
      if (faces[i].alive && (fi < 0 || faces[i].d < faces[fi].d)) fi = i;
    if (fi < 0) break;
    face_at_stop = fi;
    const Face f = faces[fi];
    if (!want_depth && f.d > margin && originInStar(verts, faces, &out.point_a, &out.point_b)) {
      // Only the sign is wanted, and every face is farther from the origin than the margin: the
      // polytope (points of D) holds the ball of that radius about it, the certificate the
      // tetrahedron's margin gives above. GJK leaves the origin on a face of its tetrahedron
      // (within rounding) for many overlapping pairs with a sphere, which converged EPA took
      // ~50 steps to decide; one or two expansions push that face off.
      out.status = Separation::Overlapping;
      out.distance = 0.0;
      out.converged = true;
      out.iterations += eit;
      return out;
    }
    const Vertex w = D.support(f.n);
    const double up = f.n.dot(w.w);
    best_up = std::min(best_up, up);
    if (best_up - f.d <= kConvexDistanceRelative * std::max(f.d, 0.0) + tiny || up - f.d <= tiny) {
      epa_converged = true;
      break;
    }
    // Expand: flood-fill the faces w sees from f across shared edges (a connected cap), remove
    // them, and close the hole with faces from its horizon edges to w.
    const int wi = static_cast<int>(verts.size());
    verts.push_back(w);
    std::vector<int> stack{fi};
    std::vector<std::pair<int, int>> horizon;
    faces[fi].alive = false;
    while (!stack.empty()) {
      const int g = stack.back();
      stack.pop_back();
      for (int e = 0; e < 3; ++e) {
        const int from = faces[g].v[e], to = faces[g].v[(e + 1) % 3];
        const auto twin = edge_face.find({to, from});
        const int h = twin == edge_face.end() ? -1 : twin->second;
        if (h >= 0 && faces[h].alive && faces[h].n.dot(w.w - verts[faces[h].v[0]].w) > tiny) {
          faces[h].alive = false;
          stack.push_back(h);
        } else if (h < 0 || faces[h].alive) {
          horizon.emplace_back(from, to);
        }
      }
    }
    for (const auto& e : horizon) addFace(e.first, e.second, wi);
  }
  out.iterations += eit;
  out.converged = epa_converged;
  const Face& f = faces[face_at_stop];
  const double depth = epa_converged ? f.d : best_up;  // at the cap: the overestimate (contact side)
  // Witnesses: the projection f.d * n of the origin on the face, in barycentric coordinates.
  const Eigen::Vector3d p = f.d * f.n;
  const Eigen::Vector3d &w0 = verts[f.v[0]].w, &w1 = verts[f.v[1]].w, &w2 = verts[f.v[2]].w;
  const Eigen::Vector3d n = (w1 - w0).cross(w2 - w0);
  const double n2 = n.squaredNorm();
  double l1 = 1.0 / 3.0, l2 = 1.0 / 3.0;
  if (n2 > 0.0) {
    l1 = (p - w0).cross(w2 - w0).dot(n) / n2;
    l2 = (w1 - w0).cross(p - w0).dot(n) / n2;
  }
  const double l0 = 1.0 - l1 - l2;
  out.normal = f.n;
  out.point_a = l0 * verts[f.v[0]].a + l1 * verts[f.v[1]].a + l2 * verts[f.v[2]].a + ra * f.n;
  out.point_b = l0 * verts[f.v[0]].b + l1 * verts[f.v[1]].b + l2 * verts[f.v[2]].b - rb * f.n;
  if (f.d + r > margin) {
    out.status = Separation::Overlapping;
    out.distance = -(depth + r);
  } else {
    out.status = Separation::Touching;
    out.distance = 0.0;
  }
  return out;
}

}  // namespace

SignedDistanceResult convexSignedDistance(const ConvexSupport& a, const Eigen::Matrix3d& R_a, const Eigen::Vector3d& p_a,
                                          const ConvexSupport& b, const Eigen::Matrix3d& R_b, const Eigen::Vector3d& p_b,
                                          bool want_depth, double* lower_bound) {
  return gjkEpa(a, R_a, p_a, b, R_b, p_b, want_depth, lower_bound, std::numeric_limits<double>::infinity(),
                "convexSignedDistance");
}

ConvexScreening screenConvexPair(const ConvexSupport& a, const Eigen::Matrix3d& R_a, const Eigen::Vector3d& p_a,
                                 const ConvexSupport& b, const Eigen::Matrix3d& R_b, const Eigen::Vector3d& p_b,
                                 double gap) {
  if (std::isnan(gap) || gap < 0.0) throw std::invalid_argument("screenConvexPair: gap must be >= 0, got " + std::to_string(gap));
  double lower = 0.0;
  const SignedDistanceResult d = gjkEpa(a, R_a, p_a, b, R_b, p_b, false, &lower, gap, "screenConvexPair");
  ConvexScreening out;
  if (d.status == Separation::Separated && lower > gap) {
    out.verdict = ConvexScreening::Verdict::Far;
  } else if (d.status == Separation::Overlapping) {
    out.verdict = ConvexScreening::Verdict::Overlapping;
    out.common_point = d.point_a;
  }
  out.lower_bound = lower;  // (0 unless Separated)
  out.iterations = d.iterations;
  return out;
}

}  // namespace fcl_quadric
