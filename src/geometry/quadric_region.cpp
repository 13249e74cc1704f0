// Composite quadric models: CSG trees of quadric atoms and the certified box-subdivision engine
// (docs/algorithms.md section 9; Choi 2008 ch.6 for the boundary elements and Figure 29 for the
// CSG membership predicates).
#include "fcl_quadric/geometry/quadric_region.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "fcl_quadric/algebra/double_double.h"
#include "fcl_quadric/algebra/quadric_matrix.h"
#include "fcl_quadric/geometry/ellipsoid.h"
#include "algebra/dense_decompositions.h"
#include "algebra/input_checks.h"
#include "geometry/plane_frame.h"
#include "geometry/region_dual_bound.h"
#include "geometry/region_formula.h"

namespace fcl_quadric {

using namespace tolerance_region;
using detail::Formula;
using detail::FormulaBox;
using detail::goldenPositive;
using detail::chooseSplitAxis;
using detail::Tri;
using detail::atomBox;
using detail::enclose;
using detail::Enclosure;

const char* toString(FaceShape s) {
  switch (s) {
    case FaceShape::Planar: return "planar";
    case FaceShape::Convex: return "convex";
    case FaceShape::Concave: return "concave";
    case FaceShape::Saddle: return "saddle";
  }
  return "?";
}

const char* toString(RegionRelation r) {
  switch (r) {
    case RegionRelation::Separated: return "separated";
    case RegionRelation::Touching: return "touching";
    case RegionRelation::Overlapping: return "overlapping";
  }
  return "?";
}

// Definition 6.1 (§6.2.1). For a non-degenerate quadric the Gaussian curvature has the sign of
// -det Q: det Q > 0 is a saddle (one negative principal curvature everywhere: concave). For
// det Q < 0 both curvatures have one sign, that of A on the tangent plane, which is definite: a
// 2D subspace where A is positive definite needs two positive eigenvalues (convex), negative
// definite two negative ones (concave). Degenerate quadrics (cylinders, cones, plane pairs): the
// non-zero curvature follows the same inertia rule; a pair of planes is planar.
FaceShape classifyFace(const Eigen::Matrix4d& Q) {
  const Eigen::Matrix3d A = Q.topLeftCorner<3, 3>();
  const double scale = Q.cwiseAbs().maxCoeff();
  const double a_scale = A.cwiseAbs().maxCoeff();
  if (a_scale <= 1e-12 * scale) return FaceShape::Planar;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(A, Eigen::EigenvaluesOnly);
  int np = 0, nn = 0;
  for (int i = 0; i < 3; ++i) {
    if (eig.eigenvalues()[i] > 1e-12 * a_scale) ++np;
    if (eig.eigenvalues()[i] < -1e-12 * a_scale) ++nn;
  }
  const double det = Q.determinant();
  const double det_scale = std::pow(scale, 4);
  if (det > 1e-12 * det_scale) return FaceShape::Saddle;  // hyperboloid of one sheet, ...
  if (nn == 0) return FaceShape::Convex;
  if (np == 0) return FaceShape::Concave;
  if (np == 1 && nn == 1 && std::fabs(det) <= 1e-12 * det_scale) return FaceShape::Planar;  // plane pair
  return np >= 2 ? FaceShape::Convex : FaceShape::Concave;
}

// --- QuadricRegion ------------------------------------------------------------------------------

QuadricRegion QuadricRegion::atom(const Eigen::Matrix4d& Q) {
  detail::checkQuadricMatrix(Q);
  if (!(Q.cwiseAbs().maxCoeff() > 0.0)) throw std::invalid_argument("quadric matrix must not be zero");
  QuadricRegion r;
  r.op_ = Op::Atom;
  r.Q_ = 0.5 * (Q + Q.transpose());
  return r;
}

QuadricRegion QuadricRegion::halfspace(const Eigen::Vector3d& n, double d) {
  if (!n.allFinite() || !std::isfinite(d)) {
    std::ostringstream os;
    os << "half-space normal and offset must be finite, got n = [" << n.transpose() << "], d = " << d;
    throw std::invalid_argument(os.str());
  }
  const double len = n.norm();
  if (!(len > 0.0)) throw std::invalid_argument("half-space normal must be non-zero");
  const Eigen::Vector3d u = n / len;
  Eigen::Matrix4d Q = Eigen::Matrix4d::Zero();
  Q.topRightCorner<3, 1>() = 0.5 * u;
  Q.bottomLeftCorner<1, 3>() = 0.5 * u.transpose();
  Q(3, 3) = -d / len;
  QuadricRegion r;
  r.op_ = Op::Atom;
  r.Q_ = Q;
  return r;
}

QuadricRegion QuadricRegion::combine(Op op, std::vector<QuadricRegion> children) {
  if (op == Op::Atom) throw std::invalid_argument("QuadricRegion::combine: op must be union, intersection or difference");
  if (children.empty()) throw std::invalid_argument("QuadricRegion::combine: a CSG operation needs at least one child");
  QuadricRegion r;
  r.op_ = op;
  r.children_ = std::move(children);
  return r;
}

QuadricRegion QuadricRegion::transformedAffine(const Eigen::Matrix3d& M, const Eigen::Vector3d& p) const {
  return transformedHomogeneous(quadric::affineTransform(M, p));
}

QuadricRegion QuadricRegion::transformed(const Eigen::Matrix3d& R, const Eigen::Vector3d& p) const {
  detail::checkRotation(R, "CSG pose rotation");
  detail::checkPosition(p, "CSG pose translation");
  // T^-1 = [R^T, -R^T p] exactly (rigid), so Q' = T^-T Q T^-1 needs no inversion.
  Eigen::Matrix4d Tinv = Eigen::Matrix4d::Identity();
  Tinv.topLeftCorner<3, 3>() = R.transpose();
  Tinv.topRightCorner<3, 1>() = -R.transpose() * p;
  return transformedByInverse(Tinv);
}

QuadricRegion QuadricRegion::transformedHomogeneous(const Eigen::Matrix4d& T) const {
  const Eigen::Matrix4d Tinv = T.inverse();
  if (!Tinv.allFinite()) throw std::invalid_argument("CSG pose must be invertible");
  return transformedByInverse(Tinv);
}

QuadricRegion QuadricRegion::transformedByInverse(const Eigen::Matrix4d& Tinv) const {
  QuadricRegion r;
  r.op_ = op_;
  if (op_ == Op::Atom) {
    const Eigen::Matrix4d Q = Tinv.transpose() * Q_ * Tinv;
    r.Q_ = 0.5 * (Q + Q.transpose());
  }
  r.children_.reserve(children_.size());
  for (const QuadricRegion& c : children_) r.children_.push_back(c.transformedByInverse(Tinv));
  return r;
}

namespace {

// Sign of X^T Q X at x with the rounding pad: -1 certified < 0, +1 certified > 0, 0 otherwise.
int atomPointSign(const Eigen::Matrix4d& Q, const Eigen::Vector3d& x) {
  const Eigen::Vector4d X(x[0], x[1], x[2], 1.0);
  const double v = X.dot(Q * X);
  const Eigen::Vector4d Xa = X.cwiseAbs();
  const double pad = kRegionSignRelative * Xa.dot(Q.cwiseAbs() * Xa);
  if (v > pad) return 1;
  if (v < -pad) return -1;
  return 0;
}

/// atomPointSign from double-double arithmetic (for classifyTree): X^T Q X as the sum of its 16
/// terms X_i Q_ij X_j, each an exact product (twoProd) times X_j in double-double, summed in
/// double-double. Each term is within a few 2^-104 of its magnitude and each of the 15 sums adds
/// at most 2^-104 of the running magnitude, so the value is within 2^-96 |X|^T |Q| |X|; the sign is
/// trusted beyond 2^-90 of it. Far out along a posed cylinder's axis (|x| ~ 1e6) the double
/// evaluation's band (kRegionSignRelative, 2^-40) exceeds the atom's value; this one does not.
int atomPointSignAccurate(const Eigen::Matrix4d& Q, const Eigen::Vector3d& x) {
  const double X[4] = {x[0], x[1], x[2], 1.0};
  DoubleDouble v(0.0);
  double mag = 0.0;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      v += DoubleDouble(detail::twoProd(X[i], Q(i, j))) * DoubleDouble(X[j]);
      mag += std::fabs(X[i]) * std::fabs(Q(i, j)) * std::fabs(X[j]);
    }
  const double pad = 0x1p-90 * mag;
  const double value = toDouble(v);
  if (!std::isfinite(value) || !std::isfinite(pad)) return 0;
  if (value > pad) return 1;
  if (value < -pad) return -1;
  return 0;
}

/// Figure 29 (§6.1): interior / boundary predicates through the tree, three-valued, over the
/// atoms' signs from `sign` (-1 certified inside, +1 certified outside, 0 undecided).
template <class AtomSign>
int classifyTree(const QuadricRegion& r, const Eigen::Vector3d& x, const AtomSign& sign) {
  switch (r.op()) {
    case QuadricRegion::Op::Atom: return -sign(r.matrix(), x);
    case QuadricRegion::Op::Union: {
      int best = -1;
      for (const QuadricRegion& c : r.children()) best = std::max(best, classifyTree(c, x, sign));
      return best;
    }
    case QuadricRegion::Op::Intersection: {
      int worst = 1;
      for (const QuadricRegion& c : r.children()) worst = std::min(worst, classifyTree(c, x, sign));
      return worst;
    }
    case QuadricRegion::Op::Difference: {
      int v = classifyTree(r.children()[0], x, sign);
      for (std::size_t i = 1; i < r.children().size(); ++i) v = std::min(v, -classifyTree(r.children()[i], x, sign));
      return v;
    }
  }
  return 0;
}

}  // namespace

