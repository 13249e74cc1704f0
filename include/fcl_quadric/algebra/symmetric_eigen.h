#pragma once
/// \file symmetric_eigen.h
/// Eigen-decomposition of small real symmetric matrices (the null vectors of pencil members,
/// quadratic forms restricted to a null space) by the cyclic Jacobi method (Golub & Van Loan,
/// Matrix Computations, 4th ed., §8.5.2–8.5.3).
///
/// Why not Eigen's SelfAdjointEigenSolver / JacobiSVD: their dynamic-size instantiations cost
/// 10–25 s of compile time in every translation unit that uses them (measured with gcc -O3 on
/// dimension_reduction_ccd.cpp: 60.6 s with EigenSolver + JacobiSVD, 35.2 s without), and the
/// matrices here are at most 4 x 4. Jacobi is also the more accurate method for them: each
/// eigenvalue comes with an absolute error of a few ulps of ||A||_F, and the eigenvectors are
/// orthonormal to working precision.
///
/// Part of the algebra layer: depends on Eigen's core only.

#include <Eigen/Core>

namespace fcl_quadric {

/// Sweeps of the cyclic Jacobi method before giving up. Convergence is quadratic: a 4 x 4
/// matrix needs 5–7 sweeps to reach an off-diagonal norm below 2^-53 ||A||_F. On the cap the
/// current rotation is returned (never reached in the tests); its eigenvalues are then the
/// diagonal of a matrix whose off-diagonal part is what `off_diagonal` reports (a Gershgorin
/// bound on their error).
constexpr int kJacobiMaxSweeps = 64;

/// A = V diag(values) V^T.
struct SymmetricEigenDecomposition {
  Eigen::VectorXd values;   ///< ascending
  Eigen::MatrixXd vectors;  ///< orthonormal columns, in the order of `values`
  double off_diagonal = 0;  ///< Frobenius norm of the off-diagonal part left by the last sweep
  int sweeps = 0;           ///< sweeps used
};

/// Decomposes the symmetric part (A + A^T) / 2 of a square matrix. Throws std::invalid_argument
/// naming the entry for a non-square matrix or a non-finite entry. A 0 x 0 matrix gives empty
/// results.
SymmetricEigenDecomposition symmetricEigen(const Eigen::MatrixXd& a);

}  // namespace fcl_quadric
