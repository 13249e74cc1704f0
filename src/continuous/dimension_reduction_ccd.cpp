// Continuous collision of CQMs by dimension reduction (thesis §6.2.2; dimension_reduction_ccd.h).
#include "fcl_quadric/continuous/dimension_reduction_ccd.h"

#include <algorithm>
#include <array>
#include <complex>
#include <limits>
#include <cmath>
#include <functional>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <utility>

#include <Eigen/Dense>

#include "fcl_quadric/algebra/bernstein_polynomial.h"
#include "fcl_quadric/algebra/bivariate_bernstein.h"
#include "fcl_quadric/algebra/low_degree_roots.h"
#include "fcl_quadric/algebra/root_isolation.h"
#include "fcl_quadric/algebra/symmetric_eigen.h"

#include "../geometry/plane_frame.h"
#include "../geometry/region_formula.h"
#include "algebra/bernstein_matrix.h"
#include "algebra/dense_decompositions.h"

namespace fcl_quadric {

using namespace tolerance_reduction;

namespace {

// Polynomials in the piece's time u are kept in the Bernstein basis of [0, 1] (a list of n + 1
// coefficients: degree n), scalars, vectors and matrices alike. Products and degree elevation in
// that basis have positive weights, so their rounding stays relative to the polynomials' values
// on [0, 1]. The power basis does not: a factor such as (1 - u)^n has power coefficients of sum
// (1 + u)^n at u, and the determinants of the pencils (degree 48 in u for two bodies that both
// rotate) lost up to 12 digits to that cancellation near u = 1, enough to move a tangency by
// 2e-3 of the piece and miss the contact (docs/reliability.md finding 45).
using PVec = std::vector<Eigen::Vector4d>;
using PMat = std::vector<Eigen::Matrix4d>;

// The matrix helpers (the relative motion, posed quadrics) are shared with the space-time
// engine: algebra/bernstein_matrix.h.
using detail::bernsteinAt;
using detail::bernsteinFromPower;
using detail::bernsteinProduct;
using detail::binomialRow;
using detail::lineOfPlanes;
using detail::planeOf;
using ProductWeights = detail::BernsteinProductWeights;
Eigen::Vector4d at(const PVec& v, double u) { return v.empty() ? Eigen::Vector4d::Zero() : bernsteinAt(v, u); }
Eigen::Matrix4d at(const PMat& m, double u) { return m.empty() ? Eigen::Matrix4d::Zero() : bernsteinAt(m, u); }

// A polynomial and its companion on absolute values (the same formula on |coefficients| with
// the basis' positive weights): the magnitude against which "zero" is judged.
struct Poly {
  std::vector<double> c, mag;
  void add(std::size_t k, double v, double m) {
    if (c.size() <= k) {
      c.resize(k + 1, 0.0);
      mag.resize(k + 1, 0.0);
    }
    c[k] += v;
    mag[k] += m;
  }
};

// p raised to degree n >= its own: c'_i = sum_j C(r, j) C(n - r, i - j) / C(n, i) c_j.
Poly elevated(const Poly& p, std::size_t n) {
  if (p.c.empty() || p.c.size() == n + 1) return p;
  const std::size_t r = p.c.size() - 1;
  const ProductWeights w(r, n - r);
  Poly e;
  e.c.assign(n + 1, 0.0);
  e.mag.assign(n + 1, 0.0);
  for (std::size_t j = 0; j <= r; ++j)
    for (std::size_t q = 0; q <= n - r; ++q) {
      e.c[j + q] += w(j, q) * p.c[j];
      e.mag[j + q] += w(j, q) * p.mag[j];
    }
  return e;
}

Poly operator*(const Poly& a, const Poly& b) {
  Poly r;
  if (a.c.empty() || b.c.empty()) return r;
  const ProductWeights w(a.c.size() - 1, b.c.size() - 1);
  r.c.assign(a.c.size() + b.c.size() - 1, 0.0);
  r.mag.assign(r.c.size(), 0.0);
  for (std::size_t i = 0; i < a.c.size(); ++i)
    for (std::size_t j = 0; j < b.c.size(); ++j) {
      const double wij = w(i, j);
      r.c[i + j] += wij * a.c[i] * b.c[j];
      r.mag[i + j] += wij * a.mag[i] * b.mag[j];
    }
  return r;
}
Poly operator+(const Poly& a, const Poly& b) {
  if (a.c.empty()) return b;
  if (b.c.empty()) return a;
  const std::size_t n = std::max(a.c.size(), b.c.size()) - 1;
  Poly r = elevated(a, n);
  const Poly e = elevated(b, n);
  for (std::size_t k = 0; k <= n; ++k) r.add(k, e.c[k], e.mag[k]);
  return r;
}
Poly operator-(const Poly& a) {
  Poly r = a;
  for (double& v : r.c) v = -v;
  return r;
}
Poly operator-(const Poly& a, const Poly& b) { return a + (-b); }
// *r = *r + b (or *r - b), the same doubles as operator+ (a + (-b): negation is exact, so
// elevating -b and adding gives exactly the difference), in place: neither is copied when its
// degree is already the sum's.
void accumulate(Poly* r, const Poly& b, bool subtract) {
  if (r->c.empty()) {
    *r = subtract ? -b : b;
    return;
  }
  if (b.c.empty()) return;
  const std::size_t n = std::max(r->c.size(), b.c.size()) - 1;
  if (r->c.size() != n + 1) *r = elevated(*r, n);
  Poly lifted;
  const Poly& e = (b.c.size() == n + 1) ? b : (lifted = elevated(b, n));
  for (std::size_t k = 0; k <= n; ++k) {
    r->c[k] = subtract ? r->c[k] - e.c[k] : r->c[k] + e.c[k];
    r->mag[k] += e.mag[k];
  }
}
bool isZeroPoly(const Poly& p) {
  for (double v : p.c)
    if (v != 0.0) return false;
  return true;
}

// u -> X(u)_i as a Poly.
Poly component(const PVec& v, int i) {
  Poly p;
  for (std::size_t k = 0; k < v.size(); ++k) p.add(k, v[k][i], std::fabs(v[k][i]));
  return p;
}
Poly entry(const PMat& m, int i, int j) {
  Poly p;
  for (std::size_t k = 0; k < m.size(); ++k) p.add(k, m[k](i, j), std::fabs(m[k](i, j)));
  return p;
}
Poly dot(const PVec& a, const PVec& b) {
  Poly p;
  if (a.empty() || b.empty()) return p;
  const ProductWeights w(a.size() - 1, b.size() - 1);
  for (std::size_t k = 0; k < a.size(); ++k)
    for (std::size_t l = 0; l < b.size(); ++l)
      p.add(k + l, w(k, l) * a[k].dot(b[l]), w(k, l) * a[k].cwiseAbs().dot(b[l].cwiseAbs()));
  return p;
}
// X^T S Y.
Poly form(const PVec& X, const PMat& S, const PVec& Y) {
  Poly p;
  if (X.empty() || S.empty() || Y.empty()) return p;
  const std::size_t r = X.size() - 1, s = S.size() - 1, t = Y.size() - 1;
  const std::vector<double> cr = binomialRow(r), cs = binomialRow(s), ct = binomialRow(t), cn = binomialRow(r + s + t);
  for (std::size_t i = 0; i <= r; ++i)
    for (std::size_t j = 0; j <= s; ++j) {
      const Eigen::Vector4d SX = S[j].transpose() * X[i], SXa = S[j].cwiseAbs().transpose() * X[i].cwiseAbs();
      for (std::size_t k = 0; k <= t; ++k) {
        const double w = cr[i] * cs[j] * ct[k] / cn[i + j + k];
        p.add(i + j + k, w * SX.dot(Y[k]), w * SXa.dot(Y[k].cwiseAbs()));
      }
    }
  return p;
}
PVec scaled(const PVec& v, const Poly& s) {  // s(u) v(u)
  if (v.empty() || s.c.empty()) return {};
  const ProductWeights w(v.size() - 1, s.c.size() - 1);
  PVec r(v.size() + s.c.size() - 1, Eigen::Vector4d::Zero());
  for (std::size_t i = 0; i < v.size(); ++i)
    for (std::size_t j = 0; j < s.c.size(); ++j) r[i + j] += (w(i, j) * s.c[j]) * v[i];
  return r;
}

// Determinant of a square matrix of Polys by cofactor expansion along the row with the most
// exact zeros (the bordered forms are sparse). The minors are index lists into m (rows and
// columns kept, in order), not copies of its polynomials.
Poly det(const std::vector<std::vector<Poly>>& m, const std::vector<std::size_t>& rows,
         const std::vector<std::size_t>& cols) {
  const std::size_t n = rows.size();
  if (n == 1) return m[rows[0]][cols[0]];
  std::size_t row = 0, best = 0;
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t z = 0;
    for (std::size_t j = 0; j < n; ++j) z += isZeroPoly(m[rows[i]][cols[j]]);
    if (z > best || i == 0) {
      best = z;
      row = i;
    }
  }
  std::vector<std::size_t> minor_rows(rows);
  minor_rows.erase(minor_rows.begin() + static_cast<std::ptrdiff_t>(row));
  std::vector<std::size_t> minor_cols(n - 1);
  Poly r;
  for (std::size_t j = 0; j < n; ++j) {
    const Poly& e = m[rows[row]][cols[j]];
    if (isZeroPoly(e)) continue;
    for (std::size_t k = 0, l = 0; k < n; ++k)
      if (k != j) minor_cols[l++] = cols[k];
    accumulate(&r, e * det(m, minor_rows, minor_cols), (row + j) % 2 != 0);
  }
  return r;
}
Poly det(const std::vector<std::vector<Poly>>& m) {
  std::vector<std::size_t> all(m.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  return det(m, all, all);
}

// det [[S, π1, ..., πk], [π^T, 0]]: the quadric S bordered by k planes.
Poly bordered(const PMat& S, const std::vector<PVec>& planes) {
  const std::size_t n = 4 + planes.size();
  std::vector<std::vector<Poly>> m(n, std::vector<Poly>(n));
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) m[i][j] = entry(S, i, j);
  for (std::size_t p = 0; p < planes.size(); ++p)
    for (int i = 0; i < 4; ++i) m[i][4 + p] = m[4 + p][i] = component(planes[p], i);
  return det(m);
}

// det [a, b, c, d] of four polynomial columns.
Poly det4(const PVec& a, const PVec& b, const PVec& c, const PVec& d) {
  std::vector<std::vector<Poly>> m(4, std::vector<Poly>(4));
  const PVec* cols[4] = {&a, &b, &c, &d};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) m[i][j] = component(*cols[j], i);
  return det(m);
}

// --- Pencils: characteristic polynomials with polynomial coefficients ---------------------------

using LPoly = std::vector<Poly>;  // coefficients in λ (low -> high), each a polynomial in u
using PolyMatrix = std::vector<std::vector<Poly>>;

