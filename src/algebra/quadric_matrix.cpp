#include "fcl_quadric/algebra/quadric_matrix.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include <Eigen/LU>

namespace fcl_quadric {
namespace quadric {

namespace {
void checkPositive(const char* where, const char* what, double v) {
  if (!std::isfinite(v) || !(v > 0.0)) {
    std::ostringstream os;
    os << where << ": " << what << " must be finite and > 0, got " << v;
    throw std::invalid_argument(os.str());
  }
}
}  // namespace

Eigen::Matrix4d ellipsoid(const Eigen::Vector3d& radii) {
  for (int i = 0; i < 3; ++i) checkPositive("quadric::ellipsoid", "radius", radii[i]);
  return Eigen::Vector4d(1.0 / (radii[0] * radii[0]), 1.0 / (radii[1] * radii[1]), 1.0 / (radii[2] * radii[2]), -1.0)
      .asDiagonal();
}

Eigen::Matrix4d ellipticCylinder(double a, double b) {
  checkPositive("quadric::ellipticCylinder", "a", a);
  checkPositive("quadric::ellipticCylinder", "b", b);
  return Eigen::Vector4d(1.0 / (a * a), 1.0 / (b * b), 0.0, -1.0).asDiagonal();
}

Eigen::Matrix4d ellipticCone(double a, double b, double c) {
  checkPositive("quadric::ellipticCone", "a", a);
  checkPositive("quadric::ellipticCone", "b", b);
  checkPositive("quadric::ellipticCone", "c", c);
  return Eigen::Vector4d(1.0 / (a * a), 1.0 / (b * b), -1.0 / (c * c), 0.0).asDiagonal();
}

Eigen::Matrix4d ellipticParaboloid(double a, double b) {
  checkPositive("quadric::ellipticParaboloid", "a", a);
  checkPositive("quadric::ellipticParaboloid", "b", b);
  Eigen::Matrix4d Q = Eigen::Vector4d(1.0 / (a * a), 1.0 / (b * b), 0.0, 0.0).asDiagonal();
  Q(2, 3) = Q(3, 2) = -0.5;  // - z
  return Q;
}

Eigen::Matrix4d hyperbolicParaboloid(double a, double b) {
  checkPositive("quadric::hyperbolicParaboloid", "a", a);
  checkPositive("quadric::hyperbolicParaboloid", "b", b);
  Eigen::Matrix4d Q = Eigen::Vector4d(1.0 / (a * a), -1.0 / (b * b), 0.0, 0.0).asDiagonal();
  Q(2, 3) = Q(3, 2) = -0.5;
  return Q;
}

Eigen::Matrix4d hyperboloidOneSheet(double a, double b, double c) {
  checkPositive("quadric::hyperboloidOneSheet", "a", a);
  checkPositive("quadric::hyperboloidOneSheet", "b", b);
  checkPositive("quadric::hyperboloidOneSheet", "c", c);
  return Eigen::Vector4d(1.0 / (a * a), 1.0 / (b * b), -1.0 / (c * c), -1.0).asDiagonal();
}

Eigen::Matrix4d hyperboloidTwoSheets(double a, double b, double c) {
  checkPositive("quadric::hyperboloidTwoSheets", "a", a);
  checkPositive("quadric::hyperboloidTwoSheets", "b", b);
  checkPositive("quadric::hyperboloidTwoSheets", "c", c);
  return Eigen::Vector4d(1.0 / (a * a), 1.0 / (b * b), -1.0 / (c * c), 1.0).asDiagonal();
}

Eigen::Matrix4d planePair(const Eigen::Vector3d& n, double d, double w) {
  if (!n.allFinite() || !(std::fabs(n.norm() - 1.0) <= 1e-12) || !std::isfinite(d)) {
    std::ostringstream os;
    os << "quadric::planePair: need a finite unit normal and offset, got n = [" << n.transpose() << "], d = " << d;
    throw std::invalid_argument(os.str());
  }
  checkPositive("quadric::planePair", "half-width w", w);
  // (n.x - d)^2 - w^2 = X^T (m m^T - diag(0,0,0,w^2)) X with m = (n, -d).
  const Eigen::Vector4d m(n[0], n[1], n[2], -d);
  Eigen::Matrix4d Q = m * m.transpose();
  Q(3, 3) -= w * w;
  return Q;
}

Eigen::Matrix4d affineTransform(const Eigen::Matrix3d& M, const Eigen::Vector3d& p) {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = M;
  T.topRightCorner<3, 1>() = p;
  return T;
}

Eigen::Matrix4d transform(const Eigen::Matrix4d& Q_body, const Eigen::Matrix4d& T) {
  std::ostringstream os;
  if (!Q_body.allFinite() || !T.allFinite()) {
    os << "quadric::transform: matrices must be finite";
    throw std::invalid_argument(os.str());
  }
  if (T.row(3) != Eigen::RowVector4d(0, 0, 0, 1)) {
    os << "quadric::transform: last row of the affine map must be [0 0 0 1], got [" << T.row(3) << "]";
    throw std::invalid_argument(os.str());
  }
  const Eigen::Matrix3d M = T.topLeftCorner<3, 3>();
  const double det = M.determinant();
  const double scale = M.cwiseAbs().maxCoeff();
  if (!(std::fabs(det) > 1e-14 * scale * scale * scale) || !(std::fabs(det) > 0.0)) {
    os << "quadric::transform: singular affine map (det = " << det << ")";
    throw std::invalid_argument(os.str());
  }
  const Eigen::Matrix4d Ti = T.inverse();
  return Ti.transpose() * Q_body * Ti;
}

Eigen::Matrix4d posedEllipsoid(const Eigen::Vector3d& radii, const Eigen::Matrix3d& R, const Eigen::Vector3d& p) {
  Eigen::Matrix4d Ti = Eigen::Matrix4d::Identity();
  Ti.topLeftCorner<3, 3>() = R.transpose();
  Ti.topRightCorner<3, 1>() = -R.transpose() * p;
  return Ti.transpose() * ellipsoid(radii) * Ti;
}

Eigen::Matrix<long double, 4, 4> posedEllipsoidExtended(const Eigen::Vector3d& radii, const Eigen::Matrix3d& R,
                                                        const Eigen::Vector3d& p) {
  using Matrix4ld = Eigen::Matrix<long double, 4, 4>;
  for (int i = 0; i < 3; ++i) checkPositive("quadric::posedEllipsoidExtended", "radius", radii[i]);
  const Eigen::Matrix<long double, 3, 3> Rt = R.transpose().cast<long double>();
  Matrix4ld Ti = Matrix4ld::Identity();
  Ti.topLeftCorner<3, 3>() = Rt;
  Ti.topRightCorner<3, 1>() = -(Rt * p.cast<long double>());
  Eigen::Matrix<long double, 4, 1> diag;
  for (int i = 0; i < 3; ++i) {
    const long double r = radii[i];
    diag[i] = 1.0L / (r * r);
  }
  diag[3] = -1.0L;
  return Ti.transpose() * diag.asDiagonal() * Ti;
}

Eigen::Matrix4d affineEllipsoid(const Eigen::Matrix3d& M, const Eigen::Vector3d& p) {
  return transform(Eigen::Vector4d(1.0, 1.0, 1.0, -1.0).asDiagonal(), affineTransform(M, p));
}

double evaluate(const Eigen::Matrix4d& Q, const Eigen::Vector3d& x) {
  const Eigen::Vector4d X(x[0], x[1], x[2], 1.0);
  return X.dot(Q * X);
}

}  // namespace quadric
}  // namespace fcl_quadric
