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
  using LD = long double;
  // Work with |y| (reflect back at the end) and scale to the largest radius for conditioning.
  LD ee[N], yy[N];
  LD scale = 0;
  for (int i = 0; i < N; ++i) scale = std::max<LD>(scale, e[i]);
  for (int i = 0; i < N; ++i) {
    ee[i] = e[i] / scale;
    yy[i] = std::fabs(static_cast<LD>(y[i])) / scale;
  }
  LD emin2 = ee[0] * ee[0];
  int imin = 0;
  for (int i = 1; i < N; ++i)
    if (ee[i] * ee[i] < emin2) {
      emin2 = ee[i] * ee[i];
      imin = i;
    }
  LD inside = -1;
  for (int i = 0; i < N; ++i) inside += (yy[i] / ee[i]) * (yy[i] / ee[i]);
  auto g = [&](LD t) {
    LD s = -1;
    for (int i = 0; i < N; ++i) {
      if (yy[i] == 0) continue;  // contributes 0 (and 0/0 at its pole)
      const LD q = ee[i] * yy[i] / (ee[i] * ee[i] + t);
      s += q * q;
    }
    return s;
  };
  LD xs[N];
  bool done = false;
  if (yy[imin] == 0 && inside < 0) {
    // Eberly's degenerate case: the point lies on the principal plane through the two longer axes
    // and inside. Candidate: the root with t in (-emin^2, inf) of the reduced problem; if the
    // reduced solution would place x_imin beyond the surface, the closest point leaves that plane
    // with t = -emin^2.
    LD denom_sum = 0;
    for (int i = 0; i < N; ++i) {
      if (i == imin || yy[i] == 0) continue;
      const LD d = ee[i] * ee[i] - emin2;
      if (d == 0) {  // an axis as short as the shortest with y_i != 0: not this degenerate case
        denom_sum = 2;
        break;
      }
      const LD q = ee[i] * yy[i] / d;
      denom_sum += q * q;
    }
    if (denom_sum < 1) {
      LD s2 = 0;
      for (int i = 0; i < N; ++i) {
        if (i == imin) continue;
        xs[i] = yy[i] == 0 ? 0 : ee[i] * ee[i] * yy[i] / (ee[i] * ee[i] - emin2);
        s2 += (xs[i] / ee[i]) * (xs[i] / ee[i]);
      }
      xs[imin] = ee[imin] * std::sqrt(std::max<LD>(0, 1 - s2));
      done = true;
    }
  }
  if (!done) {
    // Largest root of g on (-emin^2, inf): bracket then safeguarded Newton.
    LD lo = -emin2, hi;
    if (inside > 0) {
      lo = 0;
      hi = 1;
      for (int k = 0; k < 2000 && g(hi) > 0; ++k) hi *= 2;
    } else {
      hi = 0;
    }
    LD t = 0.5L * (lo + hi);
    for (int it = 0; it < tolerance::kMaxPointEllipsoidIterations; ++it) {
      const LD gt = g(t);
      if (gt > 0) lo = t; else hi = t;
      LD dg = 0;
      for (int i = 0; i < N; ++i) {
        if (yy[i] == 0) continue;
        const LD d = ee[i] * ee[i] + t;
        dg += -2 * ee[i] * ee[i] * yy[i] * yy[i] / (d * d * d);
      }
      LD next = (dg < 0) ? t - gt / dg : 0.5L * (lo + hi);
      if (!(next > lo && next < hi)) next = 0.5L * (lo + hi);
      if (next == t || hi - lo <= std::numeric_limits<LD>::epsilon() * (std::fabs(lo) + std::fabs(hi))) {
        t = next;
        break;
      }
      t = next;
    }
    for (int i = 0; i < N; ++i) xs[i] = yy[i] == 0 ? 0 : ee[i] * ee[i] * yy[i] / (ee[i] * ee[i] + t);
  }
  LD d2 = 0;
  for (int i = 0; i < N; ++i) {
    (*x)[i] = static_cast<double>(std::copysign(xs[i] * scale, static_cast<LD>(y[i])));
    d2 += (xs[i] - yy[i]) * (xs[i] - yy[i]);
  }
  const double dist = static_cast<double>(std::sqrt(d2) * scale);
  return inside < 0 ? -dist : dist;
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
    LD lo = poles[0] - 1;
    for (int k = 0; k < 4000 && g(lo) > 0; ++k) lo = poles[0] - 2 * (poles[0] - lo);
    const LD eps0 = std::max<LD>(1e-30L, std::fabs(poles[0]) * 1e-18L);
    if (g(lo) < 0 && g(poles[0] - eps0) > 0) emit(root(lo, poles[0] - eps0));
    // Between consecutive poles: convex, +inf at both ends: minimum, then two roots if it is < 0.
    for (int k = 0; k + 1 < np; ++k) {
      const LD a0 = poles[k], b0 = poles[k + 1];
      if (!(b0 > a0)) continue;
      LD a = a0 + (b0 - a0) * 1e-15L, b = b0 - (b0 - a0) * 1e-15L;
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
    // (last pole, inf): +inf at the pole, -1 at inf.
    const LD last = poles[np - 1];
    const LD epsl = std::max<LD>(1e-30L, std::fabs(last) * 1e-18L);
    LD hi = last + scale;
    for (int k = 0; k < 4000 && g(hi) > 0; ++k) hi = last + 2 * (hi - last);
    if (g(last + epsl) > 0 && g(hi) < 0) emit(root(last + epsl, hi));
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

double closestPointOnEllipse(double e0, double e1, const Eigen::Vector2d& y, Eigen::Vector2d* x) {
  // Power-of-two scale (exact): the largest length into [1, 2).
  const double m = std::max({e0, e1, std::fabs(y[0]), std::fabs(y[1])});
  const double unit = std::ldexp(1.0, -std::ilogb(m));
  // Indices of the major (M) and minor (n) axes; the point folded into the first quadrant.
  const int M = e0 >= e1 ? 0 : 1, n = 1 - M;
  const double eM = unit * (M == 0 ? e0 : e1), en = unit * (M == 0 ? e1 : e0);
  const double aM = unit * std::fabs(y[M]), an = unit * std::fabs(y[n]);
  const double inside = (aM / eM) * (aM / eM) + (an / en) * (an / en);
  double xM, xn;
  if (eM == en) {
    // A circle: the radial projection (any point of it from the centre).
    const double rho = std::max(aM, an) > 1e-150 ? std::sqrt(aM * aM + an * an) : std::hypot(aM, an);
    xM = rho > 0.0 ? eM * (aM / rho) : eM;
    xn = rho > 0.0 ? eM * (an / rho) : 0.0;
  } else {
    const double D = (eM - en) * (eM + en);  // e_M^2 - e_n^2 > 0
    const double cM = eM * aM, cn = en * an;
    if (cn == 0.0) {
      // On the major axis (Eberly's degenerate case): inside the evolute's cusp the nearest point
      // leaves the axis (two mirror images; the one with x_n >= 0), else it is the vertex.
      if (cM < D) {
        xM = eM * cM / D;
        xn = en * std::sqrt(std::max(0.0, 1.0 - (xM / eM) * (xM / eM)));
      } else {
        xM = eM;
        xn = 0.0;
      }
    } else {
      // g(s) and g'(s) from u = c_max / (s + D) and v = c_min / s.
      // (Two independent reciprocals, so that each step has two divisions on its chain, not four.)
      auto eval = [&](double s, double* df) {
        const double p = 1.0 / (s + D), q = 1.0 / s;
        const double u = cM * p, v = cn * q;
        const double u2 = u * u, v2 = v * v;
        *df = -2.0 * (u2 * p + v2 * q);
        return (u2 + v2) - 1.0;
      };
      const double big = std::max(cM, cn);
      double lo = cn, hi = big > 1e-150 ? std::sqrt(cM * cM + cn * cn) : std::hypot(cM, cn);
      // One Newton step from the right end: by convexity it lands at or left of the root.
      double s = hi;
      {
        double df;
        const double f = eval(s, &df);
        const double next = s - f / df;
        s = next > lo && next < hi ? next : lo;
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
        if (!(next > lo && next < hi) || std::fabs(2.0 * f) > std::fabs(step_old * df)) {
          next = hi > 4.0 * lo ? std::sqrt(lo) * std::sqrt(hi) : 0.5 * (lo + hi);
        }
        step = std::fabs(next - s);
        if (next == s || !(hi - lo > 4.0 * std::numeric_limits<double>::epsilon() * hi)) {
          s = next;
          break;
        }
        s = next;
      }
      xM = eM * cM / (s + D);
      xn = en * cn / s;
    }
  }
  (*x)[M] = std::copysign(xM / unit, y[M]);
  (*x)[n] = std::copysign(xn / unit, y[n]);
  const double dM = xM - aM, dn = xn - an;
  const double dist = (std::max(std::fabs(dM), std::fabs(dn)) > 1e-150 ? std::sqrt(dM * dM + dn * dn)
                                                                         : std::hypot(dM, dn)) / unit;
  return inside < 1.0 ? -dist : dist;
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
