#include "fcl_quadric/continuous/motion_matrix.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "fcl_quadric/algebra/bernstein_polynomial.h"
#include "fcl_quadric/algebra/root_isolation.h"
#include "fcl_quadric/geometry/ellipsoid.h"
#include "fcl_quadric/tolerances.h"

namespace fcl_quadric {

namespace detail {

void checkNoRootOnUnitInterval(const Polynomial& p, const char* what) {
  const BernsteinPolynomial b = BernsteinPolynomial::fromPower(p.trimmed(), 0.0, 1.0);
  if (b.minCoefficient() > 0.0 || b.maxCoefficient() < 0.0) return;  // convex hull: no root
  if (b.isZero()) throw std::invalid_argument(std::string(what) + " is identically zero on [0, 1]");
  // Root-free certification by Descartes subdivision; any reported interval (even Unresolved,
  // which may hold no root) is treated as a root: a motion we cannot certify is rejected.
  const std::vector<RootInterval> roots = isolateRoots(b, 1e-12);
  if (!roots.empty()) {
    const RootInterval& r = roots.front();
    std::ostringstream os;
    os.precision(10);
    if (r.kind == RootKind::Single) {
      const double t = r.lo < r.hi ? refineRoot(b, r.lo, r.hi, 1e-12) : r.lo;
      os << what << " vanishes at t = " << t << " in [0, 1]";
    } else {
      os << what << " vanishes (or cannot be certified non-zero) at t in [" << r.lo << ", " << r.hi << "]";
    }
    throw std::invalid_argument(os.str());
  }
}

}  // namespace detail

namespace {

// det of the 3x3 block rows/cols {0,1,2} of M (the validation; N is built in extended precision).
Polynomial det3(const PolynomialMatrix4& M) {
  return M(0, 0) * (M(1, 1) * M(2, 2) - M(1, 2) * M(2, 1)) - M(0, 1) * (M(1, 0) * M(2, 2) - M(1, 2) * M(2, 0)) +
         M(0, 2) * (M(1, 0) * M(2, 1) - M(1, 1) * M(2, 0));
}

// Drops trailing zero coefficient matrices (keeps at least one).
template <class Mat>
std::vector<Mat> trimmedCoefficients(std::vector<Mat> c) {
  while (c.size() > 1 && c.back().isZero(0)) c.pop_back();
  return c;
}

PolynomialMatrix4 fromCoefficientMatrices(const std::vector<Eigen::Matrix4d>& c) {
  PolynomialMatrix4 M = PolynomialMatrix4::fromCoefficients(c);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) M(i, j) = M(i, j).trimmed();
  return M;
}

// sum_k A_k t^k times sum_l B_l t^l.
template <class Mat>
std::vector<Mat> convolve(const std::vector<Mat>& A, const std::vector<Mat>& B) {
  std::vector<Mat> C(A.size() + B.size() - 1, Mat::Zero());
  for (std::size_t k = 0; k < A.size(); ++k)
    for (std::size_t l = 0; l < B.size(); ++l) C[k + l].noalias() += A[k] * B[l];
  return C;
}

// Coefficients of s -> M(t0 + h s): sum_j s^j sum_{k >= j} C(k, j) t0^(k-j) h^j M_k.
template <class Mat>
std::vector<Mat> composeAffine(const std::vector<Mat>& M, double h, double t0) {
  using T = typename Mat::Scalar;
  const int d = static_cast<int>(M.size()) - 1;
  std::vector<Mat> R(d + 1, Mat::Zero());
  for (int k = 0; k <= d; ++k) {
    T hj = 1;
    for (int j = 0; j <= k; ++j, hj *= h) R[j] += (static_cast<T>(detail::binomial(k, j)) * std::pow(static_cast<T>(t0), k - j) * hj) * M[k];
  }
  return R;
}

// Polynomials with long double coefficients (power basis), for N in extended precision.
using PolyL = std::vector<long double>;
PolyL mul(const PolyL& a, const PolyL& b) {
  PolyL c(a.size() + b.size() - 1, 0.0L);
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j) c[i + j] += a[i] * b[j];
  return c;
}
PolyL axpy(long double s, const PolyL& a, const PolyL& b) {  // s a + b
  PolyL c(std::max(a.size(), b.size()), 0.0L);
  for (std::size_t i = 0; i < a.size(); ++i) c[i] += s * a[i];
  for (std::size_t i = 0; i < b.size(); ++i) c[i] += b[i];
  return c;
}
using PolyMatL = std::array<std::array<PolyL, 4>, 4>;
PolyMatL extended(const PolynomialMatrix4& M) {
  PolyMatL R;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) R[i][j] = PolyL(M(i, j).coefficients().begin(), M(i, j).coefficients().end());
  return R;
}
std::vector<Matrix4ld> coefficientMatrices(const PolyMatL& M) {
  std::size_t n = 1;
  for (const auto& row : M)
    for (const PolyL& p : row) n = std::max(n, p.size());
  std::vector<Matrix4ld> C(n, Matrix4ld::Zero());
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      for (std::size_t k = 0; k < M[i][j].size(); ++k) C[k](i, j) = M[i][j][k];
  return C;
}
// 2x2 minor of the 3x3 block: rows r0, r1, columns c0, c1.
PolyL minor2(const PolyMatL& M, int r0, int r1, int c0, int c1) {
  return axpy(-1.0L, mul(M[r0][c1], M[r1][c0]), mul(M[r0][c0], M[r1][c1]));
}

}  // namespace