int QuadricRegion::classifyPoint(const Eigen::Vector3d& x) const {
  // (a lambda, not the function's pointer: its own type, so the walk inlines the sign test)
  return classifyTree(*this, x, [](const Eigen::Matrix4d& Q, const Eigen::Vector3d& y) { return atomPointSign(Q, y); });
}

namespace {
void collectSignedAtoms(const QuadricRegion& r, bool neg, std::vector<Eigen::Matrix4d>* out) {
  if (r.op() == QuadricRegion::Op::Atom) {
    out->push_back(neg ? Eigen::Matrix4d(-r.matrix()) : r.matrix());
    return;
  }
  for (std::size_t i = 0; i < r.children().size(); ++i) {
    const bool sub = r.op() == QuadricRegion::Op::Difference && i > 0;
    collectSignedAtoms(r.children()[i], neg != sub, out);
  }
}
}  // namespace

std::vector<Eigen::Matrix4d> QuadricRegion::signedAtoms() const {
  std::vector<Eigen::Matrix4d> out;
  collectSignedAtoms(*this, false, &out);
  return out;
}

// --- Negation normal form -----------------------------------------------------------------------

namespace {



/// Evaluates the formula on a box and keeps the atom / node states for the exclusion test.
class BoxEval {
 public:
  BoxEval(const Formula& f, const Eigen::Vector3d& c, const Eigen::Vector3d& r)
      : f_(f), c_(c), r_(r), box_(f, atomStates(f, nullptr, c, r)) {}
  /// With `abs` (one matrix per atom, >= |atom| entrywise) sizing the rounding pads instead of
  /// |atom|: atoms carried into another frame by a rounded product (patchExcluded).
  BoxEval(const Formula& f, const std::vector<Eigen::Matrix4d>* abs, const Eigen::Vector3d& c, const Eigen::Vector3d& r)
      : f_(f), abs_(abs), c_(c), r_(r), box_(f, atomStates(f, abs, c, r)) {}
  Tri root() const { return box_.root(); }

  /// Heuristic depth of a point: the largest normalised value f / |grad f| of the undecided atoms
  /// (an approximate signed distance to the deciding surface). Only orders the search.
  double depth(const Eigen::Vector3d& x) const {
    double worst = -std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < f_.atoms.size(); ++k) {
      if (box_.atom(static_cast<int>(k)) != Tri::Unknown) continue;
      const Eigen::Matrix4d& Q = f_.atoms[k];
      const Eigen::Vector4d X(x[0], x[1], x[2], 1.0);
      const Eigen::Vector4d QX = Q * X;
      const double g = 2.0 * QX.head<3>().norm();
      worst = std::max(worst, X.dot(QX) / std::max(g, 1e-300));
    }
    return worst;
  }

  /// Axis to split: the one contributing most to the enclosure widths of the undecided atoms
  /// (normalised atoms; first- and second-order terms of the centred form), among the axes whose
  /// edge exceeds min_width. -1 when no such axis matters: the box is then within the band.
  /// Splitting by contribution lets boxes stay long along a line of (near-)contact.
  int splitAxis(double min_width, double max_aspect) const {
    Eigen::Vector3d score = Eigen::Vector3d::Zero();
    for (std::size_t k = 0; k < f_.atoms.size(); ++k) {
      if (box_.atom(static_cast<int>(k)) != Tri::Unknown) continue;
      const Eigen::Matrix4d& Q = f_.atoms[k];
      const double s = 1.0 / Q.cwiseAbs().maxCoeff();
      const Eigen::Matrix3d A = Q.topLeftCorner<3, 3>();
      const Eigen::Vector3d g = 2.0 * (A * c_ + Q.topRightCorner<3, 1>());
      for (int i = 0; i < 3; ++i) {
        double t = std::fabs(g[i]) * r_[i];
        for (int j = 0; j < 3; ++j) t += std::fabs(A(i, j)) * r_[i] * r_[j];
        score[i] += s * t;
      }
    }
    return chooseSplitAxis(score, r_, min_width, max_aspect);
  }

  /// True if the box provably holds no point of the formula (FormulaBox::excluded with the
  /// pencils below).
  bool excluded() {
    return box_.excluded([this](const std::vector<int>& atoms) { return pencilExcluded(atoms); });
  }

 private:
  static std::vector<Tri> atomStates(const Formula& f, const std::vector<Eigen::Matrix4d>* abs,
                                     const Eigen::Vector3d& c, const Eigen::Vector3d& r) {
    std::vector<Tri> out(f.atoms.size());
    for (std::size_t i = 0; i < f.atoms.size(); ++i) {
      if (abs == nullptr) {
        out[i] = atomBox(f.atoms[i], c, r);
        continue;
      }
      const Enclosure e = enclose(f.atoms[i], (*abs)[i], c, r);
      out[i] = e.lo > 0.0 ? Tri::Out : (e.hi < 0.0 ? Tri::In : Tri::Unknown);
    }
    return out;
  }
  Eigen::Matrix4d absOf(int k) const { return abs_ == nullptr ? Eigen::Matrix4d(f_.atoms[k].cwiseAbs()) : (*abs_)[k]; }

  // Lower bound of the centred form of mu f + (1 - mu) g is concave in mu (a linear term minus
  // absolute values of affine functions of mu), so golden section finds its maximum.
  bool pencilExcluded(const std::vector<int>& atoms) const {
    for (std::size_t i = 0; i < atoms.size(); ++i) {
      for (std::size_t j = i + 1; j < atoms.size(); ++j) {
        const Eigen::Matrix4d& F = f_.atoms[atoms[i]];
        const Eigen::Matrix4d& G = f_.atoms[atoms[j]];
        // Scale-balance the two atoms so mu is well spread.
        const double sf = 1.0 / F.cwiseAbs().maxCoeff(), sg = 1.0 / G.cwiseAbs().maxCoeff();
        const Eigen::Matrix4d Fa = sf * absOf(atoms[i]), Ga = sg * absOf(atoms[j]);
        auto lower = [&](double mu) {
          return enclose(mu * sf * F + (1.0 - mu) * sg * G, mu * Fa + (1.0 - mu) * Ga, c_, r_).lo;
        };
        if (goldenPositive(lower, kRegionPencilSteps)) return true;
      }
    }
    // Triples (an edge of the CQM against a third surface, e.g. a rim against a level plane):
    // weights from the first-order condition at the box centre, sum mu_i grad f_i(c) ~ 0 with
    // sum mu_i = 1 (least squares, KKT system); any weights give a valid certificate.
    for (std::size_t i = 0; i < atoms.size(); ++i)
      for (std::size_t j = i + 1; j < atoms.size(); ++j)
        for (std::size_t k = j + 1; k < atoms.size(); ++k) {
          const int ids[3] = {atoms[i], atoms[j], atoms[k]};
          Eigen::Matrix4d Qs[3], Qa[3];
          Eigen::Matrix3d G;
          for (int m = 0; m < 3; ++m) {
            const Eigen::Matrix4d& Q = f_.atoms[ids[m]];
            Qs[m] = Q / Q.cwiseAbs().maxCoeff();
            Qa[m] = absOf(ids[m]) / Q.cwiseAbs().maxCoeff();
            G.col(m) = 2.0 * (Qs[m].topLeftCorner<3, 3>() * c_ + Qs[m].topRightCorner<3, 1>());
          }
          Eigen::Matrix4d K = Eigen::Matrix4d::Zero();
          K.topLeftCorner<3, 3>() = G.transpose() * G;
          K.block<3, 1>(0, 3) = Eigen::Vector3d::Ones();
          K.block<1, 3>(3, 0) = Eigen::RowVector3d::Ones();
          Eigen::Vector4d sol;
          detail::fullPivLuSolve(K, Eigen::Vector4d(0, 0, 0, 1), &sol);
          if (!sol.allFinite()) continue;
          const Eigen::Vector3d mu = sol.head<3>();
          if ((mu.array() < 0.0).any()) continue;
          const Eigen::Matrix4d Q = mu[0] * Qs[0] + mu[1] * Qs[1] + mu[2] * Qs[2];
          const Eigen::Matrix4d Qabs = mu[0] * Qa[0] + mu[1] * Qa[1] + mu[2] * Qa[2];
          if (enclose(Q, Qabs, c_, r_).lo > 0.0) return true;
        }
    return false;
  }

  const Formula& f_;
  const std::vector<Eigen::Matrix4d>* abs_ = nullptr;
  Eigen::Vector3d c_, r_;
  FormulaBox box_;
};

// Point membership of the formula with certified atom signs: In only if certified.
Tri pointEval(const Formula& f, int n, const Eigen::Vector3d& x) {
  return detail::pointEval(f, n, [&](int a) { return atomPointSign(f.atoms[a], x); });
}

void split(const Box3& b, int axis, Box3* l, Box3* h) {
  const double mid = 0.5 * (b.lo[axis] + b.hi[axis]);
  *l = b;
  *h = b;
  l->hi[axis] = mid;
  h->lo[axis] = mid;
}