LPoly lmul(const LPoly& a, const LPoly& b) {
  LPoly r(a.size() + b.size() - 1);
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j) accumulate(&r[i + j], a[i] * b[j], false);
  return r;
}
LPoly ladd(LPoly a, const LPoly& b, bool subtract) {
  if (a.size() < b.size()) a.resize(b.size());
  for (std::size_t i = 0; i < b.size(); ++i) accumulate(&a[i], b[i], subtract);
  return a;
}
// Cofactor expansion along the first remaining row (rows first_row.. of m, columns cols), with
// the minors as index lists.
LPoly ldet(const std::vector<std::vector<LPoly>>& m, std::size_t first_row, const std::vector<std::size_t>& cols) {
  const std::size_t n = cols.size();
  if (n == 1) return m[first_row][cols[0]];
  LPoly r(1);
  std::vector<std::size_t> minor_cols(n - 1);
  for (std::size_t j = 0; j < n; ++j) {
    for (std::size_t k = 0, l = 0; k < n; ++k)
      if (k != j) minor_cols[l++] = cols[k];
    r = ladd(r, lmul(m[first_row][cols[j]], ldet(m, first_row + 1, minor_cols)), j % 2 == 1);
  }
  return r;
}
LPoly ldet(const std::vector<std::vector<LPoly>>& m) {
  std::vector<std::size_t> all(m.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  return ldet(m, 0, all);
}

// Largest |coefficient| of p, largest magnitude, and "p is zero up to its own rounding".
double maxAbs(const Poly& p) {
  double m = 0.0;
  for (double v : p.c) m = std::max(m, std::fabs(v));
  return m;
}
double maxMag(const Poly& p) {
  double m = 0.0;
  for (double v : p.mag) m = std::max(m, v);
  return m;
}
bool vanishes(const Poly& p) { return maxAbs(p) <= kReductionZeroRelative * maxMag(p); }

// det(λ M1 - M2) for square matrices of polynomials in u, optionally bordered by covectors
// (det [[λ M1 - M2, l], [l^T, 0]]: the pencil restricted to the subspace l.X = 0).
LPoly characteristic(const PolyMatrix& M1, const PolyMatrix& M2, const std::vector<std::vector<Poly>>& borders = {}) {
  const std::size_t n = M1.size(), m = n + borders.size();
  std::vector<std::vector<LPoly>> M(m, std::vector<LPoly>(m, LPoly(1)));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) M[i][j] = LPoly{-M2[i][j], M1[i][j]};
  for (std::size_t b = 0; b < borders.size(); ++b)
    for (std::size_t i = 0; i < n; ++i) M[i][n + b] = M[n + b][i] = LPoly{borders[b][i]};
  return ldet(M);
}


// The discriminant in λ of f after removing identically vanishing coefficients at both ends
// (structural roots at λ = ∞ for a singular M1 and at λ = 0 for a singular M2: a cylinder's
// point at infinity, not a tangency). Degrees 2, 3, 4 (the standard formulas); none for degree
// <= 1 (no multiple root). `stripped` receives the remaining coefficients.

// The discriminant of f = sum c_k λ^k, degree 2, 3 or 4 (the standard formulas); 0 otherwise.
double discriminant(const std::vector<double>& g) {
  const int n = static_cast<int>(g.size()) - 1;
  if (n == 2) return g[1] * g[1] - 4 * g[2] * g[0];
  if (n == 3) {
    const double a = g[3], b = g[2], c = g[1], d = g[0];
    return b * b * c * c - 4 * a * c * c * c - 4 * b * b * b * d - 27 * a * a * d * d + 18 * a * b * c * d;
  }
  if (n == 4) {
    const double a = g[4], b = g[3], c = g[2], d = g[1], e = g[0];
    const double aa = a * a, bb = b * b, cc = c * c, dd = d * d, ee = e * e;
    return 256 * aa * a * ee * e - 192 * aa * b * d * ee - 128 * aa * cc * ee + 144 * aa * c * dd * e - 27 * aa * dd * dd +
           144 * a * bb * c * ee - 6 * a * bb * dd * e - 80 * a * b * cc * d * e + 18 * a * b * c * dd * d +
           16 * a * cc * cc * e - 4 * a * cc * c * dd - 27 * bb * bb * ee + 18 * bb * b * c * d * e - 4 * bb * b * dd * d -
           4 * bb * cc * c * e + bb * cc * dd;
  }
  return 0.0;
}

// The exponent e of the power of two σ = 2^e that balances the ends of f[lo, hi): with λ = σ μ,
// the coefficients c_k σ^(k - lo) of the first and last have equal size (the roots only scale by
// σ). Pencils of matrices of very different size are far from balanced: a ball 50 times smaller
// than the other puts 50^8 ~ 4·10^13 between the ends of f (docs/reliability.md finding 50).
int balancingExponent(const LPoly& f, std::size_t lo, std::size_t hi) {
  if (hi <= lo + 1) return 0;
  const double a = maxAbs(f[lo]), b = maxAbs(f[hi - 1]);
  if (!(a > 0.0 && b > 0.0) || !std::isfinite(a) || !std::isfinite(b)) return 0;
  return static_cast<int>(std::lround((std::log2(a) - std::log2(b)) / static_cast<double>(hi - 1 - lo)));
}

// Structural zeros at both ends of f (identically vanishing coefficients): [lo, hi). A
// coefficient vanishes when it is zero within kReductionZeroRelative of its own magnitude, or
// of the largest of f's coefficients once λ is balanced (balancingExponent): a coefficient
// 1e-11 below the others there would put a root at |μ| ~ 1e-11 or 1e11, not a contact. Unbalanced,
// the comparison stripped the small end of a pencil of a large and a small ball, and the contact
// was lost (finding 50).
//
// An end whose matrix is known to be regular (`regular`: M2 for the low end, det(-M2), and M1 for
// the high end, det(M1)) is never stripped: the relative test is a heuristic, and a thin
// ellipsoid's det(-S(u)) ~ 3e5 against a Leibniz magnitude ~ 3e17 passed it as zero, so its
// contact with a ball was lost (finding 50(b)). A regular end also makes the pencil regular, so
// the other end's test cannot strip everything.
struct RegularEnds {
  bool low = false;   // det(-M2) is not identically zero
  bool high = false;  // det(M1) is not identically zero
};
std::pair<std::size_t, std::size_t> structuralRange(const LPoly& f, RegularEnds regular) {
  std::size_t lo = 0, hi = f.size();
  // Strips the ends that may vanish while `zero(k)` holds for their coefficient k.
  auto strip = [&](auto zero) {
    if (!regular.high)
      while (hi > lo && zero(hi - 1)) --hi;
    if (!regular.low)
      while (lo < hi && zero(lo)) ++lo;
  };
  strip([&](std::size_t k) { return vanishes(f[k]); });
  const int e = balancingExponent(f, lo, hi);
  std::vector<double> size(f.size(), 0.0);
  double scale = 0.0;
  for (std::size_t k = lo; k < hi; ++k) {
    size[k] = std::ldexp(maxAbs(f[k]), e * static_cast<int>(k - lo));
    scale = std::max(scale, size[k]);
  }
  strip([&](std::size_t k) { return size[k] <= kReductionZeroRelative * scale; });
  return {lo, hi};
}


// Coefficients (low -> high, `size` of them) of det(λ M1 - M2), bordered by the columns of
// `borders`, from its values at size equally spaced λ = sigma μ, μ small integers (exact
// interpolation in μ; sigma a power of two balancing the pencil, balancingExponent: at λ of
// order 1 an unbalanced pencil's values hide its small coefficients, finding 50).
std::vector<double> numericCharacteristic(const Eigen::MatrixXd& M1, const Eigen::MatrixXd& M2, const Eigen::MatrixXd& borders,
                                          std::size_t size, double sigma) {
  const int n = static_cast<int>(M1.rows()), k = static_cast<int>(borders.cols()), m = n + k;
  const int q = static_cast<int>(size);
  // Up to 8 x 8 on the stack (the pencils here are at most 5 x 5 with 6 values; the refinement
  // calls this dozens of times per seed); the same LU, without a heap allocation per value.
  using Small = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 8, 8>;
  using SmallVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 8, 1>;
  if (m > 8 || q > 8) throw std::logic_error("numericCharacteristic: pencil larger than 8 x 8");
  Small V(q, q);
  SmallVector vals(q);
  for (int j = 0; j < q; ++j) {
    const double mu = j - 0.5 * (q - 1);
    Small M = Small::Zero(m, m);
    M.topLeftCorner(n, n) = (sigma * mu) * M1 - M2;
    if (k > 0) {
      M.topRightCorner(n, k) = borders;
      M.bottomLeftCorner(k, n) = borders.transpose();
    }
    vals[j] = M.fullPivLu().determinant();
    double p = 1.0;
    for (int i = 0; i < q; ++i, p *= mu) V(j, i) = p;
  }
  const SmallVector c = V.fullPivLu().solve(vals);
  std::vector<double> out(c.data(), c.data() + q);
  for (int i = 0; i < q; ++i) out[i] /= std::pow(sigma, i);  // μ^i = λ^i / sigma^i (exact)
  return out;
}


// The negative multiple root of f(λ) = sum c_k λ^k at u (external tangency): the negative real
// critical point of f where |f| is smallest relative to its magnitude. None when f has no
// negative real critical point. (Positive ones are skipped: two spheres always share a positive
// double root, the circle at infinity.)
std::optional<double> multipleRoot(const std::vector<double>& c) {
  const int n = static_cast<int>(c.size()) - 1;
  if (n < 2 || c[n] == 0.0) return std::nullopt;
  // Roots of f' (degree n - 1 <= 3), complex ones included: a multiple root of f perturbed by
  // rounding may leave f' a near-real pair.
  std::vector<double> dc(n);
  for (int k = 1; k <= n; ++k) dc[k - 1] = k * c[k];
  // Non-finite coefficients (an overflowed evaluation): no critical point, as the companion
  // matrix's NaN eigenvalues gave before (lowDegreeRoots would throw).
  for (double v : dc)
    if (!std::isfinite(v)) return std::nullopt;
  const std::vector<std::complex<double>> z = lowDegreeRoots(dc);
  std::optional<double> best;
  double best_score = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < z.size(); ++i) {
    if (std::fabs(z[i].imag()) > 1e-6 * (1.0 + std::fabs(z[i].real()))) continue;
    const double x = z[i].real();
    if (x >= 0.0) continue;
    double v = 0.0, mag = 0.0, xp = 1.0;
    for (int k = 0; k <= n; ++k, xp *= x) {
      v += c[k] * xp;
      mag += std::fabs(c[k] * xp);
    }
    const double score = std::fabs(v) / std::max(mag, 1e-300);
    if (score < best_score) {
      best_score = score;
      best = x;
    }
  }
  return best;
}

