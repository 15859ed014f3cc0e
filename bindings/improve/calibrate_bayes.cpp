// SPDX-License-Identifier: MIT
// smi.calibrate_bayes{...}:
//   objective form: parameters = {{name =, lower =, upper =} | {name =, prior = {...}}, ...},
//                   loglik = function(Theta) -> vec (Theta: smi.mat, rows = points)
//   model form:     model, inputs, data (as smi.calibrate), noise = {response = sd},
//                   prior = {{param =, dist =, mean =, std =}, ...}, n
//   both:           samples, max_stages, seed, target_cov, min_sweeps, max_sweeps, moves
// Result: names, samples, mean, std, interval, map, log_evidence, log_evidence_error,
// loglik_error, diagnostics {stages, beta, acceptance, ess, sweeps, chain_correlation, converged,
// reasons}, converged, evaluations, model_runs, loglik (at the samples), noise, n, seed.
#include "bindings/improve/calibrate_bayes.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "bindings/improve/calibrate_bayes_spec.hpp"
#include "bindings/improve/lua_callbacks.hpp"
#include "bindings/improve/lua_values.hpp"
#include "bindings/improve/model_gradient.hpp"
#include "luax/luax.hpp"
#include "luax/run_context.hpp"
#include "platform/core/errors.hpp"