PointSearchResult findPointFormula(const Formula& f, const Box3& box, int extra_after_undecided, double max_aspect,
                                   double min_box_relative = kRegionMinBoxRelative) {
  PointSearchResult res;
  if (box.empty()) {
    res.status = PointSearch::Empty;
    return res;
  }
  const double min_width = min_box_relative * box.maxEdge();
  int undecided_at = -1;
  std::vector<Box3> stack{box};
  while (!stack.empty()) {
    const Box3 b = stack.back();
    stack.pop_back();
    ++res.boxes;
    const Eigen::Vector3d c = b.center(), r = b.halfWidth();
    BoxEval ev(f, c, r);
    if (ev.root() == Tri::Out) continue;
    if (ev.root() == Tri::In || pointEval(f, f.root, c) == Tri::In) {
      res.status = PointSearch::Found;
      res.point = c;
      return res;
    }
    if (ev.excluded()) continue;
    if (res.boxes >= kRegionMaxBoxes) {
      res.status = PointSearch::Undecided;
      if (undecided_at < 0) res.point = c;
      res.capped = true;
      return res;
    }
    const int axis = ev.splitAxis(min_width, max_aspect);
    if (axis < 0) {
      // Undecided within the band. Keep looking for an interior point for a bounded number of
      // boxes (a touching pair with a line or surface of contact would otherwise visit ~1/width).
      if (undecided_at < 0) {
        undecided_at = res.boxes;
        res.point = c;
      }
      if (res.boxes - undecided_at >= extra_after_undecided) {
        res.status = PointSearch::Undecided;
        return res;
      }
      continue;
    }
    Box3 lo, hi;
    split(b, axis, &lo, &hi);
    // The child whose centre looks deeper inside is searched first.
    if (ev.depth(lo.center()) <= ev.depth(hi.center())) {
      stack.push_back(hi);
      stack.push_back(lo);
    } else {
      stack.push_back(lo);
      stack.push_back(hi);
    }
  }
  res.status = undecided_at < 0 ? PointSearch::Empty : PointSearch::Undecided;
  return res;
}

}  // namespace

PointSearchResult findPoint(const QuadricRegion& region, const Box3& box, int extra_after_undecided) {
  return findPointFormula(Formula(region), box, extra_after_undecided, kRegionMaxAspect);
}

std::optional<Eigen::Vector3d> pencilInteriorCandidate(const Eigen::Matrix4d& A_in, const Eigen::Matrix4d& B_in) {
  const double na = A_in.cwiseAbs().maxCoeff(), nb = B_in.cwiseAbs().maxCoeff();
  if (!(na > 0.0 && nb > 0.0 && std::isfinite(na) && std::isfinite(nb))) return std::nullopt;
  // Positive factors move the maximiser along the same curve x(mu) and keep a(x) = b(x) < 0 there
  // (as a multiple of each): normalise both to max |entry| 1 for a balanced mu.
  const Eigen::Matrix4d A = A_in / na, B = B_in / nb;
  struct Eval {
    Eigen::Vector3d x;
    double diff;  // a(x) - b(x) = g'(mu): decreasing in mu, g being concave
  };
  auto eval = [&](double mu) -> std::optional<Eval> {
    const Eigen::Matrix4d C = mu * A + (1.0 - mu) * B;
    const Eigen::LLT<Eigen::Matrix3d> llt(C.topLeftCorner<3, 3>());
    if (llt.info() != Eigen::Success) return std::nullopt;
    const Eigen::Vector3d x = -llt.solve(Eigen::Vector3d(C.topRightCorner<3, 1>()));
    if (!x.allFinite()) return std::nullopt;
    const Eigen::Vector4d X(x[0], x[1], x[2], 1.0);
    return Eval{x, X.dot(A * X) - X.dot(B * X)};
  };
  // The mu with a positive definite block form an interval (a convex set): find one of them, then
  // its ends by bisection, keeping the last definite point on each side.
  double inside = -1.0;
  for (double mu : {1.0, 0.0, 0.5, 0.25, 0.75, 0.125, 0.375, 0.625, 0.875}) {
    if (eval(mu)) {
      inside = mu;
      break;
    }
  }
  if (inside < 0.0) return std::nullopt;
  auto end = [&](double outer) {
    if (eval(outer)) return outer;
    double in = inside, out = outer;
    for (int k = 0; k < 50; ++k) {
      const double mid = 0.5 * (in + out);
      (eval(mid) ? in : out) = mid;
    }
    return in;
  };
  double lo = end(0.0), hi = end(1.0);
  const std::optional<Eval> e_lo = eval(lo), e_hi = eval(hi);
  if (!e_lo || !e_hi) return std::nullopt;
  if (e_hi->diff >= 0.0) return e_hi->x;  // g increases up to hi: its maximum is there
  if (e_lo->diff <= 0.0) return e_lo->x;
  Eigen::Vector3d best = e_lo->x;
  for (int k = 0; k < 60 && lo < hi; ++k) {
    const double mid = 0.5 * (lo + hi);
    const std::optional<Eval> e = eval(mid);
    if (!e) break;
    best = e->x;
    (e->diff > 0.0 ? lo : hi) = mid;
  }
  return best;
}

QuadricRegion intersectionInFrame(const QuadricRegion& a, const QuadricRegion& b, const Eigen::Matrix3d& R_AB,
                                  const Eigen::Vector3d& p_AB) {
  return QuadricRegion::combine(QuadricRegion::Op::Intersection, {a, b.transformed(R_AB, p_AB)});
}

Box3 transformBox(const Box3& box, const Eigen::Matrix3d& R, const Eigen::Vector3d& p) {
  const Eigen::Vector3d c = R * box.center() + p;
  const Eigen::Vector3d r = R.cwiseAbs() * box.halfWidth();
  // Outward rounding: one relative ulp-scale pad on the radius.
  const Eigen::Vector3d pad = 1e-15 * (c.cwiseAbs() + r) + Eigen::Vector3d::Constant(1e-300);
  return Box3{c - r - pad, c + r + pad};
}

// --- maxLinear ----------------------------------------------------------------------------------

namespace {
// Bisection on the level U: findPoint(region AND d.x >= U). Empty certifies U as an upper bound;
// Found gives a point with d.x >= U; Undecided (within the band) raises the lower end only. The
// pencil exclusion of the level half-space against the atoms (the Lagrange bound
// U - d.x + lambda f >= 0) keeps each search short near the tangent point.
bool maxLinearFormula(const QuadricRegion& region, const Eigen::Vector3d& d, const Box3& box, double* upper) {
  const Formula formula(region);
  const PointSearchResult any = findPointFormula(formula, box, 0, kRegionMaxAspect);
  if (any.status == PointSearch::Empty) return false;
  const double reach = d.cwiseAbs().dot(box.halfWidth());
  double hi = d.dot(box.center()) + reach;  // certified: the box bound
  double lo = any.status == PointSearch::Found ? d.dot(any.point) : d.dot(box.center()) - reach;
  const double tol = kRegionAabbRelative * 2.0 * reach;
  // The duality bound over pairs of atoms (region_dual_bound.h), certified as the box bound is.
  // Where it is tight, the first level tried is just below it, and a point found there ends the
  // search: the levels above it, whose exclusion costs the search the most near a curve of
  // maximisers (a ring's rim: 7-14 ms each), are never searched.
  const double dual = detail::dualLinearBound(formula, d, box);
  const bool probe_below_dual = dual < hi;
  hi = std::min(hi, dual);
  for (int k = 0; k < kRegionMaxAabbBisections && hi - lo > tol; ++k) {
    const double U = probe_below_dual && k == 0 ? hi - 0.5 * tol : 0.5 * (lo + hi);
    const QuadricRegion level = QuadricRegion::halfspace(-d, -U);
    const PointSearchResult s =
        findPointFormula(Formula(QuadricRegion::combine(QuadricRegion::Op::Intersection, {region, level})), box, 0,
                         std::numeric_limits<double>::infinity());
    switch (s.status) {
      case PointSearch::Empty: hi = U; break;
      case PointSearch::Found: lo = std::max(U, d.dot(s.point)); break;
      case PointSearch::Undecided: lo = U; break;
    }
  }
  *upper = hi;
  return true;
}
}  // namespace

bool maxLinear(const QuadricRegion& region, const Eigen::Vector3d& d, const Box3& box, double* upper) {
  return maxLinearFormula(region, d, box, upper);
}

