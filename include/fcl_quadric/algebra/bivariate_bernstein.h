#pragma once
/// \file bivariate_bernstein.h
/// Tensor-product Bernstein polynomials in two variables on a box [u0,u1] x [t0,t1]:
///
///   F(u,t) = sum_{i=0}^{m} sum_{j=0}^{n} b_ij B_i^m(x) B_j^n(y),  x = (u-u0)/(u1-u0),
///                                                               y = (t-t0)/(t1-t0).
///
/// Coefficients are stored in an Eigen::MatrixXd with row i = u index, column j = t index.
/// The continuous-collision layer uses F(u,t) = det((u-1) A(t) - u B(t)) on [0,1]^2.
///
/// Part of the algebra layer: depends on the standard library and Eigen only.

#include <utility>

#include <Eigen/Core>

#include "fcl_quadric/algebra/bernstein_polynomial.h"

namespace fcl_quadric {

/// Tensor-product Bernstein polynomial of degree (m in u, n in t).
///
/// Bad input: an empty or non-finite coefficient matrix, a non-finite bound or an empty or
/// inverted box side (u0 >= u1 or t0 >= t1) throws std::invalid_argument naming the bad value.
/// Every operation is a fixed number of de Casteljau passes over the rows or columns; there
/// are no open-ended iterations.
class BivariateBernstein {
 public:
  /// The zero polynomial of degree (0, 0) on [0,1]^2.
  BivariateBernstein();

  /// From coefficients b_ij (rows: u index 0..m, columns: t index 0..n).
  /// \throws std::invalid_argument as described in the class comment.
  explicit BivariateBernstein(Eigen::MatrixXd coefficients, double u0 = 0.0, double u1 = 1.0, double t0 = 0.0,
                              double t1 = 1.0);

  /// From the power form F(u,t) = sum_ij p_ij u^i t^j (p_ij = power(i, j)); the degree is
  /// (power.rows() - 1, power.cols() - 1). Exact in exact arithmetic (per column and per row:
  /// affine substitution, then the univariate power -> Bernstein conversion).
  /// \throws std::invalid_argument as the constructor.
  static BivariateBernstein fromPower(const Eigen::MatrixXd& power, double u0 = 0.0, double u1 = 1.0,
                                      double t0 = 0.0, double t1 = 1.0);

  int degreeU() const { return static_cast<int>(coefficients_.rows()) - 1; }
  int degreeT() const { return static_cast<int>(coefficients_.cols()) - 1; }
  double uLower() const { return u0_; }
  double uUpper() const { return u1_; }
  double tLower() const { return t0_; }
  double tUpper() const { return t1_; }
  const Eigen::MatrixXd& coefficients() const { return coefficients_; }

  /// F(u,t) by de Casteljau in t along every row, then in u.
  /// \throws std::invalid_argument if u or t is not finite (outside the box it extrapolates).
  double evaluate(double u, double t) const;
  double operator()(double u, double t) const { return evaluate(u, t); }

  /// The univariate polynomial t -> F(u, t) in the Bernstein basis of [t0, t1] (degree n).
  /// \throws std::invalid_argument if u is not finite.
  BernsteinPolynomial atU(double u) const;
  /// The univariate polynomial u -> F(u, t) in the Bernstein basis of [u0, u1] (degree m).
  /// \throws std::invalid_argument if t is not finite.
  BernsteinPolynomial atT(double t) const;

  /// Split at u (u0 < u < u1): the pieces on [u0,u] x [t0,t1] and [u,u1] x [t0,t1].
  /// \throws std::invalid_argument if u is not finite or not strictly inside (u0, u1).
  std::pair<BivariateBernstein, BivariateBernstein> subdivideU(double u) const;
  /// Split at t (t0 < t < t1): the pieces on [u0,u1] x [t0,t] and [u0,u1] x [t,t1].
  /// \throws std::invalid_argument if t is not finite or not strictly inside (t0, t1).
  std::pair<BivariateBernstein, BivariateBernstein> subdivideT(double t) const;

  /// The same polynomial on the box [ua,ub] x [ta,tb] (stable inside the current box).
  /// \throws std::invalid_argument if a bound is not finite, ua >= ub or ta >= tb.
  BivariateBernstein restrict(double ua, double ub, double ta, double tb) const;

  /// dF/du, degree (max(m-1,0), n); zero when m == 0.
  BivariateBernstein derivativeU() const;
  /// dF/dt, degree (m, max(n-1,0)); zero when n == 0.
  BivariateBernstein derivativeT() const;

  /// Bounds of F on the box by the convex hull property.
  double minCoefficient() const { return coefficients_.minCoeff(); }
  double maxCoefficient() const { return coefficients_.maxCoeff(); }

 private:
  struct Unchecked {};
  BivariateBernstein(Eigen::MatrixXd coefficients, double u0, double u1, double t0, double t1, Unchecked);

  Eigen::MatrixXd coefficients_;
  double u0_;
  double u1_;
  double t0_;
  double t1_;
};

}  // namespace fcl_quadric
