// SPDX-License-Identifier: MIT
#pragma once
// Designs of experiments on the unit cube [0, 1]^d: optimized Latin hypercubes, Sobol'
// low-discrepancy points and full factorial grids. Mapping to bounds or to distributions'
// quantiles is the caller's job (scale_to_bounds below, Distribution::quantile per column).
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "platform/core/cancel.hpp"

namespace smi::surrogate::doe {

/// Space-filling criterion optimized by the enhanced stochastic evolutionary (ESE) search of
/// Jin, Chen & Sudjianto (2005). phip: minimise phi_p = (sum_{i<j} d_ij^-p)^(1/p) (Morris &
/// Mitchell 1995); maximin: the same with p = 50, which ranks designs by their smallest
/// distance first; none: a plain random Latin hypercube.
/// The range of the phi_p exponent (larger overflows the pair distances' powers).
inline constexpr double kMinPhiP = 1.0, kMaxPhiP = 200.0;

struct LhsOptions {
  std::string criterion = "maximin";  // "maximin" | "phip" | "none"
  double p = 50.0;                    // exponent for "phip"
  int iterations = 0;                 // ESE outer iterations; 0 = automatic by size
  bool centered = false;              // points at cell centres instead of uniform in the cell
};

/// n points in [0,1]^d, each column a permutation of the n strata. Same seed, same design.
/// The optimisation reads `stop` (the run's cancellation token) between steps and throws
/// smi::Interrupted with its reason.
Eigen::MatrixXd lhs(Eigen::Index n, Eigen::Index d, std::uint64_t seed, const LhsOptions& opt = {},
                    const cancel::Token& stop = cancel::process_token());

/// phi_p of the rows of X (Euclidean distances). Throws for two identical rows.
double phi_p(const Eigen::MatrixXd& X, double p);
/// Smallest Euclidean distance between two rows.
double min_distance(const Eigen::MatrixXd& X);

/// Largest dimension sobol() supports (Joe & Kuo direction numbers written out in sobol.cpp).
int sobol_max_dim();
/// Points 1..n of the unscrambled Sobol' sequence (Gray-code order, 32-bit) in d dimensions,
/// skipping the all-zero point 0 so that every coordinate lies in (0, 1) and can go through a
/// quantile function. `skip` extra points may be dropped as well.
Eigen::MatrixXd sobol(Eigen::Index n, Eigen::Index d, Eigen::Index skip = 0);

/// smi.doe.sobol's option: points of the sequence skipped first.
struct SobolOptions {
  Eigen::Index skip = 0;
};

/// All combinations of levels[j] values in column j (first column varies slowest).
Eigen::MatrixXd full_factorial(const std::vector<Eigen::VectorXd>& levels);

/// Maps U in [0,1]^d to lo + (hi - lo) * U column by column.
Eigen::MatrixXd scale_to_bounds(const Eigen::MatrixXd& U, const Eigen::VectorXd& lo, const Eigen::VectorXd& hi);

}  // namespace smi::surrogate::doe
