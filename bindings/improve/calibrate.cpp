// smi.calibrate{...}: optimisation-based calibration, general (any objective or any model).
//
// Objective form:
//   smi.calibrate{parameters = {{name =, lower =, upper =, start =}, ...} (or {name, lower, upper, start}),
//                 objective = function(theta) return value [, {response = part}] end, ...}
// Statistical form (Son et al. eq. 9, CRN, spec §7):
//   smi.calibrate{model = function(X, names) return {y = vec} end | obj with obj:evaluate(X)
//                         | {response = surrogate, ...},
//                 inputs = {name = {dist = "normal"|"lognormal"|"uniform"|"truncnormal"|"weibull"|"gumbel"
//                                          |"gamma"|"beta"|"triangular"|"constant",
//                                   mean = number | {lower, upper, start}, std = ...,
//                                   fixed shape: lower/upper (truncnormal, beta), loc (weibull, gamma),
//                                   mode_at (triangular); see improve::kInputFamiliesHelp}, ...}
//                          (a list of {name =, ...} keeps its order; else the model's inputs order,
//                           `order`, or sorted names),
//                 data = {response = vec | smi.dist}, metric = "pr" | "loglik" | function(pred, data),
//                 n = 2000, crn = "random" | "quantiles", grid = {lo, hi, nodes} | {response = {...}},
//                 grid_nodes = 4001, bandwidth = "silverman", threads = 1, design_bounds = {x = {lo, hi}},
//                 bootstrap = replicates | {replicates =, level =, seed =, maxeval =},
//                 penalty = function(theta) return number end (prior knowledge, added),
//                 moment_start = false (true: every start first matched to the data's means and sds), ...}
// Common: method = "slsqp"|"lbfgs"|"cobyla"|"bobyqa"|"neldermead", multistart, seed, maxeval, xtol_rel,
//         ftol_abs, fd_step, initial_step, hops = 0, hop_step = 0.2 (basin hopping per start),
//         identifiability = true|false|{points, rel_tol, abs_tol, tolerance, step},
//         prior = {{param = name, mean =, std =} | {name =, fn = function(theta), mean =, std =}, ...},
//         prior_weight = 1, progress = function(row) end.
// Result: params, theta, names, objective, metrics (parts; "penalty", "prior"), converged, status,
//         method, evaluations, warnings, at_bounds, history, starts, starts_agree, optima, agreement,
//         identifiability (span, weak, profiles; directions, tolerance), near_optimal, bootstrap;
//         statistical form also inputs, distributions (smi.dist per input), grids, model_runs, n,
//         seed, metric.
#include "bindings/improve/calibrate.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <new>

#include "bindings/improve/lua_callbacks.hpp"
#include "bindings/improve/model_gradient.hpp"
#include "kernels/core/errors.hpp"
#include "kernels/improve/design_bounds.hpp"
#include "kernels/improve/overlap_start.hpp"
#include "luax/luax.hpp"

