// Distance of non-convex composite quadric models by branch and bound over convex relaxations:
// docs/algorithms.md section 12b, region_distance.h.
#include "fcl_quadric/geometry/region_distance.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <queue>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "fcl_quadric/geometry/convex_distance.h"
#include "fcl_quadric/geometry/ellipsoid.h"
#include "geometry/region_formula.h"

namespace fcl_quadric {

using namespace tolerance_region_distance;

DistanceOperand DistanceOperand::ofRegion(const QuadricRegion& region, const Box3& box, const Eigen::Matrix3d& R,
                                          const Eigen::Vector3d& p) {
  DistanceOperand op;
  op.region = &region;
  op.box = box;
  op.R = R;
  op.p = p;
  return op;
}

DistanceOperand DistanceOperand::ofConvex(const ConvexSupport& convex, const Eigen::Matrix3d& R,
                                          const Eigen::Vector3d& p) {
  DistanceOperand op;
  op.convex = &convex;
  op.R = R;
  op.p = p;
  return op;
}

namespace {

using detail::Formula;
using detail::Tri;
using Conjunction = std::vector<int>;

/// One operand as the search sees it: its convex pieces on a box, and its exact membership.
class Side {
 public:
  /// A convex piece (in the operand's frame) and the undecided atoms it relaxes.
  struct Piece {
    ConvexSupport support;
    Conjunction atoms;
  };

  Side(const DistanceOperand& op, const char* which) : op_(op) {
    const bool is_region = op.region != nullptr;
    if (is_region == (op.convex != nullptr))
      throw std::invalid_argument(std::string("regionDistance: operand ") + which +
                                  " must be exactly one of a region and a convex support");
    detail::checkRotation(op.R, (std::string("regionDistance: ") + which + " rotation").c_str());
    detail::checkPosition(op.p, (std::string("regionDistance: ") + which + " translation").c_str());
    if (!is_region) return;
    if (op.box.empty() || !op.box.lo.allFinite() || !op.box.hi.allFinite())
      throw std::invalid_argument(std::string("regionDistance: ") + which + "'s bounding box is empty or not finite");
    formula_.emplace(*op.region);
    const std::size_t n = formula_->atoms.size();
    exact_.assign(n, false);
    concave_slack_.assign(n, true);
    for (std::size_t k = 0; k < n; ++k) {
      const Eigen::Matrix4d& Q = formula_->atoms[k];
      if (detail::isPlanarAtom(Q)) {
        exact_[k] = true;
        concave_slack_[k] = false;
        continue;
      }
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(Q.topLeftCorner<3, 3>(), Eigen::EigenvaluesOnly);
      const double lmax = es.eigenvalues().cwiseAbs().maxCoeff();
      // Positive semidefinite: a convex atom (ConvexSupport::fromRegion's class, with its gate:
      // a piece fromRegion refused would be dropped; its tangent planes bound it, so its
      // relaxation needs no slack).
      const bool psd = es.eigenvalues().minCoeff() >= -tolerance_support::kSupportIndefiniteRelative * lmax;
      exact_[k] = psd;
      concave_slack_[k] = !psd;
    }
  }

  bool isRegion() const { return formula_.has_value(); }
  const DistanceOperand& operand() const { return op_; }
  const Box3& rootBox() const { return op_.box; }

  /// The convex pieces whose union contains the model's part in X (empty: none there).
  std::vector<Piece> pieces(const Box3& X) const {
    std::vector<Piece> out;
    if (!isRegion()) {
      out.push_back(Piece{*op_.convex, {}});
      return out;
    }
    const Eigen::Vector3d c = X.center();
    const Eigen::Vector3d r = X.halfWidth();
    std::vector<Tri> st(formula_->atoms.size());
    for (std::size_t k = 0; k < st.size(); ++k) st[k] = detail::atomBox(formula_->atoms[k], c, r);
    bool overflow = false;
    const std::vector<Conjunction> dnf = expand(formula_->root, st, &overflow);
    for (const Conjunction& conj : dnf) {
      std::optional<ConvexSupport> s = relax(conj, X);
      if (s) out.push_back(Piece{std::move(*s), conj});
    }
    return out;
  }