namespace smi::bind::improve {

using namespace smi::improve;

namespace {

constexpr const char* kBayesMeta = "smi.calibrate_bayes";
/// The central interval's level (r.interval).
constexpr double kIntervalLevel = 0.9;  // literal: the level the result promises (r.interval_level), not a setting

/// loglik(Theta) -> vec, one Lua call per batch (on the Lua thread).
BatchLogLikelihood lua_loglik(lua_State* L, int slot) {
  return [L, slot](const Eigen::MatrixXd& T) {
    StackGuard guard(L);
    lua_pushvalue(L, slot);
    lua::push_mat(L, T);
    lua::call(L, 1, 1);
    const Eigen::VectorXd v = read_vector(L, -1, "the value returned by loglik");
    if (v.size() != T.rows())
      throw DimensionMismatch(fmt::format("loglik returned {} values for the {} rows of Theta: return one log-likelihood per row", v.size(), T.rows()));
    return v;
  };
}

/// The model as the population likelihood calls it: Krigings without Lua, else the Lua model.
Model population_model(lua_State* L, const BayesSpec& s) {
  if (Model m = kriging_model(L, s.population_spec, s.responses, s.population.threads)) return m;
  return LuaModel(L, s.population_spec.model_parts, s.population_spec.input_names_slot, s.responses, LuaGate(L));
}

/// Type-7 quantile of a sorted vector.
double quantile(const std::vector<double>& sorted, double p) {
  const double h = p * static_cast<double>(sorted.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, sorted.size() - 1);
  return sorted[lo] + (h - static_cast<double>(lo)) * (sorted[hi] - sorted[lo]);
}

void set_named(lua_State* L, const char* key, const std::vector<std::string>& names, const Eigen::VectorXd& v) {
  lua_createtable(L, 0, static_cast<int>(names.size()));
  for (std::size_t k = 0; k < names.size(); ++k) {
    lua_pushnumber(L, v[static_cast<Eigen::Index>(k)]);
    lua_setfield(L, -2, names[k].c_str());
  }
  lua_setfield(L, -2, key);
}

void set_list(lua_State* L, const char* key, const std::vector<TmcmcStage>& st, double TmcmcStage::*field) {
  lua_createtable(L, static_cast<int>(st.size()), 0);
  for (std::size_t i = 0; i < st.size(); ++i) {
    lua_pushnumber(L, st[i].*field);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  lua_setfield(L, -2, key);
}

void push_diagnostics(lua_State* L, const TmcmcResult& r) {
  lua_createtable(L, 0, 8);
  lua::set_integer(L, "stages", static_cast<lua_Integer>(r.stages.size()));
  set_list(L, "beta", r.stages, &TmcmcStage::beta);
  set_list(L, "acceptance", r.stages, &TmcmcStage::acceptance);
  set_list(L, "ess", r.stages, &TmcmcStage::ess);
  set_list(L, "chain_correlation", r.stages, &TmcmcStage::chain_correlation);
  set_list(L, "scale", r.stages, &TmcmcStage::scale);
  lua_createtable(L, static_cast<int>(r.stages.size()), 0);
  for (std::size_t i = 0; i < r.stages.size(); ++i) {
    lua_pushinteger(L, r.stages[i].sweeps);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  lua_setfield(L, -2, "sweeps");
  lua::set_boolean(L, "converged", r.converged);
  lua_createtable(L, static_cast<int>(r.reasons.size()), 0);
  for (std::size_t i = 0; i < r.reasons.size(); ++i) {
    lua_pushstring(L, r.reasons[i].c_str());
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  lua_setfield(L, -2, "reasons");
  lua_setfield(L, -2, "diagnostics");
}

/// The printed summary (__tostring): one line per parameter, then evidence and diagnostics.
std::string summary(const std::vector<std::string>& names, const Eigen::VectorXd& mean, const Eigen::VectorXd& sd, const Eigen::MatrixXd& iv,
                    const TmcmcResult& r, double loglik_error) {
  std::string t = fmt::format("smi.calibrate_bayes: {} posterior samples, {} stages, {}\n", r.samples.rows(), r.stages.size(),
                              r.converged ? "converged" : "NOT converged");
  std::size_t w = 4;
  for (const auto& n : names) w = std::max(w, n.size());
  t += fmt::format("  {:<{}}  {:>12}  {:>12}  {:>12}  {:>12}\n", "name", w, "mean", "std", "5 %", "95 %");
  for (std::size_t k = 0; k < names.size(); ++k) {
    const auto i = static_cast<Eigen::Index>(k);
    t += fmt::format("  {:<{}}  {:>12.6g}  {:>12.6g}  {:>12.6g}  {:>12.6g}\n", names[k], w, mean[i], sd[i], iv(i, 0), iv(i, 1));
  }
  t += fmt::format("  log evidence {:.4f} +- {:.4f} (sampler)", r.log_evidence, r.log_evidence_error);
  if (loglik_error > 0.0) t += fmt::format(", log-likelihood error {:.4f} at the MAP", loglik_error);
  t += fmt::format("\n  {} likelihood evaluations; last stage acceptance {:.2f}", r.evaluations, r.stages.back().acceptance);
  for (const auto& reason : r.reasons) t += "\n  not converged: " + reason;
  return t;
}

// long: the result table's fields, one after another (data, no logic)
void push_result(lua_State* L, const BayesSpec& s, const TmcmcResult& r, double loglik_error, long model_runs) {
  std::vector<std::string> names;
  for (const Prior& p : s.priors) names.push_back(p.name);
  const Eigen::Index d = r.samples.cols();
  const Eigen::VectorXd mean = r.samples.colwise().mean();
  const Eigen::VectorXd sd =
      ((r.samples.rowwise() - mean.transpose()).array().square().colwise().sum() / static_cast<double>(std::max<Eigen::Index>(1, r.samples.rows() - 1)))
          .sqrt();
  Eigen::MatrixXd iv(d, 2);
  for (Eigen::Index k = 0; k < d; ++k) {
    std::vector<double> col(r.samples.col(k).data(), r.samples.col(k).data() + r.samples.rows());
    std::sort(col.begin(), col.end());
    iv(k, 0) = quantile(col, 0.5 * (1.0 - kIntervalLevel));
    iv(k, 1) = quantile(col, 0.5 * (1.0 + kIntervalLevel));
  }
  lua_createtable(L, 0, 20);
  lua_createtable(L, static_cast<int>(d), 0);
  for (std::size_t k = 0; k < names.size(); ++k) {
    lua_pushstring(L, names[k].c_str());
    lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
  }
  lua_setfield(L, -2, "names");
  lua::push_mat(L, r.samples);
  lua_setfield(L, -2, "samples");
  lua::set_vec(L, "loglik", r.loglik);
  set_named(L, "mean", names, mean);
  set_named(L, "std", names, sd);
  set_named(L, "map", names, r.samples.row(r.map_index).transpose());
  lua_createtable(L, 0, static_cast<int>(d));
  for (std::size_t k = 0; k < names.size(); ++k) {
    lua_createtable(L, 2, 0);
    lua_pushnumber(L, iv(static_cast<Eigen::Index>(k), 0));
    lua_rawseti(L, -2, 1);
    lua_pushnumber(L, iv(static_cast<Eigen::Index>(k), 1));
    lua_rawseti(L, -2, 2);
    lua_setfield(L, -2, names[k].c_str());
  }
  lua_setfield(L, -2, "interval");
  lua::set_number(L, "interval_level", kIntervalLevel);
  lua::set_number(L, "log_evidence", r.log_evidence);
  lua::set_number(L, "log_evidence_error", r.log_evidence_error);
  lua::set_number(L, "loglik_error", loglik_error);
  push_diagnostics(L, r);
  lua::set_boolean(L, "converged", r.converged);
  lua::set_integer(L, "evaluations", r.evaluations);
  lua::set_integer(L, "model_runs", model_runs);
  lua::set_integer(L, "seed", static_cast<lua_Integer>(s.sampler.seed));
  if (s.model_form) {
    lua::set_integer(L, "n", s.population.n);
    set_named(L, "noise", s.responses, s.noise_sd);
  }
  lua::set_string(L, "printable", summary(names, mean, sd, iv, r, loglik_error));
}

int bayes_tostring(lua_State* L) {
  lua_getfield(L, 1, "printable");
  return 1;
}

}  // namespace

int calibrate_bayes(lua_State* L) {
  luaL_checktype(L, 1, LUA_TTABLE);
  lua_settop(L, 1);
  return lua::protect(L, "smi.calibrate_bayes", [&] {
    const BayesSpec s = read_bayes_spec(L, 1);
    const PriorSet prior(s.priors);
    const cancel::Token& stop = lua::cancel_token(L);
    if (!s.model_form) {
      const TmcmcResult r = tmcmc(prior, lua_loglik(L, s.loglik_slot), s.sampler, stop);
      push_result(L, s, r, 0.0, 0);
    } else {
      Eigen::MatrixXd noise = s.noise_sd.array().square().matrix().asDiagonal();
      const PopulationLikelihood like(s.population_spec.inputs, prior.size(), s.data, noise, population_model(L, s), s.population);
      const TmcmcResult r = tmcmc(prior, [&like](const Eigen::MatrixXd& T) { return like(T); }, s.sampler, stop);
      const double err = like.evaluate(r.samples.row(r.map_index)).error[0];
      push_result(L, s, r, err, like.model_calls());
    }
    luaL_setmetatable(L, kBayesMeta);
    return 1;
  });
}

void register_bayes_meta(lua_State* L) {
  const luaL_Reg meta[] = {{"__tostring", bayes_tostring}, {nullptr, nullptr}};
  lua::register_table_type(L, kBayesMeta, nullptr, meta);
}

}  // namespace smi::bind::improve
