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
  using LD = long double;
  LD ee2[N], c2[N];  // e_i^2 and (e_i y_i)^2
  for (int i = 0; i < N; ++i) {
    ee2[i] = static_cast<LD>(e[i]) * e[i];
    c2[i] = ee2[i] * static_cast<LD>(y[i]) * y[i];
  }
  auto g = [&](LD t) {
    LD s = -1;
    for (int i = 0; i < N; ++i)  // a zero coordinate contributes nothing (and 0/0 at its pole)
      if (c2[i] != 0) s += c2[i] / ((ee2[i] + t) * (ee2[i] + t));
    return s;
  };
  auto dg = [&](LD t) {
    LD s = 0;
    for (int i = 0; i < N; ++i)
      if (c2[i] != 0) s -= 2 * c2[i] / ((ee2[i] + t) * (ee2[i] + t) * (ee2[i] + t));
    return s;
  };
  int count = 0;
  auto emit = [&](LD t) {
    if (count >= max_out) return;
    Eigen::Matrix<double, N, 1> x;
    for (int i = 0; i < N; ++i) {
      if (c2[i] == 0) {
        if (ee2[i] + t == 0) return;  // t = -e_i^2 with y_i = 0: the points of the loop below
        x[i] = 0;
      } else {
        x[i] = static_cast<double>(ee2[i] * y[i] / (ee2[i] + t));
      }
    }
    out[count++] = x;
  };
  // Root of g on (a, b) where g changes sign: bisection-safeguarded Newton.
  auto root = [&](LD a, LD b) {
    LD ga = g(a);
    LD t = 0.5L * (a + b);
    for (int it = 0; it < tolerance::kMaxPointEllipsoidIterations; ++it) {
      const LD gt = g(t);
      if ((gt > 0) == (ga > 0)) {
        a = t;
        ga = gt;
      } else {
        b = t;
      }
      const LD d = dg(t);
      LD next = d != 0 ? t - gt / d : 0.5L * (a + b);
      if (!(next > a && next < b)) next = 0.5L * (a + b);
      if (next == t || b - a <= 4 * std::numeric_limits<LD>::epsilon() * (std::fabs(a) + std::fabs(b))) return next;
      t = next;
    }
    return t;
  };
  // Poles in increasing order of -e_i^2 (i.e. decreasing e_i^2), only where y_i != 0.
  LD poles[N];
  int np = 0;
  for (int i = 0; i < N; ++i)
    if (c2[i] > 0) poles[np++] = -ee2[i];
  for (int i = 1; i < np; ++i)  // insertion sort of <= 3 values
    for (int j = i; j > 0 && poles[j] < poles[j - 1]; --j) std::swap(poles[j], poles[j - 1]);
  LD scale = 1;
  for (int i = 0; i < N; ++i) scale = std::max(scale, ee2[i] + static_cast<LD>(std::sqrt(c2[i])));
  if (np == 0) {
    // y = 0: every critical point has t = -e_i^2 (handled below).
  } else {
    // (-inf, first pole): g -> -1 at -inf, +inf at the pole.
    // (A step of at least 1e-15 of the pole: a plain 1 is absorbed by poles beyond ~1e19, e > 4e9,
    // and g there divided by zero; found by a session 45 scratch audit of extreme sizes.)
    LD lo = poles[0] - std::max<LD>(1, std::fabs(poles[0]) * 1e-15L);
    for (int k = 0; k < 4000 && g(lo) > 0; ++k) lo = poles[0] - 2 * (poles[0] - lo);
    const LD eps0 = std::max<LD>(1e-30L, std::fabs(poles[0]) * 1e-18L);
    if (g(lo) < 0 && g(poles[0] - eps0) > 0) emit(root(lo, poles[0] - eps0));
    // Between consecutive poles: convex, +inf at both ends: minimum, then two roots if it is < 0.
    for (int k = 0; k + 1 < np; ++k) {
      const LD a0 = poles[k], b0 = poles[k + 1];
      if (!(b0 > a0)) continue;
      // Off each pole by 1e-15 of the interval, and at least 1e-18 of the pole: at poles beyond
      // ~1e100 a narrower interval's step was absorbed (a == a0) and g divided by zero (session 45).
      const LD guard = std::max<LD>((b0 - a0) * 1e-15L, std::fabs(a0) * 1e-18L);
      if (!(b0 - a0 > 4 * guard)) continue;
      LD a = a0 + guard, b = b0 - guard;
      // minimise by bisection on dg (increasing on the interval)
      LD lo2 = a, hi2 = b;
      for (int it = 0; it < 200; ++it) {
        const LD m = 0.5L * (lo2 + hi2);
        if (dg(m) < 0) lo2 = m; else hi2 = m;
      }
      const LD tm = 0.5L * (lo2 + hi2);
      if (g(tm) < 0) {
        if (g(a) > 0) emit(root(a, tm));
        if (g(b) > 0) emit(root(tm, b));
      }
    }
    // (last pole, inf): +inf at the pole, -1 at inf. When that pole is -e_min^2 (a coordinate along
    // a shortest axis), the root is the closest point: closestPointPrincipal's, which solves in the
    // shifted unknown. The search below on t misses a root within 1e-18 of the pole, which a tiny
    // coordinate along the shortest axis puts there: the closest point was then missing from the
    // list, up to 0.4 of the scale nearer than the best point listed (session 45, a scratch audit
    // of 20,000 interior points near a principal plane).
    const LD last = poles[np - 1];
    double emin = e[0];
    for (int i = 1; i < N; ++i) emin = std::min(emin, e[i]);
    bool minor_pole = false;
    for (int i = 0; i < N; ++i) minor_pole = minor_pole || (e[i] == emin && c2[i] != 0);
    if (minor_pole) {
      if (count < max_out) closestPointPrincipal<N>(e, y, &out[count++]);
    } else {
      const LD epsl = std::max<LD>(1e-30L, std::fabs(last) * 1e-18L);
      LD hi = last + scale;
      for (int k = 0; k < 4000 && g(hi) > 0; ++k) hi = last + 2 * (hi - last);
      if (g(last + epsl) > 0 && g(hi) < 0) emit(root(last + epsl, hi));
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
      const LD d = ee2[k] - ee2[i];
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
