#include "fcl_quadric/algebra/root_isolation.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace fcl_quadric {
namespace {

constexpr double kUnitRoundoff = 0.5 * DBL_EPSILON;
/// Factor applied to every error bound after it is accumulated in floating point, so that the
/// rounding of the bound computation itself is covered.
constexpr double kBoundInflation = 1.0 + 16.0 * kUnitRoundoff;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// --------------------------------------------------------------------------------------------
// Bernstein coefficients with absolute error bounds: the polynomial represented exactly by the
// caller's coefficients has, on the node's interval, Bernstein coefficients in
// [c_i - e_i, c_i + e_i]. The caller's coefficients have e_i = 0.

/// Sign classes of an interval coefficient.
enum SignClass { kNegative = -1, kExactZero = 0, kPositive = 1, kUncertain = 2 };

SignClass signClass(double c, double e) {
  if (c > e) return kPositive;
  if (c < -e) return kNegative;
  if (c == 0.0 && e == 0.0) return kExactZero;
  return kUncertain;
}

int sign(double v) { return (v > 0.0) - (v < 0.0); }

enum class Descartes { kNoRoot, kOneRoot, kUndecided };

/// Descartes' rule for every polynomial whose coefficients lie in the error boxes:
///  - kNoRoot: all exact coefficients are >= 0 or all <= 0 (no root in the open interval);
///  - kOneRoot: end coefficients have certain opposite signs and every assignment of the
///    uncertain coefficients gives exactly one sign variation (uncertain coefficients only in
///    the transition between the two runs);
///  - kUndecided otherwise.
Descartes classify(const std::vector<double>& c, const std::vector<double>& e) {
  const std::size_t n1 = c.size();
  bool nonneg = true;
  bool nonpos = true;
  for (std::size_t i = 0; i < n1; ++i) {
    if (c[i] - e[i] < 0.0) nonneg = false;
    if (c[i] + e[i] > 0.0) nonpos = false;
  }
  if (nonneg || nonpos) return Descartes::kNoRoot;
  const SignClass s0 = signClass(c.front(), e.front());
  const SignClass sn = signClass(c.back(), e.back());
  if (s0 == kUncertain || sn == kUncertain || s0 == kExactZero || sn == kExactZero || s0 == sn) {
    return Descartes::kUndecided;
  }
  // i2: first coefficient with certain sign sn; i1: last one with certain sign s0 before it.
  std::size_t i2 = 0;
  while (signClass(c[i2], e[i2]) != sn) ++i2;  // terminates: the last coefficient has sign sn
  std::size_t i1 = 0;
  for (std::size_t i = 0; i < i2; ++i) {
    if (signClass(c[i], e[i]) == s0) i1 = i;
  }
  for (std::size_t i = 0; i < n1; ++i) {
    const SignClass s = signClass(c[i], e[i]);
    if (i < i1 && s != s0 && s != kExactZero) return Descartes::kUndecided;
    if (i > i2 && s != sn && s != kExactZero) return Descartes::kUndecided;
  }
  return Descartes::kOneRoot;
}

/// Knuth's TwoSum: x + y = s + err exactly.
double twoSumError(double x, double y, double s) {
  const double bv = s - x;
  const double av = s - bv;
  return (x - av) + (y - bv);
}

/// Split at the unit parameter 1/2 with exact per-operation rounding errors (TwoSum): halving
/// is exact unless it underflows, which is detected and covered by adding DBL_TRUE_MIN.
void splitHalf(const std::vector<double>& c, const std::vector<double>& e, std::vector<double>* left,
               std::vector<double>* left_e, std::vector<double>* right, std::vector<double>* right_e) {
  const std::size_t n1 = c.size();
  std::vector<double> w(c);
  std::vector<double> we(e);
  left->assign(n1, 0.0);
  left_e->assign(n1, 0.0);
  right->assign(n1, 0.0);
  right_e->assign(n1, 0.0);
  (*left)[0] = w[0];
  (*left_e)[0] = we[0];
  (*right)[n1 - 1] = w[n1 - 1];
  (*right_e)[n1 - 1] = we[n1 - 1];
  for (std::size_t level = n1 - 1; level > 0; --level) {
    for (std::size_t i = 0; i < level; ++i) {
      const double x = 0.5 * w[i];
      const double y = 0.5 * w[i + 1];
      const double s = x + y;
      double err = 0.5 * we[i] + 0.5 * we[i + 1] + std::abs(twoSumError(x, y, s));
      if (2.0 * x != w[i] || 2.0 * y != w[i + 1]) err += DBL_TRUE_MIN;  // inexact halving (underflow)
      w[i] = s;
      we[i] = err * kBoundInflation;
    }
    (*left)[n1 - level] = w[0];
    (*left_e)[n1 - level] = we[0];
    (*right)[level - 1] = w[level - 1];
    (*right_e)[level - 1] = we[level - 1];
  }
}

/// Split at a general unit parameter s in [0, 1]; per operation the error bound grows by
/// 4u (|w_i| + |w_{i+1}|) (two products, one sum and the rounding of 1 - s).
void splitGeneral(const std::vector<double>& c, const std::vector<double>& e, double s, std::vector<double>* left,
                  std::vector<double>* left_e, std::vector<double>* right, std::vector<double>* right_e) {
  const std::size_t n1 = c.size();
  std::vector<double> w(c);
  std::vector<double> we(e);
  std::vector<double> l(n1), le(n1), r(n1), re(n1);
  const double t = 1.0 - s;
  l[0] = w[0];
  le[0] = we[0];
  r[n1 - 1] = w[n1 - 1];
  re[n1 - 1] = we[n1 - 1];
  for (std::size_t level = n1 - 1; level > 0; --level) {
    for (std::size_t i = 0; i < level; ++i) {
      const double err = t * we[i] + s * we[i + 1] + 4.0 * kUnitRoundoff * (std::abs(w[i]) + std::abs(w[i + 1])) +
                         2.0 * DBL_TRUE_MIN;
      w[i] = t * w[i] + s * w[i + 1];
      we[i] = err * kBoundInflation;
    }
    l[n1 - level] = w[0];
    le[n1 - level] = we[0];
    r[level - 1] = w[level - 1];
    re[level - 1] = we[level - 1];
  }
  if (left != nullptr) {
    *left = std::move(l);
    *left_e = std::move(le);
  }
  if (right != nullptr) {
    *right = std::move(r);
    *right_e = std::move(re);
  }
}

/// Upper bound on |p'| * (b - a) over [a, b] (from the derivative's Bernstein coefficients):
/// n max_j (|c_{j+1} - c_j| + e_j + e_{j+1}).
double derivativeTimesWidthBound(const std::vector<double>& c, const std::vector<double>& e) {
  const std::size_t n = c.size() - 1;
  double m = 0.0;
  for (std::size_t j = 0; j < n; ++j) m = std::max(m, std::abs(c[j + 1] - c[j]) + e[j] + e[j + 1]);
  return static_cast<double>(n) * m * kBoundInflation;
}

void addToAll(std::vector<double>* e, double v) {
  for (double& x : *e) x = (x + v) * kBoundInflation;
}

/// Coefficients on the unit sub-interval [s0, s1] of the node (0 <= s0 < s1 <= 1), with error
/// bounds that include the mislabelling of the new end points (at most 6u of the node width,
/// times the derivative bound).
void restrictWithError(const std::vector<double>& c, const std::vector<double>& e, double s0, double s1,
                       std::vector<double>* out, std::vector<double>* out_e) {
  const double label = 6.0 * kUnitRoundoff * derivativeTimesWidthBound(c, e);
  *out = c;
  *out_e = e;
  if (s1 != 1.0) splitGeneral(*out, *out_e, s1, out, out_e, nullptr, nullptr);
  if (s0 != 0.0) splitGeneral(*out, *out_e, s0 / s1, nullptr, nullptr, out, out_e);
  addToAll(out_e, label);
}

/// Value and error bound at x in [lo, hi] of the node polynomial.
struct Certified {
  double value;
  double error;
};

SignClass signClass(const Certified& v) { return signClass(v.value, v.error); }

/// Compensated de Casteljau evaluation (Jiang, Li, Zhang & Wang, "Compensated de Casteljau
/// algorithm", 2010) of the node polynomial at x, with an a-posteriori bound on
/// |value - exact| that covers (i) the compensated evaluation, |err| <= u |p| +
/// 2 gamma_{3n+2}^2 sum |c_i| B_i (inflated by 2x), (ii) the coefficient error bounds e_i, and
/// (iii) the rounding of the unit parameter s = (x - lo) / (hi - lo), computed exactly with
/// TwoSum/FMA (zero on dyadic grids such as [0,1]) and multiplied by a bound on |p'|.
Certified evaluateCompensated(const std::vector<double>& c, const std::vector<double>& e, double lo, double hi,
                              double x) {
  if (x == lo) return {c.front(), e.front()};
  if (x == hi) return {c.back(), e.back()};
  const double d1 = x - lo;
  const double e1 = twoSumError(x, -lo, d1);  // x - lo = d1 + e1
  const double w = hi - lo;
  const double e2 = twoSumError(hi, -lo, w);  // hi - lo = w + e2
  const double s = d1 / w;
  const double rem = std::fma(-s, w, d1);  // d1 - s w, exact
  const double position_error = std::abs(e1) + std::abs(rem) + std::abs(s) * std::abs(e2);
  const double t = 1.0 - s;
  const double rho = twoSumError(1.0, -s, t);  // 1 - s = t + rho
  const std::size_t n1 = c.size();
  std::vector<double> b(c);
  std::vector<double> beta(n1, 0.0);
  std::vector<double> babs(n1);
  std::vector<double> be(e);
  for (std::size_t i = 0; i < n1; ++i) babs[i] = std::abs(c[i]);
  for (std::size_t level = n1 - 1; level > 0; --level) {
    for (std::size_t i = 0; i < level; ++i) {
      const double p1 = t * b[i];
      const double pi1 = std::fma(t, b[i], -p1);
      const double p2 = s * b[i + 1];
      const double pi2 = std::fma(s, b[i + 1], -p2);
      const double sum = p1 + p2;
      const double sigma = twoSumError(p1, p2, sum);
      beta[i] = (pi1 + pi2 + sigma + rho * b[i]) + (t * beta[i] + s * beta[i + 1]);
      b[i] = sum;
      babs[i] = t * babs[i] + s * babs[i + 1];
      be[i] = t * be[i] + s * be[i + 1];
    }
  }
  const double value = b[0] + beta[0];
  const double n = static_cast<double>(n1 - 1);
  const double k = (3.0 * n + 2.0) * kUnitRoundoff;
  const double gamma = k / (1.0 - k);
  double bound = 2.0 * kUnitRoundoff * std::abs(value) + 4.0 * gamma * gamma * babs[0] * kBoundInflation +
                 be[0] * (1.0 + 4.0 * (n + 2.0) * kUnitRoundoff) + 8.0 * (n + 1.0) * (n + 1.0) * DBL_TRUE_MIN;
  if (position_error != 0.0 && n1 > 1) {
    // The value was computed at a point within position_error of x: add position_error times
    // a bound on |p'| near x, i.e. |p'(x)| (plain evaluation plus its error bound) plus
    // position_error max |p''| (both from Bernstein coefficients, scaled by powers of w).
    const std::size_t n = n1 - 1;
    std::vector<double> dv(n);
    double dmax = 0.0;
    double demax = 0.0;
    for (std::size_t j = 0; j < n; ++j) {
      dv[j] = static_cast<double>(n) * (c[j + 1] - c[j]);
      dmax = std::max(dmax, std::abs(dv[j]));
      demax = std::max(demax, static_cast<double>(n) * (e[j] + e[j + 1]));
    }
    double second = 0.0;
    for (std::size_t j = 0; j + 2 <= n; ++j) {
      second = std::max(second, std::abs(c[j + 2] - 2.0 * c[j + 1] + c[j]) + e[j] + 2.0 * e[j + 1] + e[j + 2]);
    }
    second *= static_cast<double>(n) * static_cast<double>(n - 1) * kBoundInflation;
    const double d_at_x = std::abs(detail::deCasteljauEvaluate(dv, s));
    const double d_error = 8.0 * static_cast<double>(n + 1) * kUnitRoundoff * dmax + demax;
    const double w_low = w * (1.0 - 2.0 * kUnitRoundoff);
    const double slope = (d_at_x + d_error) / w_low + second * position_error / (w_low * w_low);
    bound += position_error * slope * (1.0 + 8.0 * kUnitRoundoff);
  }
  return {value, bound * kBoundInflation};
}

// --------------------------------------------------------------------------------------------

struct Node {
  std::vector<double> c;
  std::vector<double> e;
  double lo;
  double hi;
  int depth;
  bool is_point;
  RootKind kind;
  /// bezierClip(): an ancestor (or this node) was certified to hold exactly one root in its
  /// open interval, so this node holds it iff its end values have opposite signs.
  bool one_root = false;
};

struct Found {
  RootInterval interval;
  std::vector<double> c;  ///< local coefficients on [lo, hi] (lo < hi only)
  std::vector<double> e;  ///< their error bounds
};

/// Kind of an exact zero at an endpoint, from the adjacent coefficient (derivative sign).
RootKind endpointKind(double adjacent) { return adjacent != 0.0 ? RootKind::Single : RootKind::Unresolved; }

/// Kind of an exact zero at an interior split point: both one-sided derivative estimates must
/// have certain, equal signs.
RootKind splitPointKind(const std::vector<double>& l, const std::vector<double>& le, const std::vector<double>& r,
                        const std::vector<double>& re) {
  const SignClass from_right = signClass(r[1], re[1]);                     // ~ n (r1 - r0) / w, r0 == 0
  const SignClass from_left = signClass(-l[l.size() - 2], le[l.size() - 2]);  // ~ n (l_n - l_{n-1}) / w
  const bool ok = (from_right == kPositive || from_right == kNegative) && from_right == from_left;
  return ok ? RootKind::Single : RootKind::Unresolved;
}

void checkWidth(const char* where, const char* what, double w, bool allow_zero) {
  if (!std::isfinite(w) || w < 0.0 || (!allow_zero && w == 0.0)) {
    std::ostringstream os;
    os << where << ": " << what << " must be finite and " << (allow_zero ? ">= 0" : "> 0") << " (got " << w << ")";
    throw std::invalid_argument(os.str());
  }
}

/// Midpoint of [lo, hi] and the exact rounding error of its computation (m_exact = m + err).
std::pair<double, double> midpoint(double lo, double hi) {
  const double x = 0.5 * lo;
  const double y = 0.5 * hi;
  const double m = x + y;
  return {m, twoSumError(x, y, m)};
}

/// Splits a node at its midpoint; returns the midpoint. Children's bounds include the
/// mislabelling of the midpoint when it is not exactly representable.
double splitNodeHalf(const Node& node, Node* left, Node* right) {
  const std::pair<double, double> mid = midpoint(node.lo, node.hi);
  splitHalf(node.c, node.e, &left->c, &left->e, &right->c, &right->e);
  if (mid.second != 0.0) {
    // |m - m_exact| |p'| <= |err| * bound(|p'| w) / w, with w bounded below by (hi - lo)(1 - 2u).
    const double w = (node.hi - node.lo) * (1.0 - 2.0 * kUnitRoundoff);
    const double label = std::abs(mid.second) * derivativeTimesWidthBound(node.c, node.e) / w * kBoundInflation;
    addToAll(&left->e, label);
    addToAll(&right->e, label);
  }
  left->lo = node.lo;
  left->hi = mid.first;
  right->lo = mid.first;
  right->hi = node.hi;
  left->depth = right->depth = node.depth + 1;
  left->is_point = right->is_point = false;
  left->kind = right->kind = RootKind::Single;
  left->one_root = right->one_root = node.one_root;
  return mid.first;
}

/// Descartes / VCA isolation; shared by isolateRoots() and firstRoot(). Produces intervals in
/// left-to-right order (depth first, left child first); stops after the first when
/// `first_only`.
std::vector<Found> isolate(const BernsteinPolynomial& p, double min_width, bool first_only) {
  std::vector<Found> out;
  const std::vector<double>& c0 = p.coefficients();
  const std::size_t n = c0.size() - 1;
  const std::vector<double> zero_e(c0.size(), 0.0);
  if (p.isZero()) {
    out.push_back({{p.lower(), p.upper(), RootKind::Unresolved}, c0, zero_e});
    return out;
  }
  std::vector<Node> stack;
  // LIFO: push the right end first so that the output comes out sorted.
  if (c0[n] == 0.0) stack.push_back({{}, {}, p.upper(), p.upper(), 0, true, endpointKind(c0[n - 1])});
  stack.push_back({c0, zero_e, p.lower(), p.upper(), 0, false, RootKind::Single});
  if (c0[0] == 0.0) stack.push_back({{}, {}, p.lower(), p.lower(), 0, true, endpointKind(c0[1])});

  int nodes = 0;
  while (!stack.empty()) {
    Node node = std::move(stack.back());
    stack.pop_back();
    if (node.is_point) {
      out.push_back({{node.lo, node.hi, node.kind}, {}, {}});
      if (first_only) return out;
      continue;
    }
    const Descartes d = classify(node.c, node.e);
    if (d == Descartes::kNoRoot) continue;  // endpoint zeros are reported as points
    ++nodes;
    if (d == Descartes::kOneRoot) {
      out.push_back({{node.lo, node.hi, RootKind::Single}, std::move(node.c), std::move(node.e)});
      if (first_only) return out;
      continue;
    }
    const double m = 0.5 * node.lo + 0.5 * node.hi;
    // Cap reached, interval small enough, depth exhausted or no representable midpoint:
    // report conservatively.
    if (nodes > kMaxIsolationNodes || node.hi - node.lo <= min_width || node.depth >= kMaxIsolationDepth ||
        !(node.lo < m && m < node.hi)) {
      out.push_back({{node.lo, node.hi, RootKind::Unresolved}, std::move(node.c), std::move(node.e)});
      if (first_only) return out;
      continue;
    }
    Node left;
    Node right;
    splitNodeHalf(node, &left, &right);
    const bool zero_at_m = left.c.back() == 0.0 && left.e.back() == 0.0;
    const RootKind mid_kind = zero_at_m ? splitPointKind(left.c, left.e, right.c, right.e) : RootKind::Single;
    stack.push_back(std::move(right));
    if (zero_at_m) stack.push_back({{}, {}, left.hi, left.hi, 0, true, mid_kind});
    stack.push_back(std::move(left));
  }
  return out;
}

/// [smin, smax]: the intersection with the axis of the convex hull of the points
/// (i/n, c_i - e_i) and (i/n, c_i + e_i), which contains the control polygon of every
/// polynomial within the error bounds. Returns false when it is empty.
bool hullAxisIntersection(const std::vector<double>& c, const std::vector<double>& e, double* smin, double* smax) {
  const std::size_t n = c.size() - 1;
  const double inv_n = 1.0 / static_cast<double>(n);
  std::vector<double> xs;
  std::vector<double> ys;
  for (std::size_t i = 0; i <= n; ++i) {
    xs.push_back(static_cast<double>(i) * inv_n);
    ys.push_back(c[i] - e[i]);
    if (e[i] != 0.0) {
      xs.push_back(static_cast<double>(i) * inv_n);
      ys.push_back(c[i] + e[i]);
    }
  }
  double lo = kInfinity;
  double hi = -kInfinity;
  for (std::size_t i = 0; i < xs.size(); ++i) {
    if (ys[i] == 0.0) {
      lo = std::min(lo, xs[i]);
      hi = std::max(hi, xs[i]);
      continue;
    }
    for (std::size_t j = i + 1; j < xs.size(); ++j) {
      if (ys[j] == 0.0 || sign(ys[i]) == sign(ys[j])) continue;
      // Crossing of the segment: fraction ys_i / (ys_i - ys_j) in (0, 1).
      const double f = std::min(std::max(ys[i] / (ys[i] - ys[j]), 0.0), 1.0);
      const double s = xs[i] + (xs[j] - xs[i]) * f;
      lo = std::min(lo, s);
      hi = std::max(hi, s);
    }
  }
  if (lo > hi) return false;
  *smin = std::max(lo, 0.0);
  *smax = std::min(hi, 1.0);
  return true;
}

bool lessInterval(const RootInterval& x, const RootInterval& y) {
  return x.lo < y.lo || (x.lo == y.lo && x.hi < y.hi);
}

/// Safeguarded Newton/bisection on a node polynomial with certified sign decisions. `slo` is
/// the sign of p at lo (hi has the opposite sign). Returns a bracket of width <= tol (Single),
/// or the tightest bracket it could certify (Unresolved) when the evaluation error bound or the
/// iteration cap prevents reaching tol.
RootInterval refineNode(const std::vector<double>& c, const std::vector<double>& e, double a, double b, double lo,
                        double hi, int slo, double tol) {
  // Derivative coefficients on [a, b] (only steer the iteration; no certification needed).
  const std::size_t n = c.size() - 1;
  std::vector<double> dc(std::max<std::size_t>(n, 1), 0.0);
  for (std::size_t i = 0; i < n; ++i) dc[i] = static_cast<double>(n) * (c[i + 1] - c[i]) / (b - a);

  // Updates the bracket with a certified sign at x; returns false if x is a certified exact
  // zero (then *zero = true) or the sign is uncertain.
  bool exact_zero = false;
  double zero_at = 0.0;
  auto probe = [&](double x) -> bool {
    const Certified v = evaluateCompensated(c, e, a, b, x);
    const SignClass s = signClass(v.value, v.error);
    if (s == kExactZero) {
      exact_zero = true;
      zero_at = x;
      return false;
    }
    if (s == kUncertain) return false;
    if (static_cast<int>(s) == slo) {
      lo = x;
    } else {
      hi = x;
    }
    return true;
  };

  double x = 0.5 * lo + 0.5 * hi;
  double dx_old = hi - lo;
  double dx = dx_old;
  for (int it = 0; it < kMaxRefineRootIterations; ++it) {
    if (hi - lo <= tol) return {lo, hi, RootKind::Single};
    const double mid = 0.5 * lo + 0.5 * hi;
    if (!(lo < mid && mid < hi)) return {lo, hi, RootKind::Single};  // adjacent doubles
    const double width_before = hi - lo;
    if (!probe(x)) {
      if (exact_zero) return {zero_at, zero_at, RootKind::Single};
      // Uncertain sign at x: probe symmetrically at growing distances until both sides are
      // certain or outside the bracket (at most kMaxRefineRootIterations doublings).
      double delta = std::max({0.5 * tol, 2.0 * (std::nextafter(std::abs(x), kInfinity) - std::abs(x)), DBL_TRUE_MIN});
      for (int k = 0; k < kMaxRefineRootIterations; ++k, delta *= 2.0) {
        const double xl = x - delta;
        const double xr = x + delta;
        bool left_done = !(lo < xl);
        bool right_done = !(xr < hi);
        if (left_done && right_done) break;
        if (!left_done) left_done = probe(xl);
        if (exact_zero) return {zero_at, zero_at, RootKind::Single};
        if (!right_done && lo < xr && xr < hi) right_done = probe(xr);
        if (exact_zero) return {zero_at, zero_at, RootKind::Single};
        if (left_done && right_done) break;
      }
      if (!(hi - lo < width_before)) {  // no progress possible: accuracy limit reached
        return {lo, hi, hi - lo <= tol ? RootKind::Single : RootKind::Unresolved};
      }
      x = 0.5 * lo + 0.5 * hi;
      dx_old = dx = hi - lo;
      continue;
    }
    if (hi - lo <= tol) return {lo, hi, RootKind::Single};
    // Newton candidate from x (rtsafe safeguard: inside the bracket and the step at most half
    // of the one before the last), else bisection.
    const double fx = detail::deCasteljauEvaluate(c, (x - a) / (b - a));
    const double d = detail::deCasteljauEvaluate(dc, (x - a) / (b - a));
    double step = 0.0;
    bool newton = false;
    if (d != 0.0) {
      step = fx / d;
      const double xn = x - step;
      newton = lo < xn && xn < hi && std::abs(step) <= 0.5 * std::abs(dx_old);
    }
    dx_old = dx;
    if (!newton) {
      x = 0.5 * lo + 0.5 * hi;
      dx = hi - lo;
      continue;
    }
    dx = step;
    x -= step;
    // Close to convergence: probe on both sides of the Newton iterate to close the bracket.
    const double near = std::max(tol, 8.0 * DBL_EPSILON * std::abs(x));
    if (std::abs(step) <= near) {
      const double xl = std::min(x - 0.5 * tol, std::nextafter(x, -kInfinity));
      const double xr = std::max(x + 0.5 * tol, std::nextafter(x, kInfinity));
      if (lo < xl && xl < hi) probe(xl);
      if (exact_zero) return {zero_at, zero_at, RootKind::Single};
      if (lo < xr && xr < hi) probe(xr);
      if (exact_zero) return {zero_at, zero_at, RootKind::Single};
      if (!(lo < x && x < hi)) {
        x = 0.5 * lo + 0.5 * hi;
        dx = hi - lo;
      }
    }
  }
  // Cap reached: the bracket is still valid.
  return {lo, hi, hi - lo <= tol ? RootKind::Single : RootKind::Unresolved};
}

}  // namespace

