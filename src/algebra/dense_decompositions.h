#pragma once
/// \file dense_decompositions.h
/// The Eigen dense decompositions that several translation units of the core library share,
/// compiled once (dense_decompositions.cpp) instead of in each of them.
///
/// Why: gcc spends seconds of template instantiation on each of Eigen's decompositions in every
/// translation unit that uses one (gcc 12, front end alone: SelfAdjointEigenSolver<Matrix2d>
/// 3.5-5 s, ColPivHouseholderQR ~4 s, FullPivLU<Matrix3d> or <Matrix4d> ~1.3 s; docs/reliability.md
/// section 1, "Session 50"). Only decompositions used by two or more translation units are here:
/// moving one used once saves nothing. Each function runs exactly the decomposition its callers
/// ran before, on the same matrix type and the same values, so the results are the same bits;
/// only where the code is instantiated changes. Internal (src/); Eigen's core only in this header.

#include <Eigen/Core>

namespace fcl_quadric {
namespace detail {

/// a = vectors diag(values) vectors^T for a symmetric 2 x 2 matrix (its lower triangle is read):
/// Eigen::SelfAdjointEigenSolver<Matrix2d>(a).eigenvalues() (ascending) and .eigenvectors().
struct SymmetricEigen2 {
  Eigen::Vector2d values;
  Eigen::Matrix2d vectors;
};
SymmetricEigen2 selfAdjointEigen(const Eigen::Matrix2d& a);

/// With lu = Eigen::FullPivLU(a): *x = lu.solve(b), computed whether or not a is invertible
/// (FullPivLU then solves on its nonzero pivots), and returns lu.isInvertible().
bool fullPivLuSolve(const Eigen::Matrix3d& a, const Eigen::Vector3d& b, Eigen::Vector3d* x);
bool fullPivLuSolve(const Eigen::Matrix4d& a, const Eigen::Vector4d& b, Eigen::Vector4d* x);
/// Eigen::FullPivLU(a).kernel(): a basis of the null space, one column per dimension (a single
/// zero column when a is invertible, as Eigen returns it).
Eigen::MatrixXd fullPivLuKernel(const Eigen::Matrix4d& a);

/// Eigen::LDLT(a).solve(b).
Eigen::Vector2d ldltSolve(const Eigen::Matrix2d& a, const Eigen::Vector2d& b);

/// With qr = Eigen::ColPivHouseholderQR(a): false if qr.rank() < a.cols() (dependent columns);
/// else *x = qr.solve(b) (least squares) and true.
bool colPivQrSolve(const Eigen::Matrix<double, 3, Eigen::Dynamic>& a, const Eigen::Vector3d& b, Eigen::VectorXd* x);

}  // namespace detail
}  // namespace fcl_quadric
