#pragma once
// Private: the and/or formula of a composite quadric model (negation normal form of its CSG tree)
// and the three-valued logic over it that the certified subdivision engines share — the static
// one over boxes in space (quadric_region.cpp, findPoint) and the space-time one of continuous
// collision (continuous/region_ccd.cpp). docs/algorithms.md section 9.
//
// What differs between the engines is how an atom (or a pencil of atoms) is enclosed on a box;
// what is shared is how the enclosures decide the formula: an and-node is Out when one child is
// Out, an or-node In when one child is In, and a box is excluded when every disjunctive branch
// of the simplified formula has a conjunction of atoms with a certified-positive pencil (the
// static analogue of the separating pencil, thesis §4.2).

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "fcl_quadric/geometry/quadric_region.h"

namespace fcl_quadric {
namespace detail {

/// True if the atom {X^T Q X <= 0} is a plane 2 b.x + c <= 0 or a constant: its quadratic part is
/// zero or negligible (1e-14) against its linear part. The one test of the support mappings
/// (convex_support.cpp), the convex cover and the grown regions (region_distance_bound.cpp).
inline bool isPlanarAtom(const Eigen::Matrix4d& Q) {
  const double amax = Q.topLeftCorner<3, 3>().cwiseAbs().maxCoeff();
  return amax == 0.0 || amax <= 1e-14 * Q.topRightCorner<3, 1>().norm();
}

/// The region as an and/or formula over signed atoms (differences pushed to the atoms: the
/// closure of the complement of {f <= 0} is {-f <= 0}).
struct Formula {
  struct Node {
    bool is_and = true;
    std::vector<int> atoms;
    std::vector<int> nodes;
  };
  std::vector<Eigen::Matrix4d> atoms;
  std::vector<Node> nodes;
  int root = 0;  // always a node

  explicit Formula(const QuadricRegion& r) {
    nodes.push_back(Node{true, {}, {}});
    root = 0;
    addInto(0, r, false);
  }

