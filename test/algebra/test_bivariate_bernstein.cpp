// Tests of BivariateBernstein against direct (exact rational) evaluation of the power form.
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include <Eigen/Core>
#include <gtest/gtest.h>

#include "algebra/exact_rational.h"
#include "fcl_quadric/algebra/bivariate_bernstein.h"

namespace fcl_quadric {
namespace {

using algebra_test::Q;

struct Box {
  double u0, u1, t0, t1;
};

Eigen::MatrixXd randomMatrix(std::mt19937_64& rng, int rows, int cols) {
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  Eigen::MatrixXd M(rows, cols);
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) M(i, j) = d(rng);
  }
  return M;
}

Box randomBox(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> a(-1.0, 1.0);
  std::uniform_real_distribution<double> w(0.5, 2.0);
  Box b{};
  b.u0 = a(rng);
  b.u1 = b.u0 + w(rng);
  b.t0 = a(rng);
  b.t1 = b.t0 + w(rng);
  return b;
}

/// Exact value of sum_ij P(i,j) u^i t^j.
Q exactPower(const Eigen::MatrixXd& P, double u, double t) {
  Q value = 0;
  Q ui = 1;
  for (int i = 0; i < P.rows(); ++i) {
    Q tj = 1;
    for (int j = 0; j < P.cols(); ++j) {
      value += Q(P(i, j)) * ui * tj;
      tj *= Q(t);
    }
    ui *= Q(u);
  }
  return value;
}

/// Scale for absolute tolerances: sum |P(i,j)| max(|u|,1)^i max(|t|,1)^j over the box.
double powerScale(const Eigen::MatrixXd& P, const Box& b) {
  const double mu = std::max({1.0, std::abs(b.u0), std::abs(b.u1)});
  const double mt = std::max({1.0, std::abs(b.t0), std::abs(b.t1)});
  double s = 0.0;
  for (int i = 0; i < P.rows(); ++i) {
    for (int j = 0; j < P.cols(); ++j) s += std::abs(P(i, j)) * std::pow(mu, i) * std::pow(mt, j);
  }
  return s;
}

TEST(BivariateBernstein, FromPowerEvaluatesLikeThePowerForm) {
  std::mt19937_64 rng(41);
  for (int trial = 0; trial < 60; ++trial) {
    const Eigen::MatrixXd P = randomMatrix(rng, 1 + trial % 5, 1 + (trial / 5) % 5);
    const Box b = randomBox(rng);
    const BivariateBernstein F = BivariateBernstein::fromPower(P, b.u0, b.u1, b.t0, b.t1);
    EXPECT_EQ(F.degreeU(), P.rows() - 1);
    EXPECT_EQ(F.degreeT(), P.cols() - 1);
    std::uniform_real_distribution<double> ud(b.u0, b.u1);
    std::uniform_real_distribution<double> td(b.t0, b.t1);
    const double tol = 1e-13 * powerScale(P, b);
    for (int k = 0; k < 5; ++k) {
      const double u = ud(rng);
      const double t = td(rng);
      EXPECT_NEAR(F.evaluate(u, t), exactPower(P, u, t).get_d(), tol);
    }
    // Corners are the corner coefficients.
    EXPECT_NEAR(F.coefficients()(0, 0), exactPower(P, b.u0, b.t0).get_d(), tol);
    EXPECT_NEAR(F.coefficients()(P.rows() - 1, P.cols() - 1), exactPower(P, b.u1, b.t1).get_d(), tol);
  }
}

TEST(BivariateBernstein, AtUAndAtTAgreeWithEvaluate) {
  std::mt19937_64 rng(42);
  for (int trial = 0; trial < 60; ++trial) {
    const Box b = randomBox(rng);
    const Eigen::MatrixXd P = randomMatrix(rng, 1 + trial % 5, 1 + (trial / 5) % 5);
    const BivariateBernstein F = BivariateBernstein::fromPower(P, b.u0, b.u1, b.t0, b.t1);
    std::uniform_real_distribution<double> ud(b.u0, b.u1);
    std::uniform_real_distribution<double> td(b.t0, b.t1);
    const double tol = 1e-13 * powerScale(P, b);
    for (int k = 0; k < 4; ++k) {
      const double u = ud(rng);
      const double t = td(rng);
      const BernsteinPolynomial fu = F.atU(u);
      const BernsteinPolynomial ft = F.atT(t);
      EXPECT_EQ(fu.degree(), F.degreeT());
      EXPECT_EQ(fu.lower(), b.t0);
      EXPECT_EQ(ft.degree(), F.degreeU());
      EXPECT_EQ(ft.upper(), b.u1);
      const double exact = exactPower(P, u, t).get_d();
      EXPECT_NEAR(fu.evaluate(t), exact, tol);
      EXPECT_NEAR(ft.evaluate(u), exact, tol);
    }
  }
}

TEST(BivariateBernstein, SubdivisionPiecesMatchTheWhole) {
  std::mt19937_64 rng(43);
  for (int trial = 0; trial < 40; ++trial) {
    const Box b = randomBox(rng);
    const Eigen::MatrixXd P = randomMatrix(rng, 2 + trial % 4, 2 + (trial / 4) % 4);
    const BivariateBernstein F = BivariateBernstein::fromPower(P, b.u0, b.u1, b.t0, b.t1);
    std::uniform_real_distribution<double> ud(b.u0, b.u1);
    std::uniform_real_distribution<double> td(b.t0, b.t1);
    const double us = ud(rng);
    const double ts = td(rng);
    const auto u_halves = F.subdivideU(us);
    const auto t_halves = F.subdivideT(ts);
    EXPECT_EQ(u_halves.first.uUpper(), us);
    EXPECT_EQ(u_halves.second.uLower(), us);
    EXPECT_EQ(t_halves.first.tUpper(), ts);
    EXPECT_EQ(t_halves.second.tLower(), ts);
    const double tol = 1e-13 * powerScale(P, b);
    for (int k = 0; k < 4; ++k) {
      const double t = td(rng);
      const double u = ud(rng);
      const double exact = exactPower(P, u, t).get_d();
      const BivariateBernstein& pu = u <= us ? u_halves.first : u_halves.second;
      const BivariateBernstein& pt = t <= ts ? t_halves.first : t_halves.second;
      EXPECT_NEAR(pu.evaluate(u, t), exact, tol);
      EXPECT_NEAR(pt.evaluate(u, t), exact, tol);
    }
  }
}

