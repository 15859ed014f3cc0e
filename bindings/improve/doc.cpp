// Reference texts of smi.calibrate and smi.refine.decision_matrix (this folder). Defaults are
// read from the kernels' option structs (improve/bounded_optimizer.hpp, statistical_objective.hpp,
// bootstrap.hpp, identifiability.hpp).
#include "bindings/doc.hpp"
#include "kernels/improve/bootstrap.hpp"
#include "kernels/improve/bounded_optimizer.hpp"
#include "kernels/improve/identifiability.hpp"
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
  model = nil                 -- model form: an smi.model, an smi.kriging (or a table of them by
                              -- output), or a function(X) returning {output = vec}
  inputs = nil                -- model form: {name = {dist = "normal", mean = m | {lo, hi, start},
                              -- std = s | {lo, hi, start}} | {value = x}, ...} (or a list with name =);
                              -- dist: any of the nine families (truncnormal/beta with fixed lower/upper,
                              -- gamma/weibull with a fixed loc, triangular with mode_at)
  data = nil                  -- model form: {output = vec of measurements | a dist (an experimental PDF)}
  metric = "pr"               -- "pr", "loglik", or function(predicted, data) returning a number
  penalty = nil               -- function(theta) returning a number added to the metric (prior knowledge)
  prior = nil                 -- {{param = "x.mean", mean =, std =} | {name =, fn = function(theta), mean =,
                              -- std =}, ...}: adds 0.5((v - mean)/std)^2 each, reported as metrics.prior
  prior_weight = 1            -- factor on the prior part
  gradient = "auto"           -- "auto": analytic where the model gives one (Kriging, m:gradient),
                              -- else the MODEL's differences at the CRN sample ("model": one call
                              -- of the model on k + 1 stacked blocks of n rows for k calibrated
                              -- inputs, chained through the quantile derivatives, KDE and metric
                              -- like the analytic path; a solver model runs the blocks as one
                              -- parallel, resumable evaluation; k blocks where the value at that
                              -- point was just computed), else (custom metric, lscv/sj) the
                              -- objective's differences ("differences": 2k' + 1 evaluations a
                              -- gradient for k' parameters); r.gradient says which ran. Either
                              -- differences are computed only where SLSQP uses them: not at a
                              -- line-search trial it rejects (the same iterates, less work)
  model_differences = "forward" -- or "central" (2k + 1 blocks, O(h^2))
  model_step = 1e-6           -- relative step of model differences (input sd units); a solver whose
                              -- printed outputs carry d digits needs about 10^(-d/2)
  overlap_start = true        -- a start where a response's PR is near 2 (no overlap) is first moved
                              -- to a moment-matching start
  moment_start = false        -- true: every start is first moved to match the responses' means and
                              -- sds (Levenberg-Marquardt, analytic Jacobian where the model has a
                              -- gradient), kept when the objective is lower: fewer evaluations
  n = ${n}                    -- CRN sample size per evaluation
  crn = "random"              -- "random" draws or "quantiles" (stratified) common random numbers
  grid = nil                  -- {output = {lower, upper}}: PR integration ranges
  grid_nodes = ${grid_nodes}  -- nodes of the default PR grids
  bandwidth = "${bandwidth}"  -- KDE rule for the predicted outputs
  order = nil                 -- the input column order for a function model (names)
  design_bounds = nil         -- {input = {lower, upper}}: the surrogate's design range; leaving it warns
  threads = ${threads}        -- KDE evaluation threads; with Kriging models and no Lua metric, penalty,
                              -- prior function or progress, the starts run side by side on them instead
  parameters = nil            -- objective form: {{name, lower, upper, start}, ...} (start: mid-range)
  objective = nil             -- objective form: function(theta) returning a number; theta[name]
  method = "slsqp"            -- "slsqp", "lbfgs" (gradient-based too), "cobyla", "bobyqa" or "neldermead"
  multistart = ${multistart}  -- starts: the given one plus multistart - 1 seeded points
  hops = ${hops}              -- basin hopping: each start jumps hops times from its optimum and keeps
                              -- a lower optimum it finds (for multimodal fits; 0: no hops)
  hop_step = ${hop_step}      -- the largest jump of a hop, as a share of each parameter's range
  maxeval = ${maxeval}        -- objective evaluations per start (finite-difference probes included)
  xtol_rel = ${xtol_rel}      -- relative tolerance on the scaled parameters
  ftol_abs = ${ftol_abs}      -- absolute tolerance on the objective
                              -- Why these fit a Monte Carlo objective: on common random numbers
                              -- the objective is a fixed, smooth function of the parameters (PR's
                              -- grid makes it piecewise smooth at about 1e-9), so with a gradient
                              -- from the model (analytic, or model differences, exact to ~1e-7) the
                              -- optimiser reaches them like on any smooth function: ftol_abs sits
                              -- just above that 1e-9 roughness, xtol_rel far above the differences'
                              -- error. The Monte Carlo error of the optimum (the sample of n, about
                              -- 1/sqrt(n)) is not an optimiser tolerance: r.tolerance and bootstrap
                              -- report it. Objective differences (2k + 1 evaluations a gradient)
                              -- may spend maxeval first: r.starts[i].criterion then says which
                              -- tolerance was missed and by how much.
  fd_step = ${fd_step}        -- central-difference step in scaled units
  initial_step = ${initial_step}  -- derivative-free methods' first step, scaled units
  seed = smi.seed             -- CRN sample, multistart points and bootstrap
  identifiability = true      -- true, false, or {points = ${ident_points}, rel_tol = ${ident_rel_tol},
                              -- abs_tol = ${ident_abs_tol}, tolerance =, directions = true}: a sweep
                              -- of each parameter and the directions the data determine or not
  intervals = nil             -- {level = 0.9} profile intervals (loglik / objective read as a negative
                              -- log-likelihood) or {delta = rise}; observations = n (data count)
                              -- gives the small-sample delta n/2 ln(1 + t²(n-k)/(n-k)), k parameters
  bootstrap = nil             -- replicates, or {replicates = ${boot_replicates}, level = ${boot_level},
                              -- seed =, maxeval =, multistart =, warm = false}: full calibrations
                              -- on resampled data (model form; warm = true starts at the optimum)
  progress = nil              -- function(row) called after each optimizer step; false: no progress
                              -- line (by default one line on stderr when it is a terminal and not
                              -- --quiet: "calibration: start 2/4, 137 evaluations, best 0.288,
                              -- ETA 0:42", and the same for the bootstrap and near-optimal stages)
returns: r with r.params {name = value}, r.theta (in parameter order), r.names, r.objective,
  r.metrics (per output), r.tolerance (the objective rise that still fits as well as the optimum:
  identifiability.tolerance, or PR 0.01 per response, loglik 1.920729 = chi2_1(0.95)/2, else 1e-6
  of the optimum) and r.tolerance_basis (its reason in words), r.prior_value (the prior part at the
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
  r.bootstrap {lower, upper, std, level, replicates, failed, samples}
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

@ module smi.refine
Model refinement: the weighted decision matrix (spec section 6) over candidate model revisions;
the paper's criteria are in require "smi.refine.criteria".

@ smi.refine.decision_matrix{candidates =, criteria =} -> result
The weighted decision matrix: each criterion rates every candidate by its magnitude (smaller is
better, normalized by the largest), weighted, summed into an overall rating per candidate.
options:
  candidates = (required)  -- a list of names, or of tables with name = ... (passed to magnitudes)
  criteria = (required)    -- {{name =, weight =, magnitude = function(candidate, j) | {values} |
                           -- {name = value}}, ...}
  tie_tol = 1e-12          -- overall ratings closer than this are ties
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
  const smi::improve::OptimizerOptions opt;
  const smi::improve::StatisticalOptions st;
  const smi::improve::BootstrapOptions boot;
  const smi::improve::IdentifiabilityOptions id;
  return {"bindings/improve/doc.cpp",
          fill(kText, {{"n", num(static_cast<double>(st.n))},
                       {"grid_nodes", num(static_cast<double>(st.grid_nodes))},
                       {"bandwidth", st.bandwidth},
                       {"threads", num(st.threads)},
                       {"multistart", num(opt.multistart)},
                       {"hops", num(opt.hops)},
                       {"hop_step", num(opt.hop_step)},
                       {"maxeval", num(opt.maxeval)},
                       {"xtol_rel", num(opt.xtol_rel)},
                       {"ftol_abs", num(opt.ftol_abs)},
                       {"fd_step", num(opt.fd_step)},
                       {"initial_step", num(opt.initial_step)},
                       {"ident_points", num(id.points)},
                       {"ident_rel_tol", num(id.rel_tol)},
                       {"ident_abs_tol", num(id.abs_tol)},
                       {"boot_replicates", num(boot.replicates)},
                       {"boot_level", num(boot.level)}})};
}

}  // namespace smi::bind