 private:
  int addAtom(const Eigen::Matrix4d& Q) {
    atoms.push_back(Q);
    return static_cast<int>(atoms.size()) - 1;
  }
  // Adds the subtree of r (negated if neg) as children of node `parent`.
  void addInto(int parent, const QuadricRegion& r, bool neg) {
    using Op = QuadricRegion::Op;
    if (r.op() == Op::Atom) {
      const int a = addAtom(neg ? Eigen::Matrix4d(-r.matrix()) : r.matrix());
      nodes[parent].atoms.push_back(a);
      return;
    }
    bool is_and = r.op() != Op::Union;
    if (neg) is_and = !is_and;
    int target = parent;
    if (nodes[parent].is_and != is_and) {
      nodes.push_back(Node{is_and, {}, {}});
      target = static_cast<int>(nodes.size()) - 1;
      nodes[parent].nodes.push_back(target);
    }
    for (std::size_t i = 0; i < r.children().size(); ++i) {
      const bool sub = r.op() == Op::Difference && i > 0;
      addInto(target, r.children()[i], neg != sub);
    }
  }
};

enum class Tri { In, Out, Unknown };

struct Enclosure {
  double lo, hi;
};

// Centred form of f(X) = X^T Q X on the box c + [-r, r]: f(c+h) = f(c) + g.h + h^T A h with
// g = 2(A c + b); |g.h| <= |g|.r and h^T A h in [sum min(0,A_ii) r_i^2 - sum_{i!=j} |A_ij| r_i r_j,
// sum max(0,A_ii) r_i^2 + sum_{i!=j} |A_ij| r_i r_j]. Padded by kRegionSignRelative times the
// absolute-value expression (rounding of every term).
// `Qabs` (>= |Q| entrywise) sizes the pad: for a pencil mu F + (1-mu) G it is
// mu |F| + (1-mu) |G|, which also covers the cancellation in forming the combination.
inline Enclosure enclose(const Eigen::Matrix4d& Q, const Eigen::Matrix4d& Qabs, const Eigen::Vector3d& c,
                         const Eigen::Vector3d& r) {
  const Eigen::Matrix3d A = Q.topLeftCorner<3, 3>();
  const Eigen::Vector3d b = Q.topRightCorner<3, 1>();
  const Eigen::Vector3d Ac = A * c;
  const double fc = c.dot(Ac) + 2.0 * b.dot(c) + Q(3, 3);
  const Eigen::Vector3d g = 2.0 * (Ac + b);
  const double lin = g.cwiseAbs().dot(r);
  double qlo = 0.0, qhi = 0.0;
  for (int i = 0; i < 3; ++i) {
    qlo += std::min(0.0, A(i, i)) * r[i] * r[i];
    qhi += std::max(0.0, A(i, i)) * r[i] * r[i];
    for (int j = 0; j < 3; ++j) {
      if (i == j) continue;
      const double t = std::fabs(A(i, j)) * r[i] * r[j];
      qlo -= t;
      qhi += t;
    }
  }
  const Eigen::Vector4d Xa((c.cwiseAbs() + r)[0], (c.cwiseAbs() + r)[1], (c.cwiseAbs() + r)[2], 1.0);
  const double pad = tolerance_region::kRegionSignRelative * Xa.dot(Qabs * Xa);
  return {fc - lin + qlo - pad, fc + lin + qhi + pad};
}

inline Enclosure enclose(const Eigen::Matrix4d& Q, const Eigen::Vector3d& c, const Eigen::Vector3d& r) {
  return enclose(Q, Q.cwiseAbs(), c, r);
}

inline Tri atomBox(const Eigen::Matrix4d& Q, const Eigen::Vector3d& c, const Eigen::Vector3d& r) {
  const Enclosure e = enclose(Q, c, r);
  if (e.lo > 0.0) return Tri::Out;
  if (e.hi < 0.0) return Tri::In;
  return Tri::Unknown;
}

/// Membership of the formula from certified atom signs: sign(k) is -1 (certified inside atom k),
/// +1 (certified outside) or 0 (undecided). In / Out only when certified.
template <class AtomSign>
Tri pointEval(const Formula& f, int n, const AtomSign& sign) {
  const Formula::Node& node = f.nodes[n];
  bool any_unknown = false;
  for (int a : node.atoms) {
    const int s = sign(a);
    const Tri t = s < 0 ? Tri::In : (s > 0 ? Tri::Out : Tri::Unknown);
    if (node.is_and && t == Tri::Out) return Tri::Out;
    if (!node.is_and && t == Tri::In) return Tri::In;
    if (t == Tri::Unknown) any_unknown = true;
  }
  for (int m : node.nodes) {
    const Tri t = pointEval(f, m, sign);
    if (node.is_and && t == Tri::Out) return Tri::Out;
    if (!node.is_and && t == Tri::In) return Tri::In;
    if (t == Tri::Unknown) any_unknown = true;
  }
  if (any_unknown) return Tri::Unknown;
  return node.is_and ? Tri::In : Tri::Out;
}

/// The formula evaluated on one box from the atoms' enclosure states (In: certified negative on
/// the box, Out: certified positive, Unknown), and the pencil exclusion over its branches.
class FormulaBox {
 public:
  FormulaBox(const Formula& f, std::vector<Tri> atom_states)
      : f_(&f), atom_(std::move(atom_states)), node_(f.nodes.size(), Tri::Unknown) {
    root_ = eval(f.root);
  }
  Tri root() const { return root_; }
  Tri atom(int k) const { return atom_[k]; }

  /// True if the box provably holds no point of the formula: for each disjunctive branch of the
  /// simplified formula, `pencil_excluded(atoms)` certifies the conjunction of its undecided
  /// atoms empty on the box. At most kMaxBranches branches are examined (beyond: not excluded,
  /// the conservative answer).
  template <class PencilTest>
  bool excluded(const PencilTest& pencil_excluded) {
    if (root_ == Tri::Out) return true;
    if (root_ == Tri::In) return false;
    work_ = 0;
    std::vector<int> atoms;
    std::vector<int> ors;
    if (f_->nodes[f_->root].is_and) {
      gather(f_->root, &atoms, &ors);
    } else {
      ors.push_back(f_->root);
    }
    return excludedConj(atoms, ors, pencil_excluded);
  }

 private:
  static constexpr int kMaxBranches = 64;

  Tri eval(int n) {
    const Formula::Node& node = f_->nodes[n];
    bool any_unknown = false;
    auto fold = [&](Tri t) -> bool {  // returns true when decided
      if (node.is_and && t == Tri::Out) return true;
      if (!node.is_and && t == Tri::In) return true;
      if (t == Tri::Unknown) any_unknown = true;
      return false;
    };
    for (int a : node.atoms)
      if (fold(atom_[a])) return node_[n] = node.is_and ? Tri::Out : Tri::In;
    for (int m : node.nodes)
      if (fold(eval(m))) return node_[n] = node.is_and ? Tri::Out : Tri::In;
    if (any_unknown) return node_[n] = Tri::Unknown;
    return node_[n] = node.is_and ? Tri::In : Tri::Out;
  }

