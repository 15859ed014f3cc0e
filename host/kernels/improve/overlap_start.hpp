#pragma once
// Starts that work (issue 11 item 2). PR is ∫|f_exp − f_pre|: when the predicted and the
// experimental PDFs do not overlap it sits at 2 and is flat, so a gradient method started there
// never moves (and differences see only noise). Before optimising, a start whose PR for some
// response is within `saturation` of 2 is moved by a short minimisation of a moment mismatch,
// which is smooth and informative everywhere:
//   Σ_r ((mean(y_r) − mean(data_r)) / sd(data_r))² + (ln(sd(y_r) / sd(data_r)))²
// (f_exp's mean and sd for responses given as a PDF). The same model runs on the same CRN.
#include <Eigen/Core>

#include "kernels/improve/bounded_optimizer.hpp"
#include "kernels/improve/statistical_objective.hpp"

namespace smi::improve {

struct OverlapStartOptions {
  double saturation = 0.05;  ///< a response's PR above 2 − saturation counts as no overlap
  int maxeval = 200;         ///< budget of the moment-matching minimisation
};

/// The moment mismatch above at θ (one model run).
double moment_mismatch(const StatisticalObjective& obj, const Eigen::VectorXd& theta);

/// θ itself when every response's PR overlaps; else the moment-matching point, with a note.
/// Only for the PR metric (the start is returned unchanged otherwise).
PreparedStart overlap_start(const StatisticalObjective& obj, const Eigen::VectorXd& theta, const OverlapStartOptions& opt = {});

}  // namespace smi::improve
