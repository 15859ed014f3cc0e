// SPDX-License-Identifier: MIT
// The result table of smi.calibrate: everything a report needs, keyed by parameter and response
// name. Stack effects are noted per helper.
#include <fmt/format.h>

#include <cmath>
#include <memory>

#include "bindings/improve/calibrate.hpp"
#include "bindings/stats/dist_box.hpp"
#include "kernels/stats/families.hpp"
#include "luax/luax.hpp"
#include "platform/core/errors.hpp"

namespace smi::bind::improve {

using namespace smi::improve;

namespace {

/// Stack: [] -> [{name = v[i]}].
void push_named(lua_State* L, const std::vector<std::string>& names, const Eigen::VectorXd& v) {
  lua_createtable(L, 0, static_cast<int>(names.size()));
  for (std::size_t i = 0; i < names.size() && static_cast<Eigen::Index>(i) < v.size(); ++i) {
    lua_pushnumber(L, v[static_cast<Eigen::Index>(i)]);
    lua_setfield(L, -2, names[i].c_str());
  }
}

/// Stack: [] -> [{s1, s2, ...}].
void push_strings(lua_State* L, const std::vector<std::string>& v) {
  lua_createtable(L, static_cast<int>(v.size()), 0);
  for (std::size_t i = 0; i < v.size(); ++i) {
    lua_pushstring(L, v[i].c_str());
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
}

/// result.inputs, result.distributions, result.grids, n/seed. Stack: [res] -> [res].
void push_statistical(lua_State* L, const CalibrateSpec& s, const CalibrationOutcome& out) {
  const StatisticalObjective& obj = *out.stat;
  const auto m = obj.input_moments(out.opt.theta);
  lua_createtable(L, 0, static_cast<int>(s.inputs.size()));  // inputs
  lua_createtable(L, 0, static_cast<int>(s.inputs.size()));  // distributions
  for (std::size_t j = 0; j < s.inputs.size(); ++j) {
    const InputSpec& in = s.inputs[j];
    lua_createtable(L, 0, 4);
    lua::set_string(L, "dist", family_name(in.family));
    lua::set_number(L, "mean", m[j].first);
    lua::set_number(L, "std", m[j].second);
    lua::set_boolean(L, "calibrated", in.mean_param >= 0 || in.std_param >= 0);
    lua_setfield(L, -3, in.name.c_str());
    if (smi::stats::DistributionPtr d = input_distribution(in.family, m[j].first, m[j].second, in.shape, fmt::format("input '{}'", in.name))) {
      push_distribution(L, std::move(d));
      lua_setfield(L, -2, in.name.c_str());
    }
  }
  lua_setfield(L, -3, "distributions");
  lua_setfield(L, -2, "inputs");
  lua_createtable(L, 0, static_cast<int>(obj.responses().size()));
  for (const ResponseSpec& r : obj.responses()) {
    if (!r.grid) continue;
    lua_createtable(L, 3, 0);
    lua_pushnumber(L, r.grid->lo);
    lua_rawseti(L, -2, 1);
    lua_pushnumber(L, r.grid->hi);
    lua_rawseti(L, -2, 2);
    lua_pushinteger(L, static_cast<lua_Integer>(r.grid->n));
    lua_rawseti(L, -2, 3);
    lua_setfield(L, -2, r.name.c_str());
  }
  lua_setfield(L, -2, "grids");
  lua::set_integer(L, "model_runs", obj.model_runs());
  lua::set_integer(L, "model_passes", obj.model_passes());
  lua::set_integer(L, "n", static_cast<lua_Integer>(s.stat.n));
  lua::set_integer(L, "seed", static_cast<lua_Integer>(s.stat.seed));
  lua::set_string(L, "metric", s.metric_slot ? "custom" : (s.stat.metric == MetricKind::pr ? "pr" : "loglik"));
}

/// result.history: one row per evaluation. Stack: [res] -> [res].
void push_history(lua_State* L, const std::vector<std::string>& names, const std::vector<std::string>& parts,
                  const std::vector<HistoryEntry>& h) {
  lua_createtable(L, static_cast<int>(h.size()), 0);
  for (std::size_t i = 0; i < h.size(); ++i) {
    lua_createtable(L, 0, 5);
    push_named(L, names, h[i].theta);
    lua_setfield(L, -2, "params");
    lua::set_number(L, "objective", h[i].value);
    push_named(L, parts, h[i].parts);
    lua_setfield(L, -2, "metrics");
    lua::set_integer(L, "start", h[i].start + 1);
    lua::set_boolean(L, "probe", h[i].probe);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  lua_setfield(L, -2, "history");
}

/// identifiability.directions (strongest first) and .tolerance. Stack: [ident] -> [ident].
void push_directions(lua_State* L, const std::vector<std::string>& names, const DirectionsResult& d) {
  lua::set_number(L, "tolerance", d.tolerance);
  lua_createtable(L, static_cast<int>(d.directions.size()), 0);
  for (std::size_t i = 0; i < d.directions.size(); ++i) {
    const Direction& dir = d.directions[i];
    lua_createtable(L, 0, 6);
    lua::set_boolean(L, "determined", dir.determined);
    push_named(L, names, dir.loadings);
    lua_setfield(L, -2, "loadings");
    lua::set_number(L, "curvature", dir.curvature);
    lua::set_number(L, "rise", dir.rise);
    lua_createtable(L, 0, 2);
    lua::set_vec(L, "t", dir.t);
    lua::set_vec(L, "objective", dir.profile);
    lua_setfield(L, -2, "profile");
    lua_createtable(L, 2, 0);
    lua_pushnumber(L, dir.t_lower);
    lua_rawseti(L, -2, 1);
    lua_pushnumber(L, dir.t_upper);
    lua_rawseti(L, -2, 2);
    lua_setfield(L, -2, "reach");
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  lua_setfield(L, -2, "directions");
}

/// starts: each start's point, optimum, objective, evaluations and status, in start order.
void push_starts(lua_State* L, const std::vector<std::string>& names, const OptimizationResult& r) {
  lua_createtable(L, static_cast<int>(r.starts.size()), 0);
  for (std::size_t i = 0; i < r.starts.size(); ++i) {
    const StartResult& st = r.starts[i];
    lua_createtable(L, 0, 6);
    push_named(L, names, st.start);
    lua_setfield(L, -2, "start");
    push_named(L, names, st.theta);
    lua_setfield(L, -2, "params");
    lua::set_number(L, "objective", st.value);
    lua::set_integer(L, "evaluations", st.evaluations);
    lua::set_string(L, "status", st.status);
    lua::set_string(L, "criterion", st.criterion);
    lua::set_boolean(L, "converged", st.converged);
    if (!st.start_status.empty()) {
      // how the start's preparation (moment_start's Levenberg-Marquardt) ended, and its mismatch
      lua_createtable(L, 0, 3);
      lua::set_string(L, "status", st.start_status);
      lua::set_number(L, "before", st.start_criterion_before);
      lua::set_number(L, "after", st.start_criterion_after);
      lua_setfield(L, -2, "prepared");
    }
    if (st.hops > 0) {
      lua::set_integer(L, "hops", st.hops);
      lua::set_integer(L, "hops_improved", st.hops_improved);
    }
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  lua_setfield(L, -2, "starts");
}

/// agreement: whether the starts reached the best's optimum where the data can tell, per start.
void push_agreement(lua_State* L, const StartAgreement& a) {
  lua_createtable(L, 0, 8);
  lua::set_boolean(L, "agree", a.agree);
  lua::set_integer(L, "same", a.same);
  lua::set_integer(L, "starts", static_cast<lua_Integer>(a.rows.size()));
  lua::set_number(L, "tolerance", a.tolerance);
  lua::set_number(L, "largest_gap", a.largest_gap);
  lua::set_number(L, "largest_barrier", a.largest_barrier);
  if (!std::isnan(a.largest_prediction_distance)) lua::set_number(L, "largest_prediction_distance", a.largest_prediction_distance);
  lua::set_integer(L, "evaluations", a.evaluations);
  lua::set_integer(L, "predictions", a.predictions);
  lua::set_string(L, "text", describe(a));
  lua_createtable(L, static_cast<int>(a.rows.size()), 0);
  for (std::size_t i = 0; i < a.rows.size(); ++i) {
    lua_createtable(L, 0, 4);
    lua::set_number(L, "gap", a.rows[i].gap);
    lua::set_number(L, "barrier", a.rows[i].barrier);
    if (!std::isnan(a.rows[i].prediction_distance)) lua::set_number(L, "prediction_distance", a.rows[i].prediction_distance);
    lua::set_boolean(L, "same_prediction", a.rows[i].same_prediction);
    lua::set_boolean(L, "within", a.rows[i].within);
    lua::set_boolean(L, "same", a.rows[i].same);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  lua_setfield(L, -2, "rows");
  lua_setfield(L, -2, "agreement");
}

/// optima: the distinct optima the starts reached (each with the start that found it).
void push_optima(lua_State* L, const std::vector<std::string>& names, const OptimizationResult& r) {
  lua_createtable(L, static_cast<int>(r.optima.size()), 0);
  for (std::size_t i = 0; i < r.optima.size(); ++i) {
    const StartResult& st = r.starts[static_cast<std::size_t>(r.optima[i])];
    lua_createtable(L, 0, 3);
    push_named(L, names, st.theta);
    lua_setfield(L, -2, "params");
    lua::set_number(L, "objective", st.value);
    lua::set_integer(L, "start", r.optima[i] + 1);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  lua_setfield(L, -2, "optima");
}

/// identifiability: spans, weak parameters, one-at-a-time profiles and the directions.
void push_identifiability(lua_State* L, const std::vector<std::string>& names, const CalibrationOutcome& out) {
  const IdentifiabilityResult& id = *out.ident;
  lua_createtable(L, 0, 4);
  push_named(L, names, id.span);
  lua_setfield(L, -2, "span");
  std::vector<std::string> weak;
  for (std::size_t i = 0; i < names.size(); ++i)
    if (id.weak[i]) weak.push_back(names[i]);
  push_strings(L, weak);
  lua_setfield(L, -2, "weak");
  lua_createtable(L, 0, static_cast<int>(names.size()));
  for (std::size_t i = 0; i < names.size(); ++i) {
    lua_createtable(L, 0, 2);
    lua::set_vec(L, "nodes", id.nodes.row(static_cast<Eigen::Index>(i)).transpose());
    lua::set_vec(L, "values", id.profiles.row(static_cast<Eigen::Index>(i)).transpose());
    lua_setfield(L, -2, names[i].c_str());
  }
  lua_setfield(L, -2, "profiles");
  int evaluations = id.evaluations;
  if (out.directions) {
    push_directions(L, names, *out.directions);
    evaluations += out.directions->evaluations;
  }
  lua::set_integer(L, "evaluations", evaluations);
  lua_setfield(L, -2, "identifiability");
}

/// near_optimal: the points that fit as well as the optimum within the tolerance.
void push_near_optimal(lua_State* L, const std::vector<std::string>& names, const DirectionsResult& d) {
  lua_createtable(L, 0, 3);
  lua::set_number(L, "tolerance", d.tolerance);
  lua_createtable(L, static_cast<int>(d.near_optimal.size()), 0);
  for (std::size_t i = 0; i < d.near_optimal.size(); ++i) {
    push_named(L, names, d.near_optimal[i]);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  lua_setfield(L, -2, "points");
  lua::set_vec(L, "objectives", Eigen::Map<const Eigen::VectorXd>(d.near_optimal_values.data(), static_cast<Eigen::Index>(d.near_optimal_values.size())));
  lua_setfield(L, -2, "near_optimal");
}

/// bootstrap: percentile bounds, the normal interval, standard deviations, the endpoints' Monte Carlo errors, the
/// replicates they need and the replicates' optima.
void push_bootstrap(lua_State* L, const std::vector<std::string>& names, const CalibrateSpec& s, const BootstrapResult& b) {
  lua_createtable(L, 0, 12);
  push_named(L, names, b.lower);
  lua_setfield(L, -2, "lower");
  push_named(L, names, b.upper);
  lua_setfield(L, -2, "upper");
  push_named(L, names, b.stddev);
  lua_setfield(L, -2, "std");
  lua_createtable(L, 0, 2);
  push_named(L, names, b.normal_lower);
  lua_setfield(L, -2, "lower");
  push_named(L, names, b.normal_upper);
  lua_setfield(L, -2, "upper");
  lua_setfield(L, -2, "normal");
  push_named(L, names, b.lower_mc_error);
  lua_setfield(L, -2, "lower_mc_error");
  push_named(L, names, b.upper_mc_error);
  lua_setfield(L, -2, "upper_mc_error");
  lua::set_integer(L, "replicates_needed", b.replicates_needed);
  lua::set_number(L, "level", s.bootstrap->level);
  lua::set_integer(L, "replicates", static_cast<lua_Integer>(b.thetas.rows()));
  lua::set_integer(L, "failed", b.failed);
  lua_createtable(L, static_cast<int>(b.failures.size()), 0);
  for (std::size_t i = 0; i < b.failures.size(); ++i) {
    lua_createtable(L, 0, 2);
    lua::set_integer(L, "replicate", b.failures[i].first);
    lua::set_string(L, "message", b.failures[i].second);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  lua_setfield(L, -2, "failures");
  lua::set_boolean(L, "paired", b.paired);
  lua::set_integer(L, "evaluations", b.evaluations);
  lua::push_mat(L, b.thetas);
  lua_setfield(L, -2, "samples");
  lua_setfield(L, -2, "bootstrap");
}

/// intervals: each parameter's profile interval with its profile, and the delta (and level).
void push_profile_intervals(lua_State* L, const std::vector<std::string>& names, const CalibrateSpec& s, const CalibrationOutcome& out) {
  lua_createtable(L, 0, static_cast<int>(names.size()) + 3);
  for (std::size_t i = 0; i < names.size(); ++i) {
    const ProfileInterval& iv = out.profile->intervals[i];
    lua_createtable(L, 0, 6);
    lua::set_number(L, "lower", iv.lower);
    lua::set_number(L, "upper", iv.upper);
    lua::set_boolean(L, "determined", iv.determined);
    lua::set_boolean(L, "lower_open", iv.lower_open);
    lua::set_boolean(L, "upper_open", iv.upper_open);
    lua_createtable(L, 0, 2);
    lua::set_vec(L, "nodes", iv.nodes);
    lua::set_vec(L, "objective", iv.values);
    lua_setfield(L, -2, "profile");
    lua_setfield(L, -2, names[i].c_str());
  }
  lua::set_number(L, "delta", s.intervals->delta);
  if (s.interval_level > 0.0) lua::set_number(L, "level", s.interval_level);
  lua::set_integer(L, "evaluations", out.profile->evaluations);
  lua_setfield(L, -2, "intervals");
}

/// no_overlap = {{response =, metric =, value =, predicted = {lo, hi}, measured = {lo, hi}, ratio =,
/// units_hint =}, ...}. Stack: [res] -> [res].
void push_no_overlap(lua_State* L, const std::vector<NoOverlap>& rows) {
  lua_createtable(L, static_cast<int>(rows.size()), 0);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const NoOverlap& r = rows[i];
    lua_createtable(L, 0, 7);
    lua::set_string(L, "response", r.response);
    lua::set_string(L, "metric", r.metric);
    lua::set_number(L, "value", r.value);
    lua::set_vec(L, "predicted", Eigen::Vector2d(r.predicted_lo, r.predicted_hi));
    lua::set_vec(L, "measured", Eigen::Vector2d(r.measured_lo, r.measured_hi));
    lua::set_number(L, "ratio", r.ratio);
    if (!r.units_hint.empty()) lua::set_string(L, "units_hint", r.units_hint);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  lua_setfield(L, -2, "no_overlap");
}

/// r.prior_at(theta): the prior sum at θ ({name = value} or a list in r.names order), computed by
/// the kernel's prior_sum, the very sum the calibration minimised. Upvalues: the priors
/// ({{param =, mean =, std =, fn =, label =}, ...}), the parameter names, the weight.
int prior_at(lua_State* L) {
  return lua::protect(L, "prior_at", [&] {
    const int priors = lua_upvalueindex(1), names_t = lua_upvalueindex(2);
    const double weight = lua_tonumber(L, lua_upvalueindex(3));
    const std::vector<std::string> names = lua::to_strings(L, names_t, "names");
    if (!lua_istable(L, 1)) throw InvalidArgument("prior_at(theta): theta must be {name = value, ...} or a list in r.names order");
    Eigen::VectorXd t(static_cast<Eigen::Index>(names.size()));
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (lua_getfield(L, 1, names[i].c_str()) == LUA_TNIL) {
        lua_pop(L, 1);
        lua_rawgeti(L, 1, static_cast<lua_Integer>(i + 1));
      }
      if (!lua_isnumber(L, -1)) throw InvalidArgument(fmt::format("prior_at(theta): theta has no number for '{}'", names[i]));
      t[static_cast<Eigen::Index>(i)] = lua_tonumber(L, -1);
      lua_pop(L, 1);
    }
    std::vector<PriorTerm> terms;
    const auto n = static_cast<lua_Integer>(lua_rawlen(L, priors));
    for (lua_Integer i = 1; i <= n; ++i) {
      lua_rawgeti(L, priors, i);
      const int e = lua_gettop(L);
      PriorTerm p;
      lua_getfield(L, e, "label");
      p.label = lua_tostring(L, -1);
      lua_getfield(L, e, "param");
      p.param = static_cast<int>(lua_tointeger(L, -1));
      lua_getfield(L, e, "mean");
      p.mean = lua_tonumber(L, -1);
      lua_getfield(L, e, "std");
      p.std = lua_tonumber(L, -1);
      lua_pop(L, 4);
      if (lua_getfield(L, e, "fn") == LUA_TFUNCTION) {
        const int fn = lua_gettop(L);  // stays until the sum is taken
        p.fn = [L, fn, names](const Eigen::VectorXd& th) {
          lua_pushvalue(L, fn);
          lua_createtable(L, 0, static_cast<int>(names.size()));
          for (std::size_t j = 0; j < names.size(); ++j) lua::set_number(L, names[j].c_str(), th[static_cast<Eigen::Index>(j)]);
          lua::call(L, 1, 1);
          const double v = lua_isnumber(L, -1) ? lua_tonumber(L, -1) : std::nan("");
          lua_pop(L, 1);
          return v;
        };
      } else {
        lua_pop(L, 1);
      }
      terms.push_back(std::move(p));
    }
    lua_pushnumber(L, prior_sum(terms, weight, t));
    return 1;
  });
}

/// r.prior_at. Stack: [res] -> [res].
void push_prior_at(lua_State* L, const CalibrateSpec& s, const std::vector<std::string>& names) {
  lua_createtable(L, static_cast<int>(s.priors.size()), 0);
  for (std::size_t i = 0; i < s.priors.size(); ++i) {
    const PriorSpec& p = s.priors[i];
    lua_createtable(L, 0, 5);
    lua::set_string(L, "label", p.label);
    lua::set_integer(L, "param", p.param);
    lua::set_number(L, "mean", p.mean);
    lua::set_number(L, "std", p.std);
    if (p.fn_slot) {
      lua_pushvalue(L, p.fn_slot);
      lua_setfield(L, -2, "fn");
    }
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  push_strings(L, names);
  lua_pushnumber(L, s.prior_weight);
  lua_pushcclosure(L, prior_at, 3);
  lua_setfield(L, -2, "prior_at");
}

}  // namespace

void push_calibration_result(lua_State* L, const CalibrateSpec& s, const CalibrationOutcome& out) {
  std::vector<std::string> names;
  for (const auto& p : s.params) names.push_back(p.name);
  const OptimizationResult& r = out.opt;
  lua_createtable(L, 0, 24);
  push_named(L, names, r.theta);
  lua_setfield(L, -2, "params");
  push_strings(L, names);
  lua_setfield(L, -2, "names");
  lua::set_vec(L, "theta", r.theta);
  lua::set_number(L, "objective", r.value);
  push_named(L, out.part_names, r.parts);
  lua_setfield(L, -2, "metrics");
  lua::set_integer(L, "evaluations", r.evaluations);
  lua::set_integer(L, "start_evaluations", r.start_evaluations);
  lua::set_boolean(L, "converged", out.converged);
  lua::set_string(L, "status", out.status);
  lua::set_string(L, "optimizer_status", r.status);
  if (!out.message.empty()) lua::set_string(L, "message", out.message);
  if (!out.no_overlap.empty()) push_no_overlap(L, out.no_overlap);
  lua::set_number(L, "tolerance", out.tolerance);
  lua::set_string(L, "tolerance_basis", out.tolerance_basis);
  lua::set_number(L, "prior_value", out.prior_value);
  push_prior_at(L, s, names);
  lua::set_string(L, "method", method_name(s.optimizer.method));
  lua::set_string(L, "gradient", out.gradient);
  push_strings(L, out.warnings);
  lua_setfield(L, -2, "warnings");
  if (!out.not_computed.empty()) {
    lua_createtable(L, 0, static_cast<int>(out.not_computed.size()));
    for (const auto& [what, why] : out.not_computed) lua::set_string(L, what.c_str(), why);
    lua_setfield(L, -2, "not_computed");
  }
  push_strings(L, r.at_bounds);
  lua_setfield(L, -2, "at_bounds");
  push_history(L, names, out.part_names, r.history);

  push_starts(L, names, r);
  lua::set_boolean(L, "starts_agree", r.starts_agree);
  push_optima(L, names, r);
  if (out.agreement) push_agreement(L, *out.agreement);
  if (out.ident) push_identifiability(L, names, out);
  if (out.directions) push_near_optimal(L, names, *out.directions);
  if (out.boot) push_bootstrap(L, names, s, *out.boot);
  if (out.profile) push_profile_intervals(L, names, s, out);
  if (out.stat) push_statistical(L, s, out);
}

}  // namespace smi::bind::improve