  void gather(int n, std::vector<int>* atoms, std::vector<int>* ors) const {
    const Formula::Node& node = f_->nodes[n];
    for (int a : node.atoms)
      if (atom_[a] == Tri::Unknown) atoms->push_back(a);
    for (int m : node.nodes) {
      if (node_[m] != Tri::Unknown) continue;
      if (f_->nodes[m].is_and) {
        gather(m, atoms, ors);
      } else {
        ors->push_back(m);
      }
    }
  }

  template <class PencilTest>
  bool excludedConj(const std::vector<int>& atoms, std::vector<int> ors, const PencilTest& pencil_excluded) {
    if (++work_ > kMaxBranches) return false;
    if (ors.empty()) return pencil_excluded(atoms);
    const int o = ors.back();
    ors.pop_back();
    const Formula::Node& node = f_->nodes[o];
    for (int a : node.atoms) {
      if (atom_[a] != Tri::Unknown) continue;  // Out branches are excluded already
      std::vector<int> at = atoms;
      at.push_back(a);
      if (!excludedConj(at, ors, pencil_excluded)) return false;
    }
    for (int m : node.nodes) {
      if (node_[m] != Tri::Unknown) continue;
      std::vector<int> at = atoms;
      std::vector<int> os = ors;
      gather(m, &at, &os);
      if (!excludedConj(at, os, pencil_excluded)) return false;
    }
    return true;
  }

  const Formula* f_;
  std::vector<Tri> atom_;
  std::vector<Tri> node_;
  Tri root_ = Tri::Unknown;
  int work_ = 0;
};

/// Golden-section maximisation of a concave function on [0, 1] that stops as soon as a value is
/// positive: true if one is found within `steps` steps; *best is the best point found (the
/// positive one when true). The lower bound of a pencil's centred-form enclosure is concave in
/// its weight mu (a linear term minus absolute values of affine functions of mu).
template <class Fn>
bool goldenArgmax(const Fn& f, int steps, double* best) {
  double a = 0.0, b = 1.0;
  const double phi = 0.6180339887498949;
  double x1 = b - phi * (b - a), x2 = a + phi * (b - a);
  double f1 = f(x1), f2 = f(x2);
  for (int k = 0;; ++k) {
    if (f1 > 0.0 || f2 > 0.0 || k == steps) break;
    if (f1 < f2) {
      a = x1;
      x1 = x2;
      f1 = f2;
      x2 = a + phi * (b - a);
      f2 = f(x2);
    } else {
      b = x2;
      x2 = x1;
      f2 = f1;
      x1 = b - phi * (b - a);
      f1 = f(x1);
    }
  }
  *best = f1 >= f2 ? x1 : x2;
  return f1 > 0.0 || f2 > 0.0;
}

/// goldenArgmax when only the verdict matters.
template <class Fn>
bool goldenPositive(const Fn& lower, int steps) {
  double best = 0.0;
  return goldenArgmax(lower, steps, &best);
}

/// The spatial axis to split: the one with the largest score (its contribution to the undecided
/// enclosures) among the axes whose edge 2 r_i exceeds min_width; the longest edge when nothing
/// depends on the others or when the box would get more elongated than max_aspect (its centre
/// must still be able to land inside thin lenses). -1 when every edge is at most min_width.
inline int chooseSplitAxis(const Eigen::Vector3d& score, const Eigen::Vector3d& r, double min_width,
                           double max_aspect) {
  int axis = -1;
  double best = 0.0;
  for (int i = 0; i < 3; ++i) {
    if (2.0 * r[i] <= min_width) continue;
    if (axis < 0 || score[i] > best) {
      if (score[i] > 0.0 || axis < 0) {
        axis = i;
        best = score[i];
      }
    }
  }
  if (axis < 0) return axis;
  int longest = 0;
  r.maxCoeff(&longest);
  if (best == 0.0 || r[longest] > max_aspect * r[axis]) axis = longest;
  return axis;
}

}  // namespace detail
}  // namespace fcl_quadric
