#include "fcl_quadric/geometry/point_ellipsoid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "fcl_quadric/tolerances.h"

namespace fcl_quadric {
namespace detail {

template <int N>
double closestPointPrincipal(const Eigen::Matrix<double, N, 1>& e, const Eigen::Matrix<double, N, 1>& y,
                             Eigen::Matrix<double, N, 1>* x) {
  // Power-of-two scale (exact): the longest radius into [1, 2), so that no square below
  // overflows for coordinates up to 1e100 of it, and none that matters underflows. (A point
  // farther away is answered below from its direction.)
  double big = 0.0;
  for (int i = 0; i < N; ++i) big = std::max(big, e[i]);
  const double unit = std::ldexp(1.0, -std::ilogb(big));
  // The point folded into the first orthant; the shortest radius and each axis's offset
  // D_i = e_i^2 - e_min^2 >= 0 of its pole (0 for the shortest axes, which share s = 0), from a
  // product of the difference and the sum (no cancellation).
  double ee[N], a[N], c[N], D[N];
  double emin = std::numeric_limits<double>::infinity(), a_max = 0.0;
  for (int i = 0; i < N; ++i) {
    ee[i] = unit * e[i];
    a[i] = unit * std::fabs(y[i]);
    emin = std::min(emin, ee[i]);
    a_max = std::max(a_max, a[i]);
  }
  double form = 0.0, c_minor2 = 0.0, c_max = 0.0;
  for (int i = 0; i < N; ++i) {
    c[i] = ee[i] * a[i];
    D[i] = (ee[i] - emin) * (ee[i] + emin);
    form += (a[i] / ee[i]) * (a[i] / ee[i]);
    if (D[i] == 0.0) c_minor2 += c[i] * c[i];
    c_max = std::max(c_max, c[i]);
  }
  double xs[N];
  bool done = false;
  bool round = true;  // all radii equal: a circle or a sphere, the radial projection
  for (int i = 0; i < N; ++i) round = round && D[i] == 0.0;
  if (round && a_max <= 1e100) {
    double r2 = 0.0;
    for (int i = 0; i < N; ++i) r2 += a[i] * a[i];
    const double rho = std::sqrt(r2);
    for (int i = 0; i < N; ++i) xs[i] = rho > 0.0 ? emin * (a[i] / rho) : (i == 0 ? emin : 0.0);
    done = true;
  } else if (a_max > 1e100) {
    // Farther than 1e100 radii: the nearest point is the support point along y,
    // x_i = e_i c_i / |c|, to within (e_max / |y|)^2 < 1e-200 of the scale |y|.
    double n2 = 0.0;
    for (int i = 0; i < N; ++i) n2 += (c[i] / c_max) * (c[i] / c_max);
    const double norm = c_max * std::sqrt(n2);
    for (int i = 0; i < N; ++i) xs[i] = ee[i] * (c[i] / norm);
    done = true;
  }
  double lo = std::sqrt(c_minor2);  // g(lo) >= 0: the shortest axes' terms alone reach 1 there
  if (!done && c_minor2 == 0.0) {
    // No coordinate along a shortest axis: no pole at s = 0, where g is
    // sum over the other axes of (c_i / D_i)^2 - 1. If that is < 1 (only inside), the root
    // would be at s < 0, beyond the pole: the nearest point leaves the principal plane
    // (Eberly's degenerate case) with its coordinates x_i = e_i c_i / D_i on the other axes and
    // the rest along the first shortest axis. The centre itself is such a point.
    // (A shortest axis's c_i may be non-zero with its square underflowed: it counts as 0, as its
    // square does; skipped, not divided by its D_i = 0.)
    double reduced = 0.0;
    for (int i = 0; i < N; ++i)
      if (c[i] != 0.0 && D[i] != 0.0) reduced += (c[i] / D[i]) * (c[i] / D[i]);
    if (reduced < 1.0) {
      double s2 = 0.0;
      int first_minor = -1;
      for (int i = 0; i < N; ++i) {
        if (D[i] == 0.0) {
          xs[i] = 0.0;
          if (first_minor < 0) first_minor = i;
        } else {
          xs[i] = c[i] == 0.0 ? 0.0 : ee[i] * c[i] / D[i];
          s2 += (xs[i] / ee[i]) * (xs[i] / ee[i]);
        }
      }
      xs[first_minor] = emin * std::sqrt(std::max(0.0, 1.0 - s2));
      done = true;
    } else {
      lo = 0.0;
    }
  }
  if (!done) {
    // The secular equation in s = t + e_min^2 > 0 (Eberly's t, shifted so that the nearest
    // point's coordinates x_i = e_i c_i / (s + D_i) lose nothing to cancellation next to the
    // pole): g(s) = sum (c_i / (s + D_i))^2 - 1, convex and decreasing. Bracket [lo, hi] with
    // hi = |c| (g(hi) <= 0 since s + D_i >= s). One Newton step from hi lands at or left of the
    // root (convexity); Newton steps from there climb to it. A step that leaves the bracket or
    // does not halve the last one is replaced by a bisection (geometric while hi > 4 lo > 0).
    double hi2 = 0.0;
    for (int i = 0; i < N; ++i) hi2 += (c[i] / c_max) * (c[i] / c_max);
    double hi = c_max * std::sqrt(hi2);
    // g and g' from the reciprocals p_i = 1 / (s + D_i) (independent divisions); a zero c_i
    // contributes nothing (and is skipped: its pole may be s = 0).
    auto eval = [&](double s, double* df) {
      double f = -1.0, d = 0.0;
      for (int i = 0; i < N; ++i) {
        if (c[i] == 0.0) continue;
        const double p = 1.0 / (s + D[i]);
        const double u = c[i] * p, u2 = u * u;
        f += u2;
        d -= 2.0 * u2 * p;
      }
      *df = d;
      return f;
    };
    double s = hi;
    {
      double df;
      const double f = eval(s, &df);
      const double next = s - f / df;
      s = next > lo && next < hi ? next : (lo > 0.0 ? lo : 0.5 * hi);
    }
    double step = hi - lo;
    for (int it = 0; it < tolerance::kMaxPointEllipsoidIterations; ++it) {
      double df;
      const double f = eval(s, &df);
      if (f > 0.0) {
        lo = s;
      } else if (f < 0.0) {
        hi = s;
      } else {
        break;
      }
      // At the root to g's rounding (its terms are at most ~1 there): one last Newton step.
      if (std::fabs(f) <= 8.0 * std::numeric_limits<double>::epsilon()) {
        s -= f / df;
        break;
      }
      double next = s - f / df;
      const double step_old = step;
      if (!(next > lo && next < hi) || std::fabs(2.0 * f) > std::fabs(step_old * df))
        next = lo > 0.0 && hi > 4.0 * lo ? std::sqrt(lo) * std::sqrt(hi) : 0.5 * (lo + hi);
      step = std::fabs(next - s);
      if (next == s || !(hi - lo > 4.0 * std::numeric_limits<double>::epsilon() * hi)) {
        s = next;
        break;
      }
      s = next;
    }
    for (int i = 0; i < N; ++i) xs[i] = c[i] == 0.0 ? 0.0 : ee[i] * c[i] / (s + D[i]);
  }
  double d_max = 0.0;
  for (int i = 0; i < N; ++i) {
    (*x)[i] = std::copysign(xs[i] / unit, y[i]);
    d_max = std::max(d_max, std::fabs(xs[i] - a[i]));
  }
  double d2 = 0.0;
  if (d_max > 0.0)
    for (int i = 0; i < N; ++i) d2 += ((xs[i] - a[i]) / d_max) * ((xs[i] - a[i]) / d_max);
  const double dist = d_max * std::sqrt(d2) / unit;
  return form < 1.0 ? -dist : dist;
}

template <int N>
int criticalPointsPrincipal(const Eigen::Matrix<double, N, 1>& e, const Eigen::Matrix<double, N, 1>& y,
                            Eigen::Matrix<double, N, 1>* out, int max_out) {
  // The critical points are x_i = e_i^2 y_i / (e_i^2 + t) at the roots t of
  // g(t) = sum (c_i / (e_i^2 + t))^2 - 1, c_i = e_i y_i, whose poles are the -e_i^2 with c_i != 0.
  // Each root is solved in its offset s = t + e_r^2 from the pole r it lies next to (the
  // reference), with e_i^2 + t = D_i + s and D_i = (e_i - e_r)(e_i + e_r): a root next to its pole
  // keeps its relative precision, which t itself (or e_i^2 + t formed from it) lost to
  // cancellation: roots were lost, or put off the surface by up to 0.75 in the form (session 46's
  // scratch audit, docs/algorithms.md section 6).
  // Long double: no scaling is needed for radii and coordinates in the accepted ranges.
  using LD = long double;
  LD ee2[N], c2[N], ac[N];  // e_i^2, c_i^2 and |c_i|
  LD c_norm2 = 0;
  for (int i = 0; i < N; ++i) {
    ee2[i] = static_cast<LD>(e[i]) * e[i];
    ac[i] = std::fabs(static_cast<LD>(e[i]) * y[i]);
    c2[i] = ac[i] * ac[i];
    c_norm2 += c2[i];
  }
  const LD c_norm = std::sqrt(c_norm2);
  // e_i^2 - e_r^2 without cancellation, and the offsets of every pole from the reference pole r.
  auto offset = [&](int i, int r) { return (static_cast<LD>(e[i]) - e[r]) * (static_cast<LD>(e[i]) + e[r]); };
  auto offsets = [&](int r, LD D[N]) {
    for (int i = 0; i < N; ++i) D[i] = offset(i, r);
  };
  auto g = [&](const LD D[N], LD s) {
    LD f = -1;
    for (int i = 0; i < N; ++i)  // a zero coordinate contributes nothing (and 0/0 at its pole)
      if (c2[i] != 0) f += c2[i] / ((D[i] + s) * (D[i] + s));
    return f;
  };
  auto dg = [&](const LD D[N], LD s) {
    LD f = 0;
    for (int i = 0; i < N; ++i)
      if (c2[i] != 0) f -= 2 * c2[i] / ((D[i] + s) * (D[i] + s) * (D[i] + s));
    return f;
  };
  int count = 0;
  auto emit = [&](const LD D[N], LD s) {
    if (count >= max_out) return;
    Eigen::Matrix<double, N, 1> x;
    for (int i = 0; i < N; ++i) {
      if (c2[i] == 0) {
        if (D[i] + s == 0) return;  // t = -e_i^2 with y_i = 0: the points of the loop below
        x[i] = 0;
      } else {
        x[i] = static_cast<double>(ee2[i] * y[i] / (D[i] + s));
      }
    }
    out[count++] = x;
  };
  // The root of g on [a, b], where g changes sign (up to rounding at an end, which is then the
  // answer): bisection-safeguarded Newton, at most kMaxPointEllipsoidIterations steps.
  auto root = [&](const LD D[N], LD a, LD b) {
    LD ga = g(D, a);
    const LD gb = g(D, b);
    if (ga == 0 || (ga > 0) == (gb > 0)) return std::fabs(ga) <= std::fabs(gb) ? a : b;
    if (gb == 0) return b;
    LD s = 0.5L * (a + b);
    for (int it = 0; it < tolerance::kMaxPointEllipsoidIterations; ++it) {
      const LD gs = g(D, s);
      if (gs == 0) return s;
      if ((gs > 0) == (ga > 0)) {
        a = s;
        ga = gs;
      } else {
        b = s;
      }
      const LD d = dg(D, s);
      LD next = d != 0 ? s - gs / d : 0.5L * (a + b);
      if (!(next > a && next < b)) next = 0.5L * (a + b);
      if (next == s || b - a <= 4 * std::numeric_limits<LD>::epsilon() * (std::fabs(a) + std::fabs(b))) return next;
      s = next;
    }
    return s;
  };
  // The axes with c_i != 0 by decreasing e_i: their poles -e_i^2 in increasing order.
  int axis[N];
  int np = 0;
  for (int i = 0; i < N; ++i)
    if (c2[i] > 0) axis[np++] = i;
  for (int i = 1; i < np; ++i)  // insertion sort of <= 3 values
    for (int j = i; j > 0 && e[axis[j]] > e[axis[j - 1]]; --j) std::swap(axis[j], axis[j - 1]);
  if (np > 0) {
    // Brackets from g's terms alone: the term of the reference pole is >= 1 within |c_r| of it,
    // so g >= 0 there; beyond |c| of the outermost poles every term is < 1 in sum, so g < 0.
    LD D[N];
    // (-inf, first pole): g rises from -1 to +inf; s in [-|c|, -|c_r|] (every D_i <= 0 there).
    const int first = axis[0];
    offsets(first, D);
    emit(D, root(D, -c_norm, -ac[first]));
    // Between consecutive poles k and j, W apart: convex, +inf at both ends; its minimum, then two
    // roots if that is < 0. None if |c_k| + |c_j| >= W (one of the two terms is >= 1 everywhere).
    // The half next to pole k is solved in k's frame, s in (0, W/2], the other in j's,
    // s in [-W/2, 0): a root or minimum next to either pole keeps its relative precision (one
    // frame for the whole interval lost the far pole's neighbourhood to rounding, and a bracket
    // end there fell on the pole itself).
    for (int k = 0; k + 1 < np; ++k) {
      const int ik = axis[k], ij = axis[k + 1];
      const LD W = offset(ik, ij);
      if (!(W > ac[ik] + ac[ij])) continue;
      const LD half = 0.5L * W;  // the midpoint, in k's frame (-half in j's)
      LD Dk[N], Dj[N];
      offsets(ik, Dk);
      offsets(ij, Dj);
      // Which half holds the minimum (dg increasing), then the minimum by bisection on dg within it.
      // It has g >= 0 when it is within |c| of the half's pole: no roots then.
      const bool in_k = !(dg(Dk, half) < 0);
      const LD* Dm = in_k ? Dk : Dj;
      LD lo = in_k ? ac[ik] : -half, hi = in_k ? half : -ac[ij];
      if (!(lo < hi)) continue;
      for (int it = 0; it < tolerance::kMaxPointEllipsoidIterations; ++it) {
        const LD m = 0.5L * (lo + hi);
        if (!(m > lo && m < hi)) break;
        (dg(Dm, m) < 0 ? lo : hi) = m;
      }
      const LD sm = 0.5L * (lo + hi);
      if (!(g(Dm, sm) < 0)) continue;
      // The root on the minimum's side of the midpoint shares its frame; the other lies in the
      // minimum's half too if g at the midpoint is > 0, else in the other half.
      const bool mid_positive = g(Dk, half) > 0;
      if (in_k) {
        emit(Dk, root(Dk, ac[ik], sm));
        if (mid_positive)
          emit(Dk, root(Dk, sm, half));
        else
          emit(Dj, root(Dj, -half, std::max(-half, -ac[ij])));
      } else {
        if (mid_positive)
          emit(Dj, root(Dj, -half, sm));
        else
          emit(Dk, root(Dk, std::min(ac[ik], half), half));
        emit(Dj, root(Dj, sm, -ac[ij]));
      }
    }
    // (last pole, inf): +inf at the pole, -1 at inf; s in [|c_r|, |c|]. When that pole is
    // -e_min^2 (a coordinate along a shortest axis), the root is the closest point:
    // closestPointPrincipal's (in double, ~4e-16 of the scale against a 50-digit oracle).
    const int last = axis[np - 1];
    double emin = e[0];
    for (int i = 1; i < N; ++i) emin = std::min(emin, e[i]);
    if (e[last] == emin) {
      if (count < max_out) closestPointPrincipal<N>(e, y, &out[count++]);
    } else {
      offsets(last, D);
      emit(D, root(D, ac[last], c_norm));
    }
  }
  // Points with t = -e_i^2 where y_i = 0: x_k = e_k^2 y_k / (e_k^2 - e_i^2) for k != i, and x_i
  // from the surface equation (two points, if real).
  for (int i = 0; i < N; ++i) {
    if (c2[i] != 0) continue;
    Eigen::Matrix<double, N, 1> x;
    LD s = 0;
    bool ok = true;
    for (int k = 0; k < N; ++k) {
      if (k == i) continue;
      const LD d = offset(k, i);
      if (d == 0 || c2[k] == 0) {
        if (c2[k] != 0) ok = false;
        x[k] = 0;
        continue;
      }
      const LD xk = ee2[k] * y[k] / d;
      x[k] = static_cast<double>(xk);
      s += xk * xk / ee2[k];
    }
    if (!ok || s > 1) continue;
    const LD xi = std::sqrt(ee2[i] * (1 - s));
    for (int sign : {1, -1}) {
      if (count >= max_out) break;
      x[i] = static_cast<double>(sign * xi);
      out[count++] = x;
    }
  }
  return count;
}

template int criticalPointsPrincipal<2>(const Eigen::Vector2d&, const Eigen::Vector2d&, Eigen::Vector2d*, int);
template int criticalPointsPrincipal<3>(const Eigen::Vector3d&, const Eigen::Vector3d&, Eigen::Vector3d*, int);

template double closestPointPrincipal<2>(const Eigen::Vector2d&, const Eigen::Vector2d&, Eigen::Vector2d*);
template double closestPointPrincipal<3>(const Eigen::Vector3d&, const Eigen::Vector3d&, Eigen::Vector3d*);

}  // namespace detail

PointEllipsoidResult closestPointOnEllipsoid(const Ellipsoid& e, const Eigen::Vector3d& q) {
  if (!q.allFinite()) {
    std::ostringstream os;
    os << "closestPointOnEllipsoid: point must be finite, got [" << q.transpose() << "]";
    throw std::invalid_argument(os.str());
  }
  const Eigen::Vector3d y = e.rotation().transpose() * (q - e.center());
  Eigen::Vector3d x;
  PointEllipsoidResult r;
  r.signed_distance = detail::closestPointPrincipal<3>(e.radii(), y, &x);
  r.closest = e.center() + e.rotation() * x;
  return r;
}

}  // namespace fcl_quadric