MotionMatrix::MotionMatrix() : MotionMatrix({Eigen::Matrix4d::Identity()}, {Matrix4ld::Identity()}, true) {}

MotionMatrix::MotionMatrix(std::vector<Eigen::Matrix4d> M, std::vector<Matrix4ld> N, bool rigid)
    : Mk_(trimmedCoefficients(std::move(M))), Nk_ext_(trimmedCoefficients(std::move(N))), rigid_(rigid) {
  Nk_.reserve(Nk_ext_.size());
  for (const Matrix4ld& n : Nk_ext_) Nk_.push_back(n.cast<double>());
}

double MotionMatrix::linearCondition() const {
  double worst = 0.0;
  for (double t : {0.0, 0.5, 1.0}) {
    const Eigen::Matrix3d L = evaluate(t).topLeftCorner<3, 3>();
    // A map that overflows, or whose determinant underflows, has no usable inverse.
    if (!L.array().isFinite().all()) return std::numeric_limits<double>::infinity();
    // On L scaled by the power of two 2^-e that brings its largest entry into [0.5, 1) (exact):
    // no product of entries overflows (entries of 1e106 made inf - inf, a NaN, in the cofactors:
    // docs/reliability.md finding 42). The cofactors are the cross products of the rows, det the
    // expansion along row 0, det(L) = det(L 2^-e) 2^(3e) (by ldexp: inf or 0, never NaN), and
    // |L^-1| = |adj L| / |det L|, scale-free like the condition number: one division, by the
    // non-zero det of these very cofactors (Eigen's inverse forms its own determinant, which
    // came out 0 for a nearly singular L whose determinant() did not).
    int e = 0;
    std::frexp(L.cwiseAbs().maxCoeff(), &e);
    const Eigen::Matrix3d Ls = L * std::ldexp(1.0, -e);
    Eigen::Matrix3d C;
    C.row(0) = Ls.row(1).cross(Ls.row(2));
    C.row(1) = Ls.row(2).cross(Ls.row(0));
    C.row(2) = Ls.row(0).cross(Ls.row(1));
    const double det_s = Ls.row(0).dot(C.row(0));
    if (!std::isnormal(std::ldexp(det_s, 3 * e))) return std::numeric_limits<double>::infinity();
    worst = std::max(worst, Ls.norm() * (C.norm() / std::fabs(det_s)));
  }
  return worst;
}

PolynomialMatrix4 MotionMatrix::matrix() const { return fromCoefficientMatrices(Mk_); }
PolynomialMatrix4 MotionMatrix::inverse() const { return fromCoefficientMatrices(Nk_); }

MotionMatrix MotionMatrix::constant(const Eigen::Matrix3d& R, const Eigen::Vector3d& p) {
  return fromPoses(R, p, R, p);
}

MotionMatrix MotionMatrix::fromPoses(const Eigen::Isometry3d& X0, const Eigen::Isometry3d& X1) {
  return fromPoses(X0.linear(), X0.translation(), X1.linear(), X1.translation());
}

