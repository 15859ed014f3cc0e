// SPDX-License-Identifier: MIT
// smi.kriging.sequential{model, design, candidates, weights, batch, max, q2, rmse, trend, corr,
//                        seed, inputs}
//   -> {X = mat, Y = {<output> = vec}, kriging = {<output> = smi.kriging},
//       history = {{points, q2 = {<output> = x}, rmse = {...}}, ...}, reached, stop}
// The thin face of surrogate/sequential_design.hpp: the model (an smi.model, a Lua function or a
// table of the model interface) runs on `design`, then on one batch of candidate rows at a time
// (a parallel evaluator gets the whole batch) until every output's leave-one-out Q2 reaches `q2`
// and its LOO RMSE `rmse[<output>]` (when given), or the design holds `max` points.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "bindings/surrogate/kriging_box.hpp"
#include "bindings/surrogate/model_arg.hpp"
#include "bindings/surrogate/sequential_options.hpp"
#include "kernels/surrogate/sequential_design.hpp"
#include "luax/luax.hpp"
#include "luax/run_context.hpp"
#include "luax/policy.hpp"
#include "platform/core/errors.hpp"

namespace smi::bind::surrogate {
namespace {

namespace kr = smi::surrogate::kriging;

// The scalar options by the schema (sequential_options.cpp), the matrices and names by hand.
SequentialArgs read_sequential_args(lua_State* L, lua::Options& o, const ModelArg& model, const char* fname) {
  SequentialArgs a;
  a.so.fit.seed = lua::run_context(L).seed;
  sequential_schema().read(L, o.index(), a);
  auto matrix = [&](const char* key) {
    if (o.push(key) == LUA_TNIL) luaL_error(L, "%s: '%s' is required", fname, key);
    Eigen::MatrixXd m = lua::to_matrix(L, -1, key);
    lua_pop(L, 1);
    return m;
  };
  a.design = matrix("design");
  a.candidates = matrix("candidates");
  if (o.push("weights") == LUA_TNIL) a.weights = Eigen::VectorXd::Ones(a.candidates.rows());
  else a.weights = lua::to_vector(L, -1, "weights");
  lua_pop(L, 1);
  if (o.has("inputs")) {
    o.push("inputs");
    a.input_names = lua::to_strings(L, -1, "inputs");
    lua_pop(L, 1);
  } else {
    a.input_names = model.input_names;
  }
  return a;
}

// rmse = {<output> = target}: read once the model's first call has named its outputs. A key
// that names no output or a target that is not a positive number is an error (a misspelt
// output would otherwise leave its target silently unchecked).
void read_rmse_targets(lua_State* L, int rmse_idx, const std::vector<std::string>& outputs, kr::SequentialOptions& so) {
  so.rmse_target = Eigen::VectorXd::Constant(static_cast<Eigen::Index>(outputs.size()), std::numeric_limits<double>::quiet_NaN());
  std::string names;
  for (const std::string& n : outputs) names += (names.empty() ? "" : ", ") + n;
  // Read first, checked in key order: of several mistakes the one named is the same every run
  // (the table's traversal order changes from process to process).
  struct Entry {
    std::string key;
    bool named;
    double v;
  };
  std::vector<Entry> entries;
  lua_pushnil(L);
  while (lua_next(L, rmse_idx)) {
    const bool named = lua_type(L, -2) == LUA_TSTRING;
    entries.push_back({named ? lua_tostring(L, -2) : luaL_typename(L, -2), named,
                       lua_type(L, -1) == LUA_TNUMBER ? lua_tonumber(L, -1) : std::numeric_limits<double>::quiet_NaN()});
    lua_pop(L, 1);
  }
  std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.key < b.key; });
  for (const Entry& e : entries) {
    const auto it = e.named ? std::find(outputs.begin(), outputs.end(), e.key) : outputs.end();
    if (it == outputs.end())
      throw InvalidArgument("rmse: '" + e.key + "' is not an output of the model (its outputs: " + names + ")");
    if (!(e.v > 0) || !std::isfinite(e.v))
      throw InvalidArgument("rmse." + e.key + " must be a positive finite number (the LOO RMSE target in the output's units)");
    so.rmse_target(static_cast<Eigen::Index>(it - outputs.begin())) = e.v;
  }
}

