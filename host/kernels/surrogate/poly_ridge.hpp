// SPDX-License-Identifier: MIT
#pragma once
// A cheap global surrogate for screening: a polynomial in the standardised inputs (main
// effects, or main effects + squares) fitted by ridge regression, the ridge weight chosen by
// the closed-form leave-one-out error (PRESS) of the hat matrix, so that the fit reports its own
// predictivity Q2 = 1 - PRESS / sum (y - mean y)^2 without refitting (Allen 1974; Hastie,
// Tibshirani & Friedman, ESL §7.10). No cross terms: with k inputs the basis has 1 + k or
// 1 + 2k columns, which a few hundred runs determine for k = 46.
#include <Eigen/Core>
#include <string>

namespace smi::surrogate::polyfit {

enum class Basis { linear, quadratic };
Basis parse_basis(const std::string& name);
const char* basis_name(Basis b);

struct Fit {
  Basis basis = Basis::quadratic;
  Eigen::VectorXd mu, sd;    // standardisation of each input column (sd = 0: column dropped)
  Eigen::VectorXd beta;      // coefficients of the centred basis columns
  Eigen::VectorXd fmean;     // design means of the basis columns
  double intercept = 0;
  double lambda = 0;         // chosen ridge weight (0 = least squares)
  double q2 = 0;             // leave-one-out predictivity
  double r2 = 0;             // in-sample
  double press = 0;
  Eigen::Index terms = 0;    // basis columns besides the intercept

  /// Predictions at the rows of X (columns as in the design).
  Eigen::VectorXd predict(const Eigen::MatrixXd& X) const;
};

/// Fits y over the rows of X (m points, k inputs); m must exceed 2. The ridge weight is the
/// one of lambda = 0 (when the basis has fewer columns than m - 1) and s_max^2 * 10^t,
/// t = -10, -9.5, ..., 1, with the smallest PRESS; a `lambda` >= 0 given is used as is.
Fit fit(const Eigen::MatrixXd& X, const Eigen::VectorXd& y, Basis basis, double lambda = -1);

}  // namespace smi::surrogate::polyfit