MotionMatrix MotionMatrix::fromPoses(const Eigen::Matrix3d& R0, const Eigen::Vector3d& p0, const Eigen::Matrix3d& R1,
                                     const Eigen::Vector3d& p1) {
  detail::checkRotation(R0, "motion start rotation");
  detail::checkRotation(R1, "motion end rotation");
  detail::checkFinite(p0, "motion start translation");
  detail::checkFinite(p1, "motion end translation");
  Eigen::Quaterniond q0(R0), q1(R1);
  q0.normalize();
  q1.normalize();
  if (q0.coeffs().dot(q1.coeffs()) < 0.0) q1.coeffs() = -q1.coeffs();
  // Euler parameters e(t) = e_a + t e_b, e = (e0, e1, e2, e3) = (w, x, y, z) (thesis §5.1). The
  // unnormalised rotation R~(e) is a quadratic form of e, so R~(t) = R~(e_a) + t (R~(e_a + e_b) -
  // R~(e_a) - R~(e_b)) + t^2 R~(e_b); E(t) = |e(t)|^2 likewise. Built on coefficient matrices.
  auto rotation = [](const Eigen::Vector4d& e) {
    Eigen::Matrix3d R;
    R << e[0] * e[0] + e[1] * e[1] - e[2] * e[2] - e[3] * e[3], 2 * (e[1] * e[2] - e[0] * e[3]),
        2 * (e[0] * e[2] + e[1] * e[3]), 2 * (e[0] * e[3] + e[1] * e[2]),
        e[0] * e[0] - e[1] * e[1] + e[2] * e[2] - e[3] * e[3], 2 * (e[2] * e[3] - e[0] * e[1]),
        2 * (e[1] * e[3] - e[0] * e[2]), 2 * (e[0] * e[1] + e[2] * e[3]),
        e[0] * e[0] - e[1] * e[1] - e[2] * e[2] + e[3] * e[3];
    return R;
  };
  const Eigen::Vector4d ea(q0.w(), q0.x(), q0.y(), q0.z());
  const Eigen::Vector4d eb = Eigen::Vector4d(q1.w(), q1.x(), q1.y(), q1.z()) - ea;
  const Eigen::Matrix3d Ra = rotation(ea), Rb = rotation(eb);
  const Eigen::Matrix3d Rk[3] = {Ra, rotation(ea + eb) - Ra - Rb, Rb};
  const double Ek[3] = {ea.squaredNorm(), 2.0 * ea.dot(eb), eb.squaredNorm()};
  const Eigen::Vector3d pk[2] = {p0, p1 - p0};
  std::vector<Eigen::Matrix4d> Mk(4, Eigen::Matrix4d::Zero());
  std::vector<Matrix4ld> Nk(4, Matrix4ld::Zero());
  for (int k = 0; k < 3; ++k) {
    Mk[k].topLeftCorner<3, 3>() = Rk[k];
    Nk[k].topLeftCorner<3, 3>() = Rk[k].transpose().cast<long double>();
    Mk[k](3, 3) = Ek[k];
    Nk[k](3, 3) = Ek[k];
    for (int l = 0; l < 2; ++l) {
      Mk[k + l].block<3, 1>(0, 3) += Ek[k] * pk[l];                                                    // E(t) p(t)
      Nk[k + l].block<3, 1>(0, 3) -= Rk[k].transpose().cast<long double>() * pk[l].cast<long double>();  // -R~(t)^T p(t)
    }
  }
  MotionMatrix m(std::move(Mk), std::move(Nk), true);
  m.linear_translation_ = std::make_pair(p0, p1);
  return m;
}

