// SPDX-License-Identifier: MIT
// The option schema of smi.calibrate (calibrate_options.hpp), in the reference's order.
#include "bindings/improve/calibrate_options.hpp"

#include <vector>

#include "kernels/improve/bounded_optimizer.hpp"
#include "luax/doc_text.hpp"
#include "kernels/improve/crn_mapping.hpp"

namespace smi::bind::improve {

using namespace smi::lua;
using smi::improve::CrnKind;
using smi::improve::method_name;
using smi::improve::parse_method;

// long: one table of 36 entries, one per option in the reference's order (data, no logic)
const Schema<CalibrateSpec>& calibrate_schema() {
  using S = CalibrateSpec;
  static const Schema<S> schema("smi.calibrate", std::vector<Option<S>>{
      by_hand<S>("model", "nil",
         "model form: an smi.model, an smi.kriging (or a table of them by\n"
         "output), or a function(X) returning {output = vec}; a Lua model is\n"
         "called one call at a time but in no fixed order when starts or\n"
         "replicates run side by side: its outputs must depend on X alone"),
      by_hand<S>("inputs", "nil",
         "model form: {name = {dist = \"normal\", mean = m | {lo, hi, start},\n"
         "std = s | {lo, hi, start}} | {value = x}, ...} (or a list with name =);\n"
         "dist: any of the nine families (truncnormal/beta with fixed lower/upper,\n"
         "gamma/weibull with a fixed loc, triangular with mode_at)"),
      by_hand<S>("data", "nil",
         "model form: {output = vec of measurements | a dist (an experimental PDF)\n"
         "| {points = vec, pdf = dist}}: with both, the PDF enters the objective and\n"
         "the points are resampled (PR tolerance, bootstrap)"),
      by_hand<S>("metric", "\"pr\"",
         "\"pr\", \"loglik\", or function(predicted, data) returning a number"),
      by_hand<S>("penalty", "nil",
         "function(theta) returning a number added to the metric (prior knowledge)"),
      by_hand<S>("prior", "nil",
         "{{param = \"x.mean\", mean =, std =} | {name =, fn = function(theta), mean =,\n"
         "std =}, ...}: adds 0.5((v - mean)/std)^2 each, reported as metrics.prior"),
      number<S>("prior_weight", &S::prior_weight, finite_at_least(0),
         "factor on the prior part"),
      string<S>("gradient", &S::gradient, {"auto", "analytic", "model", "differences"},
         "\"auto\": analytic where the model gives one (Kriging, m:gradient),\n"
         "else the MODEL's differences at the CRN sample (\"model\": one call\n"
         "of the model on k + 1 stacked blocks of n rows for k calibrated\n"
         "inputs, chained through the quantile derivatives, KDE and metric\n"
         "like the analytic path; a solver model runs the blocks as one\n"
         "parallel, resumable evaluation; k blocks where the value at that\n"
         "point was just computed), else (custom metric, lscv/sj) the\n"
         "objective's differences (\"differences\": 2k' + 1 evaluations a\n"
         "gradient for k' parameters); r.gradient says which ran. Either\n"
         "differences are computed only where SLSQP uses them: not at a\n"
         "line-search trial it rejects (the same iterates, less work)"),
      string<S>("model_differences", &S::model_differences, {"forward", "central"},
         "or \"central\" (2k + 1 blocks, O(h^2))"),
      number<S>("model_step", &S::model_step, open(0.0, smi::improve::kMaxModelStep),
         "relative step of model differences (input sd units); a solver whose\n"
         "printed outputs carry d digits needs about 10^(-d/2)"),
      boolean<S>("overlap_start", &S::overlap_start,
         "a start where a response's PR is near 2 (no overlap) is first moved\n"
         "to a moment-matching start"),
      boolean<S>("moment_start", &S::moment_start,
         "true: every start is first moved to match the responses' means and\n"
         "sds (Levenberg-Marquardt, analytic Jacobian where the model has a\n"
         "gradient), kept when the objective is lower: fewer evaluations"),
      integer<S>("n", [](auto& s) -> auto& { return s.stat.n; }, at_least(static_cast<double>(smi::improve::kMinCrnSize)),
         "CRN sample size per evaluation"),
      choice<S>("crn", [](auto& s) -> auto& { return s.stat.crn; }, Names<CrnKind>{{"random", CrnKind::random}, {"quantiles", CrnKind::quantiles}},
         "\"random\" draws or \"quantiles\" (stratified) common random numbers"),
      by_hand<S>("grid", "nil",
         "{output = {lower, upper}}: PR integration ranges"),
      integer<S>("grid_nodes", [](auto& s) -> auto& { return s.stat.grid_nodes; }, at_least(static_cast<double>(kMinGridNodes)),
         "nodes of the default PR grids"),
      string<S>("bandwidth", [](auto& s) -> auto& { return s.stat.bandwidth; }, {},
         "KDE rule for the predicted outputs"),
      by_hand<S>("order", "nil",
         "the input column order for a function model (names)"),
      by_hand<S>("design_bounds", "nil",
         "{input = {lower, upper}}: the surrogate's design range; leaving it warns"),
      integer<S>("threads", [](auto& s) -> auto& { return s.stat.threads; }, at_least(1),
         "KDE evaluation threads; with no Lua metric, penalty, prior function or\n"
         "progress, the starts and bootstrap replicates run side by side on them\n"
         "instead (a Lua model's own calls take turns)"),
      by_hand<S>("parameters", "nil",
         "objective form: {{name, lower, upper, start}, ...} (start: mid-range)"),
      by_hand<S>("objective", "nil",
         "objective form: function(theta) returning a number; theta[name]"),
      parsed<S>("method", [](auto& s) -> auto& { return s.optimizer.method; }, parse_method, method_name,
         "\"slsqp\", \"lbfgs\" (gradient-based too), \"cobyla\", \"bobyqa\" or \"neldermead\""),
      integer<S>("multistart", [](auto& s) -> auto& { return s.optimizer.multistart; }, at_least(1),
         "starts: the given one plus multistart - 1 seeded points"),
      integer<S>("hops", [](auto& s) -> auto& { return s.optimizer.hops; }, at_least(0),
         "basin hopping: each start jumps hops times from its optimum and keeps\n"
         "a lower optimum it finds (for multimodal fits; 0: no hops)"),
      number<S>("hop_step", [](auto& s) -> auto& { return s.optimizer.hop_step; }, Range{0.0, 1.0, true, false},
         "the largest jump of a hop, as a share of each parameter's range"),
      integer<S>("maxeval", [](auto& s) -> auto& { return s.optimizer.maxeval; }, at_least(1),
         "objective evaluations per start (finite-difference probes included)"),
      number<S>("xtol_rel", [](auto& s) -> auto& { return s.optimizer.xtol_rel; }, at_least(0),
         "relative tolerance on the scaled parameters"),
      number<S>("ftol_abs", [](auto& s) -> auto& { return s.optimizer.ftol_abs; }, at_least(0),
         "absolute tolerance on the objective\n"
         "Why these fit a Monte Carlo objective: on common random numbers\n"
         "the objective is a fixed, smooth function of the parameters (PR's\n"
         "grid makes it piecewise smooth at about 1e-9), so with a gradient\n"
         "from the model (analytic, or model differences, exact to ~1e-7) the\n"
         "optimiser reaches them like on any smooth function: ftol_abs sits\n"
         "just above that 1e-9 roughness, xtol_rel far above the differences'\n"
         "error. The Monte Carlo error of the optimum (the sample of n, about\n"
         "1/sqrt(n)) is not an optimiser tolerance: r.tolerance and bootstrap\n"
         "report it. Objective differences (2k + 1 evaluations a gradient)\n"
         "may spend maxeval first: r.starts[i].criterion then says which\n"
         "tolerance was missed and by how much."),
      number<S>("fd_step", [](auto& s) -> auto& { return s.optimizer.fd_step; }, Range{0.0, smi::improve::kMaxFdStep, true, false},
         "central-difference step in scaled units"),
      number<S>("initial_step", [](auto& s) -> auto& { return s.optimizer.initial_step; }, Range{0.0, 1.0, true, false},
         "derivative-free methods' first step, scaled units"),
      integer<S>("seed", [](auto& s) -> auto& { return s.optimizer.seed; }, any_value(),
         "CRN sample, multistart points and bootstrap", "smi.seed"),
      by_hand<S>("identifiability", "true",
         "true, false, or {points = ${ident_points}, rel_tol = ${ident_rel_tol},\n"
         "abs_tol = ${ident_abs_tol}, tolerance =, resamples = ${ident_resamples},\n"
         "directions = true}: a sweep of each parameter and the directions the\n"
         "data determine or not; resamples: of the data rows, measuring PR's\n"
         "tolerance (0: 0.01 per response)"),
      by_hand<S>("intervals", "nil",
         "{level = 0.9} profile intervals (loglik / objective read as a negative\n"
         "log-likelihood) or {delta = rise}; observations = n (data count)\n"
         "gives the small-sample delta n/2 ln(1 + t²(n-k)/(n-k)), k parameters"),
      by_hand<S>("bootstrap", "nil",
         "replicates, or {replicates = ${boot_replicates}, level = ${boot_level},\n"
         "seed =, maxeval =, multistart =, warm = false}: full calibrations\n"
         "on resampled data (model form), each from the optimum, then its own\n"
         "multistart points (warm = true: the optimum only), side by side for\n"
         "a C++ model; percentile bounds with their Monte Carlo errors"),
      by_hand<S>("progress", "nil",
         "function(row) called after each optimizer step; false: no progress\n"
         "line (by default one line on stderr when it is a terminal and not\n"
         "--quiet: \"calibration: start 2/4, 137 evaluations, best 0.288,\n"
         "ETA 0:42\", and the same for the bootstrap and near-optimal stages)"),
  });
  // the nested tables' schemas are built with it, so that the tests that check every schema the
  // reference builds (their empty read equals the defaults) check them too
  (void)bootstrap_schema();
  (void)identifiability_schema();
  (void)intervals_schema();
  (void)prior_schema();
  return schema;
}

const Schema<CalibrateSpec>& identifiability_schema() {
  using S = CalibrateSpec;
  static const Schema<S> schema("smi.calibrate identifiability", std::vector<Option<S>>{
      integer<S>("points", [](auto& s) -> auto& { return s.ident.points; }, at_least(3), "sweep points per parameter"),
      number<S>("rel_tol", [](auto& s) -> auto& { return s.ident.rel_tol; }, at_least(0), "relative objective change that counts"),
      number<S>("abs_tol", [](auto& s) -> auto& { return s.ident.abs_tol; }, at_least(0), "absolute objective change that counts"),
      number<S>("tolerance", &S::directions_tolerance, above(0), "\"fits as well as the optimum\"",
                "by the metric: PR measured from the data points, loglik 1.920729"),
      integer<S>("resamples", &S::tolerance_resamples, at_least(0),
                 "bootstrap resamples of the data rows measuring PR's tolerance\n"
                 "(its standard deviation at the optimum; 0: 0.01 per response)"),
      number<S>("step", [](auto& s) -> auto& { return s.directions.step; }, Range{0.0, smi::improve::kMaxDirectionsStep, true, false},
                "the directions' finite-difference step"),
      boolean<S>("directions", &S::identifiability_directions, "also the directions the data determine (and near_optimal)"),
  });
  return schema;
}

const Schema<IntervalsArgs>& intervals_schema() {
  using S = IntervalsArgs;
  static const Schema<S> schema("smi.calibrate intervals", std::vector<Option<S>>{
      number<S>("level", &S::level, open(0.0, 1.0), "a likelihood-ratio interval's level", num(CalibrateSpec{}.interval_level)),
      number<S>("delta", &S::delta, above(0), "the objective increase instead (not with level)", "nil"),
      integer<S>("observations", &S::observations, at_least(1), "the data count: the small-sample delta (with level)", "nil"),
  });
  return schema;
}

const Schema<PriorArgs>& prior_schema() {
  using S = PriorArgs;
  static const Schema<S> schema("smi.calibrate prior", std::vector<Option<S>>{
      string<S>("param", &S::param, {}, "the calibrated parameter (or fn with name)", "nil"),
      string<S>("name", &S::name, {}, "the label of a prior on fn", "nil"),
      by_hand<S>("fn", "nil", "function(theta) returning the quantity with the prior"),
      number<S>("mean", &S::mean, finite(), "the normal prior's mean", "(required)"),
      number<S>("std", &S::std, finite_above(0), "the normal prior's standard deviation, > 0", "(required)"),
  });
  return schema;
}

const Schema<smi::improve::BootstrapOptions>& bootstrap_schema() {
  using S = smi::improve::BootstrapOptions;
  static const Schema<S> schema("smi.calibrate bootstrap", std::vector<Option<S>>{
      integer<S>("replicates", &S::replicates, at_least(2), "full calibrations on resampled data"),
      number<S>("level", &S::level, open(0.0, 1.0), "the percentile intervals' level"),
      integer<S>("seed", &S::seed, any_value(), "the resampling's seed", "the calibration's"),
      integer<S>("maxeval", [](auto& s) -> auto& { return s.optimizer.maxeval; }, at_least(1), "evaluations per start",
                 "the calibration's"),
      integer<S>("multistart", [](auto& s) -> auto& { return s.optimizer.multistart; }, at_least(1), "starts per replicate",
                 "the calibration's"),
      boolean<S>("warm", &S::warm_start, "one start per replicate, the optimum (else the optimum then the multistart points)"),
      number<S>("xtol_rel", &S::xtol_rel, at_least(0),
                "the replicates' relative tolerance on the scaled parameters\n"
                "(the calibration's xtol_rel when that is coarser)"),
  });
  return schema;
}

}  // namespace smi::bind::improve
