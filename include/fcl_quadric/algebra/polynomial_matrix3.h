#pragma once
/// \file polynomial_matrix3.h
/// 3x3 matrices whose entries are univariate polynomials (power form), and the determinants of
/// the conic pencils built from them: the planar counterpart of polynomial_matrix.h, used by the
/// moving-ellipse algorithms of thesis ch.2 (homogeneous motions M(t) of the plane, conic
/// matrices A(t), B(t), characteristic polynomial f(lambda; t) = det(lambda A(t) - B(t)), eq. 2.1).
///
/// Part of the algebra layer: depends on the standard library and Eigen only.

#include <array>
#include <vector>

#include <Eigen/Core>

#include "fcl_quadric/algebra/polynomial.h"

namespace fcl_quadric {

/// A 3x3 matrix M(t) of polynomials in one variable t. Index arguments must lie in [0, 2]
/// (otherwise std::invalid_argument is thrown); matrix arguments must be finite (otherwise
/// std::invalid_argument naming the entry). All operations are fixed-size loops.
class PolynomialMatrix3 {
 public:
  /// The zero matrix.
  PolynomialMatrix3();

  /// The constant matrix M. \throws std::invalid_argument if an entry is not finite.
  explicit PolynomialMatrix3(const Eigen::Matrix3d& M);

  /// The matrix polynomial sum_k t^k M_k (M_0 first). \throws std::invalid_argument if an entry
  /// is not finite.
  static PolynomialMatrix3 fromCoefficients(const std::vector<Eigen::Matrix3d>& matrices);

  /// The linear matrix polynomial M0 + t M1. \throws std::invalid_argument as above.
  static PolynomialMatrix3 linear(const Eigen::Matrix3d& M0, const Eigen::Matrix3d& M1);

  /// Entry (i, j). \throws std::invalid_argument if i or j is outside [0, 2].
  const Polynomial& operator()(int i, int j) const;
  Polynomial& operator()(int i, int j);

  /// Largest formal degree of the entries.
  int maxDegree() const;

  /// M(t) as a numeric matrix (Horner per entry). \throws std::invalid_argument if t is not
  /// finite.
  Eigen::Matrix3d evaluate(double t) const;

  PolynomialMatrix3 transpose() const;
  PolynomialMatrix3 operator+(const PolynomialMatrix3& other) const;
  PolynomialMatrix3 operator-(const PolynomialMatrix3& other) const;
  /// Matrix product (entries are sums of polynomial products).
  PolynomialMatrix3 operator*(const PolynomialMatrix3& other) const;
  /// Scalar multiple. \throws std::invalid_argument if s is not finite.
  PolynomialMatrix3 operator*(double s) const;
  /// Every entry multiplied by the polynomial q.
  PolynomialMatrix3 operator*(const Polynomial& q) const;

  /// det M(t) by cofactor expansion along the first row (exact for polynomials in exact
  /// arithmetic; formal degree at most 3 maxDegree()).
  Polynomial determinant() const;

  /// The adjugate (classical adjoint) adj M = cof(M)^T, so that M adj M = adj M M = det(M) I.
  /// Entries are 2x2 minors (formal degree at most 2 maxDegree()); no division is performed, so
  /// it is a polynomial matrix even where M(t) is singular.
  PolynomialMatrix3 adjugate() const;

 private:
  std::array<Polynomial, 9> entries_;  // row-major
};

/// det(lambda A - B) as a polynomial of formal degree 3 in lambda; the coefficient of lambda^3
/// is det A and the constant one is det(-B) = -det B.
/// \throws std::invalid_argument if an entry of A or B is not finite.
Polynomial pencilDeterminant3(const Eigen::Matrix3d& A, const Eigen::Matrix3d& B);

/// det(lambda A(t) - B(t)) as a bivariate power-form polynomial: the returned matrix P has
/// P(k, j) = coefficient of lambda^k t^j (rows: degree 0..3 in lambda, i.e. the g_k(t) of thesis
/// eq. 2.1 in row k; columns: degree in t up to 3 max(deg A, deg B)).
Eigen::MatrixXd pencilDeterminant3(const PolynomialMatrix3& A, const PolynomialMatrix3& B);

}  // namespace fcl_quadric