  /// x (operand frame) moved onto the atoms of `atoms` it violates (Gauss-Newton on the violated
  /// ones, minimal-norm steps). \return the point, or nullopt if the model's exact-sign
  /// membership certifies it outside.
  std::optional<Eigen::Vector3d> ontoModel(Eigen::Vector3d x, const Conjunction& atoms) const {
    if (!isRegion()) return x;
    for (int step = 0; step < kRegionDistanceProjectionSteps; ++step) {
      std::vector<int> violated;
      for (int k : atoms)
        if (value(k, x) > 0.0) violated.push_back(k);
      if (violated.empty()) break;
      const int m = static_cast<int>(violated.size());
      Eigen::MatrixXd J(m, 3);
      Eigen::VectorXd g(m);
      for (int i = 0; i < m; ++i) {
        J.row(i) = gradient(violated[i], x).transpose();
        g[i] = value(violated[i], x);
      }
      const Eigen::Vector3d dx = -J.completeOrthogonalDecomposition().solve(g);
      if (!dx.allFinite()) break;
      x += dx;
    }
    if (!x.allFinite() || op_.region->classifyPoint(x) < 0) return std::nullopt;
    return x;
  }

  /// The atoms whose surfaces pass through x (within kRegionDistanceActiveRelative of the box's
  /// half diagonal, measured as |g| / |grad g|).
  std::vector<int> activeAtoms(const Eigen::Vector3d& x) const {
    std::vector<int> out;
    const double band = kRegionDistanceActiveRelative * op_.box.halfWidth().norm();
    for (std::size_t k = 0; k < formula_->atoms.size(); ++k) {
      const double gn = gradient(static_cast<int>(k), x).norm();
      if (gn > 0.0 && std::fabs(value(static_cast<int>(k), x)) <= band * gn) out.push_back(static_cast<int>(k));
    }
    return out;
  }

  /// The point nearest to y on the intersection of the surfaces of `atoms` (1 or 2 of them),
  /// from x on it: Gauss-Newton on the constraints with the step towards y projected on their
  /// tangent space (at most kRegionDistanceProjectionSteps steps, each at most a tenth of the
  /// box). nullopt if it leaves the model or does not settle.
  /// When the point found leaves the model, the surface it crossed most (largest g / |grad g|)
  /// joins `atoms` (an active set: a face becomes the edge it ran into) and the step is redone,
  /// up to two surfaces.
  std::optional<Eigen::Vector3d> nearestOnSurfaces(const Eigen::Vector3d& x0, const Eigen::Vector3d& y,
                                                   std::vector<int>* atoms) const {
    for (;;) {
      const std::optional<Eigen::Vector3d> x = stepOnSurfaces(x0, y, *atoms);
      if (!x) return std::nullopt;
      if (op_.region->classifyPoint(*x) >= 0) return x;
      if (atoms->size() >= 2) return std::nullopt;
      int worst = -1;
      double excess = 0.0;
      for (std::size_t k = 0; k < formula_->atoms.size(); ++k) {
        const int a = static_cast<int>(k);
        if (std::find(atoms->begin(), atoms->end(), a) != atoms->end()) continue;
        const double gn = gradient(a, *x).norm();
        const double e = gn > 0.0 ? value(a, *x) / gn : 0.0;
        if (e > excess) {
          excess = e;
          worst = a;
        }
      }
      if (worst < 0) return std::nullopt;
      atoms->push_back(worst);
    }
  }

