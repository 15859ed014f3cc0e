// SPDX-License-Identifier: MIT
// smi.model.lua{inputs = ..., outputs = ..., fn = function(X) ... end}: a model computed by a
// Lua function that receives the whole design matrix (one call per evaluation, never one per
// point) and returns {output = vec, ...}. No store: such models are cheap by assumption.
#include <cmath>
#include <fmt/format.h>
#include <limits>

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

int evaluate_lua(lua_State* L, Model& m) {
  const Eigen::MatrixXd X = design_of(L, 2, m);
  const Eigen::Index n = X.rows(), k = static_cast<Eigen::Index>(m.outputs.size());
  lua_getiuservalue(L, 1, 1);
  lua::push_mat(L, X);
  lua_call(L, 1, 1);  // an error in the model function is the study's error: let it propagate
  if (!lua_istable(L, -1))
    return luaL_error(L, "model '%s': fn must return a table {output = vec, ...}, got %s", m.name.c_str(), luaL_typename(L, -1));
  const int res = lua_gettop(L);
  se::EvalResult r;
  r.Y.resize(n, k);
  for (Eigen::Index j = 0; j < k; ++j) {
    const std::string& name = m.outputs[static_cast<std::size_t>(j)];
    const int t = lua_getfield(L, res, name.c_str());
    if (t == LUA_TNIL) return luaL_error(L, "model '%s': fn returned no output '%s'", m.name.c_str(), name.c_str());
    Eigen::VectorXd v = t == LUA_TNUMBER && n == 1 ? Eigen::VectorXd::Constant(1, lua_tonumber(L, -1))
                                                   : lua::to_vector(L, -1, name.c_str());
    if (v.size() != n)
      return luaL_error(L, "model '%s': fn returned %d values for output '%s', X has %d rows", m.name.c_str(),
                        static_cast<int>(v.size()), name.c_str(), static_cast<int>(n));
    r.Y.col(j) = v;
    lua_pop(L, 1);
  }
  r.status.assign(static_cast<std::size_t>(n), se::Status::Ok);
  r.reason.assign(static_cast<std::size_t>(n), "");
  r.reused.assign(static_cast<std::size_t>(n), false);
  r.duration = Eigen::VectorXd::Zero(n);
  // A non-finite output is a failed point, as it would be for a solver.
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < k; ++j)
      if (!std::isfinite(r.Y(i, j)) && r.status[static_cast<std::size_t>(i)] == se::Status::Ok) {
        r.status[static_cast<std::size_t>(i)] = se::Status::Failed;
        r.reason[static_cast<std::size_t>(i)] = fmt::format("output '{}' is {}", m.outputs[static_cast<std::size_t>(j)], r.Y(i, j));
        ++r.failed;
      }
  for (Eigen::Index i = 0; i < n; ++i)
    if (r.status[static_cast<std::size_t>(i)] != se::Status::Ok) r.Y.row(i).setConstant(std::numeric_limits<double>::quiet_NaN());
  push_results(L, m, r);
  return 2;
}

}  // namespace smi::bind::eval
