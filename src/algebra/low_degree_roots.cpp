#include "fcl_quadric/algebra/low_degree_roots.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "input_checks.h"

namespace fcl_quadric {

namespace {

using Complex = std::complex<double>;

// Roots of the monic y^2 + b1 y + b0 (stable formula: no cancellation between -b1 and the
// square root of the discriminant).
void monicQuadraticRoots(double b1, double b0, std::vector<Complex>* out) {
  const double disc = b1 * b1 - 4.0 * b0;
  if (disc >= 0.0) {
    const double q = -0.5 * (b1 + std::copysign(std::sqrt(disc), b1));
    if (q == 0.0) {  // b1 = b0 = 0
      out->emplace_back(0.0, 0.0);
      out->emplace_back(0.0, 0.0);
    } else {
      out->emplace_back(q, 0.0);
      out->emplace_back(b0 / q, 0.0);
    }
  } else {
    const double re = -0.5 * b1, im = 0.5 * std::sqrt(-disc);
    out->emplace_back(re, im);
    out->emplace_back(re, -im);
  }
}

// Newton steps on the monic cubic with coefficients b from each root of z, each step kept only
// if it lowers |p|; real roots stay real, a pair stays conjugate. Returns the largest residual
// |p(z)| / sum |b_i| |z|^i.
double polishOnCubic(const double b[3], std::vector<Complex>* z) {
  const auto pc = [b](Complex t) { return ((t + b[2]) * t + b[1]) * t + b[0]; };
  const auto dpc = [b](Complex t) { return (3.0 * t + 2.0 * b[2]) * t + b[1]; };
  const bool pair = (*z)[0].imag() != 0.0;
  for (std::size_t i = 0; i < (pair ? 1u : 2u); ++i) {
    Complex t = (*z)[i];
    double residual = std::abs(pc(t));
    for (int step = 0; step < kCubicNewtonSteps && residual > 0.0; ++step) {
      const Complex slope = dpc(t);
      if (slope == Complex(0.0, 0.0)) break;
      Complex next = t - pc(t) / slope;
      if (!pair) next.imag(0.0);
      if (!std::isfinite(next.real()) || !std::isfinite(next.imag())) break;
      const double next_residual = std::abs(pc(next));
      if (!(next_residual < residual)) break;
      t = next;
      residual = next_residual;
    }
    (*z)[i] = t;
  }
  if (pair) (*z)[1] = std::conj((*z)[0]);
  double worst = 0.0;
  for (const Complex& t : *z) {
    const double a = std::abs(t);
    const double mag = ((a + std::fabs(b[2])) * a + std::fabs(b[1])) * a + std::fabs(b[0]);
    if (mag > 0.0) worst = std::max(worst, std::abs(pc(t)) / mag);
  }
  return worst;
}

}  // namespace

std::vector<Complex> lowDegreeRoots(std::vector<double> c) {
  detail::checkCoefficients("lowDegreeRoots", c, false);
  while (!c.empty() && c.back() == 0.0) c.pop_back();
  const int d = static_cast<int>(c.size()) - 1;
  std::vector<Complex> out;
  if (d <= 0) return out;
  if (d > 3) {
    std::ostringstream os;
    os << "lowDegreeRoots: degree " << d << " above 3";
    throw std::invalid_argument(os.str());
  }
  // Fujiwara's bound from exponents only (no ratio of coefficients can overflow): every root
  // has |x| <= 2 max_i |c_i / c_d|^(1/(d-i)) < 2^(kf + 1).
  int kf = 0;
  bool any = false;
  for (int i = 0; i < d; ++i) {
    if (c[i] == 0.0) continue;
    const int e = std::ilogb(c[i]) - std::ilogb(c[d]) + 1;  // |c_i / c_d| < 2^e
    const int ki = e >= 0 ? (e + (d - i) - 1) / (d - i) : -((-e) / (d - i));  // ceil(e / (d - i))
    kf = any ? std::max(kf, ki) : ki;
    any = true;
  }
  // Work with x = 2^k y. No scaling (k = 0) while the monic coefficients and p on the bound stay
  // far from overflow (|kf| <= kLowDegreeNoScaleExponent): scaling would push the constant term
  // of a polynomial with widely spread roots into underflow. Beyond it, k = kf: the roots in y
  // are below 2 and the coefficients below 2^(d-i).
  const int k = std::abs(kf) <= kLowDegreeNoScaleExponent ? 0 : kf;
  double b[3] = {0.0, 0.0, 0.0};  // monic coefficients in y
  for (int i = 0; i < d; ++i) b[i] = std::ldexp(c[i], -(d - i) * k) / c[d];

  std::vector<Complex> y;
  if (d == 1) {
    y.emplace_back(-b[0], 0.0);
  } else if (d == 2) {
    monicQuadraticRoots(b[1], b[0], &y);
  } else {
    const auto p = [&b](double t) { return ((t + b[2]) * t + b[1]) * t + b[0]; };
    // A real root: p(-B) < 0 < p(B) on the bound B = 2^(kf - k + 1), bisected to adjacent doubles.
    const double bound = std::ldexp(1.0, kf - k + 1);
    double lo = -bound, hi = bound, r = 0.0;
    bool exact = false;
    for (int step = 0; step < kCubicBisectionSteps; ++step) {
      const double mid = 0.5 * (lo + hi);
      if (mid <= lo || mid >= hi) break;  // adjacent doubles
      const double v = p(mid);
      if (v == 0.0) {
        r = mid;
        exact = true;
        break;
      }
      (v < 0.0 ? lo : hi) = mid;
    }
    if (!exact) r = std::fabs(p(lo)) <= std::fabs(p(hi)) ? lo : hi;
    y.emplace_back(r, 0.0);
    // Deflate y^3 + b2 y^2 + b1 y + b0 = (y - r)(y^2 + e1 y + e0): forward (from the leading
    // coefficient) is stable when r is the smallest root, backward (from the constant term) when
    // it is the largest (Wilkinson). Both are tried; the pair of roots with the smaller residual
    // on the cubic, after polishing, is kept.
    std::vector<Complex> forward, backward;
    const double e1f = b[2] + r;
    monicQuadraticRoots(e1f, b[1] + r * e1f, &forward);
    double best = polishOnCubic(b, &forward);
    if (r != 0.0) {
      const double e0b = -b[0] / r;
      monicQuadraticRoots((e0b - b[1]) / r, e0b, &backward);
      if (polishOnCubic(b, &backward) < best) forward = backward;
    }
    y.push_back(forward[0]);
    y.push_back(forward[1]);
  }
  for (const Complex& t : y) out.emplace_back(std::ldexp(t.real(), k), std::ldexp(t.imag(), k));
  return out;
}

}  // namespace fcl_quadric