namespace {
// A box containing the region, from the tree: an ellipsoid atom (3x3 part positive definite,
// X^T Q X = (x - m)^T A (x - m) - k with m = -A^-1 b, k = b^T A^-1 b - c) has the extents
// sqrt(k (A^-1)_ii); intersections intersect, unions unite, differences keep the first. The
// boxes are widened by a relative 1e-9 (covers the rounding of the inverse); none if unknown.
bool treeHint(const QuadricRegion& r, Box3* out) {
  switch (r.op()) {
    case QuadricRegion::Op::Atom: {
      const Eigen::Matrix3d A = r.matrix().topLeftCorner<3, 3>();
      // Only well-conditioned positive definite parts: a cylinder rotated in floating point can
      // have a tiny positive eigenvalue, and its "ellipsoid" box must not hide unboundedness.
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(A, Eigen::EigenvaluesOnly);
      if (!(eig.eigenvalues()[0] > 1e-10 * eig.eigenvalues()[2])) return false;
      Eigen::LLT<Eigen::Matrix3d> llt(A);
      if (llt.info() != Eigen::Success) return false;
      const Eigen::Vector3d b = r.matrix().topRightCorner<3, 1>();
      const Eigen::Matrix3d Ainv = llt.solve(Eigen::Matrix3d::Identity());
      const Eigen::Vector3d m = -Ainv * b;
      const double k = b.dot(Ainv * b) - r.matrix()(3, 3);
      if (!(k > 0.0) || !Ainv.allFinite()) return false;
      const Eigen::Vector3d h = (k * Ainv.diagonal()).cwiseSqrt();
      const Eigen::Vector3d pad = 1e-9 * (h + m.cwiseAbs());
      *out = Box3{m - h - pad, m + h + pad};
      return out->lo.allFinite() && out->hi.allFinite() && (out->hi - out->lo).maxCoeff() < kRegionMaxExtent;
    }
    case QuadricRegion::Op::Intersection: {
      bool any = false;
      for (const QuadricRegion& c : r.children()) {
        Box3 b;
        if (!treeHint(c, &b)) continue;
        if (!any) {
          *out = b;
          any = true;
        } else {
          out->lo = out->lo.cwiseMax(b.lo);
          out->hi = out->hi.cwiseMin(b.hi);
        }
      }
      return any;
    }
    case QuadricRegion::Op::Union: {
      for (std::size_t i = 0; i < r.children().size(); ++i) {
        Box3 b;
        if (!treeHint(r.children()[i], &b)) return false;
        if (i == 0) {
          *out = b;
        } else {
          out->lo = out->lo.cwiseMin(b.lo);
          out->hi = out->hi.cwiseMax(b.hi);
        }
      }
      return true;
    }
    case QuadricRegion::Op::Difference: return treeHint(r.children()[0], out);
  }
  return false;
}

/// A certified interior point of the region at the search's limit of unboundedness (some |x_i| =
/// 0.9995 kRegionMaxExtent, inside the search cube and beyond the 0.999 kRegionMaxExtent at which
/// the search calls a region unbounded, so that the search would say so too), if one of a few
/// candidates is: along each atom's eigenvector whose eigenvalue is near zero or negative (a
/// cylinder's axis, a paraboloid's, a hyperboloid's or cone's negative direction, every direction
/// of a plane or of a subtracted ellipsoid), from the atom's centre over its other eigenvalues,
/// both ways. An unclipped unbounded quadric (a CSG operand) used to be found unbounded by the
/// search, 3-11 ms; this takes microseconds. A candidate is only a candidate: classifyPoint, or
/// its double-double form where the double one's band is too wide (a posed cylinder's axis),
/// certifies it; without one the search decides.
std::optional<Eigen::Vector3d> unboundedWitness(const QuadricRegion& region) {
  for (const Eigen::Matrix4d& M : region.signedAtoms()) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(M.topLeftCorner<3, 3>());
    const Eigen::Vector3d lam = es.eigenvalues();
    const Eigen::Matrix3d& V = es.eigenvectors();
    const double lmax = lam.cwiseAbs().maxCoeff();
    const Eigen::Vector3d bz = V.transpose() * M.topRightCorner<3, 1>();
    Eigen::Vector3d z0 = Eigen::Vector3d::Zero();  // the centre over the clearly positive eigenvalues
    for (int j = 0; j < 3; ++j)
      if (lam[j] > 1e-9 * lmax) z0[j] = -bz[j] / lam[j];
    const Eigen::Vector3d x0 = V * z0;
    for (int j = 0; j < 3; ++j) {
      if (lam[j] > 1e-9 * lmax) continue;
      int k = 0;
      const double vk = V.col(j).cwiseAbs().maxCoeff(&k);
      for (const double sign : {1.0, -1.0}) {
        // x = x0 + t sign v_j with |x_k| = 0.9995 kRegionMaxExtent on the side sign v_jk points to.
        const double side = sign * V(k, j) > 0.0 ? 1.0 : -1.0;
        const double t = (0.9995 * kRegionMaxExtent - side * x0[k]) / vk;
        if (!(t > 0.0)) continue;
        const Eigen::Vector3d x = x0 + t * sign * V.col(j);
        if (!detail::allFinite(x)) continue;
        auto accurate = [](const Eigen::Matrix4d& Q, const Eigen::Vector3d& y) { return atomPointSignAccurate(Q, y); };
        if (region.classifyPoint(x) > 0 || classifyTree(region, x, accurate) > 0) return x;
      }
    }
  }
  return std::nullopt;
}
}  // namespace

Box3 regionAabb(const QuadricRegion& region, const Box3* hint) {
  const QuadricRegion& f = region;
  Box3 tree_box;
  if (hint == nullptr && treeHint(region, &tree_box)) {
    if (tree_box.empty()) throw std::invalid_argument("quadric region is empty (its bounding pieces do not meet)");
    if (region.op() == QuadricRegion::Op::Atom) return tree_box;  // an ellipsoid: analytic
    hint = &tree_box;
  }
  bool have_hint = hint != nullptr && !hint->empty();
  if (!have_hint) {
    if (const std::optional<Eigen::Vector3d> far = unboundedWitness(region)) {
      int i = 0;
      far->cwiseAbs().maxCoeff(&i);
      std::ostringstream os;
      os << "quadric region is unbounded (reaches |x_" << i << "| >= " << kRegionMaxExtent
         << "); clip it with half-spaces to make it bounded";
      throw std::invalid_argument(os.str());
    }
    // The duality bounds of the six faces over the search cube. Where every one lies inside the
    // limit at which the search calls a region unbounded (0.999 kRegionMaxExtent), the region's
    // part in the cube does not reach that limit, which is the search's own test of boundedness,
    // and the bounds box it (certified): the search starts from them instead of the cube, whose
    // first stage can spend the engine's whole box budget on a small posed region (a posed
    // paraboloid shell: 1 s).
    const Box3 cube{Eigen::Vector3d::Constant(-kRegionMaxExtent), Eigen::Vector3d::Constant(kRegionMaxExtent)};
    const double limit = kRegionMaxExtent * (1.0 - 1e-3);
    const Formula formula(region);
    Box3 dual;
    bool inside = true;
    for (int i = 0; i < 3 && inside; ++i) {
      const Eigen::Vector3d e = Eigen::Vector3d::Unit(i);
      const double up = detail::dualLinearBound(formula, e, cube);
      const double down = detail::dualLinearBound(formula, -e, cube);
      inside = up < limit && down < limit;
      dual.hi[i] = up;
      dual.lo[i] = -down;
    }
    if (inside && !dual.empty()) {
      tree_box = dual;
      hint = &tree_box;
      have_hint = true;
    }
  }
  Box3 search;
  if (have_hint) {
    search = *hint;
  } else {
    search.lo = Eigen::Vector3d::Constant(-kRegionMaxExtent);
    search.hi = Eigen::Vector3d::Constant(kRegionMaxExtent);
  }
  // Stages: each stage's certified bounds give a smaller search box for the next, so the final
  // tolerance is relative to the region's own size, not to the initial search box.
  constexpr int kMaxStages = 6;
  for (int stage = 0; stage < kMaxStages; ++stage) {
    Box3 next;
    for (int i = 0; i < 3; ++i) {
      Eigen::Vector3d e = Eigen::Vector3d::Zero();
      e[i] = 1.0;
      double up = 0.0, down = 0.0;
      if (!maxLinearFormula(f, e, search, &up) || !maxLinearFormula(f, -e, search, &down))
        throw std::invalid_argument("quadric region is empty (e.g. the clipping half-spaces exclude the whole solid)");
      next.hi[i] = std::min(up, search.hi[i]);
      next.lo[i] = std::max(-down, search.lo[i]);
      if (!have_hint && stage == 0) {
        const double reach = kRegionMaxExtent * (1.0 - 1e-3);
        if (up >= reach || down >= reach) {
          std::ostringstream os;
          os << "quadric region is unbounded (reaches |x_" << i << "| >= " << kRegionMaxExtent
             << "); clip it with half-spaces to make it bounded";
          throw std::invalid_argument(os.str());
        }
      }
    }
    const bool shrunk = next.maxEdge() < 0.5 * search.maxEdge();
    // Widen by the stage tolerance so the next stage's box still contains the region.
    const Eigen::Vector3d pad = Eigen::Vector3d::Constant(2.0 * kRegionAabbRelative * search.maxEdge());
    search = Box3{next.lo - pad, next.hi + pad};
    if (!shrunk) break;
  }
  return search;
}

// --- Mass properties: exact chords, adaptive Gauss-Kronrod in y and x ----------------------