int descartesBound(const BernsteinPolynomial& p) { return p.signVariations(); }

std::vector<RootInterval> isolateRoots(const BernsteinPolynomial& p, double min_width) {
  checkWidth("isolateRoots", "min_width", min_width, true);
  std::vector<Found> found = isolate(p, min_width, false);
  std::vector<RootInterval> out;
  out.reserve(found.size());
  for (const Found& f : found) out.push_back(f.interval);
  return out;
}

std::vector<RootInterval> bezierClip(const BernsteinPolynomial& p, double tol) {
  checkWidth("bezierClip", "tol", tol, false);
  std::vector<RootInterval> out;
  const std::vector<double>& c0 = p.coefficients();
  const std::vector<double> zero_e(c0.size(), 0.0);
  const std::size_t n = c0.size() - 1;
  if (p.isZero()) {
    out.push_back({p.lower(), p.upper(), RootKind::Unresolved});
    return out;
  }
  if (c0[0] == 0.0) out.push_back({p.lower(), p.lower(), endpointKind(c0[1])});
  if (c0[n] == 0.0) out.push_back({p.upper(), p.upper(), endpointKind(c0[n - 1])});
  // Certified sign of the input polynomial at x (compensated evaluation).
  auto signAt = [&](double x) { return signClass(evaluateCompensated(c0, zero_e, p.lower(), p.upper(), x)); };
  auto isSign = [](SignClass sc) { return sc == kPositive || sc == kNegative; };

  std::vector<Node> stack;
  stack.push_back({c0, zero_e, p.lower(), p.upper(), 0, false, RootKind::Single});
  int iterations = 0;
  while (!stack.empty()) {
    Node node = std::move(stack.back());
    stack.pop_back();
    const Descartes d = classify(node.c, node.e);
    if (d == Descartes::kNoRoot) continue;
    node.one_root = node.one_root || d == Descartes::kOneRoot;
    const double w = node.hi - node.lo;
    if (++iterations > kMaxBezierClipIterations) {  // cap: report what is left, conservatively
      out.push_back({node.lo, node.hi, RootKind::Unresolved});
      continue;
    }
    if (w <= tol) {
      bool single = d == Descartes::kOneRoot;
      if (!single && node.one_root) {
        const SignClass sl = signAt(node.lo);
        const SignClass sh = signAt(node.hi);
        single = isSign(sl) && isSign(sh) && sl != sh;
      }
      out.push_back({node.lo, node.hi, single ? RootKind::Single : RootKind::Unresolved});
      continue;
    }
    double smin = 0.0;
    double smax = 1.0;
    if (!hullAxisIntersection(node.c, node.e, &smin, &smax)) continue;  // excluded by kNoRoot already
    smin = std::max(0.0, smin - kBezierClipRelativeMargin);
    smax = std::min(1.0, smax + kBezierClipRelativeMargin);
    // Clip to [new_lo, new_hi] (widened by one ulp on each clipped side); a clip narrower than
    // tol is widened to ~tol around its centre so that its end values stay certifiable.
    double new_lo = smin > 0.0 ? std::max(node.lo, std::nextafter(node.lo + smin * w, -kInfinity)) : node.lo;
    double new_hi = smax < 1.0 ? std::min(node.hi, std::nextafter(node.lo + smax * w, kInfinity)) : node.hi;
    if (new_hi - new_lo < 0.5 * tol) {
      const double centre = 0.5 * new_lo + 0.5 * new_hi;
      new_lo = std::max(node.lo, centre - 0.25 * tol);
      new_hi = std::min(node.hi, centre + 0.25 * tol);
    }
    const bool progress = new_lo < new_hi && (new_lo > node.lo || new_hi < node.hi);
    if (smax - smin > kBezierClipSplitFraction || !progress) {
      const double m = 0.5 * node.lo + 0.5 * node.hi;
      if (!(node.lo < m && m < node.hi)) {
        out.push_back({node.lo, node.hi, RootKind::Unresolved});
        continue;
      }
      Node left;
      Node right;
      splitNodeHalf(node, &left, &right);
      if (left.c.back() == 0.0 && left.e.back() == 0.0) {
        out.push_back({m, m, splitPointKind(left.c, left.e, right.c, right.e)});
        if (node.one_root) continue;  // the only root of this node is at m
      }
      if (node.one_root) {
        // Exactly one root in (lo, hi): keep only the half with the sign change when the signs
        // are certified.
        const SignClass sm = signAt(m);
        const SignClass sl = signAt(node.lo);
        const SignClass sh = signAt(node.hi);
        if (isSign(sm) && ((isSign(sl) && sl != sm) || (isSign(sh) && sh == sm))) {
          stack.push_back(std::move(left));
          continue;
        }
        if (isSign(sm) && ((isSign(sl) && sl == sm) || (isSign(sh) && sh != sm))) {
          stack.push_back(std::move(right));
          continue;
        }
      }
      stack.push_back(std::move(right));
      stack.push_back(std::move(left));
      continue;
    }
    Node clipped;
    restrictWithError(node.c, node.e, (new_lo - node.lo) / w, (new_hi - node.lo) / w, &clipped.c, &clipped.e);
    clipped.lo = new_lo;
    clipped.hi = new_hi;
    clipped.depth = node.depth + 1;
    clipped.is_point = false;
    clipped.kind = RootKind::Single;
    clipped.one_root = node.one_root;
    stack.push_back(std::move(clipped));
  }
  std::sort(out.begin(), out.end(), lessInterval);
  // Remove duplicate point roots (the same point reached from two sides).
  std::vector<RootInterval> unique;
  unique.reserve(out.size());
  for (const RootInterval& r : out) {
    if (!unique.empty() && r.lo == r.hi && unique.back().lo == r.lo && unique.back().hi == r.hi) {
      if (r.kind == RootKind::Unresolved) unique.back().kind = RootKind::Unresolved;
      continue;
    }
    unique.push_back(r);
  }
  return unique;
}