MotionMatrix MotionMatrix::fromPolynomialMatrix(const PolynomialMatrix4& M_given) {
  // Degree first: the validation below converts det L (degree up to 3 kMaxMotionDegree) to the
  // Bernstein form, and above kMaxBernsteinDegree that would overflow (session 34: a degree-2000
  // entry ran for 92 s before the CCD answered wrongly).
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      const int degree = M_given(i, j).trimmed().degree();
      if (degree > kMaxMotionDegree) {
        std::ostringstream os;
        os << "motion matrix entry (" << i << "," << j << ") has degree " << degree << " in t, above kMaxMotionDegree = "
           << kMaxMotionDegree;
        throw std::invalid_argument(os.str());
      }
    }
  }
  // M and s M are the same motion for any s != 0. Far outside [2^-32, 2^32] the products below
  // (det L, the adjugate, and the CCD function built from them) overflow to inf and NaN, and the
  // root certificates would run on garbage (found by fuzz_motion: coefficients ~1e300 passed
  // validation, then the CCD threw from deep inside). Rescale by a power of two: exact, and a
  // no-op for ordinary motions.
  double max_abs = 0.0;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) max_abs = std::max(max_abs, M_given(i, j).maxAbsCoefficient());
  // The translation and w(t) against the linear part: beyond kMaxLength apart, the motion moves
  // or shrinks the body out of the supported range, and the rescaling below would underflow
  // det L to zero (session 34's audit: a translation of 1e150 with L = I was rejected as "det of
  // the linear part identically zero").
  double max_linear = 0.0, max_rest = M_given(3, 3).maxAbsCoefficient();
  for (int i = 0; i < 3; ++i) {
    max_rest = std::max(max_rest, M_given(i, 3).maxAbsCoefficient());
    for (int j = 0; j < 3; ++j) max_linear = std::max(max_linear, M_given(i, j).maxAbsCoefficient());
  }
  if (max_linear > 0.0 && max_rest > tolerance::kMaxLength * max_linear) {
    std::ostringstream os;
    os << "motion matrix: the translation or w(t) coefficients (up to " << max_rest
       << ") exceed those of the linear part L(t) (up to " << max_linear << ") by more than kMaxLength = "
       << tolerance::kMaxLength << ": the motion leaves the supported range";
    throw std::invalid_argument(os.str());
  }
  // The last row as given: the rescaling below can flush a subnormal entry to zero (fuzz_motion,
  // session 52: (3, j) = 5e-324 beside coefficients of 1e300 was accepted; finding 43).
  for (int j = 0; j < 3; ++j) {
    if (!M_given(3, j).trimmed().isZero()) {
      std::ostringstream os;
      os << "motion matrix entry (3," << j << ") must be 0 (last row [0, 0, 0, w(t)]), has a coefficient of up to "
         << M_given(3, j).maxAbsCoefficient();
      throw std::invalid_argument(os.str());
    }
  }
  PolynomialMatrix4 M = M_given;
  if (max_abs > 0.0 && (max_abs > 0x1p32 || max_abs < 0x1p-32)) {
    int e = 0;
    (void)std::frexp(max_abs, &e);
    M = M_given * std::ldexp(1.0, -e);
  }
  const Polynomial& w = M(3, 3);
  detail::checkNoRootOnUnitInterval(w, "motion matrix w(t) = M(3,3)");
  const PolyMatL ML = extended(M);
  const Polynomial dl = det3(M);
  detail::checkNoRootOnUnitInterval(dl, "motion matrix det of the linear part L(t)");
  // Rigid (up to the scale w): L^T L = sigma I as polynomials, to rounding.
  {
    PolynomialMatrix4 G;
    double scale = 0.0, off = 0.0;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        G(i, j) = M(0, i) * M(0, j) + M(1, i) * M(1, j) + M(2, i) * M(2, j);
        scale = std::max(scale, G(i, j).maxAbsCoefficient());
      }
    }
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        const Polynomial d = i == j ? G(i, j) - G(0, 0) : G(i, j);
        off = std::max(off, d.maxAbsCoefficient());
      }
    }
    // ... and sigma = w^2, i.e. L / w is a rotation. Without it a similarity (L = s(t) R(t),
    // s != w: a uniformly scaling body) was flagged rigid, and the rigid-only shortcuts (world
    // ellipsoid without eigen-decomposition, bounding-sphere culls with the body radius) were
    // wrong for it (found by fuzz_motion: "ellipsoid rotation is not a rotation").
    off = std::max(off, (G(0, 0) - w * w).maxAbsCoefficient());
    if (scale > 0.0 && off <= 1e-13 * scale) {
      // N = [[w L^T, -L^T v], [0, sigma]] in extended precision.
      PolyMatL N;
      for (int i = 0; i < 3; ++i) {
        PolyL ltv{0.0L};
        for (int j = 0; j < 3; ++j) {
          N[i][j] = mul(ML[3][3], ML[j][i]);
          ltv = axpy(1.0L, mul(ML[j][i], ML[j][3]), ltv);
        }
        N[i][3] = axpy(-1.0L, ltv, PolyL{0.0L});
        N[3][i] = PolyL{0.0L};
      }
      N[3][3] = axpy(1.0L, mul(ML[0][0], ML[0][0]), axpy(1.0L, mul(ML[1][0], ML[1][0]), mul(ML[2][0], ML[2][0])));
      return MotionMatrix(coefficientMatrices(M), coefficientMatrices(N), true);
    }
  }
  // N = [[w adj L, -adj(L) v], [0, det L]] in extended precision (adj(L)(i, j) = cofactor(j, i)).
  PolyMatL N;
  PolyMatL adj;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      int r[2], c[2];
      for (int k = 0, n = 0; k < 3; ++k)
        if (k != j) r[n++] = k;
      for (int k = 0, n = 0; k < 3; ++k)
        if (k != i) c[n++] = k;
      const PolyL m = minor2(ML, r[0], r[1], c[0], c[1]);
      adj[i][j] = (i + j) % 2 == 0 ? m : axpy(-1.0L, m, PolyL{0.0L});
    }
  }
  for (int i = 0; i < 3; ++i) {
    PolyL adj_v{0.0L};
    for (int j = 0; j < 3; ++j) {
      N[i][j] = mul(ML[3][3], adj[i][j]);
      adj_v = axpy(1.0L, mul(adj[i][j], ML[j][3]), adj_v);
    }
    N[i][3] = axpy(-1.0L, adj_v, PolyL{0.0L});
    N[3][i] = PolyL{0.0L};
  }
  PolyL det{0.0L};
  for (int j = 0; j < 3; ++j) det = axpy(1.0L, mul(ML[0][j], adj[j][0]), det);
  N[3][3] = det;
  return MotionMatrix(coefficientMatrices(M), coefficientMatrices(N), false);
}

