#include "fcl_quadric/algebra/bivariate_bernstein.h"

#include "algebra/input_checks.h"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace fcl_quadric {
namespace {

std::vector<double> column(const Eigen::MatrixXd& M, Eigen::Index j) {
  std::vector<double> v(static_cast<std::size_t>(M.rows()));
  for (Eigen::Index i = 0; i < M.rows(); ++i) v[static_cast<std::size_t>(i)] = M(i, j);
  return v;
}

std::vector<double> row(const Eigen::MatrixXd& M, Eigen::Index i) {
  std::vector<double> v(static_cast<std::size_t>(M.cols()));
  for (Eigen::Index j = 0; j < M.cols(); ++j) v[static_cast<std::size_t>(j)] = M(i, j);
  return v;
}

void setColumn(Eigen::MatrixXd* M, Eigen::Index j, const std::vector<double>& v) {
  for (Eigen::Index i = 0; i < M->rows(); ++i) (*M)(i, j) = v[static_cast<std::size_t>(i)];
}

void setRow(Eigen::MatrixXd* M, Eigen::Index i, const std::vector<double>& v) {
  for (Eigen::Index j = 0; j < M->cols(); ++j) (*M)(i, j) = v[static_cast<std::size_t>(j)];
}

void checkMatrix(const char* where, const Eigen::MatrixXd& M) {
  if (M.rows() == 0 || M.cols() == 0) {
    throw std::invalid_argument(std::string(where) + ": empty coefficient matrix");
  }
  for (Eigen::Index j = 0; j < M.cols(); ++j) {
    for (Eigen::Index i = 0; i < M.rows(); ++i) {
      if (!std::isfinite(M(i, j))) {
        std::ostringstream os;
        os << where << ": non-finite coefficient (" << i << ", " << j << ") = " << M(i, j);
        throw std::invalid_argument(os.str());
      }
    }
  }
}

using detail::checkFiniteValue;

void checkStrictlyInside(const char* where, double x, double lo, double hi) {
  checkFiniteValue(where, "split parameter", x);
  if (!(lo < x && x < hi)) {
    std::ostringstream os;
    os.precision(17);
    os << where << ": split parameter " << x << " not strictly inside (" << lo << ", " << hi << ")";
    throw std::invalid_argument(os.str());
  }
}

}  // namespace

BivariateBernstein::BivariateBernstein()
    : coefficients_(Eigen::MatrixXd::Zero(1, 1)), u0_(0.0), u1_(1.0), t0_(0.0), t1_(1.0) {}

BivariateBernstein::BivariateBernstein(Eigen::MatrixXd coefficients, double u0, double u1, double t0, double t1)
    : coefficients_(std::move(coefficients)), u0_(u0), u1_(u1), t0_(t0), t1_(t1) {
  checkMatrix("BivariateBernstein", coefficients_);
  detail::checkInterval("BivariateBernstein (u side)", u0, u1);
  detail::checkInterval("BivariateBernstein (t side)", t0, t1);
}

BivariateBernstein::BivariateBernstein(Eigen::MatrixXd coefficients, double u0, double u1, double t0, double t1,
                                       Unchecked)
    : coefficients_(std::move(coefficients)), u0_(u0), u1_(u1), t0_(t0), t1_(t1) {}

BivariateBernstein BivariateBernstein::fromPower(const Eigen::MatrixXd& power, double u0, double u1, double t0,
                                                 double t1) {
  checkMatrix("BivariateBernstein::fromPower", power);
  detail::checkInterval("BivariateBernstein::fromPower (u side)", u0, u1);
  detail::checkInterval("BivariateBernstein::fromPower (t side)", t0, t1);
  Eigen::MatrixXd B = power;
  const int m = static_cast<int>(power.rows()) - 1;
  const int n = static_cast<int>(power.cols()) - 1;
  // Columns: polynomials in u with coefficients p_ij for fixed j.
  for (Eigen::Index j = 0; j <= n; ++j) {
    setColumn(&B, j, BernsteinPolynomial::fromPower(Polynomial(column(B, j)), u0, u1, m).coefficients());
  }
  // Rows: for fixed Bernstein index i in u, polynomials in t.
  for (Eigen::Index i = 0; i <= m; ++i) {
    setRow(&B, i, BernsteinPolynomial::fromPower(Polynomial(row(B, i)), t0, t1, n).coefficients());
  }
  return BivariateBernstein(std::move(B), u0, u1, t0, t1, Unchecked{});
}

double BivariateBernstein::evaluate(double u, double t) const {
  checkFiniteValue("BivariateBernstein::evaluate", "argument u", u);
  checkFiniteValue("BivariateBernstein::evaluate", "argument t", t);
  return atU(u).evaluate(t);
}

BernsteinPolynomial BivariateBernstein::atU(double u) const {
  checkFiniteValue("BivariateBernstein::atU", "argument u", u);
  const double x = (u - u0_) / (u1_ - u0_);
  std::vector<double> c(static_cast<std::size_t>(coefficients_.cols()));
  for (Eigen::Index j = 0; j < coefficients_.cols(); ++j) {
    const std::vector<double> col = column(coefficients_, j);
    c[static_cast<std::size_t>(j)] = (u == u0_) ? col.front() : (u == u1_) ? col.back()
                                                                           : detail::deCasteljauEvaluate(col, x);
  }
  return BernsteinPolynomial(std::move(c), t0_, t1_);
}