 private:
  std::optional<Eigen::Vector3d> stepOnSurfaces(Eigen::Vector3d x, const Eigen::Vector3d& y,
                                                const std::vector<int>& atoms) const {
    const int m = static_cast<int>(atoms.size());
    const double size = op_.box.halfWidth().norm();
    for (int step = 0; step < kRegionDistanceProjectionSteps; ++step) {
      Eigen::MatrixXd J(m, 3);
      Eigen::VectorXd g(m);
      for (int i = 0; i < m; ++i) {
        J.row(i) = gradient(atoms[i], x).transpose();
        g[i] = value(atoms[i], x);
      }
      const Eigen::Vector3d w = y - x;
      const Eigen::MatrixXd JJt = J * J.transpose();
      const Eigen::VectorXd lambda = JJt.ldlt().solve(J * w + g);
      Eigen::Vector3d dx = w - J.transpose() * lambda;
      if (!dx.allFinite()) return std::nullopt;
      const double len = dx.norm();
      if (len > 0.1 * size) dx *= 0.1 * size / len;
      x += dx;
      if (len <= 1e-15 * size) break;
    }
    if (!x.allFinite()) return std::nullopt;
    return x;
  }

  double value(int k, const Eigen::Vector3d& x) const {
    const Eigen::Vector4d X(x[0], x[1], x[2], 1.0);
    return X.dot(formula_->atoms[k] * X);
  }
  Eigen::Vector3d gradient(int k, const Eigen::Vector3d& x) const {
    const Eigen::Matrix4d& Q = formula_->atoms[k];
    return 2.0 * (Q.topLeftCorner<3, 3>() * x + Q.topRightCorner<3, 1>());
  }

  /// Disjunctive normal form of node n over the undecided atoms: {} is false, {{}} is true. A
  /// conjunction that would exceed kRegionDistanceMaxBranches drops the child (a superset); a
  /// disjunction that would, becomes true (the box).
  std::vector<Conjunction> expand(int n, const std::vector<Tri>& st, bool* overflow) const {
    const Formula::Node& node = formula_->nodes[n];
    const std::vector<Conjunction> truth{Conjunction{}};
    auto isTrue = [](const std::vector<Conjunction>& d) {
      return std::any_of(d.begin(), d.end(), [](const Conjunction& c) { return c.empty(); });
    };
    if (node.is_and) {
      std::vector<Conjunction> out = truth;
      for (int a : node.atoms) {
        if (st[a] == Tri::Out) return {};
        if (st[a] == Tri::Unknown)
          for (Conjunction& c : out) c.push_back(a);
      }
      for (int m : node.nodes) {
        const std::vector<Conjunction> d = expand(m, st, overflow);
        if (d.empty()) return {};
        if (isTrue(d)) continue;
        if (out.size() * d.size() > static_cast<std::size_t>(kRegionDistanceMaxBranches)) {
          *overflow = true;
          continue;
        }
        std::vector<Conjunction> next;
        for (const Conjunction& p : out)
          for (const Conjunction& q : d) {
            Conjunction r = p;
            r.insert(r.end(), q.begin(), q.end());
            next.push_back(std::move(r));
          }
        out = std::move(next);
      }
      return out;
    }
    std::vector<Conjunction> out;
    for (int a : node.atoms) {
      if (st[a] == Tri::In) return truth;
      if (st[a] == Tri::Unknown) out.push_back({a});
    }
    for (int m : node.nodes) {
      std::vector<Conjunction> d = expand(m, st, overflow);
      if (isTrue(d)) return truth;
      for (Conjunction& c : d) out.push_back(std::move(c));
    }
    if (out.size() > static_cast<std::size_t>(kRegionDistanceMaxBranches)) {
      *overflow = true;
      return truth;
    }
    return out;
  }

