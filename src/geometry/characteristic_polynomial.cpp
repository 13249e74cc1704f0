#include "fcl_quadric/geometry/characteristic_polynomial.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "fcl_quadric/tolerances.h"
#include "geometry/pencil.h"

namespace fcl_quadric {

std::array<double, 5> characteristicPolynomial(const Ellipsoid& a, const Ellipsoid& b) {
  // B' = M_A^T B M_A = N'^T D_B N', N' = M_B^-1 M_A = [R_B^T R_A, R_B^T (p_A - p_B); 0 1] (§4.1.2).
  const Eigen::Matrix3d C = b.rotation().transpose() * a.rotation();
  const Eigen::Vector3d w = b.rotation().transpose() * (a.center() - b.center());
  const Eigen::Vector3d dB = b.radii().cwiseProduct(b.radii()).cwiseInverse();
  Eigen::Matrix4d Np = Eigen::Matrix4d::Identity();
  Np.topLeftCorner<3, 3>() = C;
  Np.topRightCorner<3, 1>() = w;
  const Eigen::Vector4d D(dB[0], dB[1], dB[2], -1.0);
  const Eigen::Matrix4d Bm = Np.transpose() * D.asDiagonal() * Np;
  const double b11 = Bm(0, 0), b12 = Bm(0, 1), b13 = Bm(0, 2), b14 = Bm(0, 3);
  const double b22 = Bm(1, 1), b23 = Bm(1, 2), b24 = Bm(1, 3);
  const double b33 = Bm(2, 2), b34 = Bm(2, 3), b44 = Bm(3, 3);
  const double ea = 1.0 / (a.radii()[0] * a.radii()[0]);
  const double eb = 1.0 / (a.radii()[1] * a.radii()[1]);
  const double ec = 1.0 / (a.radii()[2] * a.radii()[2]);
  const double ab = ea * eb, ac = ea * ec, bc = eb * ec, abc = ab * ec;
  // Generate-Characteristic-Polynomial, thesis §4.1.3 (29 additions, 39 multiplications).
  const double b12s = b12 * b12, b13s = b13 * b13, b14s = b14 * b14;
  const double b23s = b23 * b23, b24s = b24 * b24, b34s = b34 * b34;
  const double b2233 = b22 * b33;
  const double termA = b11 * bc + b22 * ac + b33 * ab;
  const double termB = (b2233 - b23s) * ea + (b11 * b33 - b13s) * eb + (b11 * b22 - b12s) * ec;
  std::array<double, 5> T;
  T[4] = -abc;
  T[3] = termA - b44 * abc;
  T[2] = termA * b44 - termB - b34s * ab - b14s * bc - b24s * ac;
  const double tmp1 = termB * b44;
  const double tmp2 = b11 * (b2233 + eb * b34s + ec * b24s - b23s);
  const double tmp3 = b22 * (ea * b34s + ec * b14s - b13s);
  const double tmp4 = b33 * (ea * b24s + eb * b14s - b12s);
  double tmp5 = b34 * (ea * b23 * b24 + eb * b13 * b14) + b12 * (ec * b14 * b24 - b13 * b23);
  tmp5 += tmp5;
  T[1] = -tmp1 + tmp2 + tmp3 + tmp4 - tmp5;
  // Rigid case: T0 = det(-B') = det(D_B) det(N')^2 = -1/(a_B b_B c_B)^2.
  T[0] = -(dB[0] * dB[1] * dB[2]);
  return T;
}

std::array<double, 5> characteristicPolynomialAffine(const Eigen::Matrix4d& M_A, const Eigen::Matrix4d& M_B) {
  for (const Eigen::Matrix4d* M : {&M_A, &M_B}) {
    const char* name = M == &M_A ? "M_A" : "M_B";
    std::ostringstream os;
    if (!M->allFinite()) {
      os << "characteristicPolynomialAffine: " << name << " must be finite";
      throw std::invalid_argument(os.str());
    }
    if (M->row(3) != Eigen::RowVector4d(0, 0, 0, 1)) {
      os << "characteristicPolynomialAffine: last row of " << name << " must be [0 0 0 1], got ["
         << M->row(3) << "]";
      throw std::invalid_argument(os.str());
    }
    const double det = M->topLeftCorner<3, 3>().determinant();
    const double scale = M->topLeftCorner<3, 3>().cwiseAbs().maxCoeff();
    if (!(std::fabs(det) > 1e-300) || !(std::fabs(det) > 1e-14 * scale * scale * scale)) {
      os << "characteristicPolynomialAffine: linear part of " << name << " is singular (det = " << det << ")";
      throw std::invalid_argument(os.str());
    }
  }
  // In A's unit frame: N = M_B^-1 M_A = [L t; 0 1]; f(lambda) = det(lambda J - N^T J N) (pencil.h).
  const Eigen::Matrix4d N = M_B.inverse() * M_A;
  detail::Pencil<double> p;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) p.L[i][j] = N(i, j);
    p.t[i] = N(i, 3);
  }
  detail::completePencil(p);
  detail::computePencilCoefficients(p);
  // f(-nu) = sum E_k nu^k  =>  f(lambda) = sum (-1)^k E_k lambda^k.
  return {p.E[0], -p.E[1], p.E[2], -p.E[3], p.E[4]};
}