MotionMatrix MotionMatrix::compose(const MotionMatrix& outer, const MotionMatrix& inner) {
  return MotionMatrix(convolve(outer.Mk_, inner.Mk_), convolve(inner.Nk_ext_, outer.Nk_ext_), outer.rigid_ && inner.rigid_);
}

Eigen::Matrix4d MotionMatrix::homogeneous(double t) const {
  Eigen::Matrix4d m = Mk_.back();
  for (std::size_t k = Mk_.size() - 1; k-- > 0;) m = m * t + Mk_[k];
  return m;
}

Eigen::Matrix4d MotionMatrix::evaluate(double t) const {
  if (!std::isfinite(t)) throw std::invalid_argument("MotionMatrix::evaluate: non-finite t");
  const Eigen::Matrix4d m = homogeneous(t);
  return m / m(3, 3);
}

MotionMatrix MotionMatrix::restricted(double t0, double t1) const {
  if (!(t0 >= 0.0 && t0 < t1 && t1 <= 1.0)) {
    std::ostringstream os;
    os << "MotionMatrix::restricted: need 0 <= t0 < t1 <= 1, got [" << t0 << ", " << t1 << "]";
    throw std::invalid_argument(os.str());
  }
  std::vector<Eigen::Matrix4d> M = composeAffine(Mk_, t1 - t0, t0);
  std::vector<Matrix4ld> N = composeAffine(Nk_ext_, t1 - t0, t0);
  MotionMatrix r(std::move(M), std::move(N), rigid_);
  if (linear_translation_) {
    const auto& [p0, p1] = *linear_translation_;
    r.linear_translation_ = std::make_pair(Eigen::Vector3d(p0 + t0 * (p1 - p0)), Eigen::Vector3d(p0 + t1 * (p1 - p0)));
  }
  return r;
}

std::vector<Eigen::Matrix4d> multiplyCoefficients(const std::vector<Eigen::Matrix4d>& N,
                                                  const std::vector<Eigen::Matrix4d>& M) {
  return convolve(N, M);
}

std::vector<Eigen::Matrix4d> coefficientMatrices(const PolynomialMatrix4& M) {
  std::vector<Eigen::Matrix4d> Mk(M.maxDegree() + 1, Eigen::Matrix4d::Zero());
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      const std::vector<double>& c = M(i, j).coefficients();
      for (std::size_t k = 0; k < c.size(); ++k) Mk[k](i, j) = c[k];
    }
  }
  return Mk;
}

PolynomialMatrix4 coefficientMagnitudes(const PolynomialMatrix4& M) {
  PolynomialMatrix4 R;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      std::vector<double> c = M(i, j).coefficients();
      for (double& x : c) x = std::abs(x);
      R(i, j) = Polynomial(std::move(c));
    }
  }
  return R;
}

PolynomialMatrix4 congruence(const Eigen::Matrix4d& Q, const PolynomialMatrix4& N, const Eigen::Matrix4d& S) {
  return congruence(Q, coefficientMatrices(N), S);
}