  /// The convex relaxation of one conjunction on X (file comment of region_distance.h).
  std::optional<ConvexSupport> relax(const Conjunction& conj, const Box3& X) const {
    const Eigen::Vector3d c = X.center();
    const Eigen::Vector3d r = X.halfWidth();
    std::vector<QuadricRegion> parts;
    bool curved_kept = false;
    for (int k : conj) {
      const Eigen::Matrix4d& Q = formula_->atoms[k];
      const bool planar = detail::isPlanarAtom(Q);
      if (planar || (exact_[k] && !curved_kept)) {
        if (!planar) curved_kept = true;
        parts.push_back(QuadricRegion::atom(Q));
        continue;
      }
      // g(x) >= g(c) + grad.(x - c) + q_lo on X, so g <= 0 implies the half-space below.
      const Eigen::Matrix3d A = Q.topLeftCorner<3, 3>();
      const Eigen::Vector3d grad = gradient(k, c);
      const double gc = value(k, c);
      double q_lo = 0.0;
      if (concave_slack_[k]) {
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j)
            q_lo += i == j ? std::min(0.0, A(i, i)) * r[i] * r[i] : -std::fabs(A(i, j)) * r[i] * r[j];
      }
      const Eigen::Vector4d Xa(std::fabs(c[0]) + r[0], std::fabs(c[1]) + r[1], std::fabs(c[2]) + r[2], 1.0);
      const double pad = tolerance_region::kRegionSignRelative * Xa.dot(Q.cwiseAbs() * Xa);
      const double gn = grad.norm();
      // A gradient that vanishes at c (a bore's axis, a cone's apex) gives no half-space.
      if (!(gn > 1e-12 * (Q.topLeftCorner<3, 3>().cwiseAbs().maxCoeff() * (c.norm() + r.norm()) +
                           Q.topRightCorner<3, 1>().norm())))
        continue;
      parts.push_back(QuadricRegion::halfspace(grad, grad.dot(c) - gc - q_lo + pad));
    }
    if (parts.empty()) parts.push_back(QuadricRegion::halfspace(Eigen::Vector3d::UnitX(), X.hi.x()));
    const QuadricRegion conjunction =
        parts.size() == 1 ? std::move(parts.front()) : QuadricRegion::combine(QuadricRegion::Op::Intersection, parts);
    return ConvexSupport::fromRegion(conjunction, X);
  }

  DistanceOperand op_;
  std::optional<Formula> formula_;
  std::vector<bool> exact_;          // kept exactly in a piece (planes; the first PSD curved atom)
  std::vector<bool> concave_slack_;  // relaxed with the centred-form quadratic slack
};

struct BoxPairNode {
  Box3 xa, xb;
  double lower = 0.0;
  bool operator>(const BoxPairNode& o) const { return lower > o.lower; }
};

}  // namespace

