// SPDX-License-Identifier: MIT
#pragma once
// Dense linear algebra for models written in Lua (smi.mat:solve, :inverse, :det, :chol,
// smi.mat.eigh): Eigen's factorisations behind checks that turn its silent failures (Eigen
// asserts vanish under NDEBUG; a singular LU just gives inf) into errors naming the problem.
#include <Eigen/Core>

#include "platform/core/errors.hpp"

namespace smi::linalg {

/// A matrix that the operation needs invertible is singular to working precision.
struct Singular : Error {
  using Error::Error;
};
/// A matrix that the operation needs symmetric positive definite is not.
struct NotPositiveDefinite : Error {
  using Error::Error;
};

/// X with A X = B (A square n x n, B with n rows), by LU with full pivoting. Throws
/// DimensionMismatch (sizes), Singular (numerical rank below n), InvalidArgument (NaN/inf).
Eigen::MatrixXd solve(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B);
/// A^-1 (same errors as solve).
Eigen::MatrixXd inverse(const Eigen::MatrixXd& A);
/// det(A) by partial-pivot LU (0 for a singular A is a value, not an error). A square.
double det(const Eigen::MatrixXd& A);
/// The lower triangular L with A = L L^T. A symmetric (relative tolerance 1e-10) positive definite.
Eigen::MatrixXd chol(const Eigen::MatrixXd& A);

struct Eigh {
  Eigen::VectorXd values;   // ascending
  Eigen::MatrixXd vectors;  // column j belongs to values[j]; unit norm (K only) or phi^T M phi = 1
};
/// K phi = lambda phi (M empty) or K phi = lambda M phi (M symmetric positive definite). Each
/// eigenvector's sign is fixed so that its entry of largest magnitude is positive (the first such
/// entry on a tie), so the same matrices always give the same vectors.
Eigh eigh(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M = Eigen::MatrixXd());

/// Throws InvalidArgument naming `what` unless A is square, finite and symmetric to a relative
/// tolerance 1e-10 of its largest entry (the first offending pair is named).
void check_symmetric(const Eigen::MatrixXd& A, const char* what);

}  // namespace smi::linalg