RootInterval refineRootBracket(const BernsteinPolynomial& p, double lo, double hi, double tol) {
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo < hi) || lo < p.lower() || hi > p.upper()) {
    std::ostringstream os;
    os.precision(17);
    os << "refineRootBracket: bracket [" << lo << ", " << hi << "] is empty, inverted, non-finite or outside ["
       << p.lower() << ", " << p.upper() << "]";
    throw std::invalid_argument(os.str());
  }
  checkWidth("refineRootBracket", "tol", tol, true);
  const double flo = p.evaluate(lo);
  const double fhi = p.evaluate(hi);
  if (flo == 0.0) return {lo, lo, RootKind::Single};
  if (fhi == 0.0) return {hi, hi, RootKind::Single};
  if (sign(flo) == sign(fhi)) {
    std::ostringstream os;
    os.precision(17);
    os << "refineRootBracket: no sign change: p(" << lo << ") = " << flo << " and p(" << hi << ") = " << fhi;
    throw std::invalid_argument(os.str());
  }
  return refineNode(p.coefficients(), std::vector<double>(p.coefficients().size(), 0.0), p.lower(), p.upper(), lo,
                    hi, sign(flo), tol);
}

double refineRoot(const BernsteinPolynomial& p, double lo, double hi, double tol) {
  checkWidth("refineRoot", "tol", tol, true);
  const RootInterval r = refineRootBracket(p, lo, hi, std::min(2.0 * tol, DBL_MAX));
  return r.lo == r.hi ? r.lo : 0.5 * r.lo + 0.5 * r.hi;
}

