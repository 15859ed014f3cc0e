// SPDX-License-Identifier: MIT
// Adapters from Lua model values to propagate::MatrixModel.
#include "bindings/surrogate/model_arg.hpp"

#include <algorithm>
#include <cstdio>
#include <map>
#include <memory>

#include "bindings/stats/dist_box.hpp"
#include "bindings/surrogate/kriging_box.hpp"
#include "luax/luax.hpp"
#include "platform/core/errors.hpp"

namespace smi::bind::surrogate {
namespace {

/// Lua result at the top of the stack -> columns, names checked against/filled into `names`.
Eigen::MatrixXd read_outputs(lua_State* L, Eigen::Index n, std::vector<std::string>& names, const char* fname) {
  const int top = lua_gettop(L);
  std::vector<std::pair<std::string, Eigen::VectorXd>> cols;
  if (lua::test_vec(L, top)) {
    cols.emplace_back("y", *lua::test_vec(L, top));
  } else if (lua::test_mat(L, top)) {
    const Eigen::MatrixXd& M = *lua::test_mat(L, top);
    for (Eigen::Index j = 0; j < M.cols(); ++j) {
      char name[32];  // (not "y" + to_string: GCC 12 warns falsely with -Wrestrict)
      std::snprintf(name, sizeof name, "y%d", static_cast<int>(j + 1));
      cols.emplace_back(name, M.col(j));
    }
  } else if (lua_istable(L, top) && lua_rawlen(L, top) > 0) {
    cols.emplace_back("y", lua::to_vector(L, top, "model result"));
  } else if (lua_istable(L, top)) {
    // read in name order: of several outputs that are not vectors the one named is the same every
    // run (the table's traversal order changes from process to process)
    std::vector<std::string> keys;
    lua_pushnil(L);
    while (lua_next(L, top)) {
      if (lua_type(L, -2) == LUA_TSTRING) keys.emplace_back(lua_tostring(L, -2));
      lua_pop(L, 1);
    }
    std::sort(keys.begin(), keys.end());
    for (const std::string& key : keys) {
      lua_pushlstring(L, key.data(), key.size());
      lua_rawget(L, top);
      cols.emplace_back(key, lua::to_vector(L, lua_gettop(L), key.c_str()));
      lua_pop(L, 1);
    }
  } else {
    throw InvalidArgument(std::string("the model returned a ") + luaL_typename(L, top) +
                          "; expected a vec, a mat or a table {name = vec}");
  }
  lua_settop(L, top - 1);
  if (cols.empty()) throw InvalidArgument("the model returned no outputs");
  if (names.empty()) {
    // Keep the order the model announced (m.outputs) when names were preset.
    for (auto& c : cols) names.push_back(c.first);
  }
  Eigen::MatrixXd Y(n, static_cast<Eigen::Index>(names.size()));
  for (std::size_t j = 0; j < names.size(); ++j) {
    auto it = std::find_if(cols.begin(), cols.end(), [&](auto& c) { return c.first == names[j]; });
    if (it == cols.end()) throw InvalidArgument("the model's result lacks output '" + names[j] + "'");
    if (it->second.size() != n)
      throw DimensionMismatch("output '" + names[j] + "' has " + std::to_string(it->second.size()) + " values for " +
                              std::to_string(n) + " points");
    Y.col(static_cast<Eigen::Index>(j)) = it->second;
  }
  (void)fname;
  return Y;
}

std::vector<std::string> string_field(lua_State* L, int idx, const char* key) {
  std::vector<std::string> out;
  if (lua_getfield(L, idx, key) == LUA_TTABLE) {
    const lua_Integer len = static_cast<lua_Integer>(lua_rawlen(L, -1));
    for (lua_Integer i = 1; i <= len; ++i) {
      if (lua_rawgeti(L, -1, i) == LUA_TSTRING) out.emplace_back(lua_tostring(L, -1));
      lua_pop(L, 1);
    }
  }
  lua_pop(L, 1);
  return out;
}

/// {name = kriging, ...}: one model predicting each named output with its Kriging.
ModelArg kriging_table(lua_State* L, int idx, const char* fname, ModelArg m) {
  // The pointers below are used until the bound function returns, while Lua code runs in
  // between (option reads through __index, the other inputs, a Lua model): the script can
  // empty its table and collect a Kriging then. So the boxes are copied into a table of our
  // own that takes the table's stack slot: reachable, hence alive (a __close meanwhile only
  // marks them closed, luax.hpp), until the slot goes.
  std::vector<std::pair<std::string, KrigingBox*>> parts;
  lua_newtable(L);
  const int held = lua_gettop(L);
  std::string bad;  // of several bad entries, the first by name: the same every run
  bool any_bad = false;
  lua_pushnil(L);
  while (lua_next(L, idx)) {
    KrigingBox* k = test_kriging(L, -1);
    if (lua_type(L, -2) != LUA_TSTRING || !k) {
      const std::string key = lua_type(L, -2) == LUA_TSTRING ? lua_tostring(L, -2) : "not a string";
      if (!any_bad || key < bad) bad = key;
      any_bad = true;
      lua_pop(L, 1);
      continue;
    }
    parts.emplace_back(lua_tostring(L, -2), k);
    lua_pushvalue(L, -2);
    lua_pushvalue(L, -2);
    lua_rawset(L, held);
    lua_pop(L, 1);
  }
  if (any_bad)
    luaL_error(L, "%s: model table must map output names to smi.kriging models (key %s)", fname, bad.c_str());
  lua_replace(L, idx);
  if (parts.empty()) luaL_error(L, "%s: model table is empty", fname);
  std::sort(parts.begin(), parts.end(), [](auto& a, auto& b) { return a.first < b.first; });
  for (auto& p : parts) m.outputs->push_back(p.first);
  m.input_names = parts[0].second->inputs;
  m.fn = [parts](const Eigen::MatrixXd& X) -> Eigen::MatrixXd {
    Eigen::MatrixXd Y(X.rows(), static_cast<Eigen::Index>(parts.size()));
    for (std::size_t j = 0; j < parts.size(); ++j)
      Y.col(static_cast<Eigen::Index>(j)) = smi::surrogate::kriging::predict_mean(parts[j].second->model, X);
    return Y;
  };
  return m;
}

}  // namespace

ModelArg to_model(lua_State* L, int idx, const char* fname) {
  idx = lua_absindex(L, idx);
  ModelArg m;
  m.outputs = std::make_shared<std::vector<std::string>>();
  if (KrigingBox* k = test_kriging(L, idx)) {
    m.outputs->push_back(k->output);
    m.input_names = k->inputs;
    m.fn = [k](const Eigen::MatrixXd& X) -> Eigen::MatrixXd { return smi::surrogate::kriging::predict_mean(k->model, X); };
    return m;
  }
  if (lua_isfunction(L, idx)) {
    auto names = m.outputs;
    m.fn = [L, idx, names, fname](const Eigen::MatrixXd& X) -> Eigen::MatrixXd {
      lua_pushvalue(L, idx);
      lua::push_mat(L, X);
      lua::call(L, 1, 1);
      return read_outputs(L, X.rows(), *names, fname);
    };
    return m;
  }
  if (lua_type(L, idx) == LUA_TUSERDATA || lua_type(L, idx) == LUA_TTABLE) {
    // An object with the model interface? (userdata without __index cannot be indexed)
    bool indexable = lua_type(L, idx) == LUA_TTABLE;
    if (!indexable && luaL_getmetafield(L, idx, "__index") != LUA_TNIL) {
      lua_pop(L, 1);
      indexable = true;
    }
    bool has_eval = false;
    if (indexable) {
      lua_getfield(L, idx, "evaluate");
      has_eval = lua_isfunction(L, -1);
      lua_pop(L, 1);
    }
    if (has_eval) {
      m.input_names = string_field(L, idx, "inputs");
      *m.outputs = string_field(L, idx, "outputs");
      auto names = m.outputs;
      m.fn = [L, idx, names, fname](const Eigen::MatrixXd& X) -> Eigen::MatrixXd {
        lua_getfield(L, idx, "evaluate");
        lua_pushvalue(L, idx);
        lua::push_mat(L, X);
        lua::call(L, 2, 1);
        return read_outputs(L, X.rows(), *names, fname);
      };
      return m;
    }
    if (lua_type(L, idx) == LUA_TTABLE) return kriging_table(L, idx, fname, std::move(m));  // {name = kriging, ...}
  }
  luaL_error(L, "%s: model must be an smi.kriging, a table of them by output name, a function(X) or an object "
             "with :evaluate(X); got %s", fname, luaL_typename(L, idx));
  return m;
}

std::vector<smi::surrogate::propagate::Input> to_inputs(lua_State* L, int idx, const std::vector<std::string>& order,
                                        const char* fname) {
  if (!lua_istable(L, idx)) luaL_error(L, "%s: inputs must be a table of named distributions or constants", fname);
  std::vector<smi::surrogate::propagate::Input> out;
  auto read_value = [&](int vidx, const std::string& name) {
    smi::surrogate::propagate::Input in;
    in.name = name;
    if (lua_type(L, vidx) == LUA_TNUMBER)
      in.value = lua_tonumber(L, vidx);
    else if (smi::stats::DistributionPtr d = test_distribution(L, vidx))
      in.dist = d;
    else
      luaL_error(L, "%s: input '%s' must be an smi.dist or a number, got %s", fname, name.c_str(), luaL_typename(L, vidx));
    return in;
  };
  const lua_Integer len = static_cast<lua_Integer>(lua_rawlen(L, idx));
  if (len > 0) {  // {{"E", dist}, {"t", 2.0}}
    for (lua_Integer i = 1; i <= len; ++i) {
      lua_rawgeti(L, idx, i);
      if (!lua_istable(L, -1)) luaL_error(L, "%s: inputs[%d] must be {name, dist|number}", fname, static_cast<int>(i));
      lua_rawgeti(L, -1, 1);
      if (lua_type(L, -1) != LUA_TSTRING) luaL_error(L, "%s: inputs[%d][1] must be the input's name", fname, static_cast<int>(i));
      const std::string name = lua_tostring(L, -1);
      lua_rawgeti(L, -2, 2);
      out.push_back(read_value(lua_gettop(L), name));
      lua_pop(L, 3);
    }
    return out;
  }
  std::map<std::string, int> seen;
  std::vector<std::string> names;
  lua_pushnil(L);
  while (lua_next(L, idx)) {
    if (lua_type(L, -2) != LUA_TSTRING) luaL_error(L, "%s: inputs keys must be names", fname);
    names.emplace_back(lua_tostring(L, -2));
    lua_pop(L, 1);
  }
  std::sort(names.begin(), names.end());
  std::vector<std::string> cols = order.empty() ? names : order;
  for (const auto& n : cols)
    if (!std::binary_search(names.begin(), names.end(), n))
      luaL_error(L, "%s: inputs has no entry '%s' (the model expects it)", fname, n.c_str());
  for (const auto& n : names)
    if (std::find(cols.begin(), cols.end(), n) == cols.end())
      luaL_error(L, "%s: input '%s' is not among the model's inputs", fname, n.c_str());
  for (const auto& n : cols) {
    lua_getfield(L, idx, n.c_str());
    out.push_back(read_value(lua_gettop(L), n));
    lua_pop(L, 1);
  }
  return out;
}

ModelAndInputs read_model_and_inputs(lua_State* L, const lua::Options& o, const char* fname) {
  if (o.push("model") == LUA_TNIL) luaL_error(L, "%s: field 'model' is required", fname);
  const int model_idx = lua_gettop(L);  // stays on the stack while the model runs
  ModelArg model = to_model(L, model_idx, fname);
  std::vector<std::string> order = model.input_names;
  if (o.has("order")) {
    o.push("order");
    order = lua::to_strings(L, -1, "order");
    lua_pop(L, 1);
  }
  if (o.push("inputs") == LUA_TNIL) luaL_error(L, "%s: field 'inputs' is required", fname);
  std::vector<smi::surrogate::propagate::Input> inputs = to_inputs(L, lua_gettop(L), order, fname);
  lua_pop(L, 1);
  return {std::move(model), model_idx, std::move(inputs)};
}

}  // namespace smi::bind::surrogate
