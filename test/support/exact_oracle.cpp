#include "support/exact_oracle.h"

#include <stdexcept>

namespace fcl_quadric {
namespace test {
namespace {

using RMat4 = std::array<std::array<Rational, 4>, 4>;

Rational rat(double x) { return Rational(x); }  // exact: every double is a dyadic rational

/// P * (N^T J N), the primal matrix scaled by P = (r1 r2 r3)^2 > 0 so that every entry is a
/// dyadic rational (sum of products of doubles): N = [S^-1 R^T, -S^-1 R^T p; 0 1]. Scaling a
/// quadric matrix by a positive constant changes neither its solid nor the signs of the roots of
/// the characteristic polynomial (it rescales lambda by a positive factor).
RMat4 scaledPrimal(const Ellipsoid& e) {
  Rational r2[3];
  for (int i = 0; i < 3; ++i) r2[i] = rat(e.radii()[i]) * rat(e.radii()[i]);
  const Rational P = r2[0] * r2[1] * r2[2];
  // rows n_i = [R^T row i, -(R^T p)_i]
  Rational n[3][4];
  for (int i = 0; i < 3; ++i) {
    Rational rp = 0;
    for (int j = 0; j < 3; ++j) {
      n[i][j] = rat(e.rotation()(j, i));
      rp += n[i][j] * rat(e.center()[j]);
    }
    n[i][3] = -rp;
  }
  const Rational w[3] = {r2[1] * r2[2], r2[0] * r2[2], r2[0] * r2[1]};  // P / r_i^2
  RMat4 A{};
  for (int r = 0; r < 4; ++r)
    for (int c = r; c < 4; ++c) {
      Rational s = 0;
      for (int i = 0; i < 3; ++i) s += w[i] * n[i][r] * n[i][c];
      if (r == 3 && c == 3) s -= P;
      A[r][c] = s;
      A[c][r] = s;
    }
  return A;
}

/// Integer matrices 2^k A, 2^k B (common k): determinants then need no gcd computations.
mpz_class toIntegers(const RMat4& A, const RMat4& B, std::array<std::array<mpz_class, 4>, 4>* Ai,
                     std::array<std::array<mpz_class, 4>, 4>* Bi) {
  mpz_class den = 1;
  for (const RMat4* M : {&A, &B})
    for (const auto& row : *M)
      for (const auto& x : row)
        if (x.get_den() > den) den = x.get_den();  // all denominators are powers of two
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) {
      (*Ai)[r][c] = A[r][c].get_num() * (den / A[r][c].get_den());
      (*Bi)[r][c] = B[r][c].get_num() * (den / B[r][c].get_den());
    }
  return den;
}

using ZMat4 = std::array<std::array<mpz_class, 4>, 4>;

/// Determinant by expansion over 2x2 minors (exact).
mpz_class det4(const ZMat4& m) {
  mpz_class s0 = m[0][0] * m[1][1] - m[1][0] * m[0][1];
  mpz_class s1 = m[0][0] * m[1][2] - m[1][0] * m[0][2];
  mpz_class s2 = m[0][0] * m[1][3] - m[1][0] * m[0][3];
  mpz_class s3 = m[0][1] * m[1][2] - m[1][1] * m[0][2];
  mpz_class s4 = m[0][1] * m[1][3] - m[1][1] * m[0][3];
  mpz_class s5 = m[0][2] * m[1][3] - m[1][2] * m[0][3];
  mpz_class c5 = m[2][2] * m[3][3] - m[3][2] * m[2][3];
  mpz_class c4 = m[2][1] * m[3][3] - m[3][1] * m[2][3];
  mpz_class c3 = m[2][1] * m[3][2] - m[3][1] * m[2][2];
  mpz_class c2 = m[2][0] * m[3][3] - m[3][0] * m[2][3];
  mpz_class c1 = m[2][0] * m[3][2] - m[3][0] * m[2][2];
  mpz_class c0 = m[2][0] * m[3][1] - m[3][0] * m[2][1];
  return s0 * c5 - s1 * c4 + s2 * c3 + s3 * c2 - s4 * c1 + s5 * c0;
}

Rational evaluate(const RationalPolynomial& p, const Rational& x) {
  Rational r = 0;
  for (size_t i = p.size(); i-- > 0;) r = r * x + p[i];
  return r;
}

int variations(const std::vector<int>& signs) {
  int v = 0, last = 0;
  for (int s : signs) {
    if (s == 0) continue;
    if (last != 0 && s != last) ++v;
    last = s;
  }
  return v;
}

}  // namespace

std::array<Rational, 5> exactCharacteristicPolynomialUnscaled(const Ellipsoid& a, const Ellipsoid& b) {
  // Undo the positive scalings: integer matrices are den * P * A, so
  // det(lambda den P_a A - den P_b B) = den^4 P_b^4 f(lambda P_a / P_b).
  ZMat4 A, B;
  const mpz_class den = toIntegers(scaledPrimal(a), scaledPrimal(b), &A, &B);
  auto P = [](const Ellipsoid& e) {
    Rational r = 1;
    for (int i = 0; i < 3; ++i) r *= rat(e.radii()[i]) * rat(e.radii()[i]);
    return r;
  };
  const Rational Pa = P(a), Pb = P(b);
  std::array<Rational, 5> c = exactCharacteristicPolynomial(a, b);
  Rational den4 = Rational(den) * Rational(den);
  den4 *= den4;
  for (int k = 0; k < 5; ++k) {
    Rational f = den4;
    for (int i = 0; i < 4 - k; ++i) f *= Pb;
    for (int i = 0; i < k; ++i) f *= Pa;
    c[k] /= f;
  }
  return c;
}

std::array<Rational, 5> exactCharacteristicPolynomial(const Ellipsoid& a, const Ellipsoid& b) {
  ZMat4 A, B;
  toIntegers(scaledPrimal(a), scaledPrimal(b), &A, &B);
  // Exact values at lambda = 0..4, then Newton divided differences -> power basis.
  std::array<Rational, 5> y;
  for (int k = 0; k < 5; ++k) {
    ZMat4 m;
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) m[r][c] = k * A[r][c] - B[r][c];
    y[k] = Rational(det4(m));
  }
  // Divided differences on nodes 0..4.
  std::array<Rational, 5> dd = y;
  for (int j = 1; j < 5; ++j)
    for (int i = 4; i >= j; --i) dd[i] = (dd[i] - dd[i - 1]) / Rational(j);
  // Newton form -> power form: p = dd0 + dd1 x + dd2 x(x-1) + ...
  std::array<Rational, 5> coef{};
  std::vector<Rational> basis{Rational(1)};  // prod_{m<i} (x - m)
  for (int i = 0; i < 5; ++i) {
    for (size_t k = 0; k < basis.size(); ++k) coef[k] += dd[i] * basis[k];
    std::vector<Rational> next(basis.size() + 1, Rational(0));
    for (size_t k = 0; k < basis.size(); ++k) {
      next[k + 1] += basis[k];
      next[k] -= basis[k] * i;
    }
    basis = next;
  }
  return coef;
}