std::optional<double> firstRoot(const BernsteinPolynomial& p, double tol) {
  checkWidth("firstRoot", "tol", tol, false);
  if (p.isZero()) return p.lower();
  const std::vector<Found> found = isolate(p, tol, true);
  if (found.empty()) return std::nullopt;
  const Found& f = found.front();
  if (f.interval.lo == f.interval.hi || f.interval.kind == RootKind::Unresolved) return f.interval.lo;
  // Single: exactly one root in (lo, hi). Refine on the input coefficients (exact, so the
  // compensated evaluation certifies signs very close to the root) when their values at lo and
  // hi have certified opposite signs; otherwise on the local coefficients, whose end values
  // are certified by construction.
  const std::vector<double>& c0 = p.coefficients();
  const std::vector<double> zero_e(c0.size(), 0.0);
  const SignClass sl = signClass(evaluateCompensated(c0, zero_e, p.lower(), p.upper(), f.interval.lo));
  const SignClass sh = signClass(evaluateCompensated(c0, zero_e, p.lower(), p.upper(), f.interval.hi));
  if ((sl == kPositive && sh == kNegative) || (sl == kNegative && sh == kPositive)) {
    return refineNode(c0, zero_e, p.lower(), p.upper(), f.interval.lo, f.interval.hi, static_cast<int>(sl), tol).lo;
  }
  const int slo = sign(f.c.front());
  return refineNode(f.c, f.e, f.interval.lo, f.interval.hi, f.interval.lo, f.interval.hi, slo, tol).lo;
}

}  // namespace fcl_quadric
