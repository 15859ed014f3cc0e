// SPDX-License-Identifier: MIT
#include "platform/core/linalg.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <cmath>
#include <fmt/format.h>

namespace smi::linalg {
namespace {

void check_square(const Eigen::MatrixXd& A, const char* what) {
  if (A.rows() != A.cols()) throw DimensionMismatch(fmt::format("{} must be square, got {}x{}", what, A.rows(), A.cols()));
  if (A.rows() == 0) throw InvalidArgument(fmt::format("{} is empty (0x0)", what));
}

void check_finite(const Eigen::MatrixXd& A, const char* what) {
  for (Eigen::Index j = 0; j < A.cols(); ++j)
    for (Eigen::Index i = 0; i < A.rows(); ++i)
      if (!std::isfinite(A(i, j)))
        throw InvalidArgument(fmt::format("{}[{}][{}] is {}; entries must be finite", what, i + 1, j + 1, A(i, j)));
}

/// LU with full pivoting of a square, finite A; throws Singular below full numerical rank.
Eigen::FullPivLU<Eigen::MatrixXd> invertible_lu(const Eigen::MatrixXd& A, const char* what) {
  check_square(A, what);
  check_finite(A, what);
  Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
  if (!lu.isInvertible())
    throw Singular(fmt::format("{} ({}x{}) is singular: numerical rank {} of {}", what, A.rows(), A.cols(), lu.rank(), A.rows()));
  return lu;
}

}  // namespace

void check_symmetric(const Eigen::MatrixXd& A, const char* what) {
  check_square(A, what);
  check_finite(A, what);
  const double tol = 1e-10 * A.cwiseAbs().maxCoeff();
  for (Eigen::Index j = 0; j < A.cols(); ++j)
    for (Eigen::Index i = j + 1; i < A.rows(); ++i)
      if (std::abs(A(i, j) - A(j, i)) > tol)
        throw InvalidArgument(fmt::format("{} is not symmetric: [{}][{}] = {} but [{}][{}] = {}", what, i + 1, j + 1,
                                          A(i, j), j + 1, i + 1, A(j, i)));
}

Eigen::MatrixXd solve(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  check_square(A, "A");
  if (B.rows() != A.rows())
    throw DimensionMismatch(fmt::format("A is {}x{} but b has {} rows", A.rows(), A.cols(), B.rows()));
  check_finite(B, "b");
  return invertible_lu(A, "A").solve(B);
}

Eigen::MatrixXd inverse(const Eigen::MatrixXd& A) { return invertible_lu(A, "A").inverse(); }

double det(const Eigen::MatrixXd& A) {
  check_square(A, "A");
  check_finite(A, "A");
  return A.partialPivLu().determinant();
}

Eigen::MatrixXd chol(const Eigen::MatrixXd& A) {
  check_symmetric(A, "A");
  Eigen::LLT<Eigen::MatrixXd> llt(A);
  if (llt.info() != Eigen::Success)
    throw NotPositiveDefinite(fmt::format("A ({}x{}) is not positive definite (Cholesky failed)", A.rows(), A.cols()));
  return llt.matrixL();
}

Eigh eigh(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M) {
  check_symmetric(K, "K");
  Eigh out;
  if (M.size() == 0) {
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(K);
    if (es.info() != Eigen::Success) throw NotConverged("eigh: the symmetric eigensolver did not converge");
    out.values = es.eigenvalues();
    out.vectors = es.eigenvectors();
  } else {
    if (M.rows() != K.rows() || M.cols() != K.cols())
      throw DimensionMismatch(fmt::format("K is {}x{} but M is {}x{}", K.rows(), K.cols(), M.rows(), M.cols()));
    check_symmetric(M, "M");
    // Eigen's generalised solver factors M by LLT and does not report a failure: check first.
    if (Eigen::LLT<Eigen::MatrixXd>(M).info() != Eigen::Success)
      throw NotPositiveDefinite(fmt::format("M ({}x{}) is not positive definite (Cholesky failed)", M.rows(), M.cols()));
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M, Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
    if (es.info() != Eigen::Success) throw NotConverged("eigh: the generalised symmetric eigensolver did not converge");
    out.values = es.eigenvalues();
    out.vectors = es.eigenvectors();  // Eigen normalises them to phi^T M phi = 1
  }
  for (Eigen::Index j = 0; j < out.vectors.cols(); ++j) {
    Eigen::Index k = 0;
    for (Eigen::Index i = 1; i < out.vectors.rows(); ++i)
      if (std::abs(out.vectors(i, j)) > std::abs(out.vectors(k, j)) * (1 + 1e-12)) k = i;
    if (out.vectors(k, j) < 0) out.vectors.col(j) *= -1;
  }
  return out;
}

}  // namespace smi::linalg