namespace {

using IntPolynomial = std::vector<mpz_class>;  // low -> high

void trimZ(IntPolynomial& p) {
  while (!p.empty() && p.back() == 0) p.pop_back();
}

/// Divide out the content (gcd of the coefficients), keeping the signs.
void primitive(IntPolynomial& p) {
  mpz_class g = 0;
  for (const auto& c : p) g = gcd(g, c);
  if (g > 1)
    for (auto& c : p) c /= g;
}

/// Pseudo-remainder lc(b)^k a mod b, exact in integers; *k receives the power used.
IntPolynomial pseudoRemainder(IntPolynomial a, const IntPolynomial& b, int* k) {
  const mpz_class& lb = b.back();
  *k = 0;
  while (a.size() >= b.size() && !a.empty()) {
    ++*k;
    const mpz_class la = a.back();
    const size_t shift = a.size() - b.size();
    for (auto& c : a) c *= lb;
    for (size_t i = 0; i < b.size(); ++i) a[shift + i] -= la * b[i];
    a.pop_back();
    trimZ(a);
  }
  return a;
}

}  // namespace

int exactDistinctRootsBelow(const RationalPolynomial& p_in, const Rational& hi) {
  // Integer coefficients: multiply by the lcm of the denominators.
  mpz_class den = 1;
  for (const auto& c : p_in) den = lcm(den, c.get_den());
  IntPolynomial p;
  for (const auto& c : p_in) p.push_back(c.get_num() * (den / c.get_den()));
  trimZ(p);
  if (p.size() <= 1) throw std::invalid_argument("exactDistinctRootsBelow: constant polynomial");
  primitive(p);
  IntPolynomial dp;
  for (size_t i = 1; i < p.size(); ++i) dp.push_back(p[i] * static_cast<long>(i));
  primitive(dp);
  // Sturm sequence up to positive factors: s_{k+1} = -c * prem(s_{k-1}, s_k) with c > 0 chosen so
  // that the multiplier lc(s_k)^e of the pseudo-remainder does not flip the sign.
  std::vector<IntPolynomial> seq{p, dp};
  while (true) {
    const IntPolynomial& a = seq[seq.size() - 2];
    const IntPolynomial& b = seq.back();
    int k = 0;
    IntPolynomial r = pseudoRemainder(a, b, &k);
    if (r.empty()) break;
    const bool flips = sgn(b.back()) < 0 && (k % 2 == 1);
    if (!flips)
      for (auto& c : r) c = -c;
    primitive(r);
    seq.push_back(r);
  }
  std::vector<int> at_minf, at_hi;
  for (const auto& q : seq) {
    const int lead = sgn(q.back());
    at_minf.push_back((q.size() - 1) % 2 == 0 ? lead : -lead);
    Rational v = 0;
    for (size_t i = q.size(); i-- > 0;) v = v * hi + Rational(q[i]);
    at_hi.push_back(sgn(v));
  }
  return variations(at_minf) - variations(at_hi);
}

Separation exactClassify(const Ellipsoid& a, const Ellipsoid& b) {
  auto c = exactCharacteristicPolynomial(a, b);
  RationalPolynomial p(c.begin(), c.end());
  if (evaluate(p, Rational(0)) == 0) throw std::logic_error("exactClassify: f(0) = 0");
  int n = exactDistinctRootsBelow(p, Rational(0));
  if (n >= 2) return Separation::Separated;
  if (n == 1) return Separation::Touching;
  return Separation::Overlapping;
}

Rational exactImplicit(const Ellipsoid& e, const Eigen::Vector3d& x) {
  Rational q = -1;
  for (int j = 0; j < 3; ++j) {
    Rational t = 0;
    for (int i = 0; i < 3; ++i) t += Rational(e.rotation()(i, j)) * (Rational(x[i]) - Rational(e.center()[i]));
    t /= Rational(e.radii()[j]);
    q += t * t;
  }
  return q;
}

}  // namespace test
}  // namespace fcl_quadric
