// SPDX-License-Identifier: MIT
// Reference texts of smi.calibrate, smi.calibrate_bayes and smi.refine.decision_matrix (this folder). Defaults are
// read from the kernels' option structs (improve/bounded_optimizer.hpp, statistical_objective.hpp,
// bootstrap.hpp, identifiability.hpp).
#include "bindings/doc.hpp"
#include "bindings/improve/calibrate_bayes_options.hpp"
#include "bindings/improve/calibrate_options.hpp"
#include "bindings/improve/decision_matrix_options.hpp"
#include "kernels/improve/bootstrap.hpp"
#include "kernels/improve/bounded_optimizer.hpp"
#include "kernels/improve/identifiability.hpp"
#include "kernels/improve/pr_tolerance.hpp"
#include "kernels/improve/statistical_objective.hpp"

namespace smi::bind {
namespace {

const char* const kText = R"DOC(
@ smi.calibrate{...} -> result
Calibration of input distribution parameters (paper section 4), in one of two forms.
Model form: inputs whose mean/std are ranges {lower, upper, start} are calibrated so that the
model's predicted distributions (Monte Carlo with common random numbers, KDE of each output)
match the experimental data, by the probability residual (default), the log-likelihood, or your
metric. Objective form: parameters = {{name, lower, upper, start}, ...} and objective(theta).
The optimizer works in scaled [0, 1] units (the gradient-based SLSQP or L-BFGS, with analytic
gradients where the model gives them and central differences otherwise, or the derivative-free
COBYLA, BOBYQA or Nelder-Mead), from the start and multistart - 1 seeded points.
options:
${calibrate}
returns: r with r.params {name = value}, r.theta (in parameter order), r.names, r.objective,
  r.metrics (per output), r.tolerance (the objective rise that still fits as well as the optimum:
  identifiability.tolerance; for PR the standard deviation of the summed PR at the optimum over
  identifiability.resamples bootstrap resamples of the data rows, or 0.01 per response without
  data points; loglik 1.920729 = chi2_1(0.95)/2; else 1e-6 of the optimum) and r.tolerance_basis (its reason in words), r.prior_value (the prior part at the
  optimum, 0 without prior) and r.prior_at(theta) (the same sum anywhere), r.inputs {input = {dist =, mean =, std =}} and r.distributions
  {input = dist} (model form), r.history (every evaluation), r.converged, r.status (NLopt's stop
  reason, or "no_overlap": some response's PR within 1e-3 of 2, or loglik with every datum outside
  the predicted support; then converged = false, r.message names the response, the predicted and
  measured ranges and a units hint when their ratio is near a power of ten, and r.no_overlap
  {{response, metric, value, predicted = {lo, hi}, measured = {lo, hi}, ratio, units_hint}}),
  r.optimizer_status (NLopt's stop reason always), r.method,
  r.evaluations, r.model_runs (model calls), r.model_passes (n-row blocks the model computed), r.starts {{start, params, objective, evaluations, status, converged, criterion (the
  stopping rule it ended on, or "missed: maxeval 500 spent before xtol_rel ... or ftol_abs ..." with
  the last step's size),
  prepared = {status = "tolerance_reached"|"ftol_reached"|"stationary"|"max_iterations", before,
  after} (moment_start: how its Levenberg-Marquardt ended, the mismatch before and after)}, ...},
  r.start_evaluations,
  r.starts_agree (one point), r.optima (distinct optima), r.agreement {agree, same, starts,
  tolerance, largest_gap, rows = {{gap, within, same_prediction, prediction_distance, barrier,
  same}}, text} (multistart > 1: the same optimum where the data
  can tell: within the tolerance, and the same predictions or no barrier between), r.gradient,
  r.at_bounds, r.warnings (at a bound, outside the design range, not identifiable),
  r.identifiability {span, weak, profiles, evaluations, directions = {{determined, loadings,
  curvature, profile}, ...}}, r.near_optimal {tolerance, points, objectives}, r.intervals,
  r.bootstrap {lower, upper (percentiles), normal = {lower, upper} (estimate ± z sd inside the
  bounds), std, lower_mc_error, upper_mc_error (the endpoints' Monte Carlo errors), replicates_needed (for errors under 10 % of the half-width), level, replicates, failed,
  failures = {{replicate, message}, ...}, samples}, r.not_computed {analysis = error} (an analysis
  after the optimum that failed, "bootstrap" when fewer than two replicates succeeded; the
  optimum stands)
errors: both or neither form; a range with lower >= upper or a start outside it (named); a
  lognormal mean range reaching 0; data with fewer than 2 points; the model failing (its message);
  an unknown option (the closest name is suggested)
example:
  local r = smi.calibrate{
    parameters = {{"a", 0, 10}, {"b", -5, 5}},
    objective = function(t) return (t.a - 3) ^ 2 + (t.b + 1) ^ 2 end,
    identifiability = false,
  }
  print(("a = %.3f, b = %.3f, converged = %s"):format(r.params.a, r.params.b, tostring(r.converged)))

@ smi.calibrate_bayes{...} -> result
Bayesian calibration: posterior samples of the parameters and the log evidence (marginal
likelihood) log Z with its Monte Carlo error, by transitional MCMC (tempering from the prior to
the posterior; log Z is the sum over stages of log mean w). Priors are densities: uniform on a
range by default, or normal / lognormal (truncated to the range). Objective form:
parameters = {{name =, lower =, upper =} | {name =, prior = {dist =, mean =, std =}}, ...} and
loglik(Theta), called once per batch with an smi.mat of points (rows), returning a vec of
log-likelihoods. Model form: model, inputs and data as smi.calibrate's; each specimen's
responses are one joint observation: p(y_i | theta) is estimated from n propagated samples
(common random numbers) by a Gaussian kernel of covariance noise^2 + H in response space (H the
normal-reference bandwidth times the predictions' covariance), so log L is smooth in theta;
r.loglik_error is its Monte Carlo error at the MAP. See docs/bayesian-calibration.md.
options:
${calibrate_bayes}
returns: r with r.names (parameter order), r.samples (smi.mat, rows = posterior samples),
  r.loglik (vec: log L at each sample), r.mean, r.std, r.map {name = value} (the sample of highest
  posterior density), r.interval {name = {lo, hi}} (90 % central, r.interval_level),
  r.log_evidence, r.log_evidence_error (the sampler's Monte Carlo standard error), r.loglik_error
  (model form: Monte Carlo error of log L at the MAP; 0 in the objective form),
  r.diagnostics {stages, beta = {...}, acceptance = {...}, ess = {...}, sweeps = {...},
  chain_correlation = {...}, scale = {...}, converged, reasons = {...}}, r.converged,
  r.evaluations (likelihood values), r.model_runs (model calls, each on many stacked samples),
  r.seed; model form also r.n and r.noise {response = sd}; tostring(r) prints a summary
errors: both or neither form; a parameter without a range or a prior; a prior on a name that
  is not calibrated (the names listed); data of unequal lengths or a single specimen without
  noise; loglik returning NaN or the wrong count; the model failing (its message)
example:
  local r = smi.calibrate_bayes{
    parameters = {{name = "a", lower = -5, upper = 5},
                  {name = "b", prior = {dist = "normal", mean = 0, std = 2}}},
    loglik = function(T)
      local a, b = T:col(1), T:col(2)
      return -0.5 * ((a - 1) ^ 2 / 0.25 + (b + 1) ^ 2 / 0.04)
    end,
    samples = 500, seed = 1,
  }
  print(r)
  print(("a = %.2f +- %.2f, log Z = %.2f"):format(r.mean.a, r.std.a, r.log_evidence))

@ module smi.refine
Model refinement: the weighted decision matrix (spec section 6) over candidate model revisions;
the paper's criteria are in require "smi.refine.criteria".

@ smi.refine.decision_matrix{candidates =, criteria =} -> result
The weighted decision matrix: each criterion rates every candidate by its magnitude (smaller is
better, normalized by the largest), weighted, summed into an overall rating per candidate.
options:
${decision_matrix}
returns: {ratings (criterion x candidate), overall = {...}, weights, best (index), best_name,
  best_candidate, ranking = {indices into candidates, best first}, ties (indices)}; tostring(r) prints
  the matrix
errors: no candidates or criteria; a magnitude count that does not match the candidates (named);
  a magnitude that is not a number, negative or NaN (criterion and candidate named); weights that
  do not sum to 1 ("divide each weight by the sum")
example:
  local r = smi.refine.decision_matrix{
    candidates = {"airbag", "material"},
    criteria = {{name = "error", weight = 0.6, magnitude = {0.02, 0.10}},
                {name = "cost", weight = 0.4, magnitude = {60, 20}}},
  }
  print(r.best_name, r.overall[1], r.overall[2])
)DOC";

}  // namespace

DocText doc_improve() {
  const smi::improve::BootstrapOptions boot;
  const smi::improve::IdentifiabilityOptions id;
  // The option list from the schema first; then the nested tables' defaults it mentions.
  const std::string text = fill(kText, {{"calibrate", improve::calibrate_schema().doc()},
                                             {"calibrate_bayes", improve::calibrate_bayes_schema().doc()},
                                             {"decision_matrix", improve::decision_matrix_schema().doc()}});
  return {"bindings/improve/doc.cpp",
          fill(text, {{"ident_points", num(id.points)},
                       {"ident_rel_tol", num(id.rel_tol)},
                       {"ident_abs_tol", num(id.abs_tol)},
                       {"ident_resamples", num(smi::improve::kPrToleranceResamples)},
                       {"boot_replicates", num(boot.replicates)},
                       {"boot_level", num(boot.level)}})};
}

}  // namespace smi::bind