namespace smi::bind::improve {

using namespace smi::improve;

namespace {

/// progress({start =, evaluation =, objective =, best =, params = {...}}) after each optimiser step.
std::function<void(const HistoryEntry&)> progress_observer(lua_State* L, const CalibrateSpec& s) {
  if (!s.progress_slot) return {};
  std::vector<std::string> names;
  for (const auto& p : s.params) names.push_back(p.name);
  auto count = std::make_shared<int>(0);
  auto best = std::make_shared<double>(HUGE_VAL);
  return [L, slot = s.progress_slot, names, count, best](const HistoryEntry& h) {
    ++*count;
    if (h.probe) return;
    *best = std::min(*best, h.value);
    const int top = lua_gettop(L);
    lua_pushvalue(L, slot);
    lua_createtable(L, 0, 5);
    lua::set_integer(L, "start", h.start + 1);
    lua::set_integer(L, "evaluation", *count);
    lua::set_number(L, "objective", h.value);
    lua::set_number(L, "best", *best);
    lua_createtable(L, 0, static_cast<int>(names.size()));
    for (std::size_t i = 0; i < names.size(); ++i) {
      lua_pushnumber(L, h.theta[static_cast<Eigen::Index>(i)]);
      lua_setfield(L, -2, names[i].c_str());
    }
    lua_setfield(L, -2, "params");
    lua::call(L, 1, 0);
    lua_settop(L, top);
  };
}

/// The prior terms of the spec: Σ weight · ½((v − mean)/std)² over the entries, v a parameter or
/// the value of a Lua function of the parameters.
class PriorSum {
 public:
  PriorSum(lua_State* L, const CalibrateSpec& s) : priors_(s.priors), weight_(s.prior_weight) {
    std::vector<std::string> names;
    for (const auto& p : s.params) names.push_back(p.name);
    for (const PriorSpec& p : priors_)
      fns_.push_back(p.fn_slot ? std::make_shared<LuaObjective>(L, p.fn_slot, names, "prior function") : nullptr);
  }
  double operator()(const Eigen::VectorXd& t) const {
    double sum = 0.0;
    for (std::size_t i = 0; i < priors_.size(); ++i) {
      const PriorSpec& p = priors_[i];
      const double v = p.param >= 0 ? t[p.param] : (*fns_[i])(t).value;
      if (!std::isfinite(v)) throw InvalidArgument(fmt::format("prior '{}': its function returned {} (it must return a finite number)", p.label, v));
      const double z = (v - p.mean) / p.std;
      sum += 0.5 * z * z;
    }
    return weight_ * sum;
  }

 private:
  std::vector<PriorSpec> priors_;
  double weight_;
  std::vector<std::shared_ptr<LuaObjective>> fns_;
};

/// The analyst's penalty(theta) and prior terms, added to the metric: each is reported as one
/// more part ("penalty", then "prior"), so histories and results show how much of the optimum is
/// prior knowledge and how much is fit.
struct Extras {
  std::shared_ptr<LuaObjective> pen;
  std::shared_ptr<PriorSum> prior;

