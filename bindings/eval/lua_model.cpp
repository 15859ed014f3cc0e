// SPDX-License-Identifier: MIT
// smi.model.lua{inputs = ..., outputs = ..., fn = function(X) ... end}: a model computed by a
// Lua function that receives the whole design matrix (one call per evaluation, never one per
// point) and returns {output = vec, ...}. No store: such models are cheap by assumption.
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <optional>

#include "bindings/eval/lua_model_options.hpp"
#include "bindings/eval/model.hpp"
#include "luax/luax.hpp"

namespace smi::bind::eval {

namespace se = smi::eval;

int model_lua(lua_State* L) {
  luaL_checktype(L, 1, LUA_TTABLE);
  const LuaModelArgs args = lua_model_schema().read(L, 1);
  Model m;
  m.kind = Model::LuaFn;
  m.name = args.name;
  lua_getfield(L, 1, "inputs");
  m.inputs = lua::to_strings(L, -1, "inputs");
  lua_getfield(L, 1, "outputs");
  m.outputs = lua::to_strings(L, -1, "outputs");
  lua_pop(L, 2);
  if (m.inputs.empty() || m.outputs.empty()) return luaL_error(L, "smi.model.lua: inputs and outputs must name at least one variable");
  if (lua_getfield(L, 1, "fn") != LUA_TFUNCTION)
    return luaL_error(L, "smi.model.lua: option 'fn' must be a function(X) returning {output = vec, ...}, got %s",
                      luaL_typename(L, -1));
  push_model(L, std::move(m), -1);
  return 1;
}

namespace {

/// Calls the function of the smi.model.lua at idx (absolute) with X and returns its outputs,
/// rows × m.outputs. An error in the function is the study's error: it propagates.
Eigen::MatrixXd call_fn(lua_State* L, int idx, const Model& m, const Eigen::MatrixXd& X) {
  const Eigen::Index n = X.rows(), k = static_cast<Eigen::Index>(m.outputs.size());
  lua_getiuservalue(L, idx, 1);
  lua::push_mat(L, X);
  lua_call(L, 1, 1);
  if (!lua_istable(L, -1))
    luaL_error(L, "model '%s': fn must return a table {output = vec, ...}, got %s", m.name.c_str(), luaL_typename(L, -1));
  const int res = lua_gettop(L);
  Eigen::MatrixXd Y(n, k);
  for (Eigen::Index j = 0; j < k; ++j) {
    const std::string& name = m.outputs[static_cast<std::size_t>(j)];
    const int t = lua_getfield(L, res, name.c_str());
    if (t == LUA_TNIL) luaL_error(L, "model '%s': fn returned no output '%s'", m.name.c_str(), name.c_str());
    Eigen::VectorXd v = t == LUA_TNUMBER && n == 1 ? Eigen::VectorXd::Constant(1, lua_tonumber(L, -1))
                                                   : lua::to_vector(L, -1, name.c_str());
    if (v.size() != n)
      luaL_error(L, "model '%s': fn returned %d values for output '%s', X has %d rows", m.name.c_str(),
                 static_cast<int>(v.size()), name.c_str(), static_cast<int>(n));
    Y.col(j) = v;
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  return Y;
}

/// The first output of row i that is not finite, or -1.
Eigen::Index first_non_finite(const Eigen::MatrixXd& Y, Eigen::Index i) {
  for (Eigen::Index j = 0; j < Y.cols(); ++j)
    if (!std::isfinite(Y(i, j))) return j;
  return -1;
}

}  // namespace

int evaluate_lua(lua_State* L, Model& m) {
  const Eigen::MatrixXd X = design_of(L, 2, m);
  const Eigen::Index n = X.rows();
  se::EvalResult r;
  r.Y = call_fn(L, 1, m, X);
  r.status.assign(static_cast<std::size_t>(n), se::Status::Ok);
  r.reason.assign(static_cast<std::size_t>(n), "");
  r.reused.assign(static_cast<std::size_t>(n), false);
  r.duration = Eigen::VectorXd::Zero(n);
  // A non-finite output is a failed point, as it would be for a solver.
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Index j = first_non_finite(r.Y, i);
    if (j < 0) continue;
    r.status[static_cast<std::size_t>(i)] = se::Status::Failed;
    r.reason[static_cast<std::size_t>(i)] = fmt::format("output '{}' is {}", m.outputs[static_cast<std::size_t>(j)], r.Y(i, j));
    ++r.failed;
    r.Y.row(i).setConstant(std::numeric_limits<double>::quiet_NaN());
  }
  push_results(L, m, r);
  return 2;
}

std::optional<Eigen::MatrixXd> lua_model_outputs(lua_State* L, int idx, const Eigen::MatrixXd& X, std::vector<std::string>& outputs) {
  const Model* m = test_model(L, idx);
  if (m == nullptr || m->kind != Model::LuaFn) return std::nullopt;
  check_columns(L, X, *m);
  Eigen::MatrixXd Y = call_fn(L, lua_absindex(L, idx), *m, X);
  for (Eigen::Index i = 0; i < Y.rows(); ++i)
    if (first_non_finite(Y, i) >= 0) Y.row(i).setConstant(std::numeric_limits<double>::quiet_NaN());
  outputs = m->outputs;
  return Y;
}

}  // namespace smi::bind::eval