// Null vectors of the symmetric matrix M (rank n - 1: one; rank n - 2: the real points of the
// null line on the quadric Q, two at most). In the matrix's own coordinates.
//
// Rank n - 2 is judged against the largest singular value, loosely (1e-6: the multiple root is
// computed, so a line contact's matrix is only near rank n - 2). A matrix that is merely
// unbalanced can pass that test: a ball against a thin cylinder at size 1000 (singular values
// 306, 4e-5, 4e-5, 4e-19) had a null line that missed Q, and its contact got no point. When the
// null line has no real point on Q, the least singular vector is the point (docs/reliability.md
// finding 52); the candidate is still verified on both bodies.
std::vector<Eigen::VectorXd> nullPoints(const Eigen::MatrixXd& M, const Eigen::MatrixXd& Q) {
  // Singular values of a symmetric matrix: |eigenvalues|; right singular vectors: eigenvectors.
  const SymmetricEigenDecomposition eig = symmetricEigen(M);
  const int n = static_cast<int>(M.rows());
  std::vector<int> order(n);  // by decreasing |eigenvalue|, as singular values
  for (int i = 0; i < n; ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&eig](int i, int j) { return std::fabs(eig.values[i]) > std::fabs(eig.values[j]); });
  const auto sv = [&](int i) { return std::fabs(eig.values[order[i]]); };
  const Eigen::VectorXd x0 = eig.vectors.col(order[n - 1]);
  if (n < 2 || sv(n - 2) > 1e-6 * sv(0)) return {x0};
  const Eigen::VectorXd x1 = eig.vectors.col(order[n - 2]);
  const double qa = x1.dot(Q * x1), qb = x0.dot(Q * x1), qc = x0.dot(Q * x0);
  // Points x0 + s x1 (and x1 itself when qc ~ 0 fails): qa s^2 + 2 qb s + qc = 0.
  std::vector<Eigen::VectorXd> out;
  const double disc = qb * qb - qa * qc;
  if (std::fabs(qa) <= 1e-14 * Q.norm()) {
    if (qb != 0.0) out.push_back(x0 - 0.5 * qc / qb * x1);
    out.push_back(x1);
    return out;
  }
  if (disc < -1e-12 * (qb * qb + std::fabs(qa * qc))) return {x0};
  const double r = disc > 0.0 ? std::sqrt(disc) : 0.0;
  out.push_back(x0 + ((-qb - r) / qa) * x1);
  out.push_back(x0 + ((-qb + r) / qa) * x1);
  return out;
}

// --- Elements of one body in its local frame ------------------------------------------------

void collectRaw(const QuadricRegion& r, std::vector<Eigen::Matrix4d>* out) {
  if (r.op() == QuadricRegion::Op::Atom) {
    out->push_back(r.matrix());
    return;
  }
  for (const QuadricRegion& c : r.children()) collectRaw(c, out);
}

struct EdgeGeometry {
  bool line = false;
  bool empty = false;  // no points (parallel planes, a section without a real line): no subproblems
  Eigen::Vector4d U = Eigen::Vector4d::Zero(), D = Eigen::Vector4d::Zero();  // line: point, direction
  Eigen::Vector4d plane = Eigen::Vector4d::Zero();                           // conic: its plane
  int quadric = -1;                                                          // conic: signed atom
  // Conic: homogeneous basis of its plane (two directions and a point: X = E y, y in P^2) and
  // the conic in those coordinates, E^T Q E.
  Eigen::Matrix<double, 4, 3> basis = Eigen::Matrix<double, 4, 3>::Zero();
  Eigen::Matrix3d conic = Eigen::Matrix3d::Zero();
};

struct Body {
  std::vector<Eigen::Matrix4d> raw, sgn;
  BoundaryElements el;
  std::vector<EdgeGeometry> edges;
  /// Per edge of el: its index in the body's own boundary elements (a section's second line is
  /// appended to el as an edge of its own; reports name the edge it belongs to).
  std::vector<int> edge_origin;
  std::vector<std::vector<Eigen::Vector4d>> vertices;  // homogeneous points (w = 1) per vertex
  std::vector<bool> singular;  // per signed atom: a curved atom with det Q = 0 (a cylinder, a cone)
  /// Cone apexes: (face index, homogeneous point with w = 1), the finite null vector of the face's
  /// quadric. A point contact of its own, searched against every face of the other body.
  std::vector<std::pair<int, Eigen::Vector4d>> apexes;
  std::string unsupported;
};


// The lines of a plane face meeting a quadric face in a line edge (boundaryElements' EdgeKind::Line
// for a plane and a quadric: the quadric restricted to the plane has rank <= 1 in the plane's
// directions and no linear term along its null direction). In plane coordinates y (x = o + y0 u
// + y1 v) the restriction is y^T A y + 2 c.y + g: with A ~ 0 it is linear (one line, 2 c.y + g
// = 0); otherwise along A's dominant eigenvector p it is alpha s^2 + 2 beta s + g, the lines run
// along the null direction through its roots: two parallel lines (a plane through a cylinder's
// axis, a wedge's cut), or one double line (a plane tangent to a cylinder: the discriminant
// within rounding of zero, 1e-9 of its terms, is taken as zero: err toward an edge). No real line:
// an empty list (the edge has no points). Points with w = 1, unit directions with w = 0.
std::vector<std::pair<Eigen::Vector4d, Eigen::Vector4d>> sectionLines(const Eigen::Vector4d& plane,
                                                                      const Eigen::Matrix4d& Q) {
  const Eigen::Matrix<double, 4, 3> M = detail::planeFrame(plane);
  const Eigen::Matrix3d C = M.transpose() * Q * M;
  const double a11 = C(0, 0), a12 = C(0, 1), a22 = C(1, 1), g = C(2, 2);
  const Eigen::Vector2d c(C(0, 2), C(1, 2));
  const double hyp = std::hypot(0.5 * (a11 - a22), a12);
  const double lo = 0.5 * (a11 + a22) - hyp, hi = 0.5 * (a11 + a22) + hyp;
  const double alpha = std::fabs(hi) >= std::fabs(lo) ? hi : lo;
  const double eps = 1e-12 * Q.cwiseAbs().maxCoeff();  // boundaryElements' rank threshold
  const auto inPlane = [&](const Eigen::Vector2d& y, double w) {  // M (y, w), homogeneous
    return Eigen::Vector4d(M * Eigen::Vector3d(y[0], y[1], w));
  };
  std::vector<std::pair<Eigen::Vector4d, Eigen::Vector4d>> out;
  if (std::fabs(alpha) <= eps) {
    if (c.norm() == 0.0) return out;
    const Eigen::Vector2d y0 = -0.5 * g / c.squaredNorm() * c;
    out.emplace_back(inPlane(y0, 1.0), inPlane(Eigen::Vector2d(-c[1], c[0]).normalized(), 0.0));
    return out;
  }
  // A's eigenvector of alpha: the larger of the two rows of A - alpha I, turned.
  const Eigen::Vector2d r0(alpha - a22, a12), r1(a12, alpha - a11);
  const Eigen::Vector2d pdir = (r0.norm() >= r1.norm() ? r0 : r1).normalized();
  const Eigen::Vector2d ndir(-pdir[1], pdir[0]);
  const double beta = pdir.dot(c);
  double disc = beta * beta - alpha * g;
  if (disc < 0.0) {
    if (disc < -1e-9 * (beta * beta + std::fabs(alpha * g))) return out;
    disc = 0.0;
  }
  const double r = std::sqrt(disc);
  const Eigen::Vector4d D = inPlane(ndir, 0.0);
  for (double s : {(-beta - r) / alpha, (-beta + r) / alpha}) {
    out.emplace_back(inPlane(s * pdir, 1.0), D);
    if (r == 0.0) break;
  }
  return out;
}

Body makeBody(const MovingRegion& m) {
  Body b;
  collectRaw(m.region, &b.raw);
  b.sgn = m.region.signedAtoms();
  b.el = m.elements ? *m.elements : boundaryElements(m.region, *m.box);
  b.singular.assign(b.sgn.size(), false);
  // Rank is judged on the quadric in coordinates of the body's size (x = h x'), by its smallest
  // |eigenvalue| against its largest. The former test, |det Q| <= 1e-12 max|Q|^4 in the body's
  // own units, called an ellipsoid of radius 500 singular (det 1 / r^6), skipped its face-plane
  // subproblems as a cylinder's, and missed a box's face landing on it (finding 46).
  const double extent = (m.box->hi - m.box->lo).cwiseAbs().maxCoeff();
  const double h = std::ldexp(1.0, std::ilogb(extent > 0.0 && std::isfinite(extent) ? extent : 1.0));
  const Eigen::Matrix4d Dh = Eigen::Vector4d(h, h, h, 1.0).asDiagonal();
  for (std::size_t fi = 0; fi < b.el.faces.size(); ++fi) {
    const BoundaryFace& f = b.el.faces[fi];
    const Eigen::Matrix4d& Q = b.sgn[f.atom];
    if (f.planar() && !detail::isPlanarAtom(Q)) b.unsupported = "a pair of planes as one atom";
    bool rank_deficient = false;
    if (!f.planar()) {
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(Dh * Q * Dh, Eigen::EigenvaluesOnly);
      const Eigen::Vector4d ev = eig.eigenvalues().cwiseAbs();
      rank_deficient = ev.minCoeff() <= 1e-12 * ev.maxCoeff();
    }
    if (rank_deficient) {
      // A singular quadric: a cylinder (null vector at infinity), or a cone whose apex (a finite
      // null vector) is a point contact of its own, not a vertex of the boundary elements.
      b.singular[f.atom] = true;
      const Eigen::MatrixXd K = detail::fullPivLuKernel(Q);
      if (K.cols() > 1) {
        b.unsupported = "a quadric of rank 2 or less as a face";
      } else if (K.cols() == 1 && std::fabs(K(3, 0)) > 1e-9 * K.col(0).norm()) {
        b.apexes.emplace_back(static_cast<int>(fi), Eigen::Vector4d(K.col(0) / K(3, 0)));
      }
    }
  }
  // Line edges: the meet of two planes, or the lines of a plane's section of a quadric (a second
  // parallel line is appended to el as an edge of its own). An edge of two parallel planes
  // (coincident faces of a union's children) or a section with no real line has no points: it is
  // marked empty and gets no subproblems (contacts on a coincident plane are that face's own).
  const std::size_t own_edges = b.el.edges.size();
  for (std::size_t ei = 0; ei < own_edges; ++ei) {
    const BoundaryEdge e = b.el.edges[ei];
    EdgeGeometry g;
    const BoundaryFace &f0 = b.el.faces[e.face0], &f1 = b.el.faces[e.face1];
    std::optional<std::pair<Eigen::Vector4d, Eigen::Vector4d>> second_line;
    if (e.kind == EdgeKind::Line) {
      g.line = true;
      if (f0.planar() && f1.planar()) {
        Eigen::Vector3d x, d;
        g.empty = !lineOfPlanes(planeOf(b.sgn[f0.atom]), planeOf(b.sgn[f1.atom]), &x, &d);
        if (!g.empty) {
          g.U << x, 1.0;
          g.D << d.normalized(), 0.0;
        }
      } else if (f0.planar() || f1.planar()) {
        const BoundaryFace &plane = f0.planar() ? f0 : f1, &curved = f0.planar() ? f1 : f0;
        const auto lines = sectionLines(planeOf(b.sgn[plane.atom]), b.sgn[curved.atom]);
        g.empty = lines.empty();
        if (!g.empty) std::tie(g.U, g.D) = lines[0];
        if (lines.size() > 1) second_line = lines[1];
      } else {
        b.unsupported = "a line edge of two curved faces";
      }
    } else if (e.kind == EdgeKind::Conic) {
      const bool p0 = f0.planar();
      g.plane = planeOf(b.sgn[(p0 ? f0 : f1).atom]);
      g.quadric = (p0 ? f1 : f0).atom;
      const Eigen::Vector3d n = g.plane.head<3>();
      const Eigen::Vector3d o = -g.plane[3] / n.squaredNorm() * n;
      const Eigen::Vector3d e0 = n.unitOrthogonal(), e1 = n.normalized().cross(e0);
      g.basis.col(0) << e0, 0.0;
      g.basis.col(1) << e1, 0.0;
      g.basis.col(2) << o, 1.0;
      g.conic = g.basis.transpose() * b.sgn[g.quadric] * g.basis;
    }
    b.edges.push_back(g);
    b.edge_origin.push_back(static_cast<int>(ei));
    if (second_line) {
      std::tie(g.U, g.D) = *second_line;
      b.el.edges.push_back(e);
      b.edges.push_back(g);
      b.edge_origin.push_back(static_cast<int>(ei));
    }
  }
  for (const BoundaryVertex& v : b.el.vertices) {
    std::vector<int> planes, quadrics;
    for (int fi : {v.face0, v.face1, v.face2}) (b.el.faces[fi].planar() ? planes : quadrics).push_back(b.el.faces[fi].atom);
    std::vector<Eigen::Vector4d> pts;
    if (planes.size() == 3) {
      Eigen::Matrix3d N;
      Eigen::Vector3d rhs;
      for (int i = 0; i < 3; ++i) {
        const Eigen::Vector4d p = planeOf(b.sgn[planes[i]]);
        N.row(i) = p.head<3>().transpose();
        rhs[i] = -p[3];
      }
      Eigen::Vector3d x;
      if (detail::fullPivLuSolve(N, rhs, &x))
        pts.push_back(Eigen::Vector4d(0, 0, 0, 1) + (Eigen::Vector4d() << x, 0.0).finished());
    } else if (planes.size() == 2) {
      Eigen::Vector3d x, d;
      if (lineOfPlanes(planeOf(b.sgn[planes[0]]), planeOf(b.sgn[planes[1]]), &x, &d)) {
        d.normalize();
        const Eigen::Matrix4d& Q = b.sgn[quadrics[0]];
        const Eigen::Vector4d U(x[0], x[1], x[2], 1.0), D(d[0], d[1], d[2], 0.0);
        const double qa = D.dot(Q * D), qb = D.dot(Q * U), qc = U.dot(Q * U);
        const double disc = qb * qb - qa * qc;
        if (qa != 0.0 && disc >= 0.0) {
          const double r = std::sqrt(disc);
          for (double s : {(-qb - r) / qa, (-qb + r) / qa}) pts.push_back(U + s * D);
        } else if (qa == 0.0 && qb != 0.0) {
          pts.push_back(U - 0.5 * qc / qb * D);
        }
      }
    }
    b.vertices.push_back(pts);
  }
  for (const BoundaryEdge& e : b.el.edges)
    if (e.kind == EdgeKind::Curve) b.unsupported = "a quartic edge (thesis §6.5)";
  return b;
}

