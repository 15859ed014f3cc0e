// SPDX-License-Identifier: MIT
#pragma once
// "No overlap" at a calibration's optimum: a response whose predicted and
// measured distributions do not overlap at all (PR within 1e-3 of its maximum 2, or the
// predicted and measured ranges more than 4 bandwidths apart, or, for the log-likelihood, every
// datum outside the predicted support) is not a fit, whatever the
// optimiser's stopping rule says: a flat PR of 2 is a plateau every optimiser "converges" on.
// The usual cause is a units mismatch (E in GPa for a model in MPa): the ranges and the ratio
// of their centres tell the analyst which.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "kernels/improve/statistical_objective.hpp"

namespace smi::improve {

struct NoOverlap {
  std::string response;
  std::string metric;  ///< "pr" or "loglik"
  double value = 0.0;  ///< the response's part of the objective at the optimum
  double predicted_lo = 0.0, predicted_hi = 0.0;  ///< range of the predictions (CRN sample)
  double measured_lo = 0.0, measured_hi = 0.0;    ///< range of the data (f_exp's 0.1-99.9 % without data)
  double ratio = 0.0;      ///< mean prediction / mean measurement
  std::string units_hint;  ///< when the ratio is within 0.15 decades of a power of ten (not 1)
};

/// The responses without overlap at θ, given the objective's parts there (one per response).
/// `pr_margin`: PR within this of 2 counts (1e-3 by default).
std::vector<NoOverlap> find_no_overlap(const StatisticalObjective& obj, const Eigen::VectorXd& theta, const Eigen::VectorXd& parts,
                                       double pr_margin);

/// "about 1000x the data: are the inputs in the units the model expects?" for a ratio near a
/// power of ten other than 1 (0.15 decades), else empty.
std::string units_hint(double ratio);

/// One sentence per response: the name, the predicted and measured ranges, the metric, the hint.
std::string describe(const std::vector<NoOverlap>& rows);

}  // namespace smi::improve