namespace {

// The z-chord of the formula at (x, y) inside [zlo, zhi]: each atom restricted to the line is
// alpha z^2 + 2 beta z + gamma, whose real roots are breakpoints; between breakpoints membership
// is constant and read at the midpoint. Returns the integrals of 1, z, z^2 over the chord.
Eigen::Vector3d chordMoments(const Formula& f, double x, double y, double zlo, double zhi) {
  std::vector<double> bp{zlo, zhi};
  for (const Eigen::Matrix4d& Q : f.atoms) {
    const double alpha = Q(2, 2);
    const double beta = Q(2, 0) * x + Q(2, 1) * y + Q(2, 3);
    const double gamma = Q(0, 0) * x * x + Q(1, 1) * y * y + 2.0 * Q(0, 1) * x * y + 2.0 * Q(0, 3) * x +
                         2.0 * Q(1, 3) * y + Q(3, 3);
    if (alpha == 0.0) {
      if (beta != 0.0) bp.push_back(-gamma / (2.0 * beta));
      continue;
    }
    const double disc = beta * beta - alpha * gamma;
    if (disc < 0.0) continue;
    const double s = std::sqrt(disc);
    const double q = -(beta + std::copysign(s, beta));
    if (q != 0.0) {
      bp.push_back(q / alpha);
      bp.push_back(gamma / q);
    } else {
      bp.push_back(0.0);
    }
  }
  std::sort(bp.begin(), bp.end());
  Eigen::Vector3d m = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k + 1 < bp.size(); ++k) {
    const double a = std::max(bp[k], zlo), b = std::min(bp[k + 1], zhi);
    if (!(b > a)) continue;
    const Eigen::Vector3d mid(x, y, 0.5 * (a + b));
    // Plain sign at the midpoint: membership is constant on the open sub-interval.
    bool inside;
    {
      std::function<bool(int)> ev = [&](int n) -> bool {
        const Formula::Node& node = f.nodes[n];
        for (int at : node.atoms) {
          const Eigen::Vector4d X(mid[0], mid[1], mid[2], 1.0);
          const bool in = X.dot(f.atoms[at] * X) <= 0.0;
          if (node.is_and && !in) return false;
          if (!node.is_and && in) return true;
        }
        for (int sub : node.nodes) {
          const bool in = ev(sub);
          if (node.is_and && !in) return false;
          if (!node.is_and && in) return true;
        }
        return node.is_and;
      };
      inside = ev(f.root);
    }
    if (!inside) continue;
    m[0] += b - a;
    m[1] += 0.5 * (b * b - a * a);
    m[2] += (b * b * b - a * a * a) / 3.0;
  }
  return m;
}

// Adaptive Gauss-Kronrod (7-15) of a vector-valued function on [a, b].
template <typename Fn, typename V>
V gaussKronrod(const Fn& fn, double a, double b, double tol, int depth, double* err) {
  static const double xk[8] = {0.991455371120812639, 0.949107912342758525, 0.864864423359769073,
                               0.741531185599394440, 0.586087235467691130, 0.405845151377397167,
                               0.207784955007898468, 0.0};
  static const double wk[8] = {0.022935322010529225, 0.063092092629978553, 0.104790010322250184,
                               0.140653259715525919, 0.169004726639267903, 0.190350578064785410,
                               0.204432940075298892, 0.209482141084727828};
  static const double wg[4] = {0.129484966168869693, 0.279705391489276668, 0.381830050505118945,
                               0.417959183673469388};
  const double c = 0.5 * (a + b), h = 0.5 * (b - a);
  V k = wk[7] * fn(c);
  V g = wg[3] * fn(c);
  for (int i = 0; i < 7; ++i) {
    const V s = fn(c - h * xk[i]) + fn(c + h * xk[i]);
    k += wk[i] * s;
    if (i % 2 == 1) g += wg[i / 2] * s;
  }
  k *= h;
  g *= h;
  const double e = (k - g).cwiseAbs().maxCoeff();
  if (e <= tol || depth <= 0) {
    *err += e;
    return k;
  }
  return gaussKronrod<Fn, V>(fn, a, c, 0.5 * tol, depth - 1, err) + gaussKronrod<Fn, V>(fn, c, b, 0.5 * tol, depth - 1, err);
}

// Real roots of a t^2 + 2 b t + c = 0 (linear when a = 0), appended to out.
void quadraticRoots(double a, double b, double c, std::vector<double>* out) {
  if (a == 0.0) {
    if (b != 0.0) out->push_back(-c / (2.0 * b));
    return;
  }
  const double disc = b * b - a * c;
  if (disc < 0.0) return;
  const double q = -(b + std::copysign(std::sqrt(disc), b));
  if (q != 0.0) {
    out->push_back(q / a);
    out->push_back(c / q);
  } else {
    out->push_back(0.0);
  }
}

// Where the z-chord of an atom changes non-smoothly over the (x, y) plane: the conic
// disc(x, y) = beta^2 - alpha gamma = X^T (l l^T - alpha Q') X (X = (x, y, 1), beta = l.X,
// gamma = X^T Q' X, Q' = Q without its z row and column): the silhouette; for a vertical atom
// (alpha = 0 = l) the atom itself, X^T Q' X = 0: a wall where the chord jumps.
std::vector<Eigen::Matrix3d> silhouetteConics(const Formula& f) {
  std::vector<Eigen::Matrix3d> out;
  for (const Eigen::Matrix4d& Q : f.atoms) {
    const int idx[3] = {0, 1, 3};
    Eigen::Matrix3d Qp;
    Eigen::Vector3d l;
    for (int i = 0; i < 3; ++i) {
      l[i] = Q(2, idx[i]);
      for (int j = 0; j < 3; ++j) Qp(i, j) = Q(idx[i], idx[j]);
    }
    const double alpha = Q(2, 2);
    if (alpha == 0.0 && l.isZero(0.0)) {
      out.push_back(Qp);
    } else {
      out.push_back(l * l.transpose() - alpha * Qp);
    }
  }
  // Kinks: the projection of (plane atom) x (any other atom) onto the (x, y) plane, z eliminated
  // with the plane: X = M (x, y, 1), conic M^T Q M. (Quadric x quadric curves project to
  // quartics and are left to the adaptive rule.)
  for (std::size_t p = 0; p < f.atoms.size(); ++p) {
    const Eigen::Matrix4d& P = f.atoms[p];
    if (!P.topLeftCorner<3, 3>().isZero(0.0) || P(2, 3) == 0.0) continue;  // non-vertical planes only
    const Eigen::Vector3d n2 = 2.0 * P.topRightCorner<3, 1>();             // n2.x + P33 = 0
    Eigen::Matrix<double, 4, 3> M = Eigen::Matrix<double, 4, 3>::Zero();
    M(0, 0) = 1.0;
    M(1, 1) = 1.0;
    M(2, 0) = -n2[0] / n2[2];
    M(2, 1) = -n2[1] / n2[2];
    M(2, 2) = -P(3, 3) / n2[2];
    M(3, 2) = 1.0;
    for (std::size_t q = 0; q < f.atoms.size(); ++q) {
      if (q == p) continue;
      out.push_back(M.transpose() * f.atoms[q] * M);
    }
  }
  return out;
}

// Sorted breakpoints of [a, b]: a, b and the roots inside.
std::vector<double> breakpoints(std::vector<double> roots, double a, double b) {
  std::vector<double> bp{a, b};
  for (double r : roots)
    if (r > a && r < b) bp.push_back(r);
  std::sort(bp.begin(), bp.end());
  return bp;
}

}  // namespace

MassProperties regionMassProperties(const QuadricRegion& region, const Box3& box) {
  const Formula f(region);
  const double vol_box = (box.hi - box.lo).prod();
  const double tol = kRegionVolumeRelative * vol_box;
  constexpr int kMaxDepth = 18;  // bisections per Gauss-Kronrod panel (cap; error still reported)
  using V = Eigen::Matrix<double, 10, 1>;  // 1, x, y, z, xx, yy, zz, xy, xz, yz
  const std::vector<Eigen::Matrix3d> conics = silhouetteConics(f);
  double err_inner = 0.0;
  int inner_calls = 0;
  auto inner = [&](double x) -> V {
    ++inner_calls;
    auto fy = [&](double y) -> V {
      const Eigen::Vector3d m = chordMoments(f, x, y, box.lo[2], box.hi[2]);
      V v;
      v << m[0], x * m[0], y * m[0], m[1], x * x * m[0], y * y * m[0], m[2], x * y * m[0], x * m[1], y * m[1];
      return v;
    };
    // Split at the silhouettes / walls crossing this x (the chord is smooth in between).
    std::vector<double> roots;
    for (const Eigen::Matrix3d& C : conics)
      quadraticRoots(C(1, 1), C(0, 1) * x + C(1, 2), C(0, 0) * x * x + 2.0 * C(0, 2) * x + C(2, 2), &roots);
    const std::vector<double> bp = breakpoints(roots, box.lo[1], box.hi[1]);
    V sum = V::Zero();
    for (std::size_t k = 0; k + 1 < bp.size(); ++k)
      sum += gaussKronrod<decltype(fy), V>(fy, bp[k], bp[k + 1], tol / (box.hi[0] - box.lo[0]) / (bp.size() - 1),
                                           kMaxDepth, &err_inner);
    return sum;
  };
  // Outer breakpoints: x where a silhouette conic has a vertical tangent (double root in y).
  std::vector<double> xroots;
  for (const Eigen::Matrix3d& C : conics) {
    // (c01 x + c12)^2 - c11 (c00 x^2 + 2 c02 x + c22) = 0
    const double a = C(0, 1) * C(0, 1) - C(1, 1) * C(0, 0);
    const double b = C(0, 1) * C(1, 2) - C(1, 1) * C(0, 2);
    const double c = C(1, 2) * C(1, 2) - C(1, 1) * C(2, 2);
    quadraticRoots(a, b, c, &xroots);
    if (C(1, 1) == 0.0 && C(0, 1) == 0.0 && C(1, 2) == 0.0) {  // conic independent of y: x-walls
      quadraticRoots(C(0, 0), C(0, 2), C(2, 2), &xroots);
    }
  }
  const std::vector<double> xbp = breakpoints(xroots, box.lo[0], box.hi[0]);
  double err_outer = 0.0;
  V I = V::Zero();
  for (std::size_t k = 0; k + 1 < xbp.size(); ++k)
    I += gaussKronrod<decltype(inner), V>(inner, xbp[k], xbp[k + 1], tol / (xbp.size() - 1), kMaxDepth, &err_outer);
  MassProperties mp;
  mp.volume = I[0];
  // Estimated (not certified): the outer Kronrod-Gauss differences plus the mean inner one times
  // the x-width (the weights of the outer rule sum to that width).
  mp.volume_error = err_outer + (box.hi[0] - box.lo[0]) * err_inner / std::max(1, inner_calls);
  if (mp.volume > 0.0) mp.centroid = Eigen::Vector3d(I[1], I[2], I[3]) / mp.volume;
  Eigen::Matrix3d second;
  second << I[4], I[7], I[8], I[7], I[5], I[9], I[8], I[9], I[6];
  mp.inertia = second.trace() * Eigen::Matrix3d::Identity() - second;
  return mp;
}

