// Quadric matrices: each canonical quadric classifies points exactly as its defining inequality,
// and transformed matrices classify transformed points as the body-frame matrix does.
#include <gtest/gtest.h>

#include <random>

#include <Eigen/Geometry>

#include "fcl_quadric/algebra/quadric_matrix.h"
#include "fcl_quadric/geometry/ellipsoid.h"

namespace fcl_quadric {
namespace {

TEST(QuadricMatrix, CanonicalQuadricsMatchTheirDefiningInequalities) {
  std::mt19937_64 rng(81);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  const double a = 1.5, b = 0.7, c = 2.0;
  for (int i = 0; i < 10000; ++i) {
    const Eigen::Vector3d x(u(rng), u(rng), u(rng));
    const double X = x[0] * x[0] / (a * a), Y = x[1] * x[1] / (b * b), Z = x[2] * x[2] / (c * c);
    EXPECT_NEAR(quadric::evaluate(quadric::ellipsoid({a, b, c}), x), X + Y + Z - 1, 1e-12);
    EXPECT_NEAR(quadric::evaluate(quadric::ellipticCylinder(a, b), x), X + Y - 1, 1e-12);
    EXPECT_NEAR(quadric::evaluate(quadric::ellipticCone(a, b, c), x), X + Y - Z, 1e-12);
    EXPECT_NEAR(quadric::evaluate(quadric::ellipticParaboloid(a, b), x), X + Y - x[2], 1e-12);
    EXPECT_NEAR(quadric::evaluate(quadric::hyperbolicParaboloid(a, b), x), X - Y - x[2], 1e-12);
    EXPECT_NEAR(quadric::evaluate(quadric::hyperboloidOneSheet(a, b, c), x), X + Y - Z - 1, 1e-12);
    EXPECT_NEAR(quadric::evaluate(quadric::hyperboloidTwoSheets(a, b, c), x), X + Y - Z + 1, 1e-12);
    const Eigen::Vector3d n = Eigen::Vector3d(1, 2, 2) / 3.0;
    EXPECT_NEAR(quadric::evaluate(quadric::planePair(n, 0.5, 0.25), x),
                (n.dot(x) - 0.5) * (n.dot(x) - 0.5) - 0.0625, 1e-12);
  }
}

TEST(QuadricMatrix, TransformMovesTheSolidWithTheMap) {
  std::mt19937_64 rng(83);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int i = 0; i < 500; ++i) {
    Eigen::Matrix3d M;
    for (int k = 0; k < 9; ++k) M.data()[k] = u(rng);
    if (std::fabs(M.determinant()) < 0.1) continue;
    const Eigen::Vector3d p(u(rng), u(rng), u(rng));
    const Eigen::Matrix4d Qb = quadric::hyperboloidOneSheet(1.0, 2.0, 0.5);
    const Eigen::Matrix4d Qw = quadric::transform(Qb, quadric::affineTransform(M, p));
    for (int k = 0; k < 20; ++k) {
      const Eigen::Vector3d y(u(rng), u(rng), u(rng));  // body point
      EXPECT_NEAR(quadric::evaluate(Qw, M * y + p), quadric::evaluate(Qb, y), 1e-9 * (1 + y.squaredNorm()));
    }
    EXPECT_LT((Qw - Qw.transpose()).cwiseAbs().maxCoeff(), 1e-12 * Qw.cwiseAbs().maxCoeff());
  }
}

TEST(QuadricMatrix, PosedAndAffineEllipsoidsAgreeWithEllipsoidQuadricMatrix) {
  std::mt19937_64 rng(85);
  std::normal_distribution<double> nd(0.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    Eigen::Quaterniond q(nd(rng), nd(rng), nd(rng), nd(rng));
    q.normalize();
    const Eigen::Matrix3d R = q.toRotationMatrix();
    const Eigen::Vector3d r(1.0 + std::fabs(nd(rng)), 0.5 + std::fabs(nd(rng)), 0.2 + std::fabs(nd(rng)));
    const Eigen::Vector3d p(nd(rng), nd(rng), nd(rng));
    const Eigen::Matrix4d A = Ellipsoid(r, R, p).quadricMatrix();
    EXPECT_LT((quadric::posedEllipsoid(r, R, p) - A).cwiseAbs().maxCoeff(), 1e-12 * A.cwiseAbs().maxCoeff());
    EXPECT_LT((quadric::affineEllipsoid(R * r.asDiagonal(), p) - A).cwiseAbs().maxCoeff(),
              1e-10 * A.cwiseAbs().maxCoeff());
  }
}

TEST(QuadricMatrix, RejectsBadInput) {
  EXPECT_THROW(quadric::ellipsoid({1, 0, 1}), std::invalid_argument);
  EXPECT_THROW(quadric::ellipticCone(1, 1, std::nan("")), std::invalid_argument);
  EXPECT_THROW(quadric::planePair({1, 1, 0}, 0, 1), std::invalid_argument);  // not unit
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T(1, 1) = 0.0;
  EXPECT_THROW(quadric::transform(quadric::ellipsoid({1, 1, 1}), T), std::invalid_argument);
  T = Eigen::Matrix4d::Identity();
  T(3, 2) = 1.0;
  EXPECT_THROW(quadric::transform(quadric::ellipsoid({1, 1, 1}), T), std::invalid_argument);
}

}  // namespace
}  // namespace fcl_quadric
