// SPDX-License-Identifier: MIT
#pragma once
// The whole calibration pipeline behind one entry point: the objective (a
// caller's objective, or the statistical objective of Son et al. eq. 9 on a model), the prior
// and penalty terms, the gradient choice, the start preparation, the optimiser, and the analyses
// after the optimum (identifiability, start agreement, profile intervals, design bounds,
// bootstrap, the no-overlap check). smi.calibrate's binding only reads its Lua table into a
// CalibrationProblem + CalibrationOptions and pushes the CalibrationOutcome; bench/ and the C++
// tests call calibrate() directly, so they run the exact pipeline. Whatever calls back into Lua
// (an objective, a model function, a metric, a penalty, a prior function, a progress function)
// enters as a std::function capability.
#include <Eigen/Core>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "kernels/improve/bootstrap.hpp"
#include "kernels/improve/bounded_optimizer.hpp"
#include "kernels/improve/design_bounds.hpp"
#include "kernels/improve/directions.hpp"
#include "kernels/improve/identifiability.hpp"
#include "kernels/improve/no_overlap.hpp"
#include "kernels/improve/pr_tolerance.hpp"
#include "kernels/improve/profile_intervals.hpp"
#include "kernels/improve/start_agreement.hpp"
#include "kernels/improve/statistical_objective.hpp"

namespace smi::improve {

/// A scalar function of θ (own units) supplied by the caller: a penalty, a prior's function.
using ThetaFunction = std::function<double(const Eigen::VectorXd& theta)>;

/// One normal prior: weight · ½((v − mean)/std)², v = θ[param] (param >= 0) or fn(θ).
struct PriorTerm {
  std::string label;  ///< the parameter's name, or the entry's name
  int param = -1;
  ThetaFunction fn;
  double mean = 0.0;
  double std = 1.0;
};

/// One progress line of a long stage ("calibration", "bootstrap", "near-optimal"): `done` of
/// `total` units (starts, replicates, profile points), evaluations so far, the best objective
/// (NaN when the stage has none) and the estimated seconds left (negative: unknown).
struct ProgressRow {
  std::string stage;
  int done = 0;
  int total = 0;
  long evaluations = 0;
  double best = 0.0;
  double eta = -1.0;
  bool final = false;  ///< the stage's last line
};
/// Shows progress rows (a terminal line). Called from one thread at a time, at most every few
/// evaluations; must not call Lua (it may run while starts run side by side).
using ProgressLine = std::function<void(const ProgressRow&)>;

/// Σ weight · ½((v − mean)/std)² over the priors at θ; throws naming a prior whose function
/// returns a non-finite value.
double prior_sum(const std::vector<PriorTerm>& priors, double weight, const Eigen::VectorXd& theta);

/// Every default of a calibration, in one place (smi.calibrate's option names in comments).
struct CalibrationOptions {
  OptimizerOptions optimizer;  ///< method, multistart, maxeval, xtol_rel, ftol_abs, fd_step, initial_step, hops, hop_step, seed
  /// gradient: "auto" = the model's Jacobian when it has one (Kriging, m:gradient), else
  /// differences of the model at the CRN sample ("model"), else (a custom metric, lscv/sj
  /// bandwidths, the objective form) differences of the objective; "analytic" requires the
  /// model's Jacobian; "model" requires model differences to apply; "differences" always
  /// differentiates the objective (2k + 1 evaluations a gradient).
  std::string gradient = "auto";
  /// model_differences: "forward" (k + 1 model passes a gradient for k calibrated inputs) or
  /// "central" (2k + 1). Forward: SciPy's default too, and half the passes; its O(h) error at
  /// model_step 1e-6 is far below the CRN objective's own resolution.
  std::string model_differences = "forward";
  double model_step = 1e-6;  ///< model_step: relative step of model differences (input sd units)
  bool overlap_start = true;  ///< move a start where PR saturates at 2 (overlap_start = false: keep it)
  bool moment_start = false;  ///< move every start by Levenberg-Marquardt on the responses' moments (kept when better)
  double prior_weight = 1.0;

