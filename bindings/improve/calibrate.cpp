// SPDX-License-Identifier: MIT
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
//                 grid_nodes = 4001, bandwidth = "silverman", threads = 2, design_bounds = {x = {lo, hi}},
//                 bootstrap = replicates | {replicates =, level =, seed =, maxeval =},
//                 penalty = function(theta) return number end (prior knowledge, added),
//                 moment_start = false (true: every start first matched to the data's means and sds), ...}
// Common: method = "slsqp"|"lbfgs"|"cobyla"|"bobyqa"|"neldermead", multistart, seed, maxeval, xtol_rel,
//         ftol_abs, fd_step, initial_step, hops = 0, hop_step = 0.2 (basin hopping per start),
//         identifiability = true|false|{points, rel_tol, abs_tol, tolerance, step},
//         prior = {{param = name, mean =, std =} | {name =, fn = function(theta), mean =, std =}, ...},
//         prior_weight = 1, progress = function(row) end | false, gradient = "auto"|"analytic"|"model"|"differences",
//         model_differences = "forward"|"central", model_step = 1e-6.
// Result: params, theta, names, objective, metrics (parts; "penalty", "prior"), converged, status
//         (or "no_overlap" with message, no_overlap), optimizer_status, tolerance, tolerance_basis,
//         prior_value, prior_at(theta),
//         method, evaluations, warnings, at_bounds, history, starts, starts_agree, optima, agreement,
//         identifiability (span, weak, profiles; directions, tolerance), near_optimal, bootstrap;
//         statistical form also inputs, distributions (smi.dist per input), grids, model_runs, n,
//         seed, metric.
#include "bindings/improve/calibrate.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "bindings/improve/lua_callbacks.hpp"
#include "bindings/improve/model_gradient.hpp"
#include "bindings/improve/progress_line.hpp"
#include "luax/luax.hpp"
#include "platform/core/errors.hpp"

namespace smi::bind::improve {

using namespace smi::improve;

namespace {

std::vector<std::string> parameter_names(const CalibrateSpec& s) {
  std::vector<std::string> names;
  for (const auto& p : s.params) names.push_back(p.name);
  return names;
}

/// progress({start =, evaluation =, objective =, best =, params = {...}}) after each optimiser step.
std::function<void(const HistoryEntry&)> progress_observer(lua_State* L, const CalibrateSpec& s) {
  if (!s.progress_slot) return {};
  auto count = std::make_shared<int>(0);
  auto best = std::make_shared<double>(HUGE_VAL);
  return [L, slot = s.progress_slot, names = parameter_names(s), count, best](const HistoryEntry& h) {
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

/// A Lua function of θ at `slot` as a kernel capability returning its number.
ThetaFunction theta_function(lua_State* L, int slot, const CalibrateSpec& s, const char* who) {
  auto fn = std::make_shared<LuaObjective>(L, slot, parameter_names(s), who);
  return [fn](const Eigen::VectorXd& t) { return (*fn)(t).value; };
}

}  // namespace

CalibrationProblem calibration_problem(lua_State* L, const CalibrateSpec& s) {
  CalibrationProblem p;
  p.params = s.params;
  if (!s.statistical) {
    auto obj = std::make_shared<LuaObjective>(L, s.objective_slot, parameter_names(s));
    p.objective = [obj](const Eigen::VectorXd& t) { return (*obj)(t); };
    p.objective_parts = [obj] { return obj->part_names(); };
  } else {
    std::vector<std::string> responses;
    for (const auto& r : s.responses) responses.push_back(r.name);
    p.inputs = s.inputs;
    p.responses = s.responses;
    p.stat = s.stat;
    const LuaGate gate(L);  // the model's and its gradient's Lua calls take turns
    if (kriging_model(L, s, responses, 2))
      p.native_model = [L, &s, responses](int threads) { return kriging_model(L, s, responses, threads); };
    else
      p.model = LuaModel(L, s.model_parts, s.input_names_slot, responses, gate);
    p.model_thread_safe = true;
    p.jacobian = model_jacobian(L, s, responses, gate);
    if (s.metric_slot) p.metric = LuaMetric(L, s.metric_slot, s.data_slot, responses);
  }
  if (s.penalty_slot) p.penalty = theta_function(L, s.penalty_slot, s, "penalty");
  for (const PriorSpec& ps : s.priors) {
    PriorTerm t;
    t.label = ps.label;
    t.param = ps.param;
    t.mean = ps.mean;
    t.std = ps.std;
    if (ps.fn_slot) t.fn = theta_function(L, ps.fn_slot, s, "prior function");
    p.priors.push_back(std::move(t));
  }
  p.progress = progress_observer(L, s);
  p.progress_line = terminal_progress_line(L, s.progress_line);
  return p;
}

CalibrationOutcome run_calibration(lua_State* L, const CalibrateSpec& s) { return smi::improve::calibrate(calibration_problem(L, s), s); }

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