// Figure 29 predicates with a band: +1 interior, 0 boundary (within the band), -1 exterior.
int classifyBand(const QuadricRegion& r, const std::vector<Eigen::Matrix4d>& posed, std::size_t* k,
                 const Eigen::Vector3d& x, double band) {
  switch (r.op()) {
    case QuadricRegion::Op::Atom: {
      const Eigen::Matrix4d& Q = posed[(*k)++];
      const Eigen::Vector4d X(x[0], x[1], x[2], 1.0);
      const Eigen::Vector4d QX = Q * X;
      const double f = X.dot(QX);
      const double grad = 2.0 * QX.head<3>().norm();
      const Eigen::Vector4d aX = X.cwiseAbs();
      const double rounding = kReductionEvalRelative * aX.dot(Q.cwiseAbs() * aX);  // a cone's apex: grad = 0
      if (std::fabs(f) <= band * grad + band * band * Q.topLeftCorner<3, 3>().norm() + rounding) return 0;
      return f < 0.0 ? 1 : -1;
    }
    case QuadricRegion::Op::Union: {
      int best = -1;
      for (const QuadricRegion& c : r.children()) best = std::max(best, classifyBand(c, posed, k, x, band));
      return best;
    }
    case QuadricRegion::Op::Intersection: {
      int worst = 1;
      for (const QuadricRegion& c : r.children()) worst = std::min(worst, classifyBand(c, posed, k, x, band));
      return worst;
    }
    case QuadricRegion::Op::Difference: {
      int v = classifyBand(r.children()[0], posed, k, x, band);
      for (std::size_t i = 1; i < r.children().size(); ++i) v = std::min(v, -classifyBand(r.children()[i], posed, k, x, band));
      return v;
    }
  }
  return 0;
}


// The elements of one body as polynomials in a's frame on a piece.
struct Posed {
  std::vector<PMat> atoms;  // signed atoms
  std::vector<PMat> raw;
  std::vector<PVec> planes;                   // per face (planar faces only; else empty)
  std::vector<PVec> edgeU, edgeD, edgePlane;  // per edge
  std::vector<std::array<PVec, 3>> edgeBasis;  // per conic edge: the plane basis columns
  std::vector<std::vector<PVec>> vertices;
  std::vector<PVec> apexes;  // per Body::apexes
};

// Points map by `Pinv` (X_a ~ Pinv X_b), covectors and quadrics by `P` (X_b ~ P X_a).
Posed pose(const Body& b, const std::vector<Eigen::Matrix4d>& P, const std::vector<Eigen::Matrix4d>& Pinv) {
  Posed o;
  auto point = [&](const Eigen::Vector4d& X) {
    PVec v;
    for (const Eigen::Matrix4d& M : Pinv) v.push_back(M * X);
    return v;
  };
  auto covector = [&](const Eigen::Vector4d& p) {
    PVec v;
    for (const Eigen::Matrix4d& M : P) v.push_back(M.transpose() * p);
    return v;
  };
  auto quadric = [&](const Eigen::Matrix4d& Q) { return detail::bernsteinCongruence(Q, P); };
  for (const Eigen::Matrix4d& Q : b.sgn) o.atoms.push_back(quadric(Q));
  for (const Eigen::Matrix4d& Q : b.raw) o.raw.push_back(quadric(Q));
  for (const BoundaryFace& f : b.el.faces) o.planes.push_back(f.planar() ? covector(planeOf(b.sgn[f.atom])) : PVec{});
  for (const EdgeGeometry& e : b.edges) {
    o.edgeU.push_back(e.line ? point(e.U) : PVec{});
    o.edgeD.push_back(e.line ? point(e.D) : PVec{});
    o.edgePlane.push_back(e.line ? PVec{} : covector(e.plane));
    o.edgeBasis.push_back({point(e.basis.col(0)), point(e.basis.col(1)), point(e.basis.col(2))});
  }
  for (const auto& pts : b.vertices) {
    std::vector<PVec> v;
    for (const Eigen::Vector4d& X : pts) v.push_back(point(X));
    o.vertices.push_back(v);
  }
  for (const auto& [face, X] : b.apexes) o.apexes.push_back(point(X));
  return o;
}

// A candidate's contact point at piece time u, in a's frame: a point, none (not a real contact
// of the extended elements: rejected), or undefined (degenerate: the answer becomes Undecided).
struct PointAt {
  enum Kind { Point, None, Degenerate } kind = None;
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
};
PointAt degenerate() {
  PointAt p;
  p.kind = PointAt::Degenerate;
  return p;
}
PointAt affine(const Eigen::Vector4d& X, double scale) {
  PointAt p;
  if (std::fabs(X[3]) <= 1e-12 * X.head<3>().norm() / scale || X.norm() == 0.0) {
    p.kind = X.norm() == 0.0 ? PointAt::Degenerate : PointAt::None;
    return p;
  }
  p.kind = PointAt::Point;
  p.x = X.head<3>() / X[3];
  return p;
}

// The root of p in an isolating interval: refined to kReductionRootWidth when it is a certified
// simple root (a sign bracket), else the interval's midpoint (an unresolved interval is narrower
// than kReductionRootWidth).
double refined(const BernsteinPolynomial& p, const RootInterval& r) {
  if (r.kind != RootKind::Single || r.lo == r.hi) return 0.5 * (r.lo + r.hi);
  const double flo = p.evaluate(r.lo), fhi = p.evaluate(r.hi);
  if (flo == 0.0) return r.lo;
  if (fhi == 0.0) return r.hi;
  if ((flo < 0.0) == (fhi < 0.0)) return 0.5 * (r.lo + r.hi);  // rounding at the ends
  return refineRoot(p, r.lo, r.hi, kReductionRootWidth);
}

struct Task {
  CcdSubproblem sp;
  Poly g;
  std::function<std::vector<PointAt>(double)> points;
  /// g evaluated at u from the elements evaluated at u (pencil tasks): the expansion of g in u
  /// loses digits to cancellation at high degree, so its roots are refined on this.
  std::function<double(double)> value;
  /// Quadric-quadric tasks: Lemma 6.2 / §6.3.2 at a contact moment (reported, not a filter).
  std::function<std::optional<ContactConfiguration>(double)> configuration;
  /// Pencil tasks: f(λ; u) without its structural zeros; the candidates come from
  /// tangencySeeds, searched after the other tasks' candidates (pruned by their best time).
  std::vector<Poly> pencil;
  /// Pencil tasks: f(λ*; u) at the negative critical point λ* of f(·; u) where f is nearest to
  /// zero (multipleRoot()), from the elements evaluated at u. It changes sign where the double
  /// root λ* appears, as the discriminant does, but does not vanish identically when f has a
  /// permanent multiple root elsewhere (two spheres: a positive one, the circle at infinity),
  /// where the discriminant is rounding noise and cannot refine a seed: a shallow graze of two
  /// turning balls, whose Newton solution does not converge (F_u -> 0), was missed
  /// (docs/reliability.md finding 47).
  std::function<double(double)> critical_value;
};

// A root of `value` near u0 (a root of the expanded polynomial): the nearest sign change within
// widening windows (1e-9 ... 1e-2), bisected to kReductionRootWidth; u0 if none (a graze).
// Windows start 1e3 kReductionRootWidth after `after` (a root already tried, when u0 > after):
// the search then finds the next root rather than the nearest.
double refineNumerically(const std::function<double(double)>& value, double u0,
                         double after = -std::numeric_limits<double>::infinity()) {
  const double f0 = value(u0);
  if (f0 == 0.0) return u0;
  for (double w = 1e-9; w <= 1e-2; w *= 10.0) {
    const double lo = std::max({0.0, u0 - w, std::min(u0, after + 1e3 * kReductionRootWidth)});
    const double hi = std::min(1.0, u0 + w);
    double a = 0.0, b = 0.0;
    if ((value(lo) < 0.0) != (f0 < 0.0)) {
      a = lo;
      b = u0;
    } else if ((value(hi) < 0.0) != (f0 < 0.0)) {
      a = u0;
      b = hi;
    } else {
      continue;
    }
    const bool neg_a = value(a) < 0.0;
    for (int i = 0; i < 60 && b - a > kReductionRootWidth; ++i) {
      const double m = 0.5 * (a + b);
      ((value(m) < 0.0) == neg_a ? a : b) = m;
    }
    return 0.5 * (a + b);
  }
  return u0;
}