  // Diagnostics after the optimum.
  bool identifiability = true;
  bool identifiability_directions = true;  ///< identifiability = {directions = false} skips them (and near_optimal)
  IdentifiabilityOptions ident;
  DirectionsOptions directions;
  /// identifiability.tolerance as given, or 0: then chosen by the metric (near_optimal_tolerance),
  /// for PR with two or more data points per response measured from them (pr_tolerance.hpp).
  double directions_tolerance = 0.0;
  /// Resamples of the data for the measured PR tolerance (0: PR's unit-free default instead).
  int tolerance_resamples = kPrToleranceResamples;
  std::optional<BootstrapOptions> bootstrap;
  /// intervals = true | {level = 0.9, delta =}: per-parameter profile intervals.
  std::optional<ProfileOptions> intervals;
  double interval_level = 0.9;  ///< 0 when delta was given instead
  std::vector<DesignRange> design;  ///< design_bounds: the surrogates' ranges per input
  /// PR of a response within this of 2 at the optimum: no overlap (status "no_overlap").
  double no_overlap_pr = 1e-3;
};

/// What is calibrated: the objective form (objective set) or the statistical form (model set).
struct CalibrationProblem {
  std::vector<Parameter> params;
  // Objective form.
  Objective objective;
  /// The objective's part labels, asked after the optimisation (a Lua objective learns them at its first call).
  std::function<std::vector<std::string>()> objective_parts;
  // Statistical form.
  std::vector<InputSpec> inputs;
  std::vector<ResponseSpec> responses;
  StatisticalOptions stat;
  Model model;  ///< the model (any), used when native_model is empty
  /// model and jacobian may be called from several threads at once (a Lua model behind a gate,
  /// bindings/improve/lua_gate.hpp: its calls take turns, the rest of an evaluation does not).
  bool model_thread_safe = false;
  /// A model that calls no Lua, built for `threads` prediction threads: lets the starts run side
  /// by side when nothing else calls Lua. Empty for a Lua model.
  std::function<Model(int threads)> native_model;
  StatisticalObjective::ModelJacobian jacobian;  ///< the model's own Jacobian, or empty
  CustomMetric metric;                           ///< a custom metric of the predictions, or empty
  // Both forms.
  ThetaFunction penalty;
  std::vector<PriorTerm> priors;
  /// Called after each recorded evaluation (a Lua progress function: keeps the starts sequential).
  std::function<void(const HistoryEntry&)> progress;
  /// The terminal progress line of the optimisation, the bootstrap and the near-optimal analysis.
  ProgressLine progress_line;
  /// The capabilities above may be called from several threads at once (C++ callers, or Lua behind a gate).
  bool callbacks_thread_safe = false;
};

struct CalibrationOutcome {
  OptimizationResult opt;
  std::vector<std::string> part_names;  ///< labels of Evaluation::parts (responses, then "penalty", "prior")
  std::optional<IdentifiabilityResult> ident;
  std::optional<DirectionsResult> directions;
  std::optional<ProfileResult> profile;
  std::optional<BootstrapResult> boot;
  std::optional<StartAgreement> agreement;  ///< with multistart > 1
  std::optional<StatisticalObjective> stat;
  std::vector<std::string> warnings;  ///< everything worth telling, optimiser's included
  /// The analyses after the optimum that failed ("bootstrap", "identifiability", ...) with their
  /// errors; each is also among the warnings. The optimum stands.
  std::map<std::string, std::string> not_computed;
  /// "analytic" (the model's Jacobian), "model_differences", "differences" (of the objective),
  /// "none" (a derivative-free method).
  std::string gradient = "none";
  double tolerance = 0.0;       ///< "fits as well as the optimum" (near-optimal, agreement, directions)
  std::string tolerance_basis;  ///< where it comes from, in words
  double prior_value = 0.0;     ///< the prior part at the optimum (0 without priors)
  bool converged = false;       ///< the optimiser's, and false with no overlap
  std::string status;           ///< the optimiser's, or "no_overlap"
  std::string message;          ///< with "no_overlap": what to check
  std::vector<NoOverlap> no_overlap;
  /// The prior sum at any θ (for callers checking other points against the same objective).
  ThetaFunction prior_at;
};

/// The objective increase that fits "as well as the optimum" and its basis, before any data are
/// resampled: the given tolerance; PR 0.01 per response (unit-free, [0, 2] each; calibrate()
/// replaces it by the one measured from the data points when every response has two or more); loglik ½ χ²₁(0.95) = 1.920729;
/// otherwise 1e-6 max(1, |optimum|).
std::pair<double, std::string> near_optimal_tolerance(const CalibrationProblem& p, const CalibrationOptions& o, double optimum);

/// Runs the calibration and its analyses. Throws InvalidArgument for a bad problem; an analysis
/// after the optimum that fails becomes a warning (the optimum stands).
CalibrationOutcome calibrate(const CalibrationProblem& p, const CalibrationOptions& o);

}  // namespace smi::improve
