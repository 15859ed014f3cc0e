// SPDX-License-Identifier: MIT
// The smi.model type: m:evaluate(X), m:plan(X), m.inputs, m.outputs, m.name, m.kind, and the
// conversions shared by every kind of model (design matrix in, Y and info out).
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <set>
#include <string>
#include <vector>

#include "bindings/eval/model.hpp"
#include "luax/luax.hpp"

namespace smi::bind::eval {
namespace {

namespace se = smi::eval;

Model& self(lua_State* L) { return lua::check_box<Model>(L, 1, kModelType); }

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

void push_strings(lua_State* L, const std::vector<std::string>& v) {
  lua_createtable(L, static_cast<int>(v.size()), 0);
  for (std::size_t i = 0; i < v.size(); ++i) {
    lua_pushstring(L, v[i].c_str());
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
}

const char* kind_name(Model::Kind k) {
  switch (k) {
    case Model::Command: return "command";
    case Model::Batch: return "batch";
    default: return "lua";
  }
}

int model_evaluate(lua_State* L) {
  Model& m = self(L);
  lua_settop(L, 2);
  if (m.kind == Model::LuaFn) return evaluate_lua(L, m);
  return evaluate_solver(L, m);
}

/// m:plan(X) -> {points, unique, reused, runs, eta, mean_seconds} without running anything.
int model_plan(lua_State* L) {
  Model& m = self(L);
  const Eigen::MatrixXd X = design_of(L, 2, m);
  if (!m.ev) {
    lua_createtable(L, 0, 5);
    lua::set_integer(L, "points", X.rows());
    lua::set_integer(L, "runs", 0);
    lua::set_integer(L, "reused", 0);
    lua::set_number(L, "eta", 0);
    return 1;
  }
  return lua::protect(L, "smi.model:plan", [&] {
    const se::Plan p = m.ev->plan(X);
    lua_createtable(L, 0, 5);
    lua::set_integer(L, "points", static_cast<lua_Integer>(p.points));
    lua::set_integer(L, "unique", static_cast<lua_Integer>(p.unique));
    lua::set_integer(L, "reused", static_cast<lua_Integer>(p.reused));
    lua::set_integer(L, "runs", static_cast<lua_Integer>(p.runs));
    if (p.eta_seconds >= 0) lua::set_number(L, "eta", p.eta_seconds);
    // the stored mean run time of this program and version (a study's cost plan)
    if (p.timing.count > 0) lua::set_number(L, "mean_seconds", p.timing.mean);
    return 1;
  });
}

int model_getter(lua_State* L) {
  const Model& m = self(L);
  const char* key = lua_tostring(L, 2);
  if (!key) return 0;
  const std::string k = key;
  if (k == "inputs") push_strings(L, m.inputs);
  else if (k == "outputs") push_strings(L, m.outputs);
  else if (k == "name") lua_pushstring(L, m.name.c_str());
  else if (k == "kind") lua_pushstring(L, kind_name(m.kind));
  else if (k == "version" && m.ev) lua_pushstring(L, m.ev->version().c_str());
  else return 0;
  return 1;
}

int model_tostring(lua_State* L) {
  const Model& m = self(L);
  lua_pushfstring(L, "smi.model(%s '%s': %d inputs -> %d outputs)", kind_name(m.kind), m.name.c_str(),
                  static_cast<int>(m.inputs.size()), static_cast<int>(m.outputs.size()));
  return 1;
}

const luaL_Reg kMethods[] = {{"evaluate", model_evaluate}, {"plan", model_plan}, {nullptr, nullptr}};
const luaL_Reg kMeta[] = {{"__tostring", model_tostring}, {nullptr, nullptr}};

}  // namespace

Model* test_model(lua_State* L, int idx) { return lua::test_box<Model>(L, idx, kModelType); }

void register_model_type(lua_State* L) { lua::register_type<Model>(L, kModelType, kMethods, kMeta, model_getter); }

void push_model(lua_State* L, Model m, int fn_idx) {
  fn_idx = lua_absindex(L, fn_idx);
  Model*& slot = lua::new_box<Model>(L, kModelType, 1);
  slot = new Model(std::move(m));
  lua_pushvalue(L, fn_idx);
  lua_setiuservalue(L, -2, 1);
}

Eigen::MatrixXd design_of(lua_State* L, int idx, const Model& m) {
  idx = lua_absindex(L, idx);
  const auto d = static_cast<Eigen::Index>(m.inputs.size());
  if (lua_type(L, idx) == LUA_TTABLE && !lua::test_vec(L, idx) && !lua::test_mat(L, idx) &&
      lua_getfield(L, idx, m.inputs[0].c_str()) != LUA_TNIL) {
    lua_pop(L, 1);
    // Named columns: catch typos in the names first, in name order (of several, the one named
    // is then the same every run: the table's traversal order changes from process to process).
    std::vector<std::string> keys;
    lua_pushnil(L);
    while (lua_next(L, idx)) {
      lua_pop(L, 1);
      if (lua_type(L, -1) == LUA_TSTRING) keys.emplace_back(lua_tostring(L, -1));
    }
    std::sort(keys.begin(), keys.end());
    for (const std::string& k : keys) {
      bool known = false;
      for (const auto& in : m.inputs) known = known || in == k;
      if (!known)
        luaL_error(L, "X has a column '%s' that is not an input of model '%s' (inputs: %s)", k.c_str(), m.name.c_str(),
                   joined(m.inputs).c_str());
    }
    Eigen::MatrixXd X;
    for (Eigen::Index j = 0; j < d; ++j) {
      const std::string& name = m.inputs[static_cast<std::size_t>(j)];
      const int t = lua_getfield(L, idx, name.c_str());
      if (t == LUA_TNIL)
        luaL_error(L, "X has no column '%s' (model '%s' inputs: %s)", name.c_str(), m.name.c_str(), joined(m.inputs).c_str());
      Eigen::VectorXd col;
      if (t == LUA_TNUMBER) {
        col = Eigen::VectorXd::Constant(1, lua_tonumber(L, -1));
      } else {
        const std::string what = "X." + name;
        col = lua::to_vector(L, -1, what.c_str());
      }
      lua_pop(L, 1);
      if (j == 0) X.resize(col.size(), d);
      if (col.size() != X.rows())
        luaL_error(L, "X.%s has %d values but X.%s has %d", name.c_str(), static_cast<int>(col.size()),
                   m.inputs[0].c_str(), static_cast<int>(X.rows()));
      X.col(j) = col;
    }
    return X;
  }
  lua_pop(L, lua_type(L, idx) == LUA_TTABLE && !lua::test_vec(L, idx) && !lua::test_mat(L, idx) ? 1 : 0);
  Eigen::MatrixXd X = lua::to_matrix(L, idx, "X");
  if (X.size() == 0) X.resize(0, d);
  check_columns(L, X, m);
  return X;
}

void check_columns(lua_State* L, const Eigen::MatrixXd& X, const Model& m) {
  const auto d = static_cast<Eigen::Index>(m.inputs.size());
  if (X.cols() != d)
    luaL_error(L, "X has %d columns but model '%s' has %d inputs (%s); rows are points, columns inputs in that order",
               static_cast<int>(X.cols()), m.name.c_str(), static_cast<int>(d), joined(m.inputs).c_str());
}

void push_results(lua_State* L, const Model& m, const se::EvalResult& r) {
  lua::push_named_vectors(L, m.outputs, r.Y);
  const auto n = static_cast<Eigen::Index>(r.status.size());
  lua_createtable(L, 0, 10);
  lua_createtable(L, static_cast<int>(n), 0);  // status
  lua_createtable(L, static_cast<int>(n), 0);  // reason
  lua_createtable(L, 0, 0);                    // failures
  Eigen::VectorXd ok(n), reused(n);
  int nfail = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    const se::Status s = r.status[ui];
    lua_pushstring(L, s == se::Status::Ok ? "ok" : s == se::Status::Failed ? "failed" : "not run");
    lua_rawseti(L, -4, i + 1);
    lua_pushstring(L, r.reason[ui].c_str());
    lua_rawseti(L, -3, i + 1);
    ok[i] = s == se::Status::Ok ? 1 : 0;
    reused[i] = r.reused[ui] ? 1 : 0;
    if (s == se::Status::Failed) {
      lua_createtable(L, 0, 2);
      lua::set_integer(L, "row", i + 1);
      lua::set_string(L, "reason", r.reason[ui]);
      lua_rawseti(L, -2, ++nfail);
    }
  }
  lua_setfield(L, -4, "failures");
  lua_setfield(L, -3, "reason");
  lua_setfield(L, -2, "status");
  lua::set_vec(L, "ok", std::move(ok));
  lua::set_vec(L, "reused", std::move(reused));
  lua::set_vec(L, "duration", r.duration);
  lua::set_integer(L, "failed", static_cast<lua_Integer>(r.failed));
  lua::set_integer(L, "launched", static_cast<lua_Integer>(r.launched));
  lua::set_boolean(L, "stopped", r.stopped);
}

}  // namespace smi::bind::eval
