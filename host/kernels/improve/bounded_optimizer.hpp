// SPDX-License-Identifier: MIT
#pragma once
// Bound-constrained minimisation for calibration (docs/spec/algorithms.md §7).
// Parameters are scaled to [0, 1] by their bounds; NLopt's LD_SLSQP gets a central
// finite-difference gradient in scaled units; LN_COBYLA, LN_BOBYQA and LN_NELDERMEAD are the
// derivative-free alternatives. Several seeded starts are supported, every evaluation is
// recorded, and errors thrown by the objective come back out of minimize() unchanged
// (nlopt.hpp alone would replace them by "nlopt failure").
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace smi::improve {

/// One calibration parameter: its name, bounds and starting value (lower < upper, start inside).
struct Parameter {
  std::string name;
  double lower = 0.0;
  double upper = 1.0;
  double start = 0.5;
};

/// slsqp and lbfgs use the gradient (the analytic one when OptimizerOptions::gradient is set,
/// else central differences); lbfgs (NLopt's low-storage BFGS, bounds by projection) needs fewer
/// evaluations than SLSQP on smooth bound-constrained calibrations with an analytic gradient
/// (bench/results/calibrate.md); SLSQP stays the default.
enum class Method { slsqp, cobyla, bobyqa, neldermead, lbfgs };

/// Whether the method asks for gradients (analytic or by central differences).
inline bool uses_gradient(Method m) { return m == Method::slsqp || m == Method::lbfgs; }

/// What the objective returns: the value minimised and, optionally, its parts (one per response).
struct Evaluation {
  double value = 0.0;
  Eigen::VectorXd parts;
};
/// The objective, called with θ in the parameters' own units.
using Objective = std::function<Evaluation(const Eigen::VectorXd& theta)>;
/// "slsqp", "lbfgs" (also "l-bfgs"), "cobyla", "bobyqa", "neldermead" (also "nelder-mead"); throws naming the choices.
Method parse_method(std::string_view name);
std::string method_name(Method m);

struct HistoryEntry;

/// A start moved before optimising (e.g. to where predicted and experimental PDFs overlap).
struct PreparedStart {
  Eigen::VectorXd theta;  ///< in the parameters' own units
  std::string note;       ///< empty when not moved; else why and where to (goes to warnings)
  int evaluations = 0;    ///< objective or model evaluations spent deciding (not in the history)
  /// Why a preparation that minimises something stopped ("tolerance_reached", "ftol_reached", "stationary",
  /// "max_iterations"), and its criterion before and after; empty / NaN when it does not say.
  std::string status;
  double criterion_before = std::numeric_limits<double>::quiet_NaN();
  double criterion_after = std::numeric_limits<double>::quiet_NaN();
};

/// The objective's value and its gradient in the parameters' own units.
using ObjectiveGradient = std::function<Evaluation(const Eigen::VectorXd& theta, Eigen::VectorXd& grad)>;

/// The largest central-difference step, scaled units: a tenth of a range is no longer a derivative.
inline constexpr double kMaxFdStep = 0.1;

struct OptimizerOptions {
  Method method = Method::slsqp;
  double xtol_rel = 1e-6;
  double ftol_abs = 1e-8;
  /// Budget of objective evaluations per start, finite-difference probes included.
  int maxeval = 500;
  /// Central-difference step in scaled [0, 1] units (spec §7: 1e-4 to 1e-3), at most kMaxFdStep.
  double fd_step = 1e-4;
  /// Initial step of the derivative-free methods, scaled units (spec: about 10 % of the range).
  double initial_step = 0.1;
  /// Number of starts: the given start, then multistart − 1 seeded uniform points in the box.
  int multistart = 1;
  /// Starts optimised side by side (pool::parallel_for, one task per start); the result does not depend on it. Above 1
  /// the objective, gradient, prepare_start and observer are called from several threads at
  /// once and must be safe for that (C++ models, a Lua model behind its gate: yes; other Lua callbacks: no).
  int start_threads = 1;
  std::uint64_t seed = 0;
  /// Called after every recorded evaluation (progress display); may throw to abort.
  std::function<void(const HistoryEntry&)> observer;
  /// Called with every start (own units) before it is optimised; may move it.
  std::function<PreparedStart(const Eigen::VectorXd& theta)> prepare_start;
  /// Analytic gradient for SLSQP: when set, one call gives value and gradient (no
  /// finite-difference probes).
  ObjectiveGradient gradient;
  /// Basin hopping (monotone): after its local run each start jumps `hops` times from its best
  /// point by a uniform step of up to ±hop_step (scaled units) in every parameter and runs the
  /// local method again, keeping the new optimum when it is lower. Local methods stop in the
  /// first basin they enter; on a multimodal objective the hops let every start reach the
  /// lowest basin near it, so independent starts end at the same optimum (at (hops + 1) times
  /// the cost at most: each hop's local run has its own `maxeval`).
  int hops = 0;
  double hop_step = 0.2;
  /// SLSQP only: compute a gradient only where NLopt will use it. NLopt's SLSQP asks for the value
  /// AND the gradient at the first trial point of every line search (its "mode -2", which saves a
  /// call when the full step is accepted) and discards that gradient when the step is rejected.
  /// With this set, the first trial's value comes first; when it fails the line search's
  /// sufficient-decrease test f − f0 <= 0.1 ∇f0·(x − x0) (with a margin for rounding), the
  /// gradient is not computed (NLopt never reads it: the line search goes on with values, then
  /// asks for the gradient at the accepted point). The iterates are the same bit for bit; only the
  /// work for rejected steps goes (k model passes, or 2k objective evaluations, per rejected step).
  /// Worth it when a gradient costs several values (differences: 2k evaluations, or k model
  /// passes); with an analytic gradient about as cheap as a value (a Kriging's Jacobian), the
  /// value computed apart costs about what the skipped gradients save (the steering column's
  /// trial 2: 5 to 10 % more CPU in one measurement), so it is off by default and the
  /// calibration turns it on for differences. A run that ends on its budget gets further with it (its probes are saved).
  bool defer_gradient = false;
};


struct HistoryEntry {
  Eigen::VectorXd theta;
  double value = 0.0;
  Eigen::VectorXd parts;
  int start = 0;       ///< 0-based index of the start this evaluation belongs to
  bool probe = false;  ///< a finite-difference probe rather than a point the optimiser asked for
};

struct StartResult {
  Eigen::VectorXd start;  ///< where the optimiser began (after prepare_start)
  Eigen::VectorXd given;  ///< the start before prepare_start
  Eigen::VectorXd theta;
  double value = 0.0;
  int evaluations = 0;
  std::string status;  ///< NLopt's stop reason: "xtol_reached", "roundoff_limited", ...
  /// The criterion it ended on ("xtol_rel 1e-06 reached") or "missed: ..." naming the tolerances
  /// it did not reach and how far the last step was from them.
  std::string criterion;
  bool converged = false;
  int deferred_gradients = 0;  ///< gradients not computed at rejected line-search trials (defer_gradient)
  int hops = 0;           ///< basin hops tried (OptimizerOptions::hops)
  int hops_improved = 0;  ///< of them, those that found a lower optimum (kept)
  std::string start_status;        ///< prepare_start's PreparedStart::status (empty: none said)
  double start_criterion_before = std::numeric_limits<double>::quiet_NaN();  ///< and its criterion
  double start_criterion_after = std::numeric_limits<double>::quiet_NaN();
};

struct OptimizationResult {
  Eigen::VectorXd theta;  ///< best point over all starts
  double value = 0.0;
  Eigen::VectorXd parts;
  int evaluations = 0;  ///< all objective evaluations, all starts
  int start_evaluations = 0;  ///< spent by prepare_start (checking and moving starts)
  bool converged = false;
  std::string status;  ///< status of the best start
  int best = 0;        ///< index into `starts` of the start whose optimum is theta (the first on ties)
  std::vector<HistoryEntry> history;
  std::vector<StartResult> starts;
  std::vector<std::string> warnings;
  /// θ where each parameter sits on (or within 1e-6 of the range of) a bound.
  std::vector<std::string> at_bounds;
  /// Distinct optima over the starts (indices into `starts`, best first): two starts end at the
  /// same optimum when their objectives agree to 1e-6 + 1e-4 |f| and their points to 1e-2 (times sqrt k) of
  /// the box (scaled distance).
  std::vector<int> optima;
  bool starts_agree = true;  ///< one distinct optimum
};

/// Checks names, finiteness and lower < upper, start within bounds; throws InvalidArgument naming
/// the parameter.
void validate_parameters(const std::vector<Parameter>& params);

/// Minimises f over the box. Rethrows the objective's own exception.
OptimizationResult minimize(const std::vector<Parameter>& params, const Objective& f, const OptimizerOptions& opt);

/// Central-difference gradient of f at θ in the parameters' own units with absolute steps h
/// (one per parameter); 2k evaluations.
Eigen::VectorXd central_gradient(const Objective& f, const Eigen::VectorXd& theta, const Eigen::VectorXd& h);

}  // namespace smi::improve
