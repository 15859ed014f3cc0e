// SPDX-License-Identifier: MIT
#include "eigen_solve.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace cfe {

namespace {

using SpMat = Eigen::SparseMatrix<double>;

void finish(Modes& out, const Eigen::MatrixXd& M, bool allow_rigid) {
  // Mass-normalise explicitly so the contract phi' M phi = 1 holds whatever the solver returned.
  for (Eigen::Index k = 0; k < out.phi.cols(); ++k) out.phi.col(k) /= std::sqrt(out.phi.col(k).dot(M * out.phi.col(k)));
  if (!allow_rigid && !(out.lambda(0) > 0)) {
    std::ostringstream os;
    os << "first eigenvalue " << out.lambda(0) << " (rad/s)^2 <= 0: the model is unrestrained (check supports)";
    throw std::runtime_error(os.str());
  }
}

// Number of eigenvalues below mu: negative pivots of LDL'(K - mu M) (Sylvester's law of inertia).
std::optional<int> sturm_count(const SpMat& K, const SpMat& M, double mu) {
  Eigen::SimplicialLDLT<SpMat> ldlt(K - mu * M);
  if (ldlt.info() != Eigen::Success) return std::nullopt;
  return static_cast<int>((ldlt.vectorD().array() < 0).count());
}

// Shift-invert block subspace iteration with Rayleigh-Ritz (Bathe's method). Converges the
// lowest `count` modes at the rate lambda_count / lambda_(p+1) per sweep; p = 2 count.
std::optional<Modes> subspace(const SpMat& K, const SpMat& M, int count) {
  const Eigen::Index n = K.rows();
  const Eigen::Index p = std::min<Eigen::Index>(n, std::max(2 * count, count + 8));
  // A small negative shift keeps K - shift M positive definite even with rigid-body modes.
  const double shift = -1.0;
  Eigen::SimplicialLDLT<SpMat> ldlt(K - shift * M);
  if (ldlt.info() != Eigen::Success) return std::nullopt;

  // Deterministic start: a fixed pseudo-random block (same numbers on every run).
  Eigen::MatrixXd X(n, p);
  std::uint64_t s = 0x9e3779b97f4a7c15ULL;
  for (Eigen::Index j = 0; j < p; ++j)
    for (Eigen::Index i = 0; i < n; ++i) {
      s = s * 6364136223846793005ULL + 1442695040888963407ULL;
      X(i, j) = static_cast<double>(s >> 11) * 0x1.0p-53 - 0.5;
    }
  Eigen::VectorXd lambda, previous;
  for (int sweep = 0; sweep < 80; ++sweep) {
    const Eigen::MatrixXd MX = M * X;
    Eigen::MatrixXd Y = ldlt.solve(MX);
    // K Y = M X + shift M Y: the projected stiffness without multiplying by K, whose large
    // entries (1e7 N mm/rad lock, 1e5 N/mm tie) would cost digits by cancellation.
    Eigen::MatrixXd KY = MX + shift * (M * Y);
    // Columns differ in scale by lambda ratios; equal M-norms keep Y'MY well conditioned.
    Eigen::MatrixXd MY = M * Y;
    for (Eigen::Index j = 0; j < p; ++j) {
      const double d = 1.0 / std::sqrt(Y.col(j).dot(MY.col(j)));
      Y.col(j) *= d;
      MY.col(j) *= d;
      KY.col(j) *= d;
    }
    Eigen::MatrixXd Kr = Y.transpose() * KY, Mr = Y.transpose() * MY;
    Kr = 0.5 * (Kr + Kr.transpose()).eval();
    Mr = 0.5 * (Mr + Mr.transpose()).eval();
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> rr(Kr, Mr);
    if (rr.info() != Eigen::Success) return std::nullopt;
    X = Y * rr.eigenvectors();
    lambda = rr.eigenvalues();
    // Converged when every wanted Ritz pair has a small residual ||K x - lambda M x|| / ||K x||.
    const Eigen::MatrixXd KX = K * X.leftCols(count), MXk = M * X.leftCols(count);
    double worst = 0;
    for (int k = 0; k < count; ++k)
      worst = std::max(worst, (KX.col(k) - lambda(k) * MXk.col(k)).norm() / KX.col(k).norm());
    // Residuals bottom out near 1e-10 (K spans 1e2..1e7 N/mm), but the eigenvalues are then
    // exact far beyond the 6 digits asked: their error is quadratic in the vector error. So ask
    // for a small residual and eigenvalues that no longer move (1e-11 relative).
    double moved = std::numeric_limits<double>::infinity();
    if (previous.size() == lambda.size())
      moved = ((lambda.head(count) - previous.head(count)).array().abs() / lambda.head(count).array().abs().max(1.0)).maxCoeff();
    previous = lambda;
    if (worst < 1e-8 && moved < 1e-11) {
      // The subspace could have missed a mode; the Sturm count between the wanted and the next
      // Ritz value proves it did not.
      const double mu = p > count ? 0.5 * (lambda(count - 1) + lambda(count)) : lambda(count - 1) * (1 + 1e-9);
      const auto below = sturm_count(K, M, mu);
      if (!below || *below != count) return std::nullopt;
      Modes out;
      out.lambda = lambda.head(count);
      out.phi = X.leftCols(count);
      return out;
    }
  }
  return std::nullopt;
}

}  // namespace

Eigen::VectorXd Modes::frequency_hz() const {
  return lambda.unaryExpr([](double l) { return std::sqrt(std::max(l, 0.0)) / (2.0 * std::numbers::pi); });
}

Modes solve_modes_dense(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M, int count, bool allow_rigid) {
  count = static_cast<int>(std::min<Eigen::Index>(count, K.rows()));
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M, Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
  if (es.info() != Eigen::Success) throw std::runtime_error("eigen-solution failed: the mass matrix is not positive definite");
  Modes out;
  out.lambda = es.eigenvalues().head(count);
  out.phi = es.eigenvectors().leftCols(count);
  finish(out, M, allow_rigid);
  return out;
}

Modes solve_modes(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M, int count, bool allow_rigid) {
  count = static_cast<int>(std::min<Eigen::Index>(count, K.rows()));
  // Subspace iteration needs room for a guard block; tiny systems go dense.
  if (K.rows() >= 4 * count) {
    const SpMat Ks = K.sparseView(), Ms = M.sparseView();
    if (auto m = subspace(Ks, Ms, count)) {
      finish(*m, M, allow_rigid);
      return *m;
    }
  }
  return solve_modes_dense(K, M, count, allow_rigid);
}

}  // namespace cfe
