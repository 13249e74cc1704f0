#include "fcl_quadric/geometry/ellipsoid.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "fcl_quadric/algebra/quadric_matrix.h"
#include "fcl_quadric/tolerances.h"

namespace fcl_quadric {
namespace detail {

void checkFinite(const Eigen::Vector3d& v, const char* what) {
  if (!v.allFinite()) {
    std::ostringstream os;
    os << what << " must be finite, got [" << v[0] << ", " << v[1] << ", " << v[2] << "]";
    throw std::invalid_argument(os.str());
  }
}

void checkRotation(const Eigen::Matrix3d& R, const char* what) {
  if (R == Eigen::Matrix3d::Identity()) return;  // common (OcTree leaves, unrotated shapes) and exact
  // Hand-written: this runs for every posed shape of every query. Columns c0, c1, c2: the six
  // entries of R^T R - I and det R = c0 . (c1 x c2). std::isfinite raises no FP exception.
  bool finite = true;
  for (int i = 0; i < 9; ++i) finite &= std::isfinite(R.data()[i]);
  if (finite) {
    const Eigen::Vector3d c0 = R.col(0), c1 = R.col(1), c2 = R.col(2);
    const double tol = tolerance::kRotationOrthogonality;
    const double defect = std::max({std::fabs(c0.squaredNorm() - 1.0), std::fabs(c1.squaredNorm() - 1.0),
                                    std::fabs(c2.squaredNorm() - 1.0), std::fabs(c0.dot(c1)), std::fabs(c0.dot(c2)),
                                    std::fabs(c1.dot(c2))});
    if (defect <= tol && c0.dot(c1.cross(c2)) > 0.0) return;
  }
  std::ostringstream os;
  if (!finite) {
    os << what << " must be finite, got\n" << R;
  } else {
    const double defect = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
    os << what << " is not a rotation (max |R^T R - I| = " << defect << ", det = " << R.determinant()
       << "; tolerance " << tolerance::kRotationOrthogonality << ")";
  }
  throw std::invalid_argument(os.str());
}

}  // namespace detail

Ellipsoid::Ellipsoid(const Eigen::Vector3d& radii, const Eigen::Matrix3d& R_WE, const Eigen::Vector3d& p_WE)
    : radii_(radii), R_(R_WE), p_(p_WE) {
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(radii[i]) || !(radii[i] > 0.0)) {
      std::ostringstream os;
      os << "ellipsoid radius " << "abc"[i] << " must be finite and > 0, got " << radii[i];
      throw std::invalid_argument(os.str());
    }
    if (!(radii[i] >= tolerance::kMinRadius && radii[i] <= tolerance::kMaxLength)) {
      std::ostringstream os;
      os << "ellipsoid radius " << "abc"[i] << " must be in [" << tolerance::kMinRadius << ", "
         << tolerance::kMaxLength << "], got " << radii[i];
      throw std::invalid_argument(os.str());
    }
  }
  detail::checkRotation(R_WE, "ellipsoid rotation");
  detail::checkFinite(p_WE, "ellipsoid centre");
  if (!(p_WE.cwiseAbs().maxCoeff() <= tolerance::kMaxLength)) {
    std::ostringstream os;
    os << "ellipsoid centre coordinates must be within +-" << tolerance::kMaxLength << ", got ["
       << p_WE.transpose() << "]";
    throw std::invalid_argument(os.str());
  }
}

Ellipsoid::Ellipsoid(const Eigen::Vector3d& radii, const Eigen::Isometry3d& X_WE)
    : Ellipsoid(radii, X_WE.linear(), X_WE.translation()) {}

Ellipsoid Ellipsoid::sphere(double r, const Eigen::Vector3d& p_WE) {
  return Ellipsoid(Eigen::Vector3d::Constant(r), Eigen::Matrix3d::Identity(), p_WE);
}

Ellipsoid Ellipsoid::fromAffine(const Eigen::Matrix3d& M, const Eigen::Vector3d& p) {
  if (!M.allFinite()) {
    std::ostringstream os;
    os << "affine map of an ellipsoid must be finite, got\n" << M;
    throw std::invalid_argument(os.str());
  }
  detail::checkFinite(p, "ellipsoid centre");
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(M * M.transpose());
  const Eigen::Vector3d ev = es.eigenvalues();  // ascending
  if (!(ev[0] > 0.0) || !(ev[0] >= 1e-24 * ev[2])) {
    std::ostringstream os;
    os << "affine map of an ellipsoid is singular or too ill-conditioned (squared singular values " << ev[0]
       << " .. " << ev[2] << ")";
    throw std::invalid_argument(os.str());
  }
  Eigen::Matrix3d R = es.eigenvectors();
  if (R.determinant() < 0.0) R.col(2) = -R.col(2);
  return Ellipsoid(ev.cwiseSqrt(), R, p);
}

Eigen::Matrix4d Ellipsoid::quadricMatrix() const { return quadric::posedEllipsoid(radii_, R_, p_); }

double Ellipsoid::implicit(const Eigen::Vector3d& x) const {
  const Eigen::Vector3d u = (R_.transpose() * (x - p_)).cwiseQuotient(radii_);
  return u.squaredNorm() - 1.0;
}

Eigen::Vector3d Ellipsoid::normalAt(const Eigen::Vector3d& x) const {
  const Eigen::Vector3d u = (R_.transpose() * (x - p_)).cwiseQuotient(radii_.cwiseProduct(radii_));
  return (R_ * u).normalized();
}

double Ellipsoid::support(const Eigen::Vector3d& n) const {
  // h(n) = n.p + |S R^T n|
  return n.dot(p_) + (R_.transpose() * n).cwiseProduct(radii_).norm();
}

Eigen::Vector3d Ellipsoid::supportPoint(const Eigen::Vector3d& n) const {
  // argmax: p + R S^2 R^T n / |S R^T n|
  Eigen::Vector3d m = (R_.transpose() * n).cwiseProduct(radii_);
  double norm = m.norm();
  if (norm == 0.0 || std::isinf(norm)) {  // n = 0, or |m|^2 under/overflows: rescale m first
    const double s = m.cwiseAbs().maxCoeff();
    if (s == 0.0) return p_;  // n = 0: every point attains h(0) = 0 (was 0/0 = NaN)
    m /= s;
    norm = m.norm();
  }
  return p_ + R_ * (m.cwiseProduct(radii_) / norm);
}

}  // namespace fcl_quadric
