// SPDX-License-Identifier: MIT
#pragma once
// The generalized eigenproblem K phi = lambda M phi (spec §7) for the lowest modes.
#include <Eigen/Core>

namespace cfe {

struct Modes {
  Eigen::VectorXd lambda;  // (rad/s)^2, ascending
  Eigen::MatrixXd phi;     // columns mass-normalised: phi' M phi = 1
  Eigen::VectorXd frequency_hz() const;
};

/// The `count` lowest modes. Sparse shift-invert subspace iteration, verified by a Sturm
/// sequence count (no mode skipped); falls back to the dense solver if either check fails.
/// Throws std::runtime_error when M is not positive definite or, unless allow_rigid,
/// lambda_1 <= 0 (an unrestrained model), naming the value.
Modes solve_modes(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M, int count = 10, bool allow_rigid = false);

/// Reference path: all modes by Eigen's dense GeneralizedSelfAdjointEigenSolver, first `count`
/// kept. O(n^3); the tests compare the fast path against it.
Modes solve_modes_dense(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M, int count = 10, bool allow_rigid = false);

}  // namespace cfe
