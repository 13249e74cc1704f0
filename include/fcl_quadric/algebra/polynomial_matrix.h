#pragma once
/// \file polynomial_matrix.h
/// 4x4 matrices whose entries are univariate polynomials, and the determinants of the
/// quadric pencils built from them.
///
/// Part of the algebra layer: depends on the standard library and Eigen only.

#include <array>
#include <vector>

#include <Eigen/Core>

#include "fcl_quadric/algebra/polynomial.h"

namespace fcl_quadric {

/// A 4x4 matrix M(t) of polynomials in one variable t. Index arguments must lie in [0, 3]
/// (otherwise std::invalid_argument is thrown); matrix arguments must be finite (otherwise
/// std::invalid_argument naming the entry). All operations are fixed-size loops.
class PolynomialMatrix4 {
 public:
  /// The zero matrix.
  PolynomialMatrix4();

  /// The constant matrix M. \throws std::invalid_argument if an entry is not finite.
  explicit PolynomialMatrix4(const Eigen::Matrix4d& M);

  /// The matrix polynomial sum_k t^k M_k (M_0 first). \throws std::invalid_argument if an entry
  /// is not finite.
  static PolynomialMatrix4 fromCoefficients(const std::vector<Eigen::Matrix4d>& matrices);

  /// The linear matrix polynomial M0 + t M1. \throws std::invalid_argument as above.
  static PolynomialMatrix4 linear(const Eigen::Matrix4d& M0, const Eigen::Matrix4d& M1);

  /// Entry (i, j). \throws std::invalid_argument if i or j is outside [0, 3].
  const Polynomial& operator()(int i, int j) const;
  Polynomial& operator()(int i, int j);

  /// Largest formal degree of the entries.
  int maxDegree() const;

  /// M(t) as a numeric matrix (Horner per entry). \throws std::invalid_argument if t is not
  /// finite.
  Eigen::Matrix4d evaluate(double t) const;

  PolynomialMatrix4 transpose() const;
  PolynomialMatrix4 operator+(const PolynomialMatrix4& other) const;
  PolynomialMatrix4 operator-(const PolynomialMatrix4& other) const;
  /// Matrix product (entries are sums of polynomial products).
  PolynomialMatrix4 operator*(const PolynomialMatrix4& other) const;
  /// Scalar multiple. \throws std::invalid_argument if s is not finite.
  PolynomialMatrix4 operator*(double s) const;
  /// Every entry multiplied by the polynomial q.
  PolynomialMatrix4 operator*(const Polynomial& q) const;

  /// det M(t) as a polynomial, by Laplace expansion along the first two rows over the six
  /// complementary pairs of 2x2 minors (exact for polynomials in exact arithmetic; formal degree
  /// at most 4 maxDegree()).
  Polynomial determinant() const;

 private:
  std::array<Polynomial, 16> entries_;  // row-major
};

/// det(lambda A - B) as a polynomial of formal degree 4 in lambda; the coefficient of
/// lambda^4 is det A and the constant one is det(-B) = det B.
/// \throws std::invalid_argument if an entry of A or B is not finite.
Polynomial pencilDeterminant(const Eigen::Matrix4d& A, const Eigen::Matrix4d& B);

/// det(lambda A(t) - B(t)) as a bivariate power-form polynomial: the returned matrix P has
/// P(k, j) = coefficient of lambda^k t^j (rows: degree 0..4 in lambda; columns: degree in t up
/// to 4 max(deg A, deg B)). This is the input of BivariateBernstein::fromPower(); e.g.
/// F(u,t) = det((u-1) A(t) - u B(t)) = det(u (A - B)(t) - A(t)) is
/// pencilDeterminant(A - B, A) with lambda = u.
Eigen::MatrixXd pencilDeterminant(const PolynomialMatrix4& A, const PolynomialMatrix4& B);

}  // namespace fcl_quadric
