// SPDX-License-Identifier: MIT
#include "bindings/improve/calibrate_bayes_spec.hpp"

#include <fmt/format.h>

#include <cmath>

#include "bindings/improve/calibrate_bayes_options.hpp"
#include "bindings/improve/lua_values.hpp"
#include "luax/luax.hpp"
#include "luax/run_context.hpp"
#include "platform/core/errors.hpp"

namespace smi::bind::improve {

using namespace smi::improve;

namespace {

/// A prior table at `e` ({dist, mean, std[, lower, upper]}) into `p` (whose name and range are set).
void read_prior_density(lua_State* L, int e, const std::string& where, bool range_allowed, Prior& p) {
  const BayesPriorArgs a = bayes_prior_schema().read(L, e, where.c_str());
  p.kind = a.dist == "lognormal" ? PriorKind::lognormal : PriorKind::normal;
  if (std::isnan(a.mean) || std::isnan(a.std))
    throw InvalidArgument(fmt::format("{}: needs mean = and std = (a {} prior of the parameter itself)", where, a.dist));
  p.mean = a.mean;
  p.std = a.std;
  const bool ranged = std::isfinite(a.lower) || std::isfinite(a.upper);
  if (ranged && !range_allowed)
    throw InvalidArgument(fmt::format("{}: the prior is truncated to the parameter's range {{lo, hi}} in inputs; drop lower/upper here", where));
  if (std::isfinite(a.lower)) p.lower = a.lower;
  if (std::isfinite(a.upper)) p.upper = a.upper;
}

/// parameters = {{name =, lower =, upper =} | {name, lower, upper} | {name =, prior = {...}}, ...}.
void read_parameters(lua_State* L, int spec, BayesSpec& s) {
  if (lua_getfield(L, spec, "parameters") != LUA_TTABLE || lua_rawlen(L, -1) == 0)
    throw InvalidArgument("parameters must be a non-empty list of {name =, lower =, upper =} or {name =, prior = {dist =, mean =, std =}}");
  const int t = lua_gettop(L);
  for (int i = 1; i <= static_cast<int>(lua_rawlen(L, t)); ++i) {
    const std::string where = fmt::format("parameters[{}]", i);
    if (lua_rawgeti(L, t, i) != LUA_TTABLE) throw InvalidArgument(where + " must be a table {name =, lower =, upper =}");
    const int e = lua_gettop(L);
    Prior p;
    if (lua_getfield(L, e, "name") == LUA_TNIL) {
      lua_pop(L, 1);
      lua_rawgeti(L, e, 1);
    }
    if (lua_type(L, -1) != LUA_TSTRING) throw InvalidArgument(where + ".name (or [1]) must be a string");
    p.name = lua_tostring(L, -1);
    lua_pop(L, 1);
    for (int b = 0; b < 2; ++b) {
      const char* key = b ? "upper" : "lower";
      if (lua_getfield(L, e, key) == LUA_TNIL) {
        lua_pop(L, 1);
        lua_rawgeti(L, e, b + 2);
      }
      if (!lua_isnil(L, -1)) (b ? p.upper : p.lower) = read_number(L, -1, where + "." + key);
      lua_pop(L, 1);
    }
    const int pt = lua_getfield(L, e, "prior");
    if (pt == LUA_TTABLE) read_prior_density(L, lua_gettop(L), where + ".prior", true, p);
    else if (pt != LUA_TNIL) throw InvalidArgument(fmt::format("{}.prior must be a table {{dist =, mean =, std =}}, got {}", where, lua_typename(L, pt)));
    else if (!std::isfinite(p.lower) || !std::isfinite(p.upper))
      throw InvalidArgument(fmt::format("{} ('{}'): give lower and upper (a uniform prior) or prior = {{dist = \"normal\", mean =, std =}}", where, p.name));
    lua_pop(L, 2);
    for (const Prior& q : s.priors)
      if (q.name == p.name) throw InvalidArgument(fmt::format("{}: the name '{}' is given twice", where, p.name));
    s.priors.push_back(p);
  }
  lua_pop(L, 1);
}

/// prior = {{param =, dist =, mean =, std =}, ...} on the model form's parameters (already uniform).
void read_model_priors(lua_State* L, int spec, BayesSpec& s) {
  const int t = lua_getfield(L, spec, "prior");
  if (t == LUA_TNIL) {
    lua_pop(L, 1);
    return;
  }
  if (t != LUA_TTABLE) throw InvalidArgument("prior must be a list of {param = \"x.mean\", dist = \"normal\", mean =, std =}");
  const int list = lua_gettop(L);
  for (int i = 1; i <= static_cast<int>(lua_rawlen(L, list)); ++i) {
    const std::string where = fmt::format("prior[{}]", i);
    if (lua_rawgeti(L, list, i) != LUA_TTABLE) throw InvalidArgument(where + " must be a table {param =, dist =, mean =, std =}");
    const int e = lua_gettop(L);
    const BayesPriorArgs a = bayes_prior_schema().read(L, e, where.c_str());
    Prior* target = nullptr;
    std::string names;
    for (Prior& p : s.priors) {
      if (p.name == a.param) target = &p;
      names += (names.empty() ? "" : ", ") + p.name;
    }
    if (!target)
      throw InvalidArgument(fmt::format("{}.param: no calibrated parameter named \"{}\" (the parameters are: {})", where, a.param, names));
    if (target->kind != PriorKind::uniform) throw InvalidArgument(fmt::format("{}: a second prior on '{}'", where, a.param));
    read_prior_density(L, e, where, false, *target);
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
}

/// The data as a specimens x responses matrix (every response the same length), and the noise.
void read_data_and_noise(lua_State* L, int spec, BayesSpec& s) {
  const auto& rs = s.population_spec.responses;
  const Eigen::Index n = rs.front().data.size();
  s.data.resize(n, static_cast<Eigen::Index>(rs.size()));
  for (std::size_t r = 0; r < rs.size(); ++r) {
    s.responses.push_back(rs[r].name);
    if (rs[r].f_exp && rs[r].data.size() == 0)
      throw InvalidArgument(fmt::format("data.{} is a distribution: the population likelihood needs each specimen's measured values", rs[r].name));
    if (rs[r].data.size() != n)
      throw InvalidArgument(fmt::format("data.{} has {} values but data.{} has {}: give every response of every specimen, in the same order",
                                        rs[r].name, rs[r].data.size(), rs.front().name, n));
    s.data.col(static_cast<Eigen::Index>(r)) = rs[r].data;
  }
  s.noise_sd.resize(s.data.cols());
  s.noise_given.assign(rs.size(), false);
  const int nt = lua_getfield(L, spec, "noise");
  if (nt != LUA_TNIL && nt != LUA_TTABLE) throw InvalidArgument("noise must be a table {response = sd, ...}");
  if (nt == LUA_TTABLE)
    for (const std::string& key : sorted_keys(L, -1)) {
      bool known = false;
      for (std::size_t r = 0; r < rs.size(); ++r) known = known || rs[r].name == key;
      if (!known) throw InvalidArgument(fmt::format("noise.{}: no response of that name in data", key));
    }
  for (std::size_t r = 0; r < rs.size(); ++r) {
    const auto ri = static_cast<Eigen::Index>(r);
    if (nt == LUA_TTABLE && raw_field(L, -1, rs[r].name.c_str()) != LUA_TNIL) {
      s.noise_sd[ri] = read_number(L, -1, "noise." + rs[r].name);
      s.noise_given[r] = true;
      if (!(s.noise_sd[ri] > 0.0) || !std::isfinite(s.noise_sd[ri]))
        throw InvalidArgument(fmt::format("noise.{} must be a standard deviation > 0, got {}", rs[r].name, s.noise_sd[ri]));
    } else {
      const Eigen::VectorXd d = s.data.col(ri);
      const double sd = n > 1 ? std::sqrt((d.array() - d.mean()).square().sum() / static_cast<double>(n - 1)) : 0.0;
      s.noise_sd[ri] = s.noise_fraction * sd;
      if (!(s.noise_sd[ri] > 0.0))
        throw InvalidArgument(fmt::format("data.{} has no scatter to set a default noise from ({} specimen(s)): give noise = {{{} = sd}}",
                                          rs[r].name, n, rs[r].name));
    }
    if (nt == LUA_TTABLE) lua_pop(L, 1);
  }
  lua_pop(L, 1);
}

void read_model_form(lua_State* L, int idx, BayesSpec& s) {
  if (lua::Options(L, idx, "smi.calibrate_bayes").has("parameters"))
    throw InvalidArgument("with a model, the calibrated parameters are the input ranges: give mean/std as {lower, upper, start}");
  s.model_form = true;
  read_population(L, idx, s.population_spec);
  if (s.population_spec.params.empty())
    throw InvalidArgument("no input has a calibrated mean or std: give mean = {lower, upper} (or std) for the unknown inputs");
  for (const auto& p : s.population_spec.params) {
    Prior q;
    q.name = p.name;
    q.lower = p.lower;
    q.upper = p.upper;
    s.priors.push_back(q);
  }
  read_model_priors(L, idx, s);
  read_data_and_noise(L, idx, s);
}

}  // namespace

BayesSpec read_bayes_spec(lua_State* L, int idx) {
  idx = lua_absindex(L, idx);
  BayesSpec s;
  s.sampler.seed = lua::run_context(L).seed;
  calibrate_bayes_schema().read(L, idx, s);
  s.population.seed = s.sampler.seed;
  const lua::Options o(L, idx, "smi.calibrate_bayes");
  const bool has_loglik = o.has("loglik"), has_model = o.has("model");
  if (has_loglik == has_model) throw InvalidArgument("give either loglik = function(Theta) with parameters, or model with inputs and data");
  if (has_loglik) {
    for (const char* key : {"inputs", "data", "noise", "prior"})
      if (o.has(key))
        throw InvalidArgument(fmt::format("{} belongs to the model form; with loglik = ... give parameters (each with its range or prior)", key));
    read_parameters(L, idx, s);
    if (lua_getfield(L, idx, "loglik") != LUA_TFUNCTION) throw InvalidArgument("loglik must be a function(Theta) returning a vec");
    s.loglik_slot = lua_gettop(L);
  } else {
    read_model_form(L, idx, s);
  }
  if (s.sampler.max_sweeps < s.sampler.min_sweeps)
    throw InvalidArgument(fmt::format("max_sweeps ({}) must be at least min_sweeps ({})", s.sampler.max_sweeps, s.sampler.min_sweeps));
  return s;
}

}  // namespace smi::bind::improve
