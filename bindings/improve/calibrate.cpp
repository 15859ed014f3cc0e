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
//                 penalty = function(theta) return number end (prior knowledge, added), ...}
// Common: method = "slsqp"|"cobyla"|"bobyqa"|"neldermead", multistart, seed, maxeval, xtol_rel,
//         ftol_abs, fd_step, initial_step, identifiability = true|false|{points, rel_tol, abs_tol},
//         progress = function(row) end.
// Result: params, theta, names, objective, metrics, converged, status, method, evaluations,
//         warnings, at_bounds, history, starts, identifiability, bootstrap; statistical form also
//         inputs, distributions (smi.dist per input), grids, model_runs, n, seed, metric.
#include "improve/calibrate.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "core/errors.hpp"
#include "improve/design_bounds.hpp"
#include "improve/lua_callbacks.hpp"
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

/// The statistical objective plus the analyst's penalty(theta), when given: the penalty is
/// added to the value and reported as one more part ("penalty"), so histories and results show
/// how much of the optimum is prior and how much is fit.
Objective with_penalty(lua_State* L, const CalibrateSpec& s, Objective metric) {
  if (!s.penalty_slot) return metric;
  std::vector<std::string> names;
  for (const auto& p : s.params) names.push_back(p.name);
  auto pen = std::make_shared<LuaObjective>(L, s.penalty_slot, names, "penalty");
  return [metric = std::move(metric), pen](const Eigen::VectorXd& t) {
    Evaluation e = metric(t);
    if (e.parts.size() == 0) e.parts = Eigen::VectorXd::Constant(1, e.value);  // a metric without parts
    const double p = (*pen)(t).value;
    if (!std::isfinite(p)) throw InvalidArgument(fmt::format("penalty returned {} (it must be a finite number)", p));
    e.value += p;
    e.parts.conservativeResize(e.parts.size() + 1);
    e.parts[e.parts.size() - 1] = p;
    return e;
  };
}

}  // namespace

CalibrationOutcome run_calibration(lua_State* L, const CalibrateSpec& s) {
  CalibrationOutcome out;
  OptimizerOptions oo = s.optimizer;
  oo.observer = progress_observer(L, s);
  Objective f;
  if (!s.statistical) {
    std::vector<std::string> names;
    for (const auto& p : s.params) names.push_back(p.name);
    auto obj = std::make_shared<LuaObjective>(L, s.objective_slot, names);
    f = [obj](const Eigen::VectorXd& t) { return (*obj)(t); };
    out.opt = minimize(s.params, f, oo);
    out.part_names = obj->part_names();
  } else {
    std::vector<std::string> responses;
    for (const auto& r : s.responses) responses.push_back(r.name);
    LuaModel model(L, s.model_parts, s.input_names_slot, responses);
    CustomMetric metric;
    if (s.metric_slot) metric = LuaMetric(L, s.metric_slot, s.data_slot, responses);
    out.stat.emplace(s.inputs, s.responses, s.params, model, s.stat, metric);
    const StatisticalObjective& obj = *out.stat;
    f = with_penalty(L, s, [&obj](const Eigen::VectorXd& t) { return obj(t); });
    out.opt = minimize(s.params, f, oo);
    out.part_names = responses;
    if (s.penalty_slot) {
      // per-response parts, or one "metric" part when a custom metric returned a bare number
      if (out.opt.parts.size() != static_cast<Eigen::Index>(responses.size()) + 1) out.part_names = {"metric"};
      out.part_names.push_back("penalty");
    }
  }
  out.warnings = out.opt.warnings;

  if (s.identifiability) {
    out.ident = identifiability(s.params, f, out.opt.theta, s.ident);
    out.warnings.insert(out.warnings.end(), out.ident->warnings.begin(), out.ident->warnings.end());
  }
  if (out.stat) {
    const StatisticalObjective& obj = *out.stat;
    if (!s.design.empty()) {
      std::vector<std::string> names;
      std::vector<double> means;
      const auto m = obj.input_moments(out.opt.theta);
      for (std::size_t j = 0; j < s.inputs.size(); ++j) {
        names.push_back(s.inputs[j].name);
        means.push_back(m[j].first);
      }
      for (auto& w : design_bound_warnings(names, obj.inputs_at(out.opt.theta), means, s.design)) out.warnings.push_back(w);
    }
    if (s.bootstrap) {
      std::vector<Eigen::VectorXd> data;
      for (const auto& r : obj.responses()) data.push_back(r.data);
      ObjectiveFactory make = [&obj, &s, L](const std::vector<Eigen::VectorXd>& d) -> Objective {
        auto o = std::make_shared<StatisticalObjective>(obj.with_data(d));
        return with_penalty(L, s, [o](const Eigen::VectorXd& t) { return (*o)(t); });
      };
      out.boot = bootstrap_calibration(s.params, out.opt.theta, data, make, *s.bootstrap);
      out.warnings.insert(out.warnings.end(), out.boot->warnings.begin(), out.boot->warnings.end());
    }
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