TEST(BivariateBernstein, RestrictMatchesDirectEvaluation) {
  std::mt19937_64 rng(44);
  for (int trial = 0; trial < 40; ++trial) {
    const Box b = randomBox(rng);
    const Eigen::MatrixXd P = randomMatrix(rng, 1 + trial % 5, 1 + (trial / 5) % 5);
    const BivariateBernstein F = BivariateBernstein::fromPower(P, b.u0, b.u1, b.t0, b.t1);
    std::uniform_real_distribution<double> ud(b.u0, b.u1);
    std::uniform_real_distribution<double> td(b.t0, b.t1);
    double ua = ud(rng), ub = ud(rng), ta = td(rng), tb = td(rng);
    if (ua > ub) std::swap(ua, ub);
    if (ta > tb) std::swap(ta, tb);
    if (!(ua < ub) || !(ta < tb)) continue;
    const BivariateBernstein R = F.restrict(ua, ub, ta, tb);
    const double tol = 1e-13 * powerScale(P, b);
    // Every coefficient of R at the corners is the value there; interior values agree.
    EXPECT_NEAR(R.coefficients()(0, 0), exactPower(P, ua, ta).get_d(), tol);
    EXPECT_NEAR(R.coefficients()(R.degreeU(), 0), exactPower(P, ub, ta).get_d(), tol);
    EXPECT_NEAR(R.coefficients()(0, R.degreeT()), exactPower(P, ua, tb).get_d(), tol);
    std::uniform_real_distribution<double> ru(ua, ub);
    std::uniform_real_distribution<double> rt(ta, tb);
    for (int k = 0; k < 4; ++k) {
      const double u = ru(rng);
      const double t = rt(rng);
      EXPECT_NEAR(R.evaluate(u, t), exactPower(P, u, t).get_d(), tol);
    }
    // Convex hull property on the sub-box.
    for (int k = 0; k < 4; ++k) {
      const Q v = exactPower(P, ru(rng), rt(rng));
      EXPECT_LE(R.minCoefficient() - tol, v.get_d());
      EXPECT_GE(R.maxCoefficient() + tol, v.get_d());
    }
  }
}

TEST(BivariateBernstein, PartialDerivativesMatchPowerFormDerivatives) {
  std::mt19937_64 rng(45);
  for (int trial = 0; trial < 50; ++trial) {
    const Box b = randomBox(rng);
    const Eigen::MatrixXd P = randomMatrix(rng, 1 + trial % 5, 1 + (trial / 5) % 5);
    const BivariateBernstein F = BivariateBernstein::fromPower(P, b.u0, b.u1, b.t0, b.t1);
    // Power-form partial derivatives, computed directly.
    Eigen::MatrixXd Pu = Eigen::MatrixXd::Zero(std::max<Eigen::Index>(P.rows() - 1, 1), P.cols());
    for (int i = 1; i < P.rows(); ++i) Pu.row(i - 1) = i * P.row(i);
    Eigen::MatrixXd Pt = Eigen::MatrixXd::Zero(P.rows(), std::max<Eigen::Index>(P.cols() - 1, 1));
    for (int j = 1; j < P.cols(); ++j) Pt.col(j - 1) = j * P.col(j);
    const BivariateBernstein Fu = F.derivativeU();
    const BivariateBernstein Ft = F.derivativeT();
    std::uniform_real_distribution<double> ud(b.u0, b.u1);
    std::uniform_real_distribution<double> td(b.t0, b.t1);
    const double tol = 1e-12 * powerScale(P, b) * (P.rows() + P.cols());
    for (int k = 0; k < 4; ++k) {
      const double u = ud(rng);
      const double t = td(rng);
      EXPECT_NEAR(Fu.evaluate(u, t), exactPower(Pu, u, t).get_d(), tol);
      EXPECT_NEAR(Ft.evaluate(u, t), exactPower(Pt, u, t).get_d(), tol);
    }
  }
}

TEST(BivariateBernstein, RejectsBadInput) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Eigen::MatrixXd M = Eigen::MatrixXd::Ones(2, 3);
  EXPECT_THROW(BivariateBernstein(Eigen::MatrixXd(0, 2)), std::invalid_argument);
  EXPECT_THROW(BivariateBernstein(M, 1.0, 0.0, 0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(BivariateBernstein(M, 0.0, 1.0, 1.0, 1.0), std::invalid_argument);
  M(1, 2) = nan;
  EXPECT_THROW(BivariateBernstein(M, 0.0, 1.0, 0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(BivariateBernstein::fromPower(M), std::invalid_argument);
  const BivariateBernstein F(Eigen::MatrixXd::Ones(2, 3));
  EXPECT_THROW(F.subdivideU(0.0), std::invalid_argument);
  EXPECT_THROW(F.subdivideT(1.5), std::invalid_argument);
  EXPECT_THROW(F.restrict(0.5, 0.25, 0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(F.evaluate(nan, 0.5), std::invalid_argument);
  EXPECT_THROW(F.atU(nan), std::invalid_argument);
}

}  // namespace
}  // namespace fcl_quadric