BernsteinPolynomial BivariateBernstein::atT(double t) const {
  checkFiniteValue("BivariateBernstein::atT", "argument t", t);
  const double y = (t - t0_) / (t1_ - t0_);
  std::vector<double> c(static_cast<std::size_t>(coefficients_.rows()));
  for (Eigen::Index i = 0; i < coefficients_.rows(); ++i) {
    const std::vector<double> r = row(coefficients_, i);
    c[static_cast<std::size_t>(i)] = (t == t0_) ? r.front() : (t == t1_) ? r.back() : detail::deCasteljauEvaluate(r, y);
  }
  return BernsteinPolynomial(std::move(c), u0_, u1_);
}

std::pair<BivariateBernstein, BivariateBernstein> BivariateBernstein::subdivideU(double u) const {
  checkStrictlyInside("BivariateBernstein::subdivideU", u, u0_, u1_);
  const double x = (u - u0_) / (u1_ - u0_);
  Eigen::MatrixXd L(coefficients_.rows(), coefficients_.cols());
  Eigen::MatrixXd R(coefficients_.rows(), coefficients_.cols());
  std::vector<double> left;
  std::vector<double> right;
  for (Eigen::Index j = 0; j < coefficients_.cols(); ++j) {
    detail::deCasteljauSplit(column(coefficients_, j), x, &left, &right);
    setColumn(&L, j, left);
    setColumn(&R, j, right);
  }
  return {BivariateBernstein(std::move(L), u0_, u, t0_, t1_, Unchecked{}),
          BivariateBernstein(std::move(R), u, u1_, t0_, t1_, Unchecked{})};
}

std::pair<BivariateBernstein, BivariateBernstein> BivariateBernstein::subdivideT(double t) const {
  checkStrictlyInside("BivariateBernstein::subdivideT", t, t0_, t1_);
  const double y = (t - t0_) / (t1_ - t0_);
  Eigen::MatrixXd L(coefficients_.rows(), coefficients_.cols());
  Eigen::MatrixXd R(coefficients_.rows(), coefficients_.cols());
  std::vector<double> left;
  std::vector<double> right;
  for (Eigen::Index i = 0; i < coefficients_.rows(); ++i) {
    detail::deCasteljauSplit(row(coefficients_, i), y, &left, &right);
    setRow(&L, i, left);
    setRow(&R, i, right);
  }
  return {BivariateBernstein(std::move(L), u0_, u1_, t0_, t, Unchecked{}),
          BivariateBernstein(std::move(R), u0_, u1_, t, t1_, Unchecked{})};
}

BivariateBernstein BivariateBernstein::restrict(double ua, double ub, double ta, double tb) const {
  detail::checkInterval("BivariateBernstein::restrict (u side)", ua, ub);
  detail::checkInterval("BivariateBernstein::restrict (t side)", ta, tb);
  // In place along each column (contiguous: Eigen's storage is column-major), then along the
  // rows, all rows at once (the lanes: a column's entries).
  Eigen::MatrixXd B = coefficients_;
  const auto rows = static_cast<std::size_t>(B.rows()), cols = static_cast<std::size_t>(B.cols());
  for (Eigen::Index j = 0; j < B.cols(); ++j) detail::restrictInPlace(&B(0, j), rows, 1, 1, u0_, u1_, ua, ub);
  detail::restrictInPlace(B.data(), cols, B.rows(), rows, t0_, t1_, ta, tb);
  return BivariateBernstein(std::move(B), ua, ub, ta, tb, Unchecked{});
}

BivariateBernstein BivariateBernstein::derivativeU() const {
  const Eigen::Index m = coefficients_.rows() - 1;
  if (m == 0) {
    return BivariateBernstein(Eigen::MatrixXd::Zero(1, coefficients_.cols()), u0_, u1_, t0_, t1_, Unchecked{});
  }
  const double scale = static_cast<double>(m) / (u1_ - u0_);
  Eigen::MatrixXd D = scale * (coefficients_.bottomRows(m) - coefficients_.topRows(m));
  return BivariateBernstein(std::move(D), u0_, u1_, t0_, t1_, Unchecked{});
}

BivariateBernstein BivariateBernstein::derivativeT() const {
  const Eigen::Index n = coefficients_.cols() - 1;
  if (n == 0) {
    return BivariateBernstein(Eigen::MatrixXd::Zero(coefficients_.rows(), 1), u0_, u1_, t0_, t1_, Unchecked{});
  }
  const double scale = static_cast<double>(n) / (t1_ - t0_);
  Eigen::MatrixXd D = scale * (coefficients_.rightCols(n) - coefficients_.leftCols(n));
  return BivariateBernstein(std::move(D), u0_, u1_, t0_, t1_, Unchecked{});
}

}  // namespace fcl_quadric
