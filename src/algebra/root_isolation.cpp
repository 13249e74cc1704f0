#include "fcl_quadric/algebra/root_isolation.h"

#include "fcl_quadric/tolerances.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "algebra/sign.h"

namespace fcl_quadric {
namespace {

using tolerance::kUnitRoundoff;
/// Factor applied to every error bound after it is accumulated in floating point, so that the
/// rounding of the bound computation itself is covered.
constexpr double kBoundInflation = 1.0 + 16.0 * kUnitRoundoff;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

using detail::sign;

/// Knuth's TwoSum: x + y = s + err exactly, for s = fl(x + y).
double twoSumError(double x, double y, double s) {
  const double bv = s - x;
  const double av = s - bv;
  return (x - av) + (y - bv);
}

// --------------------------------------------------------------------------------------------
// Certified sign decisions.
//
// A coefficient is known as a value c and a radius r: the exact coefficient (of the polynomial
// represented exactly by the caller's doubles) lies in [c - r, c + r].

/// Sign classes of an interval coefficient.
enum SignClass { kNegative = -1, kExactZero = 0, kPositive = 1, kUncertain = 2 };

SignClass signClass(double c, double r) {
  if (c > r) return kPositive;
  if (c < -r) return kNegative;
  if (c == 0.0 && r == 0.0) return kExactZero;
  return kUncertain;
}

bool isSign(SignClass s) { return s == kPositive || s == kNegative; }

enum class Descartes { kNoRoot, kOneRoot, kUndecided };

/// Descartes' rule for every polynomial whose coefficients lie in the boxes [c_i -+ r_i]:
///  - kNoRoot: all exact coefficients are >= 0 or all <= 0 (no root in the open interval);
///  - kOneRoot: end coefficients have certain opposite signs and every assignment of the
///    uncertain coefficients gives exactly one sign variation (uncertain coefficients only in
///    the transition between the two runs);
///  - kUndecided otherwise.
Descartes classify(const std::vector<double>& c, const std::vector<double>& r) {
  const std::size_t n1 = c.size();
  bool nonneg = true;
  bool nonpos = true;
  for (std::size_t i = 0; i < n1; ++i) {
    if (c[i] - r[i] < 0.0) nonneg = false;
    if (c[i] + r[i] > 0.0) nonpos = false;
  }
  if (nonneg || nonpos) return Descartes::kNoRoot;
  const SignClass s0 = signClass(c.front(), r.front());
  const SignClass sn = signClass(c.back(), r.back());
  if (!isSign(s0) || !isSign(sn) || s0 == sn) return Descartes::kUndecided;
  // i2: first coefficient with certain sign sn; i1: last one with certain sign s0 before it.
  std::size_t i2 = 0;
  while (signClass(c[i2], r[i2]) != sn) ++i2;  // terminates: the last coefficient has sign sn
  std::size_t i1 = 0;
  for (std::size_t i = 0; i < i2; ++i) {
    if (signClass(c[i], r[i]) == s0) i1 = i;
  }
  for (std::size_t i = 0; i < n1; ++i) {
    const SignClass s = signClass(c[i], r[i]);
    if (i < i1 && s != s0 && s != kExactZero) return Descartes::kUndecided;
    if (i > i2 && s != sn && s != kExactZero) return Descartes::kUndecided;
  }
  return Descartes::kOneRoot;
}

// --------------------------------------------------------------------------------------------
// Sub-interval coefficients in double-double arithmetic.
//
// IsolationNode coefficients are unevaluated sums hi_i + lo_i (normalised by TwoSum) plus an absolute
// error bound err_i: the exact Bernstein coefficient of the input polynomial on the node's
// interval lies within err_i of hi_i + lo_i. Working in double-double keeps err_i at the level
// of u^2 times the coefficient magnitudes, so sign decisions near a root are limited by the
// root's conditioning relative to u^2 rather than u.

struct SplitCoeffs {
  std::vector<double> hi;
  std::vector<double> lo;
  std::vector<double> err;
};

SplitCoeffs exactCoeffs(const std::vector<double>& c) {
  return SplitCoeffs{c, std::vector<double>(c.size(), 0.0), std::vector<double>(c.size(), 0.0)};
}

/// Radii for sign decisions on the hi parts: |lo_i| + err_i (inflated).
std::vector<double> radii(const SplitCoeffs& k) {
  std::vector<double> r(k.hi.size());
  for (std::size_t i = 0; i < r.size(); ++i) r[i] = (std::abs(k.lo[i]) + k.err[i]) * kBoundInflation;
  return r;
}

/// Split at the unit parameter 1/2: each new coefficient is (a + b) / 2 in double-double.
/// Halving is exact unless it underflows (detected; DBL_TRUE_MIN is added to the bound); the
/// only rounding is that of the low-order sum, bounded by 2u times its magnitude.
void splitHalf(const SplitCoeffs& in, SplitCoeffs* left, SplitCoeffs* right) {
  const std::size_t n1 = in.hi.size();
  SplitCoeffs w = in;
  SplitCoeffs l{std::vector<double>(n1), std::vector<double>(n1), std::vector<double>(n1)};
  SplitCoeffs r = l;
  auto store = [](SplitCoeffs* dst, std::size_t j, const SplitCoeffs& src, std::size_t i) {
    dst->hi[j] = src.hi[i];
    dst->lo[j] = src.lo[i];
    dst->err[j] = src.err[i];
  };
  store(&l, 0, w, 0);
  store(&r, n1 - 1, w, n1 - 1);
  for (std::size_t level = n1 - 1; level > 0; --level) {
    for (std::size_t i = 0; i < level; ++i) {
      const double x = 0.5 * w.hi[i];
      const double y = 0.5 * w.hi[i + 1];
      const double xl = 0.5 * w.lo[i];
      const double yl = 0.5 * w.lo[i + 1];
      const double s = x + y;
      const double e = twoSumError(x, y, s);
      const double t = (xl + yl) + e;
      const double h = s + t;
      const double lo = twoSumError(s, t, h);
      double err = 0.5 * w.err[i] + 0.5 * w.err[i + 1] + 2.0 * kUnitRoundoff * (std::abs(xl) + std::abs(yl) + std::abs(e));
      if (2.0 * x != w.hi[i] || 2.0 * y != w.hi[i + 1] || 2.0 * xl != w.lo[i] || 2.0 * yl != w.lo[i + 1]) {
        err += 2.0 * DBL_TRUE_MIN;  // inexact halving (underflow)
      }
      w.hi[i] = h;
      w.lo[i] = lo;
      w.err[i] = err * kBoundInflation;
    }
    store(&l, n1 - level, w, 0);
    store(&r, level - 1, w, level - 1);
  }
  *left = std::move(l);
  *right = std::move(r);
}

/// a * (th + tl) + b * s in double-double, where 1 - s = th + tl exactly; returns the bound on
/// the rounding committed (relative u^2-level terms, inflated generously).
void combine(double ah, double al, double bh, double bl, double th, double tl, double s, double* h, double* l,
             double* rounding) {
  const double p = ah * th;
  const double pe = std::fma(ah, th, -p);
  const double q = bh * s;
  const double qe = std::fma(bh, s, -q);
  const double sum = p + q;
  const double se = twoSumError(p, q, sum);
  const double small = ((pe + qe) + se) + ((ah * tl + al * th) + bl * s);
  *h = sum + small;
  *l = twoSumError(sum, small, *h);
  *rounding = 4.0 * kUnitRoundoff *
                  (std::abs(pe) + std::abs(qe) + std::abs(se) + std::abs(ah * tl) + std::abs(al * th) +
                   std::abs(bl * s)) +
              std::abs(al * tl) + 8.0 * DBL_TRUE_MIN;
}

/// Split at a general unit parameter s in [0, 1] in double-double; either output may be null.
void splitGeneral(const SplitCoeffs& in, double s, SplitCoeffs* left, SplitCoeffs* right) {
  const std::size_t n1 = in.hi.size();
  const double th = 1.0 - s;
  const double tl = twoSumError(1.0, -s, th);
  SplitCoeffs w = in;
  SplitCoeffs l{std::vector<double>(n1), std::vector<double>(n1), std::vector<double>(n1)};
  SplitCoeffs r = l;
  l.hi[0] = w.hi[0];
  l.lo[0] = w.lo[0];
  l.err[0] = w.err[0];
  r.hi[n1 - 1] = w.hi[n1 - 1];
  r.lo[n1 - 1] = w.lo[n1 - 1];
  r.err[n1 - 1] = w.err[n1 - 1];
  for (std::size_t level = n1 - 1; level > 0; --level) {
    for (std::size_t i = 0; i < level; ++i) {
      double h = 0.0;
      double lo = 0.0;
      double rounding = 0.0;
      combine(w.hi[i], w.lo[i], w.hi[i + 1], w.lo[i + 1], th, tl, s, &h, &lo, &rounding);
      const double err = (std::abs(th) + std::abs(tl)) * w.err[i] + s * w.err[i + 1] + rounding;
      w.hi[i] = h;
      w.lo[i] = lo;
      w.err[i] = err * kBoundInflation;
    }
    l.hi[n1 - level] = w.hi[0];
    l.lo[n1 - level] = w.lo[0];
    l.err[n1 - level] = w.err[0];
    r.hi[level - 1] = w.hi[level - 1];
    r.lo[level - 1] = w.lo[level - 1];
    r.err[level - 1] = w.err[level - 1];
  }
  if (left != nullptr) *left = std::move(l);
  if (right != nullptr) *right = std::move(r);
}

/// Upper bound on |p'| * (b - a) over [a, b] (from the derivative's Bernstein coefficients):
/// n max_j (|c_{j+1} - c_j| + r_j + r_{j+1}).
double derivativeTimesWidthBound(const std::vector<double>& c, const std::vector<double>& r) {
  const std::size_t n = c.size() - 1;
  double m = 0.0;
  for (std::size_t j = 0; j < n; ++j) m = std::max(m, std::abs(c[j + 1] - c[j]) + r[j] + r[j + 1]);
  return static_cast<double>(n) * m * kBoundInflation;
}

void addToAll(std::vector<double>* e, double v) {
  for (double& x : *e) x = (x + v) * kBoundInflation;
}

/// Coefficients on the unit sub-interval [s0, s1] of the node (0 <= s0 < s1 <= 1). The new end
/// points are labelled by doubles within 6u of the node width of the points actually used;
/// that mislabelling times the derivative bound is added to every error bound.
SplitCoeffs restrictCoeffs(const SplitCoeffs& in, double s0, double s1) {
  const double label = 6.0 * kUnitRoundoff * derivativeTimesWidthBound(in.hi, radii(in));
  SplitCoeffs out = in;
  if (s1 != 1.0) splitGeneral(out, s1, &out, nullptr);
  if (s0 != 0.0) splitGeneral(out, s0 / s1, nullptr, &out);
  addToAll(&out.err, label);
  return out;
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

struct IsolationNode {
  SplitCoeffs k;
  double lo;
  double hi;
  int depth;
  bool is_point;
  RootKind kind;
  /// bezierClip(): an ancestor (or this node) was certified to hold exactly one root in its
  /// open interval, so this node holds it iff its end values have opposite signs.
  bool one_root;
};

IsolationNode pointNode(double x, RootKind kind) { return IsolationNode{SplitCoeffs{}, x, x, 0, true, kind, false}; }

struct Found {
  RootInterval interval;
  std::vector<double> c;  ///< local coefficients (hi parts) on [lo, hi] (lo < hi only)
  std::vector<double> r;  ///< their radii
};

/// Kind of an exact zero at an endpoint of the input interval, from the adjacent (exact)
/// coefficient, whose sign is that of the derivative there.
RootKind endpointKind(double adjacent) { return adjacent != 0.0 ? RootKind::Single : RootKind::Unresolved; }

/// Kind of an exact zero at an interior split point: both one-sided derivative estimates must
/// have certain, equal signs.
RootKind splitPointKind(const SplitCoeffs& l, const SplitCoeffs& r) {
  const std::vector<double> lr = radii(l);
  const std::vector<double> rr = radii(r);
  const std::size_t n = l.hi.size() - 1;
  const SignClass from_right = signClass(r.hi[1], rr[1]);        // ~ n (r1 - r0) / w, r0 == 0
  const SignClass from_left = signClass(-l.hi[n - 1], lr[n - 1]);  // ~ n (l_n - l_{n-1}) / w, l_n == 0
  return (isSign(from_right) && from_right == from_left) ? RootKind::Single : RootKind::Unresolved;
}

bool exactZero(const SplitCoeffs& k, std::size_t i) { return k.hi[i] == 0.0 && k.lo[i] == 0.0 && k.err[i] == 0.0; }

void checkWidth(const char* where, const char* what, double w, bool allow_zero) {
  if (!std::isfinite(w) || w < 0.0 || (!allow_zero && w == 0.0)) {
    std::ostringstream os;
    os << where << ": " << what << " must be finite and " << (allow_zero ? ">= 0" : "> 0") << " (got " << w << ")";
    throw std::invalid_argument(os.str());
  }
}

/// Splits a node at its midpoint. The children's bounds include the mislabelling of the
/// midpoint when 0.5 lo + 0.5 hi is not exact (never on dyadic grids such as [0,1]).
void splitNodeHalf(const IsolationNode& node, IsolationNode* left, IsolationNode* right) {
  const double x = 0.5 * node.lo;
  const double y = 0.5 * node.hi;
  const double m = x + y;
  const double m_error = twoSumError(x, y, m);  // exact midpoint = m + m_error
  splitHalf(node.k, &left->k, &right->k);
  if (m_error != 0.0) {
    // |m - m_exact| |p'| <= |m_error| * bound(|p'| w) / w, with w bounded below.
    const double w = (node.hi - node.lo) * (1.0 - 2.0 * kUnitRoundoff);
    const double label = std::abs(m_error) * derivativeTimesWidthBound(node.k.hi, radii(node.k)) / w * kBoundInflation;
    addToAll(&left->k.err, label);
    addToAll(&right->k.err, label);
  }
  left->lo = node.lo;
  left->hi = m;
  right->lo = m;
  right->hi = node.hi;
  left->depth = right->depth = node.depth + 1;
  left->is_point = right->is_point = false;
  left->kind = right->kind = RootKind::Single;
  left->one_root = right->one_root = node.one_root;
}

/// Descartes / VCA isolation in the unit parameter s of [a, b] (so that every subdivision point
/// is an exact dyadic rational); shared by isolateRoots() and firstRoot(). Produces intervals
/// in s, left to right (depth first, left child first); stops after the first when
/// `first_only`. p must not be identically zero.
std::vector<Found> isolateUnit(const BernsteinPolynomial& p, double min_width, bool first_only) {
  std::vector<Found> out;
  const std::vector<double>& c0 = p.coefficients();
  const std::size_t n = c0.size() - 1;
  std::vector<IsolationNode> stack;
  // LIFO: push the right end first so that the output comes out sorted.
  if (c0[n] == 0.0) stack.push_back(pointNode(1.0, endpointKind(c0[n - 1])));
  stack.push_back(IsolationNode{exactCoeffs(c0), 0.0, 1.0, 0, false, RootKind::Single, false});
  if (c0[0] == 0.0) stack.push_back(pointNode(0.0, endpointKind(c0[1])));

  int nodes = 0;
  while (!stack.empty()) {
    IsolationNode node = std::move(stack.back());
    stack.pop_back();
    if (node.is_point) {
      out.push_back({{node.lo, node.hi, node.kind}, {}, {}});
      if (first_only) return out;
      continue;
    }
    std::vector<double> r = radii(node.k);
    const Descartes d = classify(node.k.hi, r);
    if (d == Descartes::kNoRoot) continue;  // endpoint zeros are reported as points
    ++nodes;
    if (d == Descartes::kOneRoot) {
      out.push_back({{node.lo, node.hi, RootKind::Single}, std::move(node.k.hi), std::move(r)});
      if (first_only) return out;
      continue;
    }
    const double m = 0.5 * node.lo + 0.5 * node.hi;
    // Cap reached, interval small enough, depth exhausted or no representable midpoint:
    // report conservatively.
    if (nodes > kMaxIsolationNodes || node.hi - node.lo <= min_width || node.depth >= kMaxIsolationDepth ||
        !(node.lo < m && m < node.hi)) {
      out.push_back({{node.lo, node.hi, RootKind::Unresolved}, std::move(node.k.hi), std::move(r)});
      if (first_only) return out;
      continue;
    }
    IsolationNode left;
    IsolationNode right;
    splitNodeHalf(node, &left, &right);
    const bool zero_at_m = exactZero(left.k, n);
    const RootKind mid_kind = zero_at_m ? splitPointKind(left.k, right.k) : RootKind::Single;
    stack.push_back(std::move(right));
    if (zero_at_m) stack.push_back(pointNode(left.hi, mid_kind));
    stack.push_back(std::move(left));
  }
  return out;
}

/// [smin, smax]: the intersection with the axis of the convex hull of the points
/// (i/n, c_i - r_i) and (i/n, c_i + r_i), which contains the control polygon of every
/// polynomial within the radii. Returns false when it is empty.
bool hullAxisIntersection(const std::vector<double>& c, const std::vector<double>& rad, double* smin,
                          double* smax) {
  const std::size_t n = c.size() - 1;
  const double inv_n = 1.0 / static_cast<double>(n);
  std::vector<double> xs;
  std::vector<double> ys;
  for (std::size_t i = 0; i <= n; ++i) {
    xs.push_back(static_cast<double>(i) * inv_n);
    ys.push_back(c[i] - rad[i]);
    if (rad[i] != 0.0) {
      xs.push_back(static_cast<double>(i) * inv_n);
      ys.push_back(c[i] + rad[i]);
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

/// Encloses t = a + s (b - a): returns doubles down <= t_exact <= up (equal when the mapping is
/// exact, e.g. always for [a, b] = [0, 1]). The rounding of each operation is computed exactly
/// (TwoSum, FMA) and the result is widened outward by it plus one ulp.
std::pair<double, double> mapToT(double s, double a, double b) {
  if (s == 0.0) return {a, a};
  if (s == 1.0) return {b, b};
  const double w = b - a;
  const double ew = twoSumError(b, -a, w);
  const double prod = s * w;
  const double ep = std::fma(s, w, -prod);
  const double t = a + prod;
  const double et = twoSumError(a, prod, t);
  // t_exact = t + et + ep + s ew
  const double err = std::abs(et) + std::abs(ep) + std::abs(s * ew) * (1.0 + 4.0 * kUnitRoundoff);
  if (err == 0.0) return {t, t};
  const double pad = err * kBoundInflation;
  return {std::max(a, std::nextafter(t - pad, -kInfinity)), std::min(b, std::nextafter(t + pad, kInfinity))};
}

RootInterval mapToT(const RootInterval& r, double a, double b) {
  return {mapToT(r.lo, a, b).first, mapToT(r.hi, a, b).second, r.kind};
}

/// A width in t converted to the unit parameter so that mapped intervals (widened by
/// mapToT()) stay within `width` whenever width >= 2 slack, slack being the widening.
double unitWidth(double width, double a, double b) {
  const double slack = 8.0 * kUnitRoundoff * (std::abs(a) + std::abs(b)) + 4.0 * DBL_TRUE_MIN;
  const double wt = std::max(width - slack, 0.5 * width);
  return wt / (b - a) * (1.0 - 8.0 * kUnitRoundoff);
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
  if (p.isZero()) return {RootInterval{p.lower(), p.upper(), RootKind::Unresolved}};
  const std::vector<Found> found = isolateUnit(p, unitWidth(min_width, p.lower(), p.upper()), false);
  std::vector<RootInterval> out;
  out.reserve(found.size());
  for (const Found& f : found) out.push_back(mapToT(f.interval, p.lower(), p.upper()));
  return out;
}

std::vector<RootInterval> bezierClip(const BernsteinPolynomial& p, double tol) {
  checkWidth("bezierClip", "tol", tol, false);
  std::vector<RootInterval> out;
  const std::vector<double>& c0 = p.coefficients();
  const std::vector<double> zero_r(c0.size(), 0.0);
  const std::size_t n = c0.size() - 1;
  if (p.isZero()) {
    out.push_back({p.lower(), p.upper(), RootKind::Unresolved});
    return out;
  }
  if (c0[0] == 0.0) out.push_back({0.0, 0.0, endpointKind(c0[1])});
  if (c0[n] == 0.0) out.push_back({1.0, 1.0, endpointKind(c0[n - 1])});
  // Certified sign of the input polynomial at the unit parameter x (compensated evaluation;
  // exact parameter, so no position error).
  auto signAt = [&](double x) { return signClass(evaluateCompensated(c0, zero_r, 0.0, 1.0, x)); };
  const double tol_unit = unitWidth(tol, p.lower(), p.upper());

  std::vector<IsolationNode> stack;
  stack.push_back(IsolationNode{exactCoeffs(c0), 0.0, 1.0, 0, false, RootKind::Single, false});
  int iterations = 0;
  while (!stack.empty()) {
    IsolationNode node = std::move(stack.back());
    stack.pop_back();
    const std::vector<double> r = radii(node.k);
    const Descartes d = classify(node.k.hi, r);
    if (d == Descartes::kNoRoot) continue;
    node.one_root = node.one_root || d == Descartes::kOneRoot;
    const double w = node.hi - node.lo;
    if (++iterations > kMaxBezierClipIterations) {  // cap: report what is left, conservatively
      out.push_back({node.lo, node.hi, RootKind::Unresolved});
      continue;
    }
    if (w <= tol_unit) {
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
    if (!hullAxisIntersection(node.k.hi, r, &smin, &smax)) continue;  // excluded by kNoRoot already
    smin = std::max(0.0, smin - kBezierClipRelativeMargin);
    smax = std::min(1.0, smax + kBezierClipRelativeMargin);
    // Clip to [new_lo, new_hi] (widened by one ulp on each clipped side); a clip narrower than
    // tol / 2 is widened to tol / 2 around its centre so that its end values stay certifiable.
    double new_lo = smin > 0.0 ? std::max(node.lo, std::nextafter(node.lo + smin * w, -kInfinity)) : node.lo;
    double new_hi = smax < 1.0 ? std::min(node.hi, std::nextafter(node.lo + smax * w, kInfinity)) : node.hi;
    if (new_hi - new_lo < 0.5 * tol_unit) {
      const double centre = 0.5 * new_lo + 0.5 * new_hi;
      new_lo = std::max(node.lo, centre - 0.25 * tol_unit);
      new_hi = std::min(node.hi, centre + 0.25 * tol_unit);
    }
    const bool progress = new_lo < new_hi && (new_lo > node.lo || new_hi < node.hi);
    if (smax - smin > kBezierClipSplitFraction || !progress) {
      const double m = 0.5 * node.lo + 0.5 * node.hi;
      if (!(node.lo < m && m < node.hi)) {
        out.push_back({node.lo, node.hi, RootKind::Unresolved});
        continue;
      }
      IsolationNode left;
      IsolationNode right;
      splitNodeHalf(node, &left, &right);
      if (exactZero(left.k, n)) {
        out.push_back({m, m, splitPointKind(left.k, right.k)});
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
    IsolationNode clipped{restrictCoeffs(node.k, (new_lo - node.lo) / w, (new_hi - node.lo) / w), new_lo, new_hi,
                 node.depth + 1, false, RootKind::Single, node.one_root};
    stack.push_back(std::move(clipped));
  }
  for (RootInterval& ri : out) ri = mapToT(ri, p.lower(), p.upper());
  std::sort(out.begin(), out.end(), lessInterval);
  // Remove duplicate point roots (the same point reached from two sides).
  std::vector<RootInterval> unique;
  unique.reserve(out.size());
  for (const RootInterval& ri : out) {
    if (!unique.empty() && ri.lo == ri.hi && unique.back().lo == ri.lo && unique.back().hi == ri.hi) {
      if (ri.kind == RootKind::Unresolved) unique.back().kind = RootKind::Unresolved;
      continue;
    }
    unique.push_back(ri);
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
  const double a = p.lower();
  const double b = p.upper();
  const double tol_unit = unitWidth(tol, a, b);
  const std::vector<Found> found = isolateUnit(p, tol_unit, true);
  if (found.empty()) return std::nullopt;
  const Found& f = found.front();
  if (f.interval.lo == f.interval.hi || f.interval.kind == RootKind::Unresolved) {
    return mapToT(f.interval.lo, a, b).first;
  }
  // Single: exactly one root in (lo, hi). Refine on the input coefficients (exact, and the unit
  // parameters are exact, so the compensated evaluation certifies signs very close to the root)
  // when their values at lo and hi have certified opposite signs; otherwise on the local
  // coefficients, whose end values are certified by construction.
  const std::vector<double>& c0 = p.coefficients();
  const std::vector<double> zero_r(c0.size(), 0.0);
  const SignClass sl = signClass(evaluateCompensated(c0, zero_r, 0.0, 1.0, f.interval.lo));
  const SignClass sh = signClass(evaluateCompensated(c0, zero_r, 0.0, 1.0, f.interval.hi));
  RootInterval bracket;
  if (isSign(sl) && isSign(sh) && sl != sh) {
    bracket = refineNode(c0, zero_r, 0.0, 1.0, f.interval.lo, f.interval.hi, static_cast<int>(sl), tol_unit);
  } else {
    bracket = refineNode(f.c, f.r, f.interval.lo, f.interval.hi, f.interval.lo, f.interval.hi, sign(f.c.front()),
                         tol_unit);
  }
  return mapToT(bracket.lo, a, b).first;
}

}  // namespace fcl_quadric