// --- Boundary elements ----------------------------------------------------------------------

namespace {

// Witnesses of boundary elements: a point of the region lying on every surface of the element.
// The certified search (mayMeet below) descends ~20 levels to its resolution before it gives up
// on an element that exists (~60 boxes of pencil tests: 70 ms for a box's 12 edges and 8
// vertices, 0.4 s for a plus-shaped union's, 1.6-2.7 ms for each circle of a capped cylinder);
// a witness keeps it at once. Where the region's formula, with the element's own atoms satisfied
// (zero on their surfaces) and every other atom's sign certified at the point, is certified In,
// a point of region ∩ {f = 0} is there (up to the rounding of the point, well inside the signs'
// pads where the planes meet at an angle and a quadric is crossed, not grazed): the search could
// never certify that element empty, so the elements kept are the same. The candidates lie on
// lines: the line of two of the element's planes (an edge or a vertex), lines of its one plane
// (a planar face; a conic edge, at the quadric's crossings), lines through the box centre (a
// curved face, at its crossings). No witness found (an atom undecided at every candidate, planes
// at grazing angles, a curve of two quadrics) leaves the decision to the search.

// An exactly linear atom (zero quadratic block): a plane.
bool isPlane(const Eigen::Matrix4d& P) { return P.topLeftCorner<3, 3>().isZero(0.0); }

// The witness test at x: the formula with the atoms in `on` satisfied and the others' signs
// certified at x in double-double (atomPointSignAccurate: far shapes keep their signs).
bool witnesses(const Formula& f, const std::vector<int>& on, const Eigen::Vector3d& x) {
  return detail::pointEval(f, f.root, [&](int a) {
           return std::find(on.begin(), on.end(), a) != on.end() ? -1 : atomPointSignAccurate(f.atoms[a], x);
         }) == Tri::In;
}

// X^T Q X along x(s) = p + s d: {a, b, c} of a s^2 + 2 b s + c (quadraticRoots' form).
std::array<double, 3> alongLine(const Eigen::Matrix4d& Q, const Eigen::Vector3d& p, const Eigen::Vector3d& d) {
  const Eigen::Vector4d P(p[0], p[1], p[2], 1.0), D(d[0], d[1], d[2], 0.0);
  return {D.dot(Q * D), D.dot(Q * P), P.dot(Q * P)};
}

bool inBox(const Box3& box, const Eigen::Vector3d& x, double pad) {
  return (x.array() >= box.lo.array() - pad).all() && (x.array() <= box.hi.array() + pad).all();
}

// The range [s_lo, s_hi] of the line p + s d inside the box; false when it misses the box.
bool clipLineToBox(const Eigen::Vector3d& p, const Eigen::Vector3d& d, const Box3& box, double* s_lo, double* s_hi) {
  *s_lo = -std::numeric_limits<double>::infinity();
  *s_hi = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    if (d[k] == 0.0) {
      if (p[k] < box.lo[k] || p[k] > box.hi[k]) return false;
      continue;
    }
    const double a = (box.lo[k] - p[k]) / d[k], b = (box.hi[k] - p[k]) / d[k];
    *s_lo = std::max(*s_lo, std::min(a, b));
    *s_hi = std::min(*s_hi, std::max(a, b));
  }
  return *s_lo <= *s_hi;
}

// The line p + s d of the planes (covectors) p1, p2 meeting at an angle (|n1 x n2| >= 1e-6 |n1|
// |n2|), and the range of s inside the box. False for grazing planes or a line missing the box.
bool planesLine(const Eigen::Vector4d& p1, const Eigen::Vector4d& p2, const Box3& box, Eigen::Vector3d* p,
                Eigen::Vector3d* d, double* s_lo, double* s_hi) {
  if (!detail::lineOfPlanes(p1, p2, p, d)) return false;
  if (!(d->norm() >= 1e-6 * p1.head<3>().norm() * p2.head<3>().norm())) return false;
  return clipLineToBox(*p, *d, box, s_lo, s_hi);
}

// A witness on the line p + s d (s in [s_lo, s_hi], inside the box) of the element on the atoms
// `ids`: the line lies on its planes (two, one, or none for a curved face), and `rest` holds its
// other atom, if any. The atoms vanishing along the line (to 1e-10 of their magnitude there) hold
// on all of it: the element's own and their duplicates (a union's shared cap). An own atom that
// crosses the line gives the candidates, its crossings (a vertex, a conic edge, a curved face);
// otherwise they are the midpoints between every other atom's crossings (an edge, a planar face).
bool lineWitness(const Formula& f, const std::vector<int>& ids, const std::vector<int>& rest, const Eigen::Vector3d& p,
                 const Eigen::Vector3d& d, double s_lo, double s_hi, const Box3& box) {
  std::vector<int> on = ids;
  std::vector<std::vector<double>> roots(f.atoms.size());
  std::vector<bool> vanishes(f.atoms.size());
  for (std::size_t a = 0; a < f.atoms.size(); ++a) {
    const std::array<double, 3> q = alongLine(f.atoms[a], p, d);
    const std::array<double, 3> m = alongLine(f.atoms[a].cwiseAbs(), p.cwiseAbs(), d.cwiseAbs());
    vanishes[a] = std::fabs(q[0]) <= 1e-10 * m[0] && std::fabs(q[1]) <= 1e-10 * m[1] && std::fabs(q[2]) <= 1e-10 * m[2];
    const bool own = std::find(ids.begin(), ids.end(), static_cast<int>(a)) != ids.end();
    if (vanishes[a] && !own) on.push_back(static_cast<int>(a));
    if (!vanishes[a]) quadraticRoots(q[0], q[1], q[2], &roots[a]);
  }
  int crossing = -1;
  for (int r : rest)
    if (!vanishes[static_cast<std::size_t>(r)]) crossing = r;
  // The line must lie on the element's other atoms (a plane's line misplaced by rounding, or a
  // second plane that is parallel but not the same).
  for (int a : ids)
    if (!vanishes[static_cast<std::size_t>(a)] && std::find(rest.begin(), rest.end(), a) == rest.end()) return false;
  // A witness may lie outside the box by 1e-9 of its size (a vertex or edge on the region's
  // bounding box, its coordinates rounded either way), well within the search's resolution.
  const double pad = 1e-9 * box.maxEdge(), pad_s = pad / d.norm();
  std::vector<double> candidates;
  if (crossing < 0) {
    std::vector<double> breaks{s_lo, s_hi};
    for (std::size_t a = 0; a < f.atoms.size(); ++a) {
      if (std::find(on.begin(), on.end(), static_cast<int>(a)) != on.end()) continue;
      for (double s : roots[a])
        if (s > s_lo && s < s_hi) breaks.push_back(s);
    }
    std::sort(breaks.begin(), breaks.end());
    for (std::size_t k = 0; k + 1 < breaks.size(); ++k)
      if (breaks[k + 1] > breaks[k]) candidates.push_back(0.5 * (breaks[k] + breaks[k + 1]));
  } else {
    // Crossings, not grazes: the atom's signs at s -+ h (double-double, atomPointSignAccurate)
    // are opposite, so the segment between those two points meets the surface, within h (1e-7 of
    // the segment, inside the search's resolution) of the candidate. A line grazing a quadric, or
    // a far shape whose atom the rounding blurs at that distance, is left to the search.
    const Eigen::Matrix4d& Q = f.atoms[static_cast<std::size_t>(crossing)];
    const double h = 1e-7 * (s_hi - s_lo);
    for (double s : roots[static_cast<std::size_t>(crossing)]) {
      if (!(s >= s_lo - pad_s && s <= s_hi + pad_s)) continue;
      if (atomPointSignAccurate(Q, p + (s - h) * d) * atomPointSignAccurate(Q, p + (s + h) * d) < 0)
        candidates.push_back(s);
    }
  }
  for (double s : candidates) {
    const Eigen::Vector3d x = p + s * d;
    if (inBox(box, x, pad) && witnesses(f, on, x)) return true;
  }
  return false;
}

// A witness on lines of the plane of atom `plane` through the box centre's projection, in eight
// directions (the frame's u and v of detail::planeFrame, turned by multiples of pi / 8). For a
// planar face (ids = {plane}, no rest; or the same plane twice, a union's shared cap), and for a
// conic edge (ids = {plane, quadric}, rest = {quadric}: the quadric's crossings of the lines are
// the candidates). False when none is found.
bool planeLinesWitness(const Formula& f, int plane_id, const std::vector<int>& ids, const std::vector<int>& rest,
                       const Box3& box) {
  const Eigen::Vector4d plane = detail::planeOf(f.atoms[plane_id]);
  const Eigen::Vector3d n = plane.head<3>(), c = box.center();
  const Eigen::Vector3d p = c - (n.dot(c) + plane[3]) / n.squaredNorm() * n;
  const Eigen::Matrix<double, 4, 3> frame = detail::planeFrame(plane);
  const Eigen::Vector3d u = frame.block<3, 1>(0, 0), v = frame.block<3, 1>(0, 1);
  for (int k = 0; k < 8; ++k) {
    const double angle = k * (0.125 * M_PI);
    const Eigen::Vector3d d = std::cos(angle) * u + std::sin(angle) * v;
    double s_lo = 0.0, s_hi = 0.0;
    if (clipLineToBox(p, d, box, &s_lo, &s_hi) && lineWitness(f, ids, rest, p, d, s_lo, s_hi, box)) return true;
  }
  return false;
}