// {<output> = f(j)} for each output name.
template <class F>
void push_per_output(lua_State* L, const std::vector<std::string>& outs, F&& push_value) {
  lua_createtable(L, 0, static_cast<int>(outs.size()));
  for (std::size_t j = 0; j < outs.size(); ++j) {
    push_value(j);
    lua_setfield(L, -2, outs[j].c_str());
  }
}

// The result table: X, Y, kriging, history, reached, stop.
void push_sequential_result(lua_State* L, const kr::SequentialResult& r, const std::vector<std::string>& outs,
                            const std::vector<std::string>& input_names) {
  lua_createtable(L, 0, 6);
  lua::push_mat(L, r.X);
  lua_setfield(L, -2, "X");
  push_per_output(L, outs, [&](std::size_t j) { lua::push_vec(L, r.Y.col(static_cast<Eigen::Index>(j))); });
  lua_setfield(L, -2, "Y");
  push_per_output(L, outs, [&](std::size_t j) {
    KrigingBox box;
    box.model = r.models[j];
    box.inputs = input_names;
    box.output = outs[j];
    lua::push_box(L, kKrigingType, std::move(box));
  });
  lua_setfield(L, -2, "kriging");
  lua_createtable(L, static_cast<int>(r.history.size()), 0);
  for (std::size_t i = 0; i < r.history.size(); ++i) {
    const auto& h = r.history[i];
    lua_createtable(L, 0, 3);
    lua::set_integer(L, "points", static_cast<lua_Integer>(h.points));
    push_per_output(L, outs, [&](std::size_t j) { lua_pushnumber(L, h.q2(static_cast<Eigen::Index>(j))); });
    lua_setfield(L, -2, "q2");
    push_per_output(L, outs, [&](std::size_t j) { lua_pushnumber(L, h.rmse(static_cast<Eigen::Index>(j))); });
    lua_setfield(L, -2, "rmse");
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  lua_setfield(L, -2, "history");
  lua_pushboolean(L, r.reached);
  lua_setfield(L, -2, "reached");
  lua::set_string(L, "stop", r.stop);
}

int sequential_call(lua_State* L) {
  constexpr const char* fname = "smi.kriging.sequential";
  luaL_checktype(L, 1, LUA_TTABLE);
  lua::Options o(L, 1, fname);
  sequential_schema().check_keys(L, 1);
  o.push("model");
  const int model_idx = lua_gettop(L);
  if (lua_isnil(L, model_idx)) return luaL_error(L, "%s: 'model' is required (an smi.model, a function or a model object)", fname);
  ModelArg model = to_model(L, model_idx, fname);
  SequentialArgs a = read_sequential_args(L, o, model, fname);
  const int rmse_t = o.push("rmse");
  const int rmse_idx = lua_gettop(L);
  if (rmse_t != LUA_TNIL && rmse_t != LUA_TTABLE) return luaL_error(L, "%s: 'rmse' must be a table {<output> = target}", fname);
  return lua::protect(L, fname, [&] {
    if (!a.input_names.empty() && static_cast<Eigen::Index>(a.input_names.size()) != a.design.cols())
      throw DimensionMismatch(std::to_string(a.input_names.size()) + " input names for " + std::to_string(a.design.cols()) +
                              " columns of the design");
    // The model's first call (the initial design) fills its output names, which the RMSE
    // targets are read by; the kernel then gets those outputs back on its own first call.
    const Eigen::MatrixXd Y0 = model.fn(a.design);
    if (rmse_t != LUA_TNIL) read_rmse_targets(L, rmse_idx, *model.outputs, a.so);
    bool served = false;
    const kr::SequentialResult r = kr::sequential_design(a.design, a.candidates, a.weights, [&](const Eigen::MatrixXd& X) {
      if (!served) {
        served = true;
        return Y0;
      }
      return model.fn(X);
    }, a.so);
    push_sequential_result(L, r, *model.outputs, a.input_names);
    return 1;
  });
}

}  // namespace

void open_sequential(lua_State* L) {  // after open_kriging: a field of smi.kriging
  lua_getfield(L, -1, "kriging");
  lua_pushcfunction(L, sequential_call);
  lua_setfield(L, -2, "sequential");
  lua_pop(L, 1);
}

}  // namespace smi::bind::surrogate