  Extras(lua_State* L, const CalibrateSpec& s) {
    std::vector<std::string> names;
    for (const auto& p : s.params) names.push_back(p.name);
    if (s.penalty_slot) pen = std::make_shared<LuaObjective>(L, s.penalty_slot, names, "penalty");
    if (!s.priors.empty()) prior = std::make_shared<PriorSum>(L, s);
  }
  bool any() const { return pen || prior; }
  double penalty(const Eigen::VectorXd& t) const {
    const double p = (*pen)(t).value;
    if (!std::isfinite(p)) throw InvalidArgument(fmt::format("penalty returned {} (it must be a finite number)", p));
    return p;
  }
  void add(Evaluation& e, const Eigen::VectorXd& t) const {
    if (!any()) return;
    if (e.parts.size() == 0) e.parts = Eigen::VectorXd::Constant(1, e.value);  // a metric without parts
    auto push = [&e](double v) {
      e.value += v;
      e.parts.conservativeResize(e.parts.size() + 1);
      e.parts[e.parts.size() - 1] = v;
    };
    if (pen) push(penalty(t));
    if (prior) push((*prior)(t));
  }
  double total(const Eigen::VectorXd& t) const { return (pen ? penalty(t) : 0.0) + (prior ? (*prior)(t) : 0.0); }
};

Objective with_extras(lua_State* L, const CalibrateSpec& s, Objective metric) {
  Extras x(L, s);
  if (!x.any()) return metric;
  return [metric = std::move(metric), x](const Eigen::VectorXd& t) {
    Evaluation e = metric(t);
    x.add(e, t);
    return e;
  };
}

/// The analytic gradient of the metric plus the extras' gradient by central differences (Lua
/// functions of θ only: no model run), steps 1e-7 of each range, one-sided at a bound.
ObjectiveGradient gradient_with_extras(lua_State* L, const CalibrateSpec& s, const StatisticalObjective& obj) {
  Extras x(L, s);
  const std::vector<Parameter> params = s.params;
  return [&obj, x, params](const Eigen::VectorXd& t, Eigen::VectorXd& g) {
    Evaluation e = obj.value_and_gradient(t, g);
    x.add(e, t);
    if (x.any())
      for (Eigen::Index i = 0; i < t.size(); ++i) {
        const Parameter& p = params[static_cast<std::size_t>(i)];
        const double h = 1e-7 * (p.upper - p.lower);
        Eigen::VectorXd up = t, dn = t;
        up[i] = std::min(p.upper, t[i] + h);
        dn[i] = std::max(p.lower, t[i] - h);
        g[i] += (x.total(up) - x.total(dn)) / (up[i] - dn[i]);
      }
    return e;
  };
}

/// Labels of the parts: the metric's own (responses), or one "metric"/"objective" part when it
/// gave none, then "penalty" and "prior" when present.
std::vector<std::string> part_labels(const CalibrateSpec& s, std::vector<std::string> own, Eigen::Index parts, const char* whole) {
  const Eigen::Index extras = (s.penalty_slot ? 1 : 0) + (s.priors.empty() ? 0 : 1);
  if (extras == 0) return own;
  if (parts != static_cast<Eigen::Index>(own.size()) + extras) own = {whole};
  if (s.penalty_slot) own.push_back("penalty");
  if (!s.priors.empty()) own.push_back("prior");
  return own;
}

/// Tolerance of "fits as well as the optimum" when not given: PR is unit-free in [0, 2] per
/// response (0.01 each); loglik is a log-likelihood (half the 95 % chi-square(1) quantile);
/// anything else relative to the optimum's value.
double default_tolerance(const CalibrateSpec& s, double optimum) {
  if (s.directions_tolerance > 0.0) return s.directions_tolerance;
  if (s.statistical && !s.metric_slot && s.stat.metric == MetricKind::pr) return 0.01 * static_cast<double>(s.responses.size());
  if (s.statistical && !s.metric_slot && s.stat.metric == MetricKind::loglik) return 1.920729;
  return 1e-6 * std::max(1.0, std::abs(optimum));
}

/// The objective form: the Lua objective (plus penalty and prior) minimised; returns that
/// objective for the analyses after the optimum.
Objective minimize_lua_objective(lua_State* L, const CalibrateSpec& s, const OptimizerOptions& oo, CalibrationOutcome& out) {
  std::vector<std::string> names;
  for (const auto& p : s.params) names.push_back(p.name);
  auto obj = std::make_shared<LuaObjective>(L, s.objective_slot, names);
  Objective f = with_extras(L, s, [obj](const Eigen::VectorXd& t) { return (*obj)(t); });
  out.opt = minimize(s.params, f, oo);
  out.part_names = part_labels(s, obj->part_names(), out.opt.parts.size(), "objective");
  return f;
}

/// The statistical form: builds the CRN objective in out.stat (the model in C++ when it is made
/// of surrogates, else through Lua), chooses threads, gradient and start preparation, and
/// minimises it; returns the objective (plus extras) for the analyses after the optimum. oo
/// receives the gradient, which the profile intervals reuse.
Objective minimize_statistical(lua_State* L, const CalibrateSpec& s, OptimizerOptions& oo, CalibrationOutcome& out) {
  std::vector<std::string> responses;
  for (const auto& r : s.responses) responses.push_back(r.name);
  // Surrogate models run without Lua; then, when nothing else in an evaluation calls Lua (a
  // custom metric, a penalty, a prior function, a progress function), the starts run side by
  // side on `threads` threads (the same result as one after another), each evaluation on one.
  StatisticalOptions so = s.stat;
  const bool lua_free_extras = !s.metric_slot && !s.penalty_slot && !s.progress_slot &&
                               std::none_of(s.priors.begin(), s.priors.end(), [](const PriorSpec& p) { return p.fn_slot != 0; });
  const int start_threads = std::min(s.stat.threads, s.optimizer.multistart);
  // Each prediction on one thread only when the starts do run side by side (not when a Lua
  // callback keeps them one after another).
  const bool side_by_side = lua_free_extras && start_threads > 1;
  Model cpp = kriging_model(L, s, responses, side_by_side ? 1 : 2);
  if (cpp && side_by_side) {
    oo.start_threads = start_threads;
    so.threads = 1;
  }
  Model model = cpp ? cpp : Model(LuaModel(L, s.model_parts, s.input_names_slot, responses));
  CustomMetric metric;
  if (s.metric_slot) metric = LuaMetric(L, s.metric_slot, s.data_slot, responses);
  out.stat.emplace(s.inputs, s.responses, s.params, model, so, metric);
  if (s.gradient != "differences") out.stat->set_model_jacobian(model_jacobian(L, s, responses));
  const StatisticalObjective& obj = *out.stat;
  Objective f = with_extras(L, s, [&obj](const Eigen::VectorXd& t) { return obj(t); });
  if (s.gradient == "analytic" && !obj.has_gradient())
    throw InvalidArgument("gradient = \"analytic\" needs metric \"pr\" or \"loglik\", a bandwidth rule with a derivative (silverman, "
                          "normal, 1.06, scott, robust, mad; not lscv or sj) and a model with a gradient (an smi.kriging, or an object with m:gradient(X)); use gradient = \"auto\"");
  if (obj.has_gradient()) {
    oo.gradient = gradient_with_extras(L, s, obj);
    out.analytic_gradient = true;
  }
  if (s.moment_start)
    oo.prepare_start = [&obj](const Eigen::VectorXd& t) { return moment_start(obj, t); };
  else if (s.overlap_start)
    oo.prepare_start = [&obj](const Eigen::VectorXd& t) { return overlap_start(obj, t); };
  out.opt = minimize(s.params, f, oo);
  // per-response parts, or one "metric" part when a custom metric returned a bare number
  out.part_names = part_labels(s, responses, out.opt.parts.size(), "metric");
  return f;
}

void append(std::vector<std::string>& to, const std::vector<std::string>& from) { to.insert(to.end(), from.begin(), from.end()); }

/// Identifiability at the optimum (the Hessian's spans), and when asked the directions that fit
/// as well as the optimum (with the predicted responses' summaries in the statistical form).
void add_identifiability(const CalibrateSpec& s, const Objective& f, CalibrationOutcome& out) {
  out.ident = identifiability(s.params, f, out.opt.theta, s.ident);
  append(out.warnings, out.ident->warnings);
  if (!s.identifiability_directions) return;
  DirectionsOptions d = s.directions;
  d.tolerance = default_tolerance(s, out.opt.value);
  Summaries summ;
  if (out.stat) summ = [&obj = *out.stat](const Eigen::VectorXd& t) { return obj.summaries(t); };
  out.directions = identifiability_directions(s.params, f, out.opt.theta, out.opt.value, d, summ);
  append(out.warnings, out.directions->warnings);
}

/// With several starts: whether they reached the best's optimum where the data can tell (within
/// the tolerance, no barrier above it between them; start_agreement.hpp). The starts' optima
/// that fit as well join the near-optimal set: they are calibrations the data cannot reject.
void add_start_agreement(const CalibrateSpec& s, const Objective& f, CalibrationOutcome& out) {
  out.agreement = start_agreement(s.params, f, out.opt, default_tolerance(s, out.opt.value),
                                  out.stat ? prediction_check(*out.stat) : PredictionCheck{});
  if (!out.opt.starts_agree) out.warnings.push_back(describe(*out.agreement));
  if (!out.directions) return;
  for (std::size_t i = 0; i < out.opt.starts.size(); ++i) {
    const StartResult& st = out.opt.starts[i];
    if (!out.agreement->rows[i].within || static_cast<int>(i) == out.opt.best) continue;
    out.directions->near_optimal.push_back(st.theta);
    out.directions->near_optimal_values.push_back(st.value);
  }
}

/// Warns when the calibrated inputs' samples leave the surrogates' design bounds.
void add_design_bound_warnings(const CalibrateSpec& s, const StatisticalObjective& obj, CalibrationOutcome& out) {
  std::vector<std::string> names;
  std::vector<double> means;
  const auto m = obj.input_moments(out.opt.theta);
  for (std::size_t j = 0; j < s.inputs.size(); ++j) {
    names.push_back(s.inputs[j].name);
    means.push_back(m[j].first);
  }
  for (auto& w : design_bound_warnings(names, obj.inputs_at(out.opt.theta), means, s.design)) out.warnings.push_back(w);
}

/// Bootstrap of the statistical calibration: each replicate recalibrates an objective on
/// resampled data, built the same way as the original (gradient, start preparation, extras).
void add_bootstrap(lua_State* L, const CalibrateSpec& s, const StatisticalObjective& obj, CalibrationOutcome& out) {
  std::vector<Eigen::VectorXd> data;
  for (const auto& r : obj.responses()) data.push_back(r.data);
  ReplicateFactory make = [&obj, &s, L](const std::vector<Eigen::VectorXd>& d) {
    auto o = std::make_shared<StatisticalObjective>(obj.with_data(d));
    Replicate rep;
    rep.f = with_extras(L, s, [o](const Eigen::VectorXd& t) { return (*o)(t); });
    if (o->has_gradient()) rep.gradient = gradient_with_extras(L, s, *o);
    if (s.moment_start)
      rep.prepare_start = [o](const Eigen::VectorXd& t) { return moment_start(*o, t); };
    else if (s.overlap_start)
      rep.prepare_start = [o](const Eigen::VectorXd& t) { return overlap_start(*o, t); };
    rep.keep = o;
    return rep;
  };
  const BootstrapOptions& bo = *s.bootstrap;
  out.boot = bootstrap_calibration(s.params, out.opt.theta, data, make, bo);
  append(out.warnings, out.boot->warnings);
}

/// Runs one analysis after the optimum. When it fails (a solver or Lua model that breaks at a
/// profile point, a path point, a resampled data set), the optimum found stands and the failure
/// is a warning naming the analysis and the error: a diagnostic must not lose the result. An
/// interruption or exhausted memory still ends the call (and a Lua abort is raised again by the
/// next Lua instruction anyway).
template <class Analysis>
void after_optimum(CalibrationOutcome& out, const char* what, Analysis&& analysis) {
  try {
    analysis();
  } catch (const smi::Interrupted&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    out.warnings.push_back(fmt::format("{} could not be computed (the optimum above stands): {}", what, e.what()));
  }
}

}  // namespace

CalibrationOutcome run_calibration(lua_State* L, const CalibrateSpec& s) {
  CalibrationOutcome out;
  OptimizerOptions oo = s.optimizer;
  oo.observer = progress_observer(L, s);
  const Objective f = s.statistical ? minimize_statistical(L, s, oo, out) : minimize_lua_objective(L, s, oo, out);
  out.warnings = out.opt.warnings;
  // The analyses at the optimum, in this order (their warnings follow the optimiser's).
  if (s.identifiability) after_optimum(out, "identifiability", [&] { add_identifiability(s, f, out); });
  if (s.optimizer.multistart > 1) after_optimum(out, "whether the starts agree", [&] { add_start_agreement(s, f, out); });
  if (s.intervals)
    after_optimum(out, "profile intervals", [&] {
      ProfileOptions po = *s.intervals;
      po.optimizer.observer = {};
      out.profile = profile_intervals(s.params, f, out.opt.theta, out.opt.value, po, oo.gradient);
      append(out.warnings, out.profile->warnings);
    });
  if (out.stat) {
    const StatisticalObjective& obj = *out.stat;
    if (!s.design.empty()) add_design_bound_warnings(s, obj, out);
    if (s.bootstrap) after_optimum(out, "bootstrap", [&] { add_bootstrap(L, s, obj, out); });
    if (obj.floored() > 0)
      out.warnings.push_back(fmt::format("loglik: {} predicted densities were below 1e-300 and floored (data outside the prediction)",
                                         obj.floored()));
  }
  return out;
}

int calibrate(lua_State* L) {
  luaL_checktype(L, 1, LUA_TTABLE);
  lua_settop(L, 1);
  return lua::protect(L, "smi.calibrate", [&] {
    const CalibrateSpec s = read_calibrate_spec(L, 1);
    const CalibrationOutcome out = run_calibration(L, s);
    push_calibration_result(L, s, out);
    return 1;
  });
}

}  // namespace smi::bind::improve