// A pencil subproblem: g is the discriminant of the characteristic polynomial f(λ; u), and the
// contact points at a candidate u come from the multiple root λ0 of f(·; u). False when the
// discriminant vanishes identically (two spheres, parallel cylinders: a permanent multiple root;
// the thesis's next subresultant is not implemented).
// The moments u at which f(λ; u) = sum_k g_k(u) λ^k has a negative multiple root (external
// tangency, thesis §6.2.2), as seeds within kPencilSeedWidth: the common zeros of F and dF/dx,
// F(x, u) = x^m f((x - 1)/x; u) (λ = (x - 1)/x maps λ < 0 to x in (0, 1), as the CCD function
// of thesis §5.3), by subdivision of [0, 1]^2 with the Bernstein bounds of F and F_x. The
// discriminant of f in λ, expanded in u (degree up to 120), loses ~1e-3 of u to cancellation
// (measured); F and F_x do not cancel. None when kPencilMaxBoxes is reached (a curve of
// multiple roots: spheres, coaxial cylinders).
// Boxes are searched depth first, earlier t first; `accept(u, newton, after)` is called on each
// new seed (in the search's order, not sorted) and returns the time limit below which the search
// goes on (a verified contact at u returns u: later boxes are pruned) and the moment up to which
// its candidates were tried. Adjacent boxes form a chain along a stretch where the pencil is
// within its pads of a tangency; the chain's first box is a seed (after = -infinity), and a later
// box of the chain is one only past the moment tried (after = that moment): a cylinder's rim
// nearly tangent to a cone over 2.5e-5 of u had a tangency outside the cone near the chain's
// start and the contact 2e-5 later, which seeding the chain once missed (docs/reliability.md
// finding 51). Failed at the box cap of the search (kPencilMaxBoxes) or when *total_boxes, the
// count of all pencil searches of the query, exceeds total_cap (the piece's share:
// kReductionMaxPencilBoxes more than at its start). Paused when *total_boxes reaches pause_at:
// the search's state (its stack of boxes, its chain, its own limit) stays in *search, and a later
// call goes on from there with a limit no later than before (the pencil passes of the piece).
struct SeedOutcome {
  double limit;  // the search goes on below this time
  double tried;  // candidates up to this moment were tried
};
struct TangencySearch {
  std::vector<std::array<double, 4>> stack{{0.0, 1.0, 0.0, 1.0}};
  double limit = 2.0, last_seed = -1.0, tried = -1.0;
  int boxes = 0;
};
enum class SearchEnd { Complete, Paused, Failed };
SearchEnd tangencySeeds(const LPoly& g, double limit, long long* total_boxes, long long pause_at, long long total_cap,
                        TangencySearch* search,
                        const std::function<SeedOutcome(double, std::optional<double>, double)>& accept) {
  // F(x, u) = sum_k g_k(u) (x - 1)^k x^(m - k) = sum_k (-1)^k g_k(u) B_{m-k}^m(x) / C(m, k): its
  // Bernstein coefficients in x come straight from the g_k (already Bernstein in u).
  const int m = static_cast<int>(g.size()) - 1;
  std::size_t d = 1;
  for (const Poly& p : g) d = std::max(d, p.c.size());
  const std::vector<double> cm = binomialRow(static_cast<std::size_t>(m));
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(m + 1, d);
  for (int k = 0; k <= m; ++k) {
    if (g[k].c.empty()) continue;
    const Poly e = elevated(g[k], d - 1);
    for (std::size_t j = 0; j < d; ++j) P(m - k, j) = ((k % 2) ? -1.0 : 1.0) * e.c[j] / cm[k];
  }
  const double scale = P.cwiseAbs().maxCoeff();
  if (scale == 0.0 || !std::isfinite(scale)) return SearchEnd::Failed;
  P /= scale;
  const BivariateBernstein F(P), Fx = F.derivativeU();
  const BivariateBernstein Fu = F.derivativeT(), Fxx = Fx.derivativeU(), Fxu = Fx.derivativeT();
  const double pad = 1e-12 * F.coefficients().cwiseAbs().maxCoeff(), padx = 1e-12 * Fx.coefficients().cwiseAbs().maxCoeff();
  std::vector<std::array<double, 4>>& stack = search->stack;
  double &last_seed = search->last_seed, &tried = search->tried;
  search->limit = std::min(search->limit, limit);
  while (!stack.empty()) {
    if (*total_boxes >= pause_at) return SearchEnd::Paused;
    const std::array<double, 4> b = stack.back();
    stack.pop_back();
    if (b[2] > search->limit) continue;
    if (++search->boxes > kPencilMaxBoxes || ++*total_boxes > total_cap) return SearchEnd::Failed;
    const BivariateBernstein Fb = F.restrict(b[0], b[1], b[2], b[3]);
    if (Fb.minCoefficient() > pad || Fb.maxCoefficient() < -pad) continue;
    const BivariateBernstein Fxb = Fx.restrict(b[0], b[1], b[2], b[3]);
    if (Fxb.minCoefficient() > padx || Fxb.maxCoefficient() < -padx) continue;
    const double wx = b[1] - b[0], wt = b[3] - b[2];
    if (wx <= kPencilSeedWidth && wt <= kPencilSeedWidth) {
      // Newton on (F, F_x) = 0 from the box centre (a simple solution: the Jacobian
      // [[F_x, F_u], [F_xx, F_xu]] = [[0, F_u], [F_xx, F_xu]] is regular at a generic
      // tangency); the centre itself if it does not converge near the box.
      const double centre = 0.5 * (b[2] + b[3]);
      double x = 0.5 * (b[0] + b[1]), u = centre;
      bool converged = false;
      for (int it = 0; it < 20; ++it) {
        const double f = F.evaluate(x, u), fx = Fx.evaluate(x, u), fu = Fu.evaluate(x, u), fxx = Fxx.evaluate(x, u),
                     fxu = Fxu.evaluate(x, u);
        const double det = fx * fxu - fu * fxx;
        if (det == 0.0 || !std::isfinite(det)) break;
        const double dx = (f * fxu - fu * fx) / det, du = (fx * fx - f * fxx) / det;
        // A near-singular Jacobian (a thin shape's flat pencil) can throw the step far off or to
        // infinity: stop there, and the box centre is the seed.
        if (!std::isfinite(dx) || !std::isfinite(du) || std::fabs(x - dx) > 2.0 || std::fabs(u - du) > 2.0) break;
        x -= dx;
        u -= du;
        if (std::fabs(du) <= 1e-15 && std::fabs(dx) <= 1e-15) {
          converged = true;
          break;
        }
      }
      std::optional<double> newton;
      if (converged && std::fabs(u - centre) <= 10 * kPencilSeedWidth && u >= 0.0 && u <= 1.0) newton = u;
      const bool chain_start = std::fabs(centre - last_seed) > 10 * kPencilSeedWidth;
      if (chain_start || centre > tried) {
        const SeedOutcome o = accept(centre, newton, chain_start ? -std::numeric_limits<double>::infinity() : tried);
        search->limit = std::min(search->limit, o.limit);
        tried = std::max(o.tried, centre + 10 * kPencilSeedWidth);
      }
      last_seed = centre;
      continue;
    }
    if (wx >= wt) {
      const double mid = 0.5 * (b[0] + b[1]);
      stack.push_back({mid, b[1], b[2], b[3]});
      stack.push_back({b[0], mid, b[2], b[3]});
    } else {
      const double mid = 0.5 * (b[2] + b[3]);
      stack.push_back({b[0], b[1], mid, b[3]});
      stack.push_back({b[0], b[1], b[2], mid});
    }
  }
  return SearchEnd::Complete;
}

// `numeric(u)` gives the pencil's numeric characteristic coefficients at u (all f.size() of
// them, from the matrices evaluated at u): the discriminant's value at u without the expansion in
// u (task.value, for refining the candidates) and the multiple root for the contact point.
//
// Structural roots (a singular face: f's end coefficients vanish identically) hide a tangency at
// λ = 0 or λ = ∞ from the stripped polynomial: when the lowest remaining coefficient c_lo(u)
// vanishes, one more root reaches λ = 0 (for a cylinder cut parallel to its axis by a conic's
// plane, the section's two lines merge: the plane becomes tangent along a line, crossing the
// conic at the ends of the contact segment). Those moments are tasks of their own (`extra`):
// the roots of c_lo (λ0 = 0) and of c_{hi-1} (λ0 = ∞; at_root then gets +infinity).
void pencilTask(Task& task, const LPoly& f, std::function<std::vector<double>(double, double)> numeric,
                std::function<std::vector<PointAt>(double, double)> at_root, std::vector<Task>* extra,
                RegularEnds regular) {
  const std::pair<std::size_t, std::size_t> range = structuralRange(f, regular);
  // The pencil in μ = λ / σ, σ = 2^e balancing its ends (exact scaling; balancingExponent): the
  // seed search's pads and the critical points are relative to the largest coefficient, and the
  // numeric coefficients come from values at λ = σ μ.
  const int e = balancingExponent(f, range.first, range.second);
  const double sigma = std::ldexp(1.0, e);
  task.points = [](double) { return std::vector<PointAt>{}; };
  auto boundaryEvent = [&](std::size_t index, double lambda) {
    Task event;
    event.sp = task.sp;
    event.g = f[index];
    event.value = [numeric, index, sigma](double u) { return numeric(u, sigma)[index]; };
    event.points = [at_root, lambda](double u) { return at_root(u, lambda); };
    extra->push_back(std::move(event));
  };
  if (range.second > range.first) {
    if (range.first > 0) boundaryEvent(range.first, 0.0);
    if (range.second < f.size()) boundaryEvent(range.second - 1, std::numeric_limits<double>::infinity());
  }
  if (range.second < range.first + 3) return;  // degree <= 1 in λ: no multiple root
  for (std::size_t k = range.first; k < range.second; ++k) {
    Poly p = f[k];
    const int shift = e * static_cast<int>(k - range.first);
    for (double& v : p.c) v = std::ldexp(v, shift);
    for (double& v : p.mag) v = std::ldexp(v, shift);
    task.pencil.push_back(std::move(p));
  }
  auto stripped = [numeric, range, e, sigma](double u) {
    const std::vector<double> c = numeric(u, sigma);
    std::vector<double> r(c.begin() + range.first, c.begin() + range.second);
    for (std::size_t j = 0; j < r.size(); ++j) r[j] = std::ldexp(r[j], e * static_cast<int>(j));
    return r;
  };
  task.value = [stripped](double u) { return discriminant(stripped(u)); };
  task.critical_value = [stripped](double u) {
    const std::vector<double> c = stripped(u);
    const std::optional<double> lambda = multipleRoot(c);
    if (!lambda) return 0.0;  // no negative critical point: refineNumerically stops there
    double v = 0.0;
    for (std::size_t k = c.size(); k-- > 0;) v = v * *lambda + c[k];
    return v;
  };
  task.points = [stripped, at_root, sigma](double u) {
    const std::optional<double> mu = multipleRoot(stripped(u));
    if (!mu) return std::vector<PointAt>{};
    return at_root(u, sigma * *mu);
  };
}

// The windows of u in [0, 1] where the bounding spheres (centre c, radius r in each body's frame)
// of a and of b, posed by Pinv, may overlap (dimension_reduction_ccd.h, "Proximity windows"):
// D(u) = |x(u) - w(u) c_a|^2 - R^2 w(u)^2 with (x, w) = Pinv(u) (c_b, 1) and R the padded sum of
// radii; subintervals with every Bernstein coefficient of D above its rounding (1e-12 of the
// coefficients' magnitude) are dropped. Merged, in increasing order.
std::vector<std::pair<double, double>> proximityWindows(const PMat& Pinv, const Eigen::Vector3d& ca,
                                                        const Eigen::Vector3d& cb, double R) {
  PVec X, Y;
  for (const Eigen::Matrix4d& M : Pinv) {
    X.push_back(M * Eigen::Vector4d(cb[0], cb[1], cb[2], 1.0));
    Eigen::Vector4d y = X.back();
    y.head<3>() -= y[3] * ca;
    y[3] = 0.0;
    Y.push_back(y);
  }
  const Poly w = component(X, 3);
  Poly w2 = w * w;
  for (std::size_t k = 0; k < w2.c.size(); ++k) {
    w2.c[k] *= R * R;
    w2.mag[k] *= R * R;
  }
  const Poly D = dot(Y, Y) - w2;
  double mag = 0.0;
  for (double m : D.mag) mag = std::max(mag, m);
  const double floor = 1e-12 * mag;
  std::vector<std::pair<double, double>> out;
  std::vector<BernsteinPolynomial> stack{BernsteinPolynomial(D.c)};
  while (!stack.empty()) {
    const BernsteinPolynomial q = std::move(stack.back());
    stack.pop_back();
    if (q.minCoefficient() > floor) continue;  // apart on [lower, upper]
    if (q.width() <= kReductionWindowResolution) {
      if (!out.empty() && out.back().second >= q.lower()) out.back().second = q.upper();
      else out.emplace_back(q.lower(), q.upper());
      continue;
    }
    auto [lo, hi] = q.subdivide(0.5 * (q.lower() + q.upper()));
    stack.push_back(std::move(hi));  // lo first: windows come out in increasing order
    stack.push_back(std::move(lo));
  }
  return out;
}

