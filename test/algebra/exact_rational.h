#pragma once
// Exact rational oracle for the algebra tests: polynomial arithmetic, basis conversions and a
// Sturm sequence in GMP rationals (mpq_class). Written independently of the library: the
// conversions follow the textbook definitions (expansion of the Bernstein basis functions,
// blossoming) rather than the library's formulas. Doubles convert to mpq_class exactly.
#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <vector>

#include <gmpxx.h>

namespace fcl_quadric {
namespace algebra_test {

using Q = mpq_class;
using QPoly = std::vector<Q>;  // low -> high

inline QPoly toQ(const std::vector<double>& c) {
  QPoly r;
  r.reserve(c.size());
  for (double v : c) r.emplace_back(v);
  return r;
}

inline void trim(QPoly* p) {
  while (p->size() > 1 && p->back() == 0) p->pop_back();
  if (p->empty()) p->emplace_back(0);
}

inline bool isZero(const QPoly& p) {
  for (const Q& v : p) {
    if (v != 0) return false;
  }
  return true;
}

inline QPoly add(const QPoly& a, const QPoly& b) {
  QPoly r(std::max(a.size(), b.size()), Q(0));
  for (std::size_t i = 0; i < a.size(); ++i) r[i] += a[i];
  for (std::size_t i = 0; i < b.size(); ++i) r[i] += b[i];
  return r;
}

inline QPoly sub(const QPoly& a, const QPoly& b) {
  QPoly r(std::max(a.size(), b.size()), Q(0));
  for (std::size_t i = 0; i < a.size(); ++i) r[i] += a[i];
  for (std::size_t i = 0; i < b.size(); ++i) r[i] -= b[i];
  return r;
}

inline QPoly mul(const QPoly& a, const QPoly& b) {
  QPoly r(a.size() + b.size() - 1, Q(0));
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (std::size_t j = 0; j < b.size(); ++j) r[i + j] += a[i] * b[j];
  }
  return r;
}

inline QPoly scale(const QPoly& a, const Q& s) {
  QPoly r(a);
  for (Q& v : r) v *= s;
  return r;
}

inline QPoly power(const QPoly& a, int k) {
  QPoly r{Q(1)};
  for (int i = 0; i < k; ++i) r = mul(r, a);
  return r;
}

inline Q eval(const QPoly& p, const Q& x) {
  Q y = p.back();
  for (std::size_t i = p.size() - 1; i-- > 0;) y = y * x + p[i];
  return y;
}

inline QPoly derivative(const QPoly& p) {
  if (p.size() == 1) return QPoly{Q(0)};
  QPoly d(p.size() - 1);
  for (std::size_t i = 1; i < p.size(); ++i) d[i - 1] = p[i] * static_cast<long>(i);
  return d;
}

/// Remainder of exact Euclidean division (b nonzero).
inline QPoly rem(QPoly a, QPoly b) {
  trim(&a);
  trim(&b);
  if (isZero(b)) throw std::invalid_argument("rem: zero divisor");
  while (!isZero(a) && a.size() >= b.size()) {
    const std::size_t k = a.size() - b.size();
    const Q f = a.back() / b.back();
    for (std::size_t j = 0; j < b.size(); ++j) a[j + k] -= f * b[j];
    a.pop_back();  // exactly zero now
    trim(&a);
  }
  return a;
}

/// leading * prod (x - r_k).
inline QPoly fromRoots(const std::vector<Q>& roots, const Q& leading = Q(1)) {
  QPoly p{leading};
  for (const Q& r : roots) p = mul(p, QPoly{-r, Q(1)});
  return p;
}

inline Q binom(int n, int k) {
  if (k < 0 || k > n) return Q(0);
  mpz_class r;
  mpz_bin_uiui(r.get_mpz_t(), static_cast<unsigned long>(n), static_cast<unsigned long>(k));
  return Q(r);
}

/// Power form in t of sum_i c_i C(n,i) (t-a)^i (b-t)^(n-i) / (b-a)^n (expanding each basis
/// function exactly).
inline QPoly bernsteinToPower(const std::vector<Q>& c, const Q& a, const Q& b) {
  const int n = static_cast<int>(c.size()) - 1;
  const QPoly t_minus_a{-a, Q(1)};
  const QPoly b_minus_t{b, Q(-1)};
  const Q inv = Q(1) / (b - a);
  Q inv_n = 1;
  for (int i = 0; i < n; ++i) inv_n *= inv;
  QPoly r{Q(0)};
  for (int i = 0; i <= n; ++i) {
    const QPoly basis = mul(power(t_minus_a, i), power(b_minus_t, n - i));
    r = add(r, scale(basis, c[static_cast<std::size_t>(i)] * binom(n, i) * inv_n));
  }
  return r;
}

inline QPoly bernsteinToPower(const std::vector<double>& c, double a, double b) {
  return bernsteinToPower(toQ(c), Q(a), Q(b));
}

/// Bernstein coefficients of degree n >= deg p on [a,b] by blossoming: c_i is the blossom of p
/// at (a^(n-i), b^i); the blossom of t^k in n arguments is e_k(args) / C(n,k).
inline std::vector<Q> powerToBernstein(const QPoly& p, int n, const Q& a, const Q& b) {
  std::vector<Q> c(static_cast<std::size_t>(n) + 1, Q(0));
  for (int i = 0; i <= n; ++i) {
    Q sum = 0;
    for (int k = 0; k < static_cast<int>(p.size()); ++k) {
      if (p[static_cast<std::size_t>(k)] == 0) continue;
      // e_k of (a repeated n-i times, b repeated i times)
      Q e = 0;
      for (int j = 0; j <= std::min(i, k); ++j) {
        if (k - j > n - i) continue;
        Q term = binom(i, j) * binom(n - i, k - j);
        for (int q = 0; q < j; ++q) term *= b;
        for (int q = 0; q < k - j; ++q) term *= a;
        e += term;
      }
      sum += p[static_cast<std::size_t>(k)] * e / binom(n, k);
    }
    c[static_cast<std::size_t>(i)] = sum;
  }
  return c;
}

inline int signOf(const Q& v) {
  const int s = mpq_sgn(v.get_mpq_t());
  return (s > 0) - (s < 0);
}

/// Exact Sturm sequence p, p', -rem, ... (no thresholds). Counts use right limits V(x+), so
/// count(a, b) is the number of distinct roots in (a, b] even at multiple roots.
class ExactSturm {
 public:
  explicit ExactSturm(QPoly p) {
    trim(&p);
    if (isZero(p)) throw std::invalid_argument("ExactSturm: zero polynomial");
    seq_.push_back(p);
    if (p.size() == 1) return;
    QPoly d = derivative(p);
    trim(&d);
    seq_.push_back(d);
    for (;;) {
      QPoly r = rem(seq_[seq_.size() - 2], seq_.back());
      if (isZero(r)) break;
      seq_.push_back(scale(r, Q(-1)));
    }
  }
  int variationsAt(const Q& x) const {
    std::vector<int> s;
    for (const QPoly& p : seq_) {
      // Sign just to the right of x: first nonzero derivative (needed at multiple roots, where
      // every member vanishes).
      QPoly d = p;
      int sd = signOf(eval(d, x));
      while (sd == 0 && d.size() > 1) {
        d = derivative(d);
        sd = signOf(eval(d, x));
      }
      s.push_back(sd);
    }
    return changes(s);
  }
  int variationsAtInfinity(bool positive) const {
    std::vector<int> s;
    for (const QPoly& p : seq_) {
      const int lead = signOf(p.back());
      s.push_back(positive || (p.size() - 1) % 2 == 0 ? lead : -lead);
    }
    return changes(s);
  }
  /// Distinct roots in (a, b].
  int count(const Q& a, const Q& b) const { return variationsAt(a) - variationsAt(b); }
  /// Distinct roots in the open interval (a, b).
  int countOpen(const Q& a, const Q& b) const { return count(a, b) - (eval(seq_[0], b) == 0 ? 1 : 0); }
  /// Distinct roots in the closed interval [a, b].
  int countClosed(const Q& a, const Q& b) const { return count(a, b) + (eval(seq_[0], a) == 0 ? 1 : 0); }
  int countAll() const { return variationsAtInfinity(false) - variationsAtInfinity(true); }

 private:
  static int changes(const std::vector<int>& s) {
    int c = 0;
    int last = 0;
    for (int v : s) {
      if (v == 0) continue;
      if (last != 0 && v != last) ++c;
      last = v;
    }
    return c;
  }
  std::vector<QPoly> seq_;
};

}  // namespace algebra_test
}  // namespace fcl_quadric