// A witness of a curved face: the quadric's crossings of the lines through the box centre along
// the axes and the four diagonals. False when none is found.
bool quadricFaceWitness(const Formula& f, int id, const Box3& box) {
  const Eigen::Vector3d c = box.center();
  for (int k = 0; k < 7; ++k) {
    const Eigen::Vector3d d = k < 3 ? Eigen::Vector3d(Eigen::Vector3d::Unit(k))
                                    : Eigen::Vector3d(1.0, (k & 1) ? 1.0 : -1.0, (k & 2) ? 1.0 : -1.0);
    double s_lo = 0.0, s_hi = 0.0;
    if (clipLineToBox(c, d, box, &s_lo, &s_hi) && lineWitness(f, {id}, {id}, c, d, s_lo, s_hi, box)) return true;
  }
  return false;
}

// A witness of the element on the atoms `ids` (2 or 3 of them), tried on the line of each pair of
// its planes that meet at an angle; false when none is found (the search decides).
bool planarWitness(const Formula& f, const std::vector<int>& ids, const Box3& box) {
  for (std::size_t i = 0; i < ids.size(); ++i)
    for (std::size_t j = i + 1; j < ids.size(); ++j) {
      Eigen::Vector3d p, d;
      double s_lo = 0.0, s_hi = 0.0;
      if (!isPlane(f.atoms[ids[i]]) || !isPlane(f.atoms[ids[j]])) continue;
      if (!planesLine(detail::planeOf(f.atoms[ids[i]]), detail::planeOf(f.atoms[ids[j]]), box, &p, &d, &s_lo, &s_hi))
        continue;
      std::vector<int> rest;
      for (std::size_t k = 0; k < ids.size(); ++k)
        if (k != i && k != j) rest.push_back(ids[k]);
      if (lineWitness(f, ids, rest, p, d, s_lo, s_hi, box)) return true;
    }
  return false;
}

// A witness of the element on the atoms `ids` (1 to 3 of them) where the kinds above apply: a
// planar or curved face, an edge or vertex on two planes, a conic edge. False otherwise (a
// quadric-quadric curve, or no witness found): the search decides.
bool elementWitness(const Formula& f, const std::vector<int>& ids, const Box3& box) {
  if (ids.size() == 1)
    return isPlane(f.atoms[ids[0]]) ? planeLinesWitness(f, ids[0], ids, {}, box) : quadricFaceWitness(f, ids[0], box);
  if (planarWitness(f, ids, box)) return true;
  if (ids.size() == 2 && isPlane(f.atoms[ids[0]]) && isPlane(f.atoms[ids[1]]))
    return planeLinesWitness(f, ids[0], ids, {}, box);  // the same plane twice (lineWitness checks)
  if (ids.size() == 2 && isPlane(f.atoms[ids[0]]) != isPlane(f.atoms[ids[1]])) {
    const int plane = isPlane(f.atoms[ids[0]]) ? ids[0] : ids[1], quadric = ids[0] + ids[1] - plane;
    return planeLinesWitness(f, plane, ids, {quadric}, box);
  }
  return false;
}

// Certified absence of an element near a line or a plane. g is the element's formula (the region
// and its surfaces' equalities, as mayMeet builds it); every point of the element lies within
// `delta` of the patch o + s e_0 (+ t e_1), (s, t) in [lo, hi], where (e_0, e_1, e_2) are
// orthonormal (to rounding). The atoms are carried into that frame, X = T Y with
// T = [E o; 0 1], as T^T Q T, their pads sized by |T|^T |Q| |T| (>= the rounded product's
// terms, far above its error at 2^-40). The frame's boxes [s] x [t] x [-delta, delta] (a line:
// [s] x [-delta, delta]^2) are cut along s and t and decided by the static engine's box test
// (BoxEval: atom enclosures and pencils, as findPointFormula). A box around a turned line or
// plane is then as thin as the element, where the search's axis-aligned boxes straddling it are
// as thick as they are long (an absent edge of a plane and a thin bore: seconds of search).
// True when every piece is excluded; false when a piece is In, reaches min_len undecided, or
// after kMaxPieces (the caller's search then decides).
bool patchExcluded(const Formula& g, const Eigen::Vector3d& o, const Eigen::Matrix3d& E, int dims,
                   const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, double delta, double min_len) {
  constexpr int kMaxPieces = 4096;
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = E;
  T.topRightCorner<3, 1>() = o;
  const Eigen::Matrix4d Tabs = T.cwiseAbs();
  Formula framed = g;
  std::vector<Eigen::Matrix4d> abs(g.atoms.size());
  for (std::size_t k = 0; k < g.atoms.size(); ++k) {
    framed.atoms[k] = T.transpose() * g.atoms[k] * T;
    abs[k] = Tabs.transpose() * g.atoms[k].cwiseAbs() * Tabs;
  }
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> stack{{lo, hi}};
  for (int pieces = 0; !stack.empty(); ++pieces) {
    if (pieces >= kMaxPieces) return false;
    const auto [a, b] = stack.back();
    stack.pop_back();
    const Eigen::Vector2d mid = 0.5 * (a + b), half = 0.5 * (b - a);
    const Eigen::Vector3d c(mid[0], dims > 1 ? mid[1] : 0.0, 0.0);
    const Eigen::Vector3d r(half[0], dims > 1 ? half[1] : delta, delta);
    const int widest = dims > 1 && half[1] > half[0] ? 1 : 0;
    BoxEval ev(framed, &abs, c, r);
    if (ev.root() == Tri::Out) continue;
    if (ev.root() == Tri::In || 2.0 * half[widest] <= min_len) return false;
    if (ev.excluded()) continue;
    Eigen::Vector2d b_lo = b, a_hi = a;
    b_lo[widest] = mid[widest];
    a_hi[widest] = mid[widest];
    // The half whose centre looks deeper inside goes first (as findPointFormula's order): an
    // element that exists, e.g. only at a cone's apex on its cap plane, is reached in about one
    // descent instead of after its excluded surroundings.
    Eigen::Vector3d c_lo = c, c_hi = c;
    c_lo[widest] -= 0.5 * half[widest];
    c_hi[widest] += 0.5 * half[widest];
    const bool lo_first = ev.depth(c_lo) <= ev.depth(c_hi);
    stack.push_back(lo_first ? std::make_pair(a_hi, b) : std::make_pair(a, b_lo));
    stack.push_back(lo_first ? std::make_pair(a, b_lo) : std::make_pair(a_hi, b));
  }
  return true;
}

// Largest |x_k| of the box's points: the scale of the coordinates' rounding.
double coordinateScale(const Box3& box) { return std::max(box.lo.cwiseAbs().maxCoeff(), box.hi.cwiseAbs().maxCoeff()); }

