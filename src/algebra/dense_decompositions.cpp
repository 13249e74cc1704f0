#include "algebra/dense_decompositions.h"

#include <Eigen/Dense>

namespace fcl_quadric {
namespace detail {

SymmetricEigen2 selfAdjointEigen(const Eigen::Matrix2d& a) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(a);
  return {es.eigenvalues(), es.eigenvectors()};
}

bool fullPivLuSolve(const Eigen::Matrix3d& a, const Eigen::Vector3d& b, Eigen::Vector3d* x) {
  const Eigen::FullPivLU<Eigen::Matrix3d> lu(a);
  *x = lu.solve(b);
  return lu.isInvertible();
}

bool fullPivLuSolve(const Eigen::Matrix4d& a, const Eigen::Vector4d& b, Eigen::Vector4d* x) {
  const Eigen::FullPivLU<Eigen::Matrix4d> lu(a);
  *x = lu.solve(b);
  return lu.isInvertible();
}

Eigen::MatrixXd fullPivLuKernel(const Eigen::Matrix4d& a) { return Eigen::FullPivLU<Eigen::Matrix4d>(a).kernel(); }

Eigen::Vector2d ldltSolve(const Eigen::Matrix2d& a, const Eigen::Vector2d& b) { return a.ldlt().solve(b); }

bool colPivQrSolve(const Eigen::Matrix<double, 3, Eigen::Dynamic>& a, const Eigen::Vector3d& b, Eigen::VectorXd* x) {
  const Eigen::ColPivHouseholderQR<Eigen::Matrix<double, 3, Eigen::Dynamic>> qr(a);
  if (qr.rank() < a.cols()) return false;
  *x = qr.solve(b);
  return true;
}

}  // namespace detail
}  // namespace fcl_quadric