PolynomialMatrix4 congruence(const Eigen::Matrix4d& Q, const std::vector<Eigen::Matrix4d>& N, const Eigen::Matrix4d& S) {
  const int d = static_cast<int>(N.size()) - 1;
  std::vector<Eigen::Matrix4d> Nk = N;
  for (Eigen::Matrix4d& m : Nk) m = m * S;
  std::vector<Eigen::Matrix4d> QN(d + 1);
  for (int k = 0; k <= d; ++k) QN[k] = Q * Nk[k];
  std::vector<Eigen::Matrix4d> A(2 * d + 1, Eigen::Matrix4d::Zero());
  for (int k = 0; k <= d; ++k)
    for (int l = 0; l <= d; ++l) A[k + l].noalias() += Nk[k].transpose() * QN[l];
  PolynomialMatrix4 R;
  std::vector<double> c(2 * d + 1);
  for (int i = 0; i < 4; ++i) {
    for (int j = i; j < 4; ++j) {
      for (int m = 0; m <= 2 * d; ++m) c[m] = 0.5 * (A[m](i, j) + A[m](j, i));
      R(i, j) = Polynomial(c).trimmed();
      R(j, i) = R(i, j);
    }
  }
  return R;
}

PolynomialMatrix4 movingQuadric(const Eigen::Matrix4d& Q_body, const MotionMatrix& motion) {
  return congruence(Q_body, motion.inverseCoefficients());
}

PiecewiseMotion::PiecewiseMotion(MotionMatrix motion) : breaks_{0.0, 1.0}, pieces_{std::move(motion)} {}

PiecewiseMotion::PiecewiseMotion(std::vector<double> breaks, std::vector<MotionMatrix> pieces)
    : breaks_(std::move(breaks)), pieces_(std::move(pieces)) {
  if (pieces_.empty() || breaks_.size() != pieces_.size() + 1) {
    std::ostringstream os;
    os << "PiecewiseMotion: need pieces.size() + 1 breaks, got " << breaks_.size() << " breaks for "
       << pieces_.size() << " pieces";
    throw std::invalid_argument(os.str());
  }
  if (breaks_.front() != 0.0 || breaks_.back() != 1.0)
    throw std::invalid_argument("PiecewiseMotion: breaks must start at 0 and end at 1");
  for (std::size_t k = 0; k + 1 < breaks_.size(); ++k) {
    if (!(breaks_[k] < breaks_[k + 1])) {
      std::ostringstream os;
      os << "PiecewiseMotion: breaks must increase strictly, got breaks[" << k << "] = " << breaks_[k]
         << " and breaks[" << k + 1 << "] = " << breaks_[k + 1];
      throw std::invalid_argument(os.str());
    }
  }
}

PiecewiseMotion PiecewiseMotion::fromKeyframes(const std::vector<double>& times,
                                               const std::vector<Eigen::Isometry3d>& poses) {
  if (times.size() < 2 || times.size() != poses.size()) {
    std::ostringstream os;
    os << "keyframes: need at least two times and as many poses as times, got " << times.size() << " times and "
       << poses.size() << " poses";
    throw std::invalid_argument(os.str());
  }
  for (std::size_t k = 0; k < times.size(); ++k) {
    if (!std::isfinite(times[k])) {
      std::ostringstream os;
      os << "keyframes: times[" << k << "] is not finite";
      throw std::invalid_argument(os.str());
    }
  }
  std::vector<MotionMatrix> pieces;
  for (std::size_t k = 0; k + 1 < poses.size(); ++k) pieces.push_back(MotionMatrix::fromPoses(poses[k], poses[k + 1]));
  return PiecewiseMotion(times, std::move(pieces));
}

bool PiecewiseMotion::isRigid() const {
  for (const MotionMatrix& m : pieces_)
    if (!m.isRigid()) return false;
  return true;
}

Eigen::Matrix4d PiecewiseMotion::evaluate(double t) const {
  if (!std::isfinite(t)) throw std::invalid_argument("PiecewiseMotion::evaluate: non-finite t");
  std::size_t k = 0;
  while (k + 1 < pieces_.size() && t > breaks_[k + 1]) ++k;
  const double s = (t - breaks_[k]) / (breaks_[k + 1] - breaks_[k]);
  return pieces_[k].evaluate(s);
}

MotionMatrix PiecewiseMotion::restricted(double t0, double t1) const {
  for (std::size_t k = 0; k < pieces_.size(); ++k) {
    const double a = breaks_[k], b = breaks_[k + 1];
    if (t0 >= a && t1 <= b && t0 < t1) {
      const double s0 = (t0 - a) / (b - a), s1 = (t1 - a) / (b - a);
      if (s0 == 0.0 && s1 == 1.0) return pieces_[k];
      return pieces_[k].restricted(s0, std::min(s1, 1.0));
    }
  }
  std::ostringstream os;
  os << "PiecewiseMotion::restricted: [" << t0 << ", " << t1 << "] is not inside one piece";
  throw std::invalid_argument(os.str());
}

}  // namespace fcl_quadric