RegionDistanceResult regionDistance(const DistanceOperand& a, const DistanceOperand& b, double tolerance) {
  if (std::isnan(tolerance) || tolerance < 0.0)
    throw std::invalid_argument("regionDistance: tolerance must be >= 0, got " + std::to_string(tolerance));
  const Side sa(a, "a");
  const Side sb(b, "b");
  auto centreOf = [](const Side& s) -> Eigen::Vector3d {
    const DistanceOperand& op = s.operand();
    return op.R * (s.isRegion() ? op.box.center() : op.convex->center()) + op.p;
  };
  auto sizeOf = [](const Side& s) {
    return s.isRegion() ? s.operand().box.halfWidth().norm() : s.operand().convex->size();
  };
  const double scale = sizeOf(sa) + sizeOf(sb) + (centreOf(sa) - centreOf(sb)).norm();
  const double tol = tolerance > 0.0 ? std::max(tolerance, kRegionDistanceFloorRelative * scale)
                                     : kRegionDistanceRelative * scale;
  const double min_a = sa.isRegion() ? kRegionDistanceMinBoxRelative * a.box.maxEdge() : 0.0;
  const double min_b = sb.isRegion() ? kRegionDistanceMinBoxRelative * b.box.maxEdge() : 0.0;

  RegionDistanceResult out;
  double upper = std::numeric_limits<double>::infinity();

  // A feasible pair of witnesses (common frame) becomes the answer when it is closer.
  auto offer = [&](const Eigen::Vector3d& pa, const Eigen::Vector3d& pb) {
    Eigen::Vector3d qa = pa, qb = pb;
    // Against a convex operand the nearest point of it to the other witness is better still.
    auto nearestOn = [](const DistanceOperand& op, const Eigen::Vector3d& x, Eigen::Vector3d* onto) {
      const SignedDistanceResult d = convexSignedDistance(ConvexSupport::points({x}), Eigen::Matrix3d::Identity(),
                                                          Eigen::Vector3d::Zero(), *op.convex, op.R, op.p, false);
      if (d.status == Separation::Separated) *onto = d.point_b;
      else *onto = x;  // inside (or on) the convex operand: distance 0
    };
    if (!sb.isRegion() && sa.isRegion()) nearestOn(b, qa, &qb);
    else if (!sa.isRegion() && sb.isRegion()) nearestOn(a, qb, &qa);
    const double d = (qa - qb).norm();
    if (d < upper) {
      upper = d;
      out.point_a = qa;
      out.point_b = qb;
    }
  };

  // Lower bound of a node, offering the witnesses of its closest pair of pieces.
  auto evaluate = [&](BoxPairNode* n) -> bool {
    const std::vector<Side::Piece> pa = sa.pieces(n->xa);
    if (pa.empty()) return false;
    const std::vector<Side::Piece> pb = sb.pieces(n->xb);
    if (pb.empty()) return false;
    double best = std::numeric_limits<double>::infinity();
    const Side::Piece* best_a = nullptr;
    const Side::Piece* best_b = nullptr;
    SignedDistanceResult best_d;
    for (const Side::Piece& u : pa)
      for (const Side::Piece& v : pb) {
        double lb = 0.0;
        const SignedDistanceResult d = convexSignedDistance(u.support, a.R, a.p, v.support, b.R, b.p, false, &lb);
        // GJK's bound is exact up to the support points' tolerance and rounding: less 1e-11 of
        // the pair's scale, as distanceLowerBound (distance.h) takes it.
        // A NaN bound (impossible for finite input) counts as contact; it is tested before any
        // ordered comparison, which would raise FE_INVALID.
        const double lower = d.status == Separation::Separated && !std::isnan(lb)
                                 ? std::max(0.0, lb - tolerance_convex::kConvexSeparationRelative * scale)
                                 : 0.0;
        if (best_a == nullptr || lower < best) {
          best = lower;
          best_a = &u;
          best_b = &v;
          best_d = d;
        }
      }
    n->lower = best;
    const std::optional<Eigen::Vector3d> wa = sa.ontoModel(a.R.transpose() * (best_d.point_a - a.p), best_a->atoms);
    const std::optional<Eigen::Vector3d> wb = sb.ontoModel(b.R.transpose() * (best_d.point_b - b.p), best_b->atoms);
    if (wa && wb) offer(a.R * *wa + a.p, b.R * *wb + b.p);
    return true;
  };

  std::priority_queue<BoxPairNode, std::vector<BoxPairNode>, std::greater<BoxPairNode>> queue;
  BoxPairNode root{a.box, b.box, 0.0};
  if (evaluate(&root)) queue.push(root);
  // Lower bounds of the nodes set aside: too small to split, or pruned (within the tolerance of the
  // best distance at the time). The certificate is the smallest lower bound of any node left.
  double floor_lower = std::numeric_limits<double>::infinity();
  for (;;) {
    const double lower = std::min(floor_lower, queue.empty() ? upper : queue.top().lower);
    out.lower_bound = std::min(lower, upper);
    if (upper - lower <= tol || queue.empty()) {
      out.converged = upper - lower <= tol;
      break;
    }
    if (out.nodes >= kRegionDistanceMaxNodes) break;
    const BoxPairNode n = queue.top();
    queue.pop();
    ++out.nodes;
    if (n.lower >= upper - tol) {
      floor_lower = std::min(floor_lower, n.lower);
      continue;
    }
    const bool split_a = sa.isRegion() && n.xa.maxEdge() > min_a;
    const bool split_b = sb.isRegion() && n.xb.maxEdge() > min_b;
    if (!split_a && !split_b) {
      floor_lower = std::min(floor_lower, n.lower);
      continue;
    }
    const bool on_a = split_a && (!split_b || n.xa.halfWidth().norm() >= n.xb.halfWidth().norm());
    const Box3& X = on_a ? n.xa : n.xb;
    int axis = 0;
    (X.hi - X.lo).maxCoeff(&axis);
    const double mid = 0.5 * (X.lo[axis] + X.hi[axis]);
    Box3 lo = X, hi = X;
    lo.hi[axis] = mid;
    hi.lo[axis] = mid;
    for (const Box3& child : {lo, hi}) {
      BoxPairNode c = n;
      (on_a ? c.xa : c.xb) = child;
      if (!evaluate(&c)) continue;
      if (c.lower < upper - tol) queue.push(c);
      else floor_lower = std::min(floor_lower, c.lower);
    }
  }
  // Polish (local): alternate nearest points between the witnesses' surfaces (the atoms through a
  // region witness, 1 or 2 of them: a face or an edge; a convex operand's own nearest point),
  // keeping each pair that is closer. The search's relaxations leave a witness on an edge up to
  // O(|X|^2) off its minimum; this takes the distance to rounding there without touching the
  // certificate.
  if (std::isfinite(upper) && upper > tol) {
    const double floor = 1e-15 * scale;
    auto local = [](const DistanceOperand& op, const Eigen::Vector3d& x) -> Eigen::Vector3d {
      return op.R.transpose() * (x - op.p);
    };
    std::vector<int> act_a = sa.isRegion() ? sa.activeAtoms(local(a, out.point_a)) : std::vector<int>{};
    std::vector<int> act_b = sb.isRegion() ? sb.activeAtoms(local(b, out.point_b)) : std::vector<int>{};
    auto usable = [](const Side& s, const std::vector<int>& act) {
      return !s.isRegion() || (!act.empty() && act.size() <= 2);
    };
    if (usable(sa, act_a) && usable(sb, act_b) && (sa.isRegion() || sb.isRegion())) {
      // The nearest point of one operand to x (common frame).
      auto nearest = [&](const Side& s, const DistanceOperand& op, std::vector<int>* act, const Eigen::Vector3d& from,
                         const Eigen::Vector3d& x) -> std::optional<Eigen::Vector3d> {
        if (!s.isRegion()) {
          const SignedDistanceResult d = convexSignedDistance(ConvexSupport::points({x}), Eigen::Matrix3d::Identity(),
                                                              Eigen::Vector3d::Zero(), *op.convex, op.R, op.p, false);
          if (d.status != Separation::Separated) return std::nullopt;
          return d.point_b;
        }
        const std::optional<Eigen::Vector3d> y = s.nearestOnSurfaces(local(op, from), local(op, x), act);
        if (!y) return std::nullopt;
        return op.R * *y + op.p;
      };
      Eigen::Vector3d pa = out.point_a, pb = out.point_b;
      for (int it = 0; it < kRegionDistancePolishSteps; ++it) {
        const std::optional<Eigen::Vector3d> nb = nearest(sb, b, &act_b, pb, pa);
        if (!nb) break;
        const std::optional<Eigen::Vector3d> na = nearest(sa, a, &act_a, pa, *nb);
        if (!na) break;
        const double d = (*na - *nb).norm();
        if (!(d < upper - floor)) break;
        upper = d;
        pa = *na;
        pb = *nb;
        out.point_a = pa;
        out.point_b = pb;
      }
    }
  }
  if (!std::isfinite(upper)) {
    // No witness pair was ever found on both models (only possible for a model that is empty up
    // to the rounding band): report the certified bound alone.
    out.status = RegionDistanceResult::Status::Separated;
    out.distance = out.lower_bound;
    return out;
  }
  out.distance = upper;
  out.status = out.lower_bound <= tol ? RegionDistanceResult::Status::Contact : RegionDistanceResult::Status::Separated;
  return out;
}

}  // namespace fcl_quadric