// Certified absence of the element on the atoms `ids` of g's region (g as patchExcluded) near the
// line of two of its planes meeting at an angle, or near its one plane. False when it has no such
// plane(s) or absence is not certified (the caller's search decides).
//  - Line: computed as p + s d (lineOfPlanes). A computed point x lies within
//    (rho_1 + rho_2) / sin(theta) of the true line, rho_i its distance to plane i (the residual
//    |n_i.x + d_i| / |n_i| plus 2^-40 of its terms for the rounding of the residual), theta the
//    planes' angle. offLine doubles that bound (a margin for the rounding of p and d) and adds
//    2^-40 of the coordinates' scale. The distance is convex along the line, so its values at a
//    segment's ends bound it on the segment; offLine's larger end value, doubled, is delta, and the
//    segment inside the box grown by delta passes within delta of every point of the true line.
//  - Plane: the frame (planeFrame's u, v and the unit normal) at the box centre's projection; the
//    true plane's points lie within a few ulps of the coordinates' scale of t = 0 (padded to
//    2^-40 of that scale), their parameters within the box's extent along u and v.
bool elementExcluded(const Formula& g, const std::vector<Eigen::Matrix4d>& atoms, const std::vector<int>& ids,
                     const Box3& box, double min_len) {
  std::vector<int> planes;
  for (int i : ids)
    if (isPlane(atoms[i])) planes.push_back(i);
  const double scale = coordinateScale(box) + box.maxEdge();
  for (std::size_t i = 0; i < planes.size(); ++i)
    for (std::size_t j = i + 1; j < planes.size(); ++j) {
      const Eigen::Vector4d p1 = detail::planeOf(atoms[planes[i]]), p2 = detail::planeOf(atoms[planes[j]]);
      Eigen::Vector3d p, d;
      if (!detail::lineOfPlanes(p1, p2, &p, &d)) continue;
      const double n1 = p1.head<3>().norm(), n2 = p2.head<3>().norm();
      const double sin_theta = d.norm() / (n1 * n2);
      if (!(sin_theta >= 1e-6)) continue;
      d.normalize();
      auto offLine = [&](double s) {
        const Eigen::Vector3d x = p + s * d;
        const Eigen::Vector4d X(x[0], x[1], x[2], 1.0), Xa = X.cwiseAbs();
        const double rho1 = (std::fabs(p1.dot(X)) + kRegionSignRelative * p1.cwiseAbs().dot(Xa)) / n1;
        const double rho2 = (std::fabs(p2.dot(X)) + kRegionSignRelative * p2.cwiseAbs().dot(Xa)) / n2;
        return 2.0 * (rho1 + rho2) / sin_theta + kRegionSignRelative * scale;
      };
      // The bound at the ends of the line clipped to the box grown by its largest edge, then the
      // segment inside the box grown by that bound doubled (a sub-segment: the bound holds on it).
      // A line missing either box is left to the search.
      const double margin = box.maxEdge();
      double s_lo = 0.0, s_hi = 0.0;
      if (!clipLineToBox(p, d, Box3{box.lo.array() - margin, box.hi.array() + margin}, &s_lo, &s_hi)) return false;
      const double delta = 2.0 * std::max(offLine(s_lo), offLine(s_hi));
      if (!(delta < margin) || !clipLineToBox(p, d, Box3{box.lo.array() - delta, box.hi.array() + delta}, &s_lo, &s_hi))
        return false;
      const Eigen::Vector3d e1 = d.unitOrthogonal();
      Eigen::Matrix3d E;
      E << d, e1, d.cross(e1);
      return patchExcluded(g, p, E, 1, Eigen::Vector2d(s_lo, 0.0), Eigen::Vector2d(s_hi, 0.0), delta, min_len);
    }
  if (planes.size() != 1) return false;
  const Eigen::Vector4d plane = detail::planeOf(atoms[planes[0]]);
  const Eigen::Vector3d n = plane.head<3>(), c = box.center(), r = box.halfWidth();
  const Eigen::Vector3d p = c - (n.dot(c) + plane[3]) / n.squaredNorm() * n;
  const Eigen::Matrix<double, 4, 3> frame = detail::planeFrame(plane);
  Eigen::Matrix3d E;
  E << frame.block<3, 1>(0, 0), frame.block<3, 1>(0, 1), n.normalized();
  const double delta = kRegionSignRelative * scale;
  // Parameters of the box's points: u.(x - p) within u.(c - p) +- |u|.r (v alike), grown by delta.
  const double su = E.col(0).cwiseAbs().dot(r) + delta, sv = E.col(1).cwiseAbs().dot(r) + delta;
  const double cu = E.col(0).dot(c - p), cv = E.col(1).dot(c - p);
  return patchExcluded(g, p, E, 2, Eigen::Vector2d(cu - su, cv - sv), Eigen::Vector2d(cu + su, cv + sv), delta,
                       min_len);
}

}  // namespace

BoundaryElements boundaryElements(const QuadricRegion& region, const Box3& box, int max_order) {
  BoundaryElements out;
  const std::vector<Eigen::Matrix4d> atoms = region.signedAtoms();
  // The region's formula over the same atoms in the same order (planarWitness evaluates it).
  const Formula formula(region);
  bool same_atoms = formula.atoms.size() == atoms.size();
  for (std::size_t i = 0; same_atoms && i < atoms.size(); ++i) same_atoms = formula.atoms[i] == atoms[i];
  // A face / edge / vertex exists unless the region intersected with the equalities of its
  // surfaces is certified empty (findPoint). Equality f = 0 is f <= 0 and -f <= 0. A witness keeps
  // it at once; near a line or a plane of its own, patches in its frame may certify it empty
  // first (elementExcluded); the search decides the rest.
  auto mayMeet = [&](const std::vector<int>& ids) {
    if (same_atoms && elementWitness(formula, ids, box)) return true;
    std::vector<QuadricRegion> parts{region};
    for (int i : ids) {
      parts.push_back(QuadricRegion::atom(atoms[i]));
      parts.push_back(QuadricRegion::atom(-atoms[i]));
    }
    // Only a certified Empty drops the element: stop at the first undecided box (a face or edge
    // set has no interior, so a search for a witness would only run to its extra-box cap).
    // The resolution is kBoundaryElementBoxRelative, coarser than the static engine's: an element
    // within it of the boundary is kept (a superset is harmless: a consumer verifies contacts),
    // and a vertex or an edge that does exist costs a descent of ~20 levels instead of ~30.
    const Formula g(QuadricRegion::combine(QuadricRegion::Op::Intersection, parts));
    if (elementExcluded(g, atoms, ids, box, kBoundaryElementBoxRelative * box.maxEdge())) return false;
    return findPointFormula(g, box, 0, kRegionMaxAspect, kBoundaryElementBoxRelative).status != PointSearch::Empty;
  };
  for (std::size_t i = 0; i < atoms.size(); ++i) {
    if (!mayMeet({static_cast<int>(i)})) continue;
    out.faces.push_back(BoundaryFace{static_cast<int>(i), classifyFace(atoms[i])});
  }
  const int nf = static_cast<int>(out.faces.size());
  if (max_order < 2) return out;
  for (int i = 0; i < nf; ++i) {
    for (int j = i + 1; j < nf; ++j) {
      const BoundaryFace &fi = out.faces[i], &fj = out.faces[j];
      if (!mayMeet({fi.atom, fj.atom})) continue;
      BoundaryEdge e;
      e.face0 = i;
      e.face1 = j;
      if (fi.planar() && fj.planar()) {
        e.kind = EdgeKind::Line;
      } else if (fi.planar() || fj.planar()) {
        // The quadric restricted to the plane: point o + s u + t v, value [s t 1] C [s t 1]^T.
        const Eigen::Matrix4d& P = atoms[fi.planar() ? fi.atom : fj.atom];
        const Eigen::Matrix4d& Q = atoms[fi.planar() ? fj.atom : fi.atom];
        Eigen::Vector4d plane;  // n2.x + P33 = 0
        plane << 2.0 * P.topRightCorner<3, 1>(), P(3, 3);
        const Eigen::Matrix<double, 4, 3> M = detail::planeFrame(plane);
        const Eigen::Vector3d o = M.block<3, 1>(0, 2);
        const Eigen::Matrix3d C = M.transpose() * Q * M;
        const double a11 = C(0, 0), a12 = C(0, 1), a22 = C(1, 1);
        const double hyp = std::hypot(0.5 * (a11 - a22), a12);
        const double min_eig = 0.5 * (a11 + a22) - hyp, max_eig = 0.5 * (a11 + a22) + hyp;
        const double eps = 1e-12 * Q.cwiseAbs().maxCoeff();
        bool lines = false;
        if (std::fabs(max_eig) <= eps && std::fabs(min_eig) <= eps) {
          lines = true;  // the quadric is affine on the plane: a line
        } else if (std::fabs(min_eig) <= eps || std::fabs(max_eig) <= eps) {
          // Rank 1: a pair of parallel lines unless the null direction carries a linear term
          // (a parabola).
          Eigen::Vector2d null_dir = (std::fabs(a11) >= std::fabs(a22)) ? Eigen::Vector2d(-a12, a11)
                                                                      : Eigen::Vector2d(a22, -a12);
          null_dir.normalize();
          const double lin = C(2, 0) * null_dir[0] + C(2, 1) * null_dir[1];
          lines = std::fabs(lin) <= eps * (1.0 + o.norm());
        }
        e.kind = lines ? EdgeKind::Line : EdgeKind::Conic;
        // Definition 6.1: a conic edge on a planar face is concave when the chord of two of its
        // points leaves the face, i.e. the quadric as used, restricted to the plane, has a
        // negative eigenvalue (complement of an ellipse, a hyperbola). Line edges never are.
        e.concave = !lines && min_eig < -eps;
      } else {
        e.kind = EdgeKind::Curve;
      }
      out.edges.push_back(e);
    }
  }
  if (max_order < 3) return out;
  for (int i = 0; i < nf; ++i)
    for (int j = i + 1; j < nf; ++j)
      for (int k = j + 1; k < nf; ++k) {
        const int planes = out.faces[i].planar() + out.faces[j].planar() + out.faces[k].planar();
        if (planes < 2) continue;  // vertices of CQMs with conic / line edges (§6.2)
        if (mayMeet({out.faces[i].atom, out.faces[j].atom, out.faces[k].atom}))
          out.vertices.push_back(BoundaryVertex{i, j, k});
      }
  return out;
}

// --- Static collision -------------------------------------------------------------------------

RegionCollision collideRegions(const QuadricRegion& a, const Box3& aabb_a, const QuadricRegion& b,
                               const Box3& aabb_b, const Eigen::Matrix3d& R_AB, const Eigen::Vector3d& p_AB) {
  RegionCollision res;
  const Box3 bb = transformBox(aabb_b, R_AB, p_AB);
  Box3 box{aabb_a.lo.cwiseMax(bb.lo), aabb_a.hi.cwiseMin(bb.hi)};
  if (box.empty()) {
    res.relation = RegionRelation::Separated;
    return res;
  }
  const PointSearchResult s = findPoint(intersectionInFrame(a, b, R_AB, p_AB), box);
  res.boxes = s.boxes;
  res.capped = s.capped;
  res.point = s.point;
  switch (s.status) {
    case PointSearch::Empty: res.relation = RegionRelation::Separated; break;
    case PointSearch::Found: res.relation = RegionRelation::Overlapping; break;
    case PointSearch::Undecided: res.relation = RegionRelation::Touching; break;
  }
  return res;
}

}  // namespace fcl_quadric