// "<type> subproblem <element of a>/<element of b> <why>": the reason of an Undecided answer.
std::string describe(const CcdSubproblem& sp, const std::string& why) {
  return std::string(toString(sp.type)) + " subproblem " + elementLabel(sp.kind_a, sp.index_a) + "/" +
         elementLabel(sp.kind_b, sp.index_b) + " " + why;
}

}  // namespace

ReductionCcdResult continuousCollideRegionsByReduction(const MovingRegion& a, const MovingRegion& b) {
  ReductionCcdResult res;
  if (!a.box || !b.box) {
    res.reason = "an unbounded body";
    return res;
  }
  const Body A = makeBody(a), B = makeBody(b);
  if (!A.unsupported.empty() || !B.unsupported.empty()) {
    res.reason = !A.unsupported.empty() ? "a: " + A.unsupported : "b: " + B.unsupported;
    return res;
  }
  std::vector<CcdSubproblem> sps = identifySubproblems(A.el, B.el);
  const auto emptyEdge = [](const Body& body, ElementKind kind, int index) {
    return kind == ElementKind::Edge && body.edges[index].empty;
  };
  sps.erase(std::remove_if(sps.begin(), sps.end(),
                           [&](const CcdSubproblem& sp) {
                             return emptyEdge(A, sp.kind_a, sp.index_a) || emptyEdge(B, sp.kind_b, sp.index_b);
                           }),
            sps.end());
  // A subproblem as reported: edges by their index in the bodies' own boundary elements.
  const auto reported = [&](CcdSubproblem sp) {
    if (sp.kind_a == ElementKind::Edge) sp.index_a = A.edge_origin[sp.index_a];
    if (sp.kind_b == ElementKind::Edge) sp.index_b = B.edge_origin[sp.index_b];
    return sp;
  };
  for (const CcdSubproblem& sp : sps)
    if (sp.type == SubproblemType::Curve) {
      res.reason = describe(reported(sp), "involves a quartic edge (thesis §6.5: not handled here)");
      return res;
    }
  const double size = std::max((a.box->hi - a.box->lo).maxCoeff(), (b.box->hi - b.box->lo).maxCoeff());
  const double band = kReductionVerifyRelative * size;

  // Start: the pair at t = 0 (static engine).
  {
    const Eigen::Matrix4d Xa = a.motion.evaluate(0.0), Xb = b.motion.evaluate(0.0);
    const Eigen::Matrix4d Xab = Xa.inverse() * Xb;
    const Eigen::Matrix3d R = Xab.topLeftCorner<3, 3>();
    if ((R.transpose() * R - Eigen::Matrix3d::Identity()).norm() > 1e-9 || std::fabs(Xab(3, 3) - 1.0) > 1e-12) {
      res.reason = "a non-rigid pose at t = 0";
      return res;
    }
    const RegionCollision c0 = collideRegions(a.region, *a.box, b.region, *b.box, R, Xab.block<3, 1>(0, 3));
    if (c0.relation != RegionRelation::Separated) {
      res.status = ReductionStatus::Decided;
      res.collide = true;
      res.time = 0.0;
      res.point = Xa.topLeftCorner<3, 3>() * c0.point + Xa.block<3, 1>(0, 3);
      return res;
    }
  }

  std::vector<double> breaks = a.motion.breaks();
  breaks.insert(breaks.end(), b.motion.breaks().begin(), b.motion.breaks().end());
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());

  // The spans solved: each piece's proximity windows, in global time.
  std::vector<std::pair<double, double>> spans;
  {
    const Eigen::Vector3d ca = 0.5 * (a.box->lo + a.box->hi), cb = 0.5 * (b.box->lo + b.box->hi);
    const double R = (0.5 * (a.box->hi - a.box->lo).norm() + 0.5 * (b.box->hi - b.box->lo).norm()) *
                     (1.0 + kReductionWindowPadRelative);
    for (std::size_t piece = 0; piece + 1 < breaks.size(); ++piece) {
      const double s0 = breaks[piece], s1 = breaks[piece + 1];
      const MotionMatrix ma = a.motion.restricted(s0, s1), mb = b.motion.restricted(s0, s1);
      const PMat Pinv =
          bernsteinProduct(bernsteinFromPower(ma.inverseCoefficients()), bernsteinFromPower(mb.matrixCoefficients()));
      for (const auto& [u0, u1] : proximityWindows(Pinv, ca, cb, R))
        spans.emplace_back(u0 == 0.0 ? s0 : s0 + (s1 - s0) * u0, u1 == 1.0 ? s1 : s0 + (s1 - s0) * u1);
    }
  }

  for (const std::pair<double, double>& span : spans) {
    const double s0 = span.first, s1 = span.second;
    // The pencil searches of this piece together (every pair of elements) may visit
    // kReductionMaxPencilBoxes boxes (docs/reliability.md finding 41).
    const long long piece_cap = res.pencil_boxes + kReductionMaxPencilBoxes;
    const MotionMatrix ma = a.motion.restricted(s0, s1), mb = b.motion.restricted(s0, s1);
    // The relative motion and its inverse in the Bernstein basis (file comment at PVec).
    const PMat P =
        bernsteinProduct(bernsteinFromPower(mb.inverseCoefficients()), bernsteinFromPower(ma.matrixCoefficients()));
    const PMat Pinv =
        bernsteinProduct(bernsteinFromPower(ma.inverseCoefficients()), bernsteinFromPower(mb.matrixCoefficients()));
    if (2 * static_cast<int>(P.size() - 1) > tolerance_region::kRegionCcdMaxDegree)
      throw CcdDegreeError("continuousCollideRegionsByReduction: relative motion of degree " + std::to_string(P.size() - 1) +
                               " exceeds kRegionCcdMaxDegree / 2 = " + std::to_string(tolerance_region::kRegionCcdMaxDegree / 2),
                           2 * static_cast<int>(P.size() - 1), tolerance_region::kRegionCcdMaxDegree);
    const Posed pa = pose(A, {Eigen::Matrix4d::Identity()}, {Eigen::Matrix4d::Identity()});
    const Posed pb = pose(B, P, Pinv);

    // The subproblems' polynomials and contact points.
    std::vector<Task> tasks;
    auto faceOf = [&](const Posed& p, const Body& body, int f) -> const PMat& { return p.atoms[body.el.faces[f].atom]; };
    for (const CcdSubproblem& sp : sps) {
      const bool a_first = sp.kind_a != ElementKind::Vertex && (sp.kind_a == ElementKind::Face || sp.kind_b == ElementKind::Edge);
      // Orient: (x, ix) is the element with the higher dimension (face before edge before vertex).
      const Posed& px = a_first ? pa : pb;
      const Posed& py = a_first ? pb : pa;
      const Body& bx = a_first ? A : B;
      const Body& by = a_first ? B : A;
      const int ix = a_first ? sp.index_a : sp.index_b, iy = a_first ? sp.index_b : sp.index_a;
      Task task;
      task.sp = sp;
      switch (sp.type) {
        case SubproblemType::FaceVertex: {
          const PMat& S = faceOf(px, bx, ix);
          for (const PVec& X : py.vertices[iy]) {
            Task t = task;
            t.g = form(X, S, X);
            t.value = [X, S](double u) {
              const Eigen::Vector4d x = at(X, u);
              return x.dot(at(S, u) * x);
            };
            t.points = [X](double u) { return std::vector<PointAt>{affine(at(X, u), 1.0)}; };
            tasks.push_back(std::move(t));
          }
          break;
        }
        case SubproblemType::QuadricLine: {
          const PMat& S = faceOf(px, bx, ix);
          const PVec &U = py.edgeU[iy], &D = py.edgeD[iy];
          const Poly qa = form(D, S, D), qb = form(D, S, U), qc = form(U, S, U);
          task.g = qb * qb - qa * qc;
          task.value = [S, U, D](double u) {
            const Eigen::Matrix4d Su = at(S, u);
            const Eigen::Vector4d Uu = at(U, u), Du = at(D, u);
            const double a2 = Du.dot(Su * Du), b2 = Du.dot(Su * Uu), c2 = Uu.dot(Su * Uu);
            return b2 * b2 - a2 * c2;
          };
          task.points = [S, U, D](double u) {
            const Eigen::Matrix4d Su = at(S, u);
            const Eigen::Vector4d Uu = at(U, u), Du = at(D, u);
            const double sa = Du.dot(Su * Du), sb = Du.dot(Su * Uu);
            if (std::fabs(sa) <= 1e-14 * Su.norm() * Du.squaredNorm()) return std::vector<PointAt>{PointAt()};
            return std::vector<PointAt>{affine(Uu - sb / sa * Du, 1.0)};
          };
          tasks.push_back(std::move(task));
          break;
        }
        case SubproblemType::QuadricPlane: {
          // Orient so that S is the curved face and π the plane.
          const bool x_planar = bx.el.faces[ix].planar();
          const Posed& pq = x_planar ? py : px;
          const Posed& pp = x_planar ? px : py;
          const Body& bq = x_planar ? by : bx;
          const int iq = x_planar ? iy : ix, ip = x_planar ? ix : iy;
          // A cylinder or a cone (singular S) touches a plane only along a generator, which ends
          // on the elements that bound the face (rims, the plane's edges, a cone's apex: its own
          // face-vertex tasks) and is found there. π^T adj(S) π only marks the moments the plane
          // is parallel to a cylinder's axis (k (π.z)^2, identically zero for a translation) or
          // passes through a cone's apex (k (π.v)^2, a double root the apex task finds).
          if (bq.singular[bq.el.faces[iq].atom]) break;
          const PMat& S = faceOf(pq, bq, iq);
          const PVec& pi = pp.planes[ip];
          task.g = -bordered(S, {pi});
          task.value = [S, pi](double u) {
            Eigen::Matrix<double, 5, 5> M = Eigen::Matrix<double, 5, 5>::Zero();
            M.topLeftCorner<4, 4>() = at(S, u);
            M.block<4, 1>(0, 4) = at(pi, u);
            M.block<1, 4>(4, 0) = at(pi, u).transpose();
            return -M.fullPivLu().determinant();
          };
          task.points = [S, pi](double u) {
            const Eigen::Matrix4d Su = at(S, u);
            const Eigen::Vector4d p = at(pi, u);
            // The pole adj(S) π: for a regular S the solution of S X = π.
            Eigen::Vector4d x;
            if (!detail::fullPivLuSolve(Su, p, &x)) return std::vector<PointAt>{PointAt()};  // cylinder: at infinity
            return std::vector<PointAt>{affine(x, 1.0)};
          };
          tasks.push_back(std::move(task));
          break;
        }
        case SubproblemType::PlaneConic: {
          const PVec& p1 = px.planes[ix];
          const PVec& p2 = py.edgePlane[iy];
          const PMat& S = py.atoms[by.edges[iy].quadric];
          task.g = bordered(S, {p1, p2});
          task.value = [S, p1, p2](double u) {
            Eigen::Matrix<double, 6, 6> M = Eigen::Matrix<double, 6, 6>::Zero();
            M.topLeftCorner<4, 4>() = at(S, u);
            M.block<4, 1>(0, 4) = at(p1, u);
            M.block<4, 1>(0, 5) = at(p2, u);
            M.block<1, 4>(4, 0) = at(p1, u).transpose();
            M.block<1, 4>(5, 0) = at(p2, u).transpose();
            return M.fullPivLu().determinant();
          };
          task.points = [S, p1, p2, band](double u) {
            const Eigen::Vector4d q1 = at(p1, u), q2 = at(p2, u);
            Eigen::Vector3d x, d;
            if (!lineOfPlanes(q1, q2, &x, &d)) {
              // Parallel planes (a cap parallel to the face): their line is at infinity, so no
              // contact unless they coincide (the conic lying in the face's plane: degenerate).
              const double n1 = q1.head<3>().norm(), n2 = q2.head<3>().norm();
              const double sign = q1.head<3>().dot(q2.head<3>()) > 0.0 ? 1.0 : -1.0;
              const double gap = std::fabs(q1[3] / n1 - sign * q2[3] / n2);
              return std::vector<PointAt>{gap > band ? PointAt() : degenerate()};
            }
            d.normalize();
            const Eigen::Matrix4d Su = at(S, u);
            const Eigen::Vector4d U(x[0], x[1], x[2], 1.0), D(d[0], d[1], d[2], 0.0);
            const double sa = D.dot(Su * D), sb = D.dot(Su * U);
            if (std::fabs(sa) <= 1e-14 * Su.norm()) return std::vector<PointAt>{PointAt()};
            return std::vector<PointAt>{affine(U - sb / sa * D, 1.0)};
          };
          tasks.push_back(std::move(task));
          break;
        }
        case SubproblemType::ConicLine: {
          // x: the conic edge, y: the line edge (either body).
          const bool x_line = bx.edges[ix].line;
          const Posed& pc = x_line ? py : px;
          const Posed& pl = x_line ? px : py;
          const Body& bc = x_line ? by : bx;
          const int ic = x_line ? iy : ix, il = x_line ? ix : iy;
          const PVec& pi = pc.edgePlane[ic];
          const PMat& S = pc.atoms[bc.edges[ic].quadric];
          const PVec &U = pl.edgeU[il], &D = pl.edgeD[il];
          // X = (π.D) U - (π.U) D: the line's point in the conic's plane.
          // U and D are points of one body: X and Y have the same Bernstein degree.
          PVec X = scaled(U, dot(pi, D));
          const PVec Y = scaled(D, dot(pi, U));
          for (std::size_t k = 0; k < Y.size() && k < X.size(); ++k) X[k] -= Y[k];
          task.g = form(X, S, X);
          task.value = [X, S](double u) {
            const Eigen::Vector4d x = at(X, u);
            return x.dot(at(S, u) * x);
          };
          task.points = [X, S, pi, U, D, band](double u) {
            const Eigen::Vector4d p = at(pi, u), Uu = at(U, u), Du = at(D, u);
            const double n = p.head<3>().norm();
            const Eigen::Vector3d x = Uu.head<3>() / Uu[3], d = Du.head<3>().normalized();
            if (std::fabs(p.head<3>().dot(d)) > 1e-9 * n) return std::vector<PointAt>{affine(at(X, u), 1.0)};
            // The line is parallel to the conic's plane: it meets the conic only when it lies in
            // the plane (within the band), where it crosses the conic at the roots of the
            // quadric along it (or touches it).
            if (std::fabs(p.head<3>().dot(x) + p[3]) > band * n) return std::vector<PointAt>{PointAt()};
            const Eigen::Matrix4d Su = at(S, u);
            const Eigen::Vector4d X0(x[0], x[1], x[2], 1.0), D0(d[0], d[1], d[2], 0.0);
            const double qa = D0.dot(Su * D0), qb = D0.dot(Su * X0), qc = X0.dot(Su * X0);
            std::vector<PointAt> out;
            auto push = [&](double s) {
              PointAt q;
              q.kind = PointAt::Point;
              q.x = x + s * d;
              out.push_back(q);
            };
            if (std::fabs(qa) <= 1e-14 * Su.norm()) {
              if (qb != 0.0) push(-0.5 * qc / qb);
            } else {
              const double disc = qb * qb - qa * qc;
              const double r = disc > 0.0 ? std::sqrt(disc) : 0.0;
              push((-qb - r) / qa);
              push((-qb + r) / qa);
            }
            return out;
          };
          tasks.push_back(std::move(task));
          break;
        }
        case SubproblemType::LineLine: {
          const PVec &U1 = px.edgeU[ix], &D1 = px.edgeD[ix], &U2 = py.edgeU[iy], &D2 = py.edgeD[iy];
          task.g = det4(U1, D1, U2, D2);
          task.value = [U1, D1, U2, D2](double u) {
            Eigen::Matrix4d M;
            M << at(U1, u), at(D1, u), at(U2, u), at(D2, u);
            return M.determinant();
          };
          task.points = [U1, D1, U2, D2](double u) {
            const Eigen::Vector4d u1 = at(U1, u), d1 = at(D1, u), u2 = at(U2, u), d2 = at(D2, u);
            const Eigen::Vector3d x1 = u1.head<3>() / u1[3], x2 = u2.head<3>() / u2[3];
            const Eigen::Vector3d e1 = d1.head<3>(), e2 = d2.head<3>();
            const Eigen::Vector3d n = e1.cross(e2);
            if (n.norm() <= 1e-12 * e1.norm() * e2.norm()) return std::vector<PointAt>{degenerate()};
            // Closest points: x1 + s e1, x2 + r e2.
            const Eigen::Vector3d w = x2 - x1;
            const double s = w.cross(e2).dot(n) / n.squaredNorm(), r = w.cross(e1).dot(n) / n.squaredNorm();
            PointAt p;
            p.kind = PointAt::Point;
            p.x = 0.5 * ((x1 + s * e1) + (x2 + r * e2));
            return std::vector<PointAt>{p};
          };
          tasks.push_back(std::move(task));
          break;
        }
        case SubproblemType::QuadricQuadric: {
          // §6.2.2 face-face: a double root of det(λ A - S(u)) (a's face A is constant).
          const Eigen::Matrix4d Aq = A.sgn[A.el.faces[sp.index_a].atom];
          const PMat& S = pb.atoms[B.el.faces[sp.index_b].atom];
          PolyMatrix M1(4, std::vector<Poly>(4)), M2(4, std::vector<Poly>(4));
          for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) {
              M1[i][j] = entry(PMat{Aq}, i, j);
              M2[i][j] = entry(S, i, j);
            }
          task.configuration = [Aq, S](double u) -> std::optional<ContactConfiguration> {
            const Eigen::Matrix4d Bu = at(S, u);
            for (double lambda : multipleRoots(Aq, Bu))
              if (lambda < 0.0) return contactConfiguration(Aq, Bu, lambda);
            return std::nullopt;
          };
          // det(-S) and det(A) vanish identically only for a singular face (makeBody's rank test).
          const RegularEnds regular{!B.singular[B.el.faces[sp.index_b].atom], !A.singular[A.el.faces[sp.index_a].atom]};
          pencilTask(task, characteristic(M1, M2),
                          [Aq, S](double u, double sigma) { return numericCharacteristic(Aq, at(S, u), Eigen::MatrixXd(4, 0), 5, sigma); },
                          [Aq, S](double u, double lambda) {
                const Eigen::Matrix4d Su = at(S, u);
                const bool inf = std::isinf(lambda);
                std::vector<PointAt> out;
                for (const Eigen::VectorXd& X : nullPoints(inf ? Aq : Eigen::Matrix4d(lambda * Aq - Su), inf ? Su : Aq))
                  out.push_back(affine(X, 1.0));
                return out;
              },
              &tasks, regular);
          tasks.push_back(std::move(task));
          break;
        }
        case SubproblemType::QuadricConic: {
          // §6.2.2 quadric-conic: the quadric's section by the conic's plane against the conic,
          // in the plane's coordinates y (X = E y).
          const bool conic_in_a = sp.kind_a == ElementKind::Edge;
          const Body& bc = conic_in_a ? A : B;
          const Posed& pc = conic_in_a ? pa : pb;
          const Posed& pf = conic_in_a ? pb : pa;
          const Body& bf = conic_in_a ? B : A;
          const int ie = conic_in_a ? sp.index_a : sp.index_b, jf = conic_in_a ? sp.index_b : sp.index_a;
          const std::array<PVec, 3> E = pc.edgeBasis[ie];
          const Eigen::Matrix3d Cc = bc.edges[ie].conic;
          const PMat& S = pf.atoms[bf.el.faces[jf].atom];
          PolyMatrix M1(3, std::vector<Poly>(3)), M2(3, std::vector<Poly>(3));
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
              M1[i][j].add(0, Cc(i, j), std::fabs(Cc(i, j)));
              M2[i][j] = form(E[i], S, E[j]);
            }
          auto restricted = [S, E](double u) {
            Eigen::Matrix<double, 4, 3> Eu;
            for (int k = 0; k < 3; ++k) Eu.col(k) = at(E[k], u);
            return Eigen::Matrix3d(Eu.transpose() * at(S, u) * Eu);
          };
          pencilTask(task, characteristic(M1, M2),
                          [Cc, restricted](double u, double sigma) {
                            return numericCharacteristic(Cc, restricted(u), Eigen::MatrixXd(3, 0), 4, sigma);
                          },
                          [Cc, S, E](double u, double lambda) {
                Eigen::Matrix<double, 4, 3> Eu;
                for (int k = 0; k < 3; ++k) Eu.col(k) = at(E[k], u);
                const Eigen::Matrix3d Cf = Eu.transpose() * at(S, u) * Eu;
                const bool inf = std::isinf(lambda);
                std::vector<PointAt> out;
                for (const Eigen::VectorXd& y : nullPoints(inf ? Cc : Eigen::Matrix3d(lambda * Cc - Cf), inf ? Cf : Cc))
                  out.push_back(affine(Eu * y, 1.0));
                return out;
              },
              &tasks, RegularEnds{});
          tasks.push_back(std::move(task));
          break;
        }
        case SubproblemType::ConicConic: {
          // §6.2.2 conic-conic, reduced to 1D: on the line ℓ = π_a ∩ π_b (in a's conic plane
          // coordinates y) the two conics cut intervals; they touch when the two binary forms
          // share a root: the bordered pencil det [[λ C_a - C_b', ℓ], [ℓ^T, 0]] (quadratic in
          // λ) has a double root. C_b' is b's conic quadric cut by a's plane, which agrees with
          // b's conic on ℓ.
          const EdgeGeometry& ea = A.edges[sp.index_a];
          const Eigen::Matrix3d Ca = ea.conic;
          const Eigen::Matrix<double, 4, 3> Ea = ea.basis;
          const PMat& Sb = pb.atoms[B.edges[sp.index_b].quadric];
          const PVec& pib = pb.edgePlane[sp.index_b];
          PolyMatrix M1(3, std::vector<Poly>(3)), M2(3, std::vector<Poly>(3));
          std::vector<Poly> ell(3);
          for (int i = 0; i < 3; ++i) {
            ell[i] = dot(PVec{Ea.col(i)}, pib);
            for (int j = 0; j < 3; ++j) {
              M1[i][j].add(0, Ca(i, j), std::fabs(Ca(i, j)));
              M2[i][j] = form(PVec{Ea.col(i)}, Sb, PVec{Ea.col(j)});
            }
          }
          pencilTask(task, characteristic(M1, M2, {ell}),
                          [Ca, Ea, Sb, pib](double u, double sigma) {
                            const Eigen::Matrix3d Cb = Ea.transpose() * at(Sb, u) * Ea;
                            const Eigen::MatrixXd l = Ea.transpose() * at(pib, u);
                            return numericCharacteristic(Ca, Cb, l, 3, sigma);
                          },
                          [Ca, Ea, pib](double u, double) {
                // The points of a's conic on ℓ (the candidate point is one of them).
                const Eigen::Vector3d l = Ea.transpose() * at(pib, u);
                const double nl = l.head<2>().norm();
                std::vector<PointAt> out;
                if (nl <= 1e-12 * l.norm()) return out;  // the planes are parallel
                const Eigen::Vector3d y0(-l[2] * l[0] / (nl * nl), -l[2] * l[1] / (nl * nl), 1.0), d(-l[1] / nl, l[0] / nl, 0.0);
                const double qa = d.dot(Ca * d), qb = d.dot(Ca * y0), qc = y0.dot(Ca * y0);
                const double disc = qb * qb - qa * qc;
                if (std::fabs(qa) <= 1e-14 * Ca.norm() || disc < -1e-9 * (qb * qb + std::fabs(qa * qc))) return out;
                const double r = disc > 0.0 ? std::sqrt(disc) : 0.0;
                for (double sgn : {-1.0, 1.0}) out.push_back(affine(Ea * (y0 + ((-qb + sgn * r) / qa) * d), 1.0));
                return out;
              },
              &tasks, RegularEnds{});
          tasks.push_back(std::move(task));
          break;
        }
        case SubproblemType::PlaneLine:  // found on the bounding elements (file comment)
        default: break;
      }
    }
    // Cone apexes against every face of the other body (a face-vertex condition at the apex;
    // no exclusion: a convex tip can first touch a concave face). Its contacts with edges and
    // vertices are not generic (thesis §6.1).
    int apex_tasks = 0;
    for (const bool apex_in_a : {true, false}) {
      const Body& bv = apex_in_a ? A : B;
      const Body& bf = apex_in_a ? B : A;
      const Posed& pv = apex_in_a ? pa : pb;
      const Posed& pf = apex_in_a ? pb : pa;
      for (std::size_t k = 0; k < bv.apexes.size(); ++k)
        for (std::size_t j = 0; j < bf.el.faces.size(); ++j) {
          Task t;
          t.sp.type = SubproblemType::FaceVertex;
          t.sp.kind_a = apex_in_a ? ElementKind::Apex : ElementKind::Face;
          t.sp.index_a = apex_in_a ? bv.apexes[k].first : static_cast<int>(j);
          t.sp.kind_b = apex_in_a ? ElementKind::Face : ElementKind::Apex;
          t.sp.index_b = apex_in_a ? static_cast<int>(j) : bv.apexes[k].first;
          const PMat& S = faceOf(pf, bf, static_cast<int>(j));
          const PVec& X = pv.apexes[k];
          t.g = form(X, S, X);
          t.value = [X, S](double u) {
            const Eigen::Vector4d x = at(X, u);
            return x.dot(at(S, u) * x);
          };
          t.points = [X](double u) { return std::vector<PointAt>{affine(at(X, u), 1.0)}; };
          tasks.push_back(std::move(t));
          ++apex_tasks;
        }
    }
    res.subproblems += static_cast<int>(sps.size()) + apex_tasks;

    // Candidates: roots and near-zero extrema of each g, sorted by time.
    struct Candidate {
      double u;
      std::size_t task;
    };
    std::vector<Candidate> cands;
    for (std::size_t k = 0; k < tasks.size(); ++k) {
      Poly& g = tasks[k].g;
      if (g.c.empty()) continue;  // pencil tasks (seeds above), or no candidate
      double cmax = 0.0, mmax = 0.0;
      for (std::size_t i = 0; i < g.c.size(); ++i) {
        cmax = std::max(cmax, std::fabs(g.c[i]));
        mmax = std::max(mmax, g.mag[i]);
      }
      if (cmax <= kReductionZeroRelative * mmax) {
        // A line permanently tangent to (or lying on) a quadric face: a box edge parallel to a
        // cylinder's axis, an edge sliding along a sphere. Its contact is a segment or a moving
        // point that exists over a whole interval of time, so it begins at t = 0 (the start
        // test), or where it enters the edge or the face: at a vertex of the edge (face-vertex)
        // or on an edge that bounds the face (conic-line, line-line). It is found there, as a
        // plane-line contact is; no candidate of its own.
        if (tasks[k].sp.type == SubproblemType::QuadricLine) continue;
        res.reason = describe(reported(tasks[k].sp), "is degenerate (identically zero)");
        return res;
      }
      std::vector<double> c = g.c;
      const double inv = 1.0 / cmax;
      for (double& v : c) v *= inv;
      const BernsteinPolynomial bp(c);
      auto seed = [&](double u) { return tasks[k].value ? refineNumerically(tasks[k].value, u) : u; };
      for (const RootInterval& r : isolateRoots(bp, kReductionRootWidth)) cands.push_back({seed(refined(bp, r)), k});
      // Grazing candidates: extrema with |g| near zero.
      const BernsteinPolynomial dp = bp.derivative();
      std::vector<double> mag = g.mag;
      for (double& v : mag) v *= inv;
      const BernsteinPolynomial pm(mag);
      for (const RootInterval& r : isolateRoots(dp, kReductionRootWidth)) {
        const double u = refined(dp, r);
        if (std::fabs(bp.evaluate(u)) <= kReductionNearRootRelative * std::max(pm(u), 1e-300)) cands.push_back({seed(u), k});
      }
    }
    std::sort(cands.begin(), cands.end(), [](const Candidate& x, const Candidate& y) { return x.u < y.u; });

    // Verification (Figure 29 predicates with the band); the earliest verified candidate wins.
    double best = 2.0;  // piece time of the best verified contact
    std::string degenerate_reason;
    auto verify = [&](const Task& task, double u) {
      ++res.candidates;
      std::vector<Eigen::Matrix4d> posedA, posedB;
      for (const PMat& S : pa.raw) posedA.push_back(at(S, u));
      for (const PMat& S : pb.raw) posedB.push_back(at(S, u));
      for (const PointAt& p : task.points(u)) {
        if (p.kind == PointAt::Degenerate) {
          degenerate_reason = describe(reported(task.sp), "has a degenerate contact point");
          return false;
        }
        if (p.kind != PointAt::Point) continue;
        std::size_t ka = 0, kb = 0;
        if (classifyBand(a.region, posedA, &ka, p.x, band) < 0) continue;
        if (classifyBand(b.region, posedB, &kb, p.x, band) < 0) continue;
        if (u < best) {
          best = u;
          res.time = s0 + (s1 - s0) * u;
          const Eigen::Matrix4d Xa = a.motion.evaluate(res.time);
          res.point = Xa.topLeftCorner<3, 3>() * p.x + Xa.block<3, 1>(0, 3);
          res.subproblem = reported(task.sp);
          res.label_a = elementLabel(res.subproblem.kind_a, res.subproblem.index_a);
          res.label_b = elementLabel(res.subproblem.kind_b, res.subproblem.index_b);
          res.configuration = task.configuration ? task.configuration(u) : std::nullopt;
        }
        return true;
      }
      return false;
    };
    // A degenerate candidate (a conic lying in a face's plane) makes the answer Undecided unless
    // a candidate within kReductionDegenerateWindow after it verifies: the same contact seen
    // through an exact root (a cone's apex landing on the face whose plane then holds the apex's
    // point conic, while the conic's own graze is located to about sqrt(eps) only).
    double degenerate_at = 2.0;
    for (const Candidate& cd : cands) {
      if (!degenerate_reason.empty() && cd.u > degenerate_at + kReductionDegenerateWindow) break;
      const bool had_degenerate = !degenerate_reason.empty();
      if (verify(tasks[cd.task], cd.u)) {
        degenerate_reason.clear();
        break;
      }
      if (!had_degenerate && !degenerate_reason.empty()) degenerate_at = cd.u;
    }
    // Pencil tasks: their seeds, only before the best contact so far. Two passes: each search
    // first runs for kPencilFirstPassBoxes boxes; those that need more are paused and go on
    // after every other search has had its turn, pruned by the contacts found meanwhile
    // (dimension_reduction_ccd.h).
    std::vector<std::size_t> order, paused;
    for (std::size_t k = 0; k < tasks.size(); ++k)
      if (!tasks[k].pencil.empty()) order.push_back(k);
    std::vector<TangencySearch> searches(tasks.size());
    for (int pass = 0; pass < 2 && degenerate_reason.empty(); ++pass) {
      for (const std::size_t k : pass == 0 ? order : paused) {
        const Task& task = tasks[k];
        // Each seed is tried at its Newton solution of (F, F_x) = 0, then refined on the pencil's
        // discriminant evaluated at u (which fails for a permanent multiple root: spheres), then on
        // f at its negative critical point (which does not).
        // A seed within a chain (after > -infinity) looks for the next root past the one tried.
        auto seed = [&](double centre, std::optional<double> newton, double after) {
          if (newton && *newton > after && *newton < best && verify(task, *newton)) return SeedOutcome{best, best};
          const double u = refineNumerically(task.value, centre, after);
          if (u < best && verify(task, u)) return SeedOutcome{best, best};
          const double uc = refineNumerically(task.critical_value, centre, after);
          if (uc != u && uc < best && verify(task, uc)) return SeedOutcome{best, best};
          return SeedOutcome{2.0, std::max({u, uc, newton.value_or(centre)})};
        };
        const long long pause_at =
            pass == 0 ? res.pencil_boxes + kPencilFirstPassBoxes : std::numeric_limits<long long>::max();
        const SearchEnd end =
            tangencySeeds(task.pencil, std::min(best, 1.0), &res.pencil_boxes, pause_at, piece_cap, &searches[k], seed);
        if (end == SearchEnd::Paused) {
          paused.push_back(k);
          continue;
        }
        if (end == SearchEnd::Failed) {
          res.reason =
              res.pencil_boxes > piece_cap
                  ? describe(reported(task.sp), "reached the piece's pencil work cap (kReductionMaxPencilBoxes)")
                  : describe(reported(task.sp), "has a curve of multiple roots (subdivision cap reached)");
          return res;
        }
      }
    }
    if (!degenerate_reason.empty()) {
      res.reason = degenerate_reason;
      return res;
    }
    if (best <= 1.0) {
      res.status = ReductionStatus::Decided;
      res.collide = true;
      return res;
    }
  }
  res.status = ReductionStatus::Decided;
  res.collide = false;
  res.time = 1.0;
  return res;
}

}  // namespace fcl_quadric
