// SPDX-License-Identifier: MIT
#include "bindings/improve/calibrate_spec.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "bindings/improve/calibrate_options.hpp"
#include "bindings/improve/lua_values.hpp"
#include "bindings/stats/dist_box.hpp"
#include "luax/luax.hpp"
#include "luax/run_context.hpp"
#include "luax/policy.hpp"
#include "platform/core/errors.hpp"

namespace smi::bind::improve {

using namespace smi::improve;

namespace {

/// A string field value at the top of the stack, or `def` for nil.
std::string read_string(lua_State* L, const std::string& what, const char* def) {
  if (lua_isnil(L, -1)) return def;
  if (lua_type(L, -1) != LUA_TSTRING) throw InvalidArgument(fmt::format("{} must be a string, got {}", what, luaL_typename(L, -1)));
  return lua_tostring(L, -1);
}

/// t[key] or t[pos] (positional fallback); pushes the value. Stack: [] -> [v].
int field_or_index(lua_State* L, int t, const char* key, int pos) {
  if (lua_getfield(L, t, key) != LUA_TNIL) return lua_type(L, -1);
  lua_pop(L, 1);
  return lua_rawgeti(L, t, pos);
}

/// A {lower, upper, start} range (named or positional) at the top of the stack -> a parameter.
Parameter read_range(lua_State* L, const std::string& name, const std::string& where) {
  const int t = lua_absindex(L, -1);
  Parameter p;
  p.name = name;
  field_or_index(L, t, "lower", 1);
  p.lower = read_number(L, -1, where + ".lower");
  lua_pop(L, 1);
  field_or_index(L, t, "upper", 2);
  p.upper = read_number(L, -1, where + ".upper");
  lua_pop(L, 1);
  if (field_or_index(L, t, "start", 3) == LUA_TNIL)
    p.start = 0.5 * (p.lower + p.upper);
  else
    p.start = read_number(L, -1, where + ".start");
  lua_pop(L, 1);
  return p;
}

void read_parameters(lua_State* L, int spec, CalibrateSpec& s) {
  if (lua_getfield(L, spec, "parameters") != LUA_TTABLE)
    throw InvalidArgument("parameters must be a list of {name = ..., lower = ..., upper = ..., start = ...}");
  const int t = lua_absindex(L, -1);
  const auto n = static_cast<int>(lua_rawlen(L, t));
  if (n == 0) throw InvalidArgument("parameters is empty: give at least one {name, lower, upper, start}");
  for (int i = 1; i <= n; ++i) {
    lua_rawgeti(L, t, i);
    const std::string where = fmt::format("parameters[{}]", i);
    if (!lua_istable(L, -1)) throw InvalidArgument(where + " must be a table {name = ..., lower = ..., upper = ..., start = ...}");
    const int e = lua_absindex(L, -1);
    if (field_or_index(L, e, "name", 1) != LUA_TSTRING) throw InvalidArgument(where + ".name (or [1]) must be a string");
    const std::string name = lua_tostring(L, -1);
    lua_pop(L, 1);
    // Named fields, or {lower, upper, start} positionally after the name.
    if (lua_getfield(L, e, "lower") == LUA_TNIL) {
      lua_pop(L, 1);
      lua_createtable(L, 3, 0);
      for (int k = 0; k < 3; ++k) {
        lua_rawgeti(L, e, k + 2);
        lua_rawseti(L, -2, k + 1);
      }
    } else {
      lua_pop(L, 1);
      lua_pushvalue(L, e);
    }
    s.params.push_back(read_range(L, name, where));
    lua_pop(L, 2);
  }
  lua_pop(L, 1);
}

/// mean/std of an input: a number (fixed) or a range (calibrated, named "<input>.<moment>").
void read_moment(lua_State* L, int in, const char* key, const std::string& input, double& fixed, int& param, CalibrateSpec& s) {
  const std::string where = fmt::format("inputs.{}.{}", input, key);
  const int t = lua_getfield(L, in, key);
  if (t == LUA_TNUMBER) {
    fixed = lua_tonumber(L, -1);
  } else if (t == LUA_TTABLE) {
    param = static_cast<int>(s.params.size());
    s.params.push_back(read_range(L, input + "." + key, where));
  } else {
    throw InvalidArgument(fmt::format("{} must be a number (fixed) or {{lower, upper, start}} (calibrated), got {}", where,
                                      lua_typename(L, t)));
  }
  lua_pop(L, 1);
}

/// The fixed shape fields of the families beyond normal/lognormal/uniform (see InputShape):
/// lower/upper (truncnormal, beta), loc (weibull, gamma), mode_at (triangular).
void read_input_shape(lua_State* L, int in, const std::string& name, InputSpec& spec_in) {
  auto number = [&](const char* key, double& out) {
    const int t = lua_getfield(L, in, key);
    if (t == LUA_TNUMBER) out = lua_tonumber(L, -1);
    else if (t != LUA_TNIL) throw InvalidArgument(fmt::format("inputs.{}.{} must be a number (fixed), got {}", name, key, lua_typename(L, t)));
    lua_pop(L, 1);
  };
  switch (spec_in.family) {
    case InputFamily::truncnormal: number("lower", spec_in.shape.lower), number("upper", spec_in.shape.upper); break;
    case InputFamily::beta:
      spec_in.shape.lower = 0.0, spec_in.shape.upper = 1.0;
      number("lower", spec_in.shape.lower), number("upper", spec_in.shape.upper);
      break;
    case InputFamily::weibull:
    case InputFamily::gamma: number("loc", spec_in.shape.loc); break;
    case InputFamily::triangular: number("mode_at", spec_in.shape.mode_at); break;
    default: break;
  }
}

void read_inputs(lua_State* L, int spec, CalibrateSpec& s) {
  if (lua_getfield(L, spec, "inputs") != LUA_TTABLE)
    throw InvalidArgument("inputs must be a table {name = {dist = \"normal\", mean = ..., std = ...}, ...}");
  const int t = lua_absindex(L, -1);
  // Column order: a list of {name = ...} keeps its order; a name-keyed table is sorted by name,
  // unless `order` lists the names.
  std::vector<std::string> names;
  const bool list = lua_rawlen(L, t) > 0;
  if (list) {
    for (int i = 1; i <= static_cast<int>(lua_rawlen(L, t)); ++i) {
      lua_rawgeti(L, t, i);
      if (!lua_istable(L, -1) || lua_getfield(L, -1, "name") != LUA_TSTRING)
        throw InvalidArgument(fmt::format("inputs[{}] must be a table with a string name", i));
      names.emplace_back(lua_tostring(L, -1));
      lua_pop(L, 2);
    }
  } else if (lua_getfield(L, spec, "order") == LUA_TTABLE) {
    names = lua::to_strings(L, -1, "order");
    lua_pop(L, 1);
  } else {
    lua_pop(L, 1);
    // A model object that knows its input order (a surrogate) fixes the columns; else by name.
    names = s.model_input_order.empty() ? sorted_keys(L, t) : s.model_input_order;
  }
  if (!list) {
    const auto keys = sorted_keys(L, t);
    auto sorted_names = names;
    std::sort(sorted_names.begin(), sorted_names.end());
    if (keys != sorted_names) {
      std::string k, n;
      for (const auto& x : keys) k += (k.empty() ? "" : ", ") + x;
      for (const auto& x : names) n += (n.empty() ? "" : ", ") + x;
      throw InvalidArgument(fmt::format("inputs ({}) and the column order ({}) name different inputs: describe every model input once",
                                        k, n));
    }
  }
  if (names.empty()) throw InvalidArgument("inputs is empty: describe at least one input");
  if (!s.model_input_order.empty() && names != s.model_input_order) {
    std::string a, b;
    for (const auto& x : names) a += (a.empty() ? "" : ", ") + x;
    for (const auto& x : s.model_input_order) b += (b.empty() ? "" : ", ") + x;
    throw InvalidArgument(fmt::format("the inputs are given in the order ({}) but the model takes ({}): follow the model's order", a, b));
  }
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string& name = names[i];
    if (list)
      lua_rawgeti(L, t, static_cast<lua_Integer>(i + 1));
    else if (lua_getfield(L, t, name.c_str()) != LUA_TTABLE)
      throw InvalidArgument(fmt::format("inputs.{} must be a table {{dist = ..., mean = ..., std = ...}} (is it listed in order?)", name));
    const int in = lua_absindex(L, -1);
    InputSpec spec_in;
    spec_in.name = name;
    lua_getfield(L, in, "dist");
    spec_in.family = parse_family(read_string(L, fmt::format("inputs.{}.dist", name), "normal"), fmt::format("inputs.{}.dist", name));
    lua_pop(L, 1);
    if (spec_in.family == InputFamily::constant) {
      if (lua_getfield(L, in, "value") == LUA_TNUMBER) {
        spec_in.mean = lua_tonumber(L, -1);
        lua_pop(L, 1);
      } else {
        lua_pop(L, 1);
        read_moment(L, in, "mean", name, spec_in.mean, spec_in.mean_param, s);
      }
    } else {
      read_moment(L, in, "mean", name, spec_in.mean, spec_in.mean_param, s);
      read_moment(L, in, "std", name, spec_in.std, spec_in.std_param, s);
      read_input_shape(L, in, name, spec_in);
    }
    s.inputs.push_back(spec_in);
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  lua_createtable(L, static_cast<int>(names.size()), 0);
  for (std::size_t i = 0; i < names.size(); ++i) {
    lua_pushstring(L, names[i].c_str());
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  s.input_names_slot = lua_gettop(L);  // stays on the stack for the model calls
}

void read_data(lua_State* L, int spec, CalibrateSpec& s) {
  if (lua_getfield(L, spec, "data") != LUA_TTABLE)
    throw InvalidArgument("data must be a table {response = vec of experimental data, ...}");
  s.data_slot = lua_gettop(L);  // stays on the stack (the custom metric receives it)
  const auto names = sorted_keys(L, s.data_slot);
  if (names.empty()) throw InvalidArgument("data is empty: give {response = vec, ...}");
  for (const std::string& r : names) {
    ResponseSpec rs;
    rs.name = r;
    lua_getfield(L, s.data_slot, r.c_str());
    const int at = lua_gettop(L);
    if (auto d = test_distribution(L, at)) {
      rs.f_exp = d;  // an experimental PDF (KDE-ebd, ...) instead of raw data
    } else if (lua_istable(L, at) && lua_getfield(L, at, "pdf") != LUA_TNIL) {
      // {points = vec, pdf = dist}: the PDF is the objective's, the points what is resampled
      rs.f_exp = test_distribution(L, -1);
      if (!rs.f_exp) throw InvalidArgument(fmt::format("data.{}.pdf must be a distribution (smi.kde_ebd(...), smi.dist...)", r));
      lua_getfield(L, at, "points");
      rs.data = read_vector(L, -1, "data." + r + ".points");
    } else {
      rs.data = read_vector(L, at, "data." + r);
    }
    lua_settop(L, at - 1);
    s.responses.push_back(std::move(rs));
  }
}

/// {input = {lower, upper}, ...} at d.
void read_design_table(lua_State* L, int d, CalibrateSpec& s, const std::string& what) {
  for (const std::string& name : sorted_keys(L, d)) {
    lua_getfield(L, d, name.c_str());
    if (!lua_istable(L, -1)) throw InvalidArgument(fmt::format("{}.{} must be {{lower, upper}}", what, name));
    lua_rawgeti(L, -1, 1);
    lua_rawgeti(L, -2, 2);
    s.design.push_back({name, read_number(L, -2, what + "." + name + "[1]"), read_number(L, -1, what + "." + name + "[2]")});
    lua_pop(L, 3);
  }
}

/// For an object model at `self` (table or userdata with :evaluate): pushes its evaluate method
/// and records a part; reads its input order (model.input_names or model.inputs: a list, or a
/// method returning one) and design ranges (model.design_bounds) when it has them.
void read_model_object(lua_State* L, int self, const std::string& output, bool explicit_design, CalibrateSpec& s) {
  const std::string who = output.empty() ? std::string("model") : "model." + output;
  if (lua_getfield(L, self, "evaluate") != LUA_TFUNCTION)
    throw InvalidArgument(fmt::format("{} has no evaluate method: give a function(X, names) or an object with m:evaluate(X)", who));
  const int fn = lua_gettop(L);
  int grad = 0;
  if (lua_getfield(L, self, "gradient") == LUA_TFUNCTION) grad = lua_gettop(L);  // stays on the stack
  else lua_pop(L, 1);
  s.model_parts.push_back({output, fn, self, grad});
  std::vector<std::string> order;
  for (const char* key : {"input_names", "inputs"}) {
    if (lua_getfield(L, self, key) == LUA_TFUNCTION) {
      lua_pushvalue(L, self);
      lua_call(L, 1, 1);
    }
    if (lua_istable(L, -1) && lua_rawlen(L, -1) > 0 && order.empty()) order = lua::to_strings(L, -1, (who + "." + key).c_str());
    lua_pop(L, 1);
  }
  if (!order.empty()) {
    if (!s.model_input_order.empty() && s.model_input_order != order)
      throw InvalidArgument(fmt::format("{} takes its inputs in another order than the other parts of the model", who));
    s.model_input_order = order;
  }
  if (!explicit_design) {
    if (lua_getfield(L, self, "design_bounds") == LUA_TFUNCTION) {
      lua_pushvalue(L, self);
      lua_call(L, 1, 1);
    }
    if (lua_istable(L, -1)) read_design_table(L, lua_gettop(L), s, who + ":design_bounds()");
    lua_pop(L, 1);
  }
}

void read_model(lua_State* L, int spec, CalibrateSpec& s) {
  lua_getfield(L, spec, "design_bounds");
  const bool explicit_design = !lua_isnil(L, -1);
  lua_pop(L, 1);
  const int t = lua_getfield(L, spec, "model");
  const int slot = lua_gettop(L);
  if (t == LUA_TFUNCTION) {
    s.model_parts.push_back({"", slot, 0});
    return;
  }
  bool has_evaluate = t == LUA_TUSERDATA;
  if (t == LUA_TTABLE) {
    has_evaluate = lua_getfield(L, slot, "evaluate") != LUA_TNIL;
    lua_pop(L, 1);
  }
  if (has_evaluate) {
    read_model_object(L, slot, "", explicit_design, s);
    return;
  }
  if (t == LUA_TTABLE) {  // {response = model object, ...}: one model per response
    const auto keys = sorted_keys(L, slot);
    if (keys.empty()) throw InvalidArgument("model is an empty table: give a function, an object with :evaluate, or {response = model}");
    for (const auto& k : keys) {
      lua_getfield(L, slot, k.c_str());
      const int part = lua_gettop(L);
      if (lua_type(L, part) != LUA_TTABLE && lua_type(L, part) != LUA_TUSERDATA)
        throw InvalidArgument(fmt::format("model.{} must be an object with :evaluate (a surrogate), got {}", k, luaL_typename(L, part)));
      read_model_object(L, part, k, explicit_design, s);
    }
    return;
  }
  throw InvalidArgument(fmt::format("model must be a function(X, names), an object with m:evaluate(X) or {{response = model}}, got {}",
                                    lua_typename(L, t)));
}

void read_design(lua_State* L, int spec, CalibrateSpec& s) {
  const int t = lua_getfield(L, spec, "design_bounds");
  if (t == LUA_TTABLE) read_design_table(L, lua_gettop(L), s, "design_bounds");
  else if (t != LUA_TNIL) throw InvalidArgument("design_bounds must be a table {input = {lower, upper}, ...}");
  lua_pop(L, 1);
}

void read_grid(lua_State* L, int spec, CalibrateSpec& s) {
  if (lua_getfield(L, spec, "grid") == LUA_TTABLE) {
    const int g = lua_absindex(L, -1);
    auto read_one = [&](int idx, const std::string& where) {
      lua_rawgeti(L, idx, 1);
      lua_rawgeti(L, idx, 2);
      lua_rawgeti(L, idx, 3);
      smi::stats::Grid grid{read_number(L, -3, where + "[1] (lower)"), read_number(L, -2, where + "[2] (upper)"),
                lua_isnil(L, -1) ? s.stat.grid_nodes : static_cast<Eigen::Index>(read_number(L, -1, where + "[3] (nodes)"))};
      lua_pop(L, 3);
      grid.validate();
      return grid;
    };
    if (lua_rawlen(L, g) > 0) {
      const smi::stats::Grid one = read_one(g, "grid");
      for (auto& r : s.responses) r.grid = one;
    } else {
      for (auto& r : s.responses)
        if (lua_getfield(L, g, r.name.c_str()) == LUA_TTABLE) {
          r.grid = read_one(lua_absindex(L, -1), "grid." + r.name);
          lua_pop(L, 1);
        } else {
          lua_pop(L, 1);
        }
    }
  }
  lua_pop(L, 1);
}

/// prior = {{param = "E.mean", mean =, std =}, {name =, fn = function(theta), mean =, std =}, ...}.
/// Functions stay on the stack (their slots are recorded).
void read_priors(lua_State* L, int spec, CalibrateSpec& s) {
  const int t = lua_getfield(L, spec, "prior");
  if (t == LUA_TNIL) {
    lua_pop(L, 1);
    return;
  }
  if (t != LUA_TTABLE || lua_rawlen(L, -1) == 0)
    throw InvalidArgument("prior must be a list of {param = \"<name>\", mean =, std =} or {name =, fn = function(theta), mean =, std =}");
  const int list = lua_gettop(L);
  const auto n = static_cast<int>(lua_rawlen(L, list));
  for (int i = 1; i <= n; ++i) {
    const std::string where = fmt::format("prior[{}]", i);
    luaL_checkstack(L, 4, "prior");
    if (lua_rawgeti(L, list, i) != LUA_TTABLE) throw InvalidArgument(where + " must be a table {param =, mean =, std =}");
    const int e = lua_gettop(L);
    const PriorArgs a = prior_schema().read(L, e, where.c_str());
    const auto given = [&](const char* key) {
      const bool g = lua_getfield(L, e, key) != LUA_TNIL;
      lua_pop(L, 1);
      return g;
    };
    PriorSpec p;
    const bool has_param = given("param"), has_fn = given("fn");
    if (has_param == has_fn) throw InvalidArgument(where + ": give either param = \"<parameter name>\" or fn = function(theta) (with name =)");
    if (has_param) {
      p.label = a.param;
      for (std::size_t j = 0; j < s.params.size(); ++j)
        if (s.params[j].name == p.label) p.param = static_cast<int>(j);
      if (p.param < 0) {
        std::string names;
        for (const auto& q : s.params) names += (names.empty() ? "" : ", ") + q.name;
        throw InvalidArgument(fmt::format("{}.param: no calibrated parameter named \"{}\" (the parameters are: {})", where, p.label, names));
      }
    } else {
      p.label = a.name;
      if (p.label.empty()) throw InvalidArgument(where + ": a prior on a function needs name = \"<label>\"");
    }
    if (!given("mean") || !given("std")) throw InvalidArgument(where + ": needs mean = and std = (a normal prior)");
    p.mean = a.mean;
    p.std = a.std;
    if (has_fn) {
      if (lua_getfield(L, e, "fn") != LUA_TFUNCTION) throw InvalidArgument(where + ".fn must be a function(theta) returning a number");
      lua_replace(L, e);  // the function takes the entry's slot and stays on the stack
      p.fn_slot = e;
    } else {
      lua_pop(L, 1);
    }
    s.priors.push_back(p);
  }
  // The list stays on the stack too, below the functions.
}

// objective = function(theta) ... end with parameters: the function stays on the stack.
void read_objective_form(lua_State* L, int idx, const lua::Options& o, CalibrateSpec& s) {
  if (o.has("inputs") || o.has("data") || o.has("metric"))
    throw InvalidArgument("inputs/data/metric belong to the model form; with objective = ... give parameters only");
  if (o.has("penalty"))
    throw InvalidArgument("penalty belongs to the model form; with objective = ... add it to the objective's value");
  read_parameters(L, idx, s);
  if (lua_getfield(L, idx, "objective") != LUA_TFUNCTION) throw InvalidArgument("objective must be a function(theta) returning a number");
  s.objective_slot = lua_gettop(L);
}

// metric = "pr" | "loglik" | ... | function: a custom metric stays on the stack.
void read_metric(lua_State* L, int idx, CalibrateSpec& s) {
  const int mt = lua_getfield(L, idx, "metric");
  if (mt == LUA_TFUNCTION) {
    s.stat.metric = MetricKind::custom;
    s.metric_slot = lua_gettop(L);
  } else {
    s.stat.metric = parse_metric(read_string(L, "metric", "pr"));
    lua_pop(L, 1);
  }
}

// penalty = function(theta) return number end: prior knowledge on the parameters themselves
// (a weighed mass, a handbook value), added to the metric's sum; its names are the
// parameters' ("k.mean", "k.std"). The function stays on the stack.
void read_penalty(lua_State* L, int idx, CalibrateSpec& s) {
  const int pen = lua_getfield(L, idx, "penalty");
  if (pen == LUA_TFUNCTION) s.penalty_slot = lua_gettop(L);
  else if (pen == LUA_TNIL) lua_pop(L, 1);
  else throw InvalidArgument(fmt::format("penalty must be a function(theta) returning a number, got a {}", luaL_typename(L, -1)));
}

// model with inputs and data: the statistical calibration's sampling, model, data and metric.
void read_model_form(lua_State* L, int idx, const lua::Options& o, CalibrateSpec& s, std::uint64_t seed) {
  if (o.has("parameters"))
    throw InvalidArgument("with a model, the calibrated parameters are the input ranges: give mean/std as {lower, upper, start}");
  s.statistical = true;
  s.stat.seed = seed;  // n, crn, grid_nodes, bandwidth, threads: read by the schema
  read_model(L, idx, s);
  read_inputs(L, idx, s);
  read_data(L, idx, s);
  read_grid(L, idx, s);
  read_design(L, idx, s);
  read_metric(L, idx, s);
  read_penalty(L, idx, s);
  for (const auto& r : s.responses)
    if (!r.f_exp_from_data && r.f_exp && r.data.size() == 0 && s.stat.metric == MetricKind::loglik)
      throw InvalidArgument(fmt::format("data.{} is a distribution, but metric \"loglik\" needs the data points", r.name));
}

// identifiability = true | false | {points =, rel_tol =, abs_tol =, tolerance =, step =, directions =}.
void read_identifiability(lua_State* L, int idx, CalibrateSpec& s) {
  const int it = lua_getfield(L, idx, "identifiability");
  if (it == LUA_TBOOLEAN) {
    s.identifiability = lua_toboolean(L, -1);
  } else if (it == LUA_TTABLE) {
    // the kernel's step whether identifiability is true or a table (a table's own 1e-3 differed)
    identifiability_schema().read(L, lua_gettop(L), s);
    s.directions.points = s.ident.points;
  } else if (it != LUA_TNIL) {
    throw InvalidArgument("identifiability must be true, false or {points =, rel_tol =, abs_tol =, tolerance =, step =}");
  }
  // PR is unit-free (range [0, 2] per response): a change below 1e-3 over a whole range is noise.
  if (it != LUA_TTABLE && s.statistical && s.stat.metric == MetricKind::pr) s.ident.abs_tol = s.ident.pr_abs_tol;
  lua_pop(L, 1);
}

// bootstrap = replicates | {replicates =, level =, seed =, maxeval =, warm =, multistart =}.
void read_bootstrap(lua_State* L, int idx, CalibrateSpec& s, std::uint64_t seed) {
  const int bt = lua_getfield(L, idx, "bootstrap");
  if (bt == LUA_TNUMBER || bt == LUA_TTABLE) {
    BootstrapOptions b;
    b.seed = seed;
    if (bt == LUA_TNUMBER) {
      if (!lua_isinteger(L, -1)) throw InvalidArgument("bootstrap must be an integer number of replicates");
      b.replicates = static_cast<int>(lua_tointeger(L, -1));
    } else {
      b.optimizer = s.optimizer;  // maxeval, multistart: the calibration's unless given
      bootstrap_schema().read(L, lua_gettop(L), b);
    }
    if (!s.statistical) throw InvalidArgument("bootstrap needs experimental data: use the model form (model, inputs, data)");
    if (bt == LUA_TNUMBER) b.optimizer = s.optimizer;
    s.bootstrap = b;
  } else if (bt != LUA_TNIL && !(bt == LUA_TBOOLEAN && !lua_toboolean(L, -1))) {
    throw InvalidArgument("bootstrap must be a number of replicates or {replicates =, level =, seed =}");
  }
  lua_pop(L, 1);
}

// intervals = true | {level =, delta =, observations =}: profile intervals. delta = ½ χ²₁(level)
// (with observations: its small-sample calibration, profile_intervals.hpp) reads the
// objective as a negative log-likelihood (metric "loglik", or an objective that is one); PR is
// not one, so it needs delta (an objective increase) given.
void read_intervals(lua_State* L, int idx, CalibrateSpec& s) {
  const int iv = lua_getfield(L, idx, "intervals");
  if (iv == LUA_TTABLE || (iv == LUA_TBOOLEAN && lua_toboolean(L, -1))) {
    ProfileOptions po;
    po.optimizer = s.optimizer;
    po.optimizer.multistart = 1;
    po.optimizer.hops = 0;  // each profile node is a warm-started constrained refit, not a new search
    bool has_delta = false;
    int observations = 0;  // > 0: the small-sample (F-calibrated) delta
    if (iv == LUA_TTABLE) {
      const IntervalsArgs a = intervals_schema().read(L, lua_gettop(L));
      observations = a.observations;
      has_delta = !std::isnan(a.delta);
      if (observations > 0 && has_delta)
        throw InvalidArgument(fmt::format("intervals.observations (the number of data of the likelihood) must be an integer >= 1 and goes with "
                                          "level, not delta; got {}", observations));
      if (!std::isnan(a.level) && has_delta) throw InvalidArgument("intervals: give level (a likelihood-ratio interval) or delta, not both");
      if (!std::isnan(a.level)) s.interval_level = a.level;
      if (has_delta) {
        po.delta = a.delta;
        s.interval_level = 0.0;
        if (!std::isfinite(po.delta)) throw InvalidArgument(fmt::format("intervals.delta must be a number > 0, got {}", po.delta));
      }
    }
    if (!has_delta) {
      if (s.statistical && s.stat.metric == MetricKind::pr)
        throw InvalidArgument("intervals: PR is not a log-likelihood, so a level has no delta; give intervals = {delta = <objective increase>} "
                              "or use metric = \"loglik\" or bootstrap");
      po.delta = observations > 0 ? likelihood_ratio_delta(s.interval_level, observations, static_cast<int>(s.params.size()))
                                  : likelihood_ratio_delta(s.interval_level);
    }
    s.intervals = po;
  } else if (iv != LUA_TNIL && !(iv == LUA_TBOOLEAN)) {
    throw InvalidArgument("intervals must be true or {level = 0.9} or {delta = <objective increase>}");
  }
  lua_pop(L, 1);
}

}  // namespace

void read_population(lua_State* L, int idx, CalibrateSpec& s) {
  idx = lua_absindex(L, idx);
  s.statistical = true;
  read_model(L, idx, s);
  read_inputs(L, idx, s);
  read_data(L, idx, s);
  validate_parameters(s.params);
}

// The values the calibration needs stay where they are read: functions (objective, metric,
// penalty, priors' fn, progress) are left on the Lua stack and their slots recorded, in this order.
CalibrateSpec read_calibrate_spec(lua_State* L, int idx) {
  idx = lua_absindex(L, idx);
  // Every scalar option (the optimiser's, the sampling's, gradient, steps, starts) by the schema
  // (calibrate_options.cpp) into the structs that hold their defaults; the seed defaults to the run's.
  CalibrateSpec s;
  s.optimizer.seed = lua::run_context(L).seed;
  calibrate_schema().read(L, idx, s);
  const std::uint64_t seed = s.optimizer.seed;
  const lua::Options o(L, idx, "smi.calibrate");  // presence of the form's keys (has)

  const bool has_objective = o.has("objective"), has_model = o.has("model");
  if (has_objective == has_model)
    throw InvalidArgument("give either objective = function(theta) ... end with parameters, or model with inputs and data");
  if (has_objective) read_objective_form(L, idx, o, s);
  else read_model_form(L, idx, o, s, seed);

  read_priors(L, idx, s);

  // Diagnostics.
  read_identifiability(L, idx, s);
  read_bootstrap(L, idx, s, seed);
  read_intervals(L, idx, s);
  const int pt = lua_getfield(L, idx, "progress");
  if (pt == LUA_TFUNCTION) {
    s.progress_slot = lua_gettop(L);
  } else if (pt == LUA_TBOOLEAN) {
    s.progress_line = lua_toboolean(L, -1);
    lua_pop(L, 1);
  } else if (pt == LUA_TNIL) {
    lua_pop(L, 1);
  } else {
    throw InvalidArgument("progress must be a function(row) called after each optimiser step, or false (no progress line)");
  }
  validate_parameters(s.params);
  return s;
}

}  // namespace smi::bind::improve
