// SPDX-License-Identifier: MIT
#pragma once
// Starts that work. PR is ∫|f_exp − f_pre|: when the predicted and the
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

/// The moment mismatch's residuals at θ, two per response with a measured sd > 0:
/// (mean(y_r) − m_r)/sd_r and ln(sd(y_r)/sd_r); with `jacobian` non-null also their derivatives in
/// θ's own units (rows: residuals, columns: parameters), by the chain rule through the model's
/// Jacobian when it has one (one model run and one Jacobian run), else by forward differences
/// (k more model runs). `runs` counts the model runs.
Eigen::VectorXd moment_residuals(const StatisticalObjective& obj, const Eigen::VectorXd& theta, Eigen::MatrixXd* jacobian, int& runs);

struct MomentStartOptions {
  int max_iterations = 30;   ///< Levenberg–Marquardt iterations (each one model + Jacobian run)
  double tolerance = 1e-10;  ///< stop when the mismatch (sum of squared residuals) is below
  /// or when a step lowers it by less than ftol_rel of itself plus ftol_abs. Where the moments
  /// cannot all be matched (data sds below what the stds' bounds allow, or a model that cannot
  /// reproduce the data) LM creeps down a long curved valley (seen on the steering column's
  /// harness: 36.10 -> 36.08 over 20 iterations; 3.3e-3 -> 1.7e-3 over 27) long after the start
  /// is as good as a start needs: ftol_abs is a residual of 1 % of the data's sd, and the data's
  /// own moments are uncertain by far more (a mean from 9 rows by a third of an sd).
  double ftol_rel = 1e-3;
  double ftol_abs = 1e-4;
};

/// Moment-matching start (and fewer evaluations for the optimiser after it):
/// Levenberg–Marquardt on moment_residuals in scaled [0, 1] units, projected on the box; a
/// parameter on a bound that the descent pushes out of the box is held there for the step. With
/// more parameters than residuals each step is the smallest that reduces the mismatch, so
/// directions the moments do not see stay where they were. The moved point is returned when the
/// objective there is lower than at θ (two objective evaluations), θ otherwise. `evaluations`
/// counts model runs (objective evaluations and moment steps alike); `status` says why LM stopped
/// ("tolerance_reached", "ftol_reached", "stationary": no free descent or no step lowering the
/// mismatch within the box, "max_iterations"), criterion_before / _after the mismatch at θ and
/// where LM ended.
PreparedStart moment_start(const StatisticalObjective& obj, const Eigen::VectorXd& theta, const MomentStartOptions& opt = {});

/// θ itself when every response's PR overlaps; else the moment-matching point, with a note.
/// Only for the PR metric (the start is returned unchanged otherwise).
PreparedStart overlap_start(const StatisticalObjective& obj, const Eigen::VectorXd& theta, const OverlapStartOptions& opt = {});

}  // namespace smi::improve