Separation classifyBySubresultants(const std::array<double, 5>& f) {
  for (int i = 0; i < 5; ++i) {
    if (!std::isfinite(f[i])) {
      std::ostringstream os;
      os << "classifyBySubresultants: coefficient f[" << i << "] must be finite, got " << f[i];
      throw std::invalid_argument(os.str());
    }
  }
  if (f[4] == 0.0) throw std::invalid_argument("classifyBySubresultants: leading coefficient f[4] is 0 (not a quartic)");
  // Thesis §4.5 uses f^(lambda) = det(lambda A + B) = f(-lambda); normalise to monic.
  const double c4 = f[4];
  const double a = -f[3] / c4, b = f[2] / c4, c = -f[1] / c4, d = f[0] / c4;
  const double a2 = a * a, a3 = a2 * a, a4 = a2 * a2, b2 = b * b, b3 = b2 * b, b4 = b2 * b2;
  const double c2 = c * c, c3 = c2 * c, c4_ = c2 * c2, d2 = d * d, d3 = d2 * d;
  const double sr22 = 3 * a2 - 8 * b;
  const double sr11 = -6 * a3 * c + 2 * a2 * b2 - 12 * a2 * d + 28 * a * b * c - 8 * b3 - 36 * c2 + 32 * b * d;
  const double sr01 = -9 * a3 * d + a2 * b * c + 3 * a * c2 + 32 * a * b * d - 4 * b2 * c - 48 * c * d;
  const double res = -27 * a4 * d2 - 4 * a3 * c3 + 18 * a3 * b * c * d - 4 * a2 * b3 * d - 6 * a2 * c2 * d +
                     144 * a2 * b * d2 + a2 * b2 * c2 - 192 * a * c * d2 - 80 * a * b2 * c * d + 18 * a * b * c3 +
                     144 * b * c2 * d - 128 * b2 * d2 + 256 * d3 - 27 * c4_ - 4 * b3 * c2 + 16 * b4 * d;
  // Zero tests are relative to the absolute evaluation of each expression (double precision path).
  const double A = std::fabs(a), B = std::fabs(b), C = std::fabs(c), D = std::fabs(d);
  const double A2 = A * A, A3 = A2 * A, B2 = B * B, C2 = C * C;
  const double s11 = 6 * A3 * C + 2 * A2 * B2 + 12 * A2 * D + 28 * A * B * C + 8 * B2 * B + 36 * C2 + 32 * B * D;
  const double s01 = 9 * A3 * D + A2 * B * C + 3 * A * C2 + 32 * A * B * D + 4 * B2 * C + 48 * C * D;
  const double sres = 27 * A2 * A2 * D * D + 4 * A3 * C2 * C + 18 * A3 * B * C * D + 4 * A2 * B2 * B * D +
                      6 * A2 * C2 * D + 144 * A2 * B * D * D + A2 * B2 * C2 + 192 * A * C * D * D +
                      80 * A * B2 * C * D + 18 * A * B * C2 * C + 144 * B * C2 * D + 128 * B2 * D * D +
                      256 * D * D * D + 27 * C2 * C2 + 4 * B2 * B * C2 + 16 * B2 * B2 * D;
  const double tol = 1e-9;  // relative; this path is a cross-check, not the certified decision
  auto zero = [tol](double x, double scale) { return std::fabs(x) <= tol * scale; };
  const bool some_negative_coefficient = a < 0 || b < 0 || c < 0;  // Var(1,a,b,c,d) = 2 (§4.5.1)
  if (!some_negative_coefficient || !(sr22 > 0)) return Separation::Overlapping;
  const bool res_zero = zero(res, sres);
  const bool sr11_zero = zero(sr11, s11);
  const bool sr01_zero = zero(sr01, s01);
  if (!res_zero && res > 0 && !sr11_zero && sr11 > 0) return Separation::Separated;  // case (1)
  if (res_zero && !sr11_zero && sr11 > 0) {                                            // case (2)
    if (!sr01_zero && sr01 > 0) return Separation::Separated;
    if (!sr01_zero && sr01 < 0) return Separation::Touching;
    return Separation::Touching;
  }
  if (res_zero && sr11_zero && sr01_zero) return Separation::Touching;  // case (3)
  return Separation::Overlapping;
}

}  // namespace fcl_quadric
