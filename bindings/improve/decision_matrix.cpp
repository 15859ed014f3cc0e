// SPDX-License-Identifier: MIT
// smi.refine.decision_matrix{candidates = {...}, criteria = {{name =, weight =, magnitude = ...}}}
// The weighted decision matrix of spec §6 with criteria written by the analyst: a magnitude is a
// Lua function(candidate, j) or a list of values (or a table keyed by candidate name).
#include "bindings/improve/decision_matrix_binding.hpp"
#include "bindings/improve/decision_matrix_options.hpp"

#include <fmt/format.h>

#include <numeric>

#include "bindings/improve/lua_values.hpp"
#include "kernels/improve/decision_matrix.hpp"
#include "luax/luax.hpp"
#include "platform/core/errors.hpp"

namespace smi::bind::improve {

using namespace smi::improve;

namespace {

constexpr const char* kDecisionMeta = "smi.decision";

/// Candidate labels: a string candidate is its own name; a table may carry `name`.
std::vector<std::string> candidate_names(lua_State* L, int cands, int J) {
  std::vector<std::string> names;
  for (int j = 1; j <= J; ++j) {
    lua_rawgeti(L, cands, j);
    std::string n = fmt::format("{}", j);
    if (lua_type(L, -1) == LUA_TSTRING) {
      n = lua_tostring(L, -1);
    } else if (lua_istable(L, -1)) {
      if (raw_field(L, -1, "name") == LUA_TSTRING) n = lua_tostring(L, -1);
      lua_pop(L, 1);
    }
    lua_pop(L, 1);
    names.push_back(n);
  }
  return names;
}

/// Magnitudes of criterion i (its table at `crit`) for all candidates.
void read_magnitudes(lua_State* L, int crit, int cands, const std::vector<std::string>& cnames, const std::string& cname,
                     Eigen::MatrixXd& M, Eigen::Index i) {
  const int J = static_cast<int>(cnames.size());
  const int t = lua_getfield(L, crit, "magnitude");
  const int mag = lua_gettop(L);
  for (int j = 1; j <= J; ++j) {
    const std::string where = fmt::format("criterion '{}', candidate '{}'", cname, cnames[static_cast<std::size_t>(j - 1)]);
    if (t == LUA_TFUNCTION) {
      lua_pushvalue(L, mag);
      lua_rawgeti(L, cands, j);
      lua_pushinteger(L, j);
      lua::call(L, 2, 1);
    } else if (t == LUA_TTABLE) {
      if (lua_rawlen(L, mag) > 0) {
        if (static_cast<int>(lua_rawlen(L, mag)) != J)
          throw DimensionMismatch(fmt::format("criterion '{}': {} magnitudes for {} candidates", cname, lua_rawlen(L, mag), J));
        lua_rawgeti(L, mag, j);
      } else {
        raw_field(L, mag, cnames[static_cast<std::size_t>(j - 1)].c_str());
      }
    } else if (t == LUA_TUSERDATA && lua::test_vec(L, mag)) {
      const Eigen::VectorXd& v = *lua::test_vec(L, mag);
      if (v.size() != J) throw DimensionMismatch(fmt::format("criterion '{}': {} magnitudes for {} candidates", cname, v.size(), J));
      lua_pushnumber(L, v[j - 1]);
    } else {
      throw InvalidArgument(fmt::format("criterion '{}': magnitude must be a function(candidate, j) or a list of {} numbers", cname, J));
    }
    M(j - 1, i) = read_number(L, -1, "magnitude of " + where);
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
}

int decision_tostring(lua_State* L) {
  lua_getfield(L, 1, "printable");
  return 1;
}

// The criteria: their names (inames), the magnitudes of every candidate (M, one column per
// criterion) and the weights w (all given, or none: equal weights).
void read_criteria(lua_State* L, int crits, int cands, const std::vector<std::string>& cnames,
                   std::vector<std::string>& inames, Eigen::MatrixXd& M, Eigen::VectorXd& w) {
  const auto I = static_cast<int>(w.size());
  int weighted = 0;
  for (int i = 1; i <= I; ++i) {
    lua_rawgeti(L, crits, i);
    if (!lua_istable(L, -1)) throw InvalidArgument(fmt::format("criteria[{}] must be a table {{name =, weight =, magnitude =}}", i));
    const int crit = lua_gettop(L);
    std::string name = fmt::format("criterion {}", i);
    if (raw_field(L, crit, "name") == LUA_TSTRING) name = lua_tostring(L, -1);
    lua_pop(L, 1);
    inames.push_back(name);
    if (raw_field(L, crit, "weight") != LUA_TNIL) {
      w[i - 1] = read_number(L, -1, fmt::format("criteria[{}] ('{}').weight", i, name));
      ++weighted;
    }
    lua_pop(L, 1);
    read_magnitudes(L, crit, cands, cnames, name, M, i - 1);
    lua_pop(L, 1);
  }
  if (weighted == 0)
    w.setConstant(1.0 / I);  // spec §6 Decision: equal weights when none are given
  else if (weighted != I)
    throw InvalidArgument(fmt::format("{} of {} criteria have a weight: give every criterion a weight, or none (equal weights)", weighted, I));
}

// The result table: M, S, ratings, overall, weights, best (index, name, candidate), ranking,
// ties, the names and warnings, and its printable text.
void push_decision(lua_State* L, const DecisionResult& r, int cands, const std::vector<std::string>& cnames,
                   const std::vector<std::string>& inames, const Eigen::VectorXd& w, const std::string& text) {
  const auto J = static_cast<int>(cnames.size());
  lua_createtable(L, 0, 16);
  lua::push_mat(L, r.magnitudes);
  lua_setfield(L, -2, "M");
  lua::push_mat(L, r.standardized);
  lua_setfield(L, -2, "S");
  lua::push_mat(L, r.ratings);
  lua_setfield(L, -2, "ratings");
  lua::set_vec(L, "overall", r.overall);
  lua::set_vec(L, "weights", w);
  lua::set_integer(L, "best", static_cast<lua_Integer>(r.best + 1));
  lua::set_string(L, "best_name", cnames[static_cast<std::size_t>(r.best)]);
  lua_rawgeti(L, cands, r.best + 1);
  lua_setfield(L, -2, "best_candidate");
  std::vector<int> order(static_cast<std::size_t>(J));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return r.overall[a] > r.overall[b]; });
  lua_createtable(L, J, 0);
  for (int k = 0; k < J; ++k) {
    lua_pushinteger(L, order[static_cast<std::size_t>(k)] + 1);
    lua_rawseti(L, -2, k + 1);
  }
  lua_setfield(L, -2, "ranking");
  lua_createtable(L, static_cast<int>(r.ties.size()), 0);
  for (std::size_t k = 0; k < r.ties.size(); ++k) {
    lua_pushinteger(L, static_cast<lua_Integer>(r.ties[k] + 1));
    lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
  }
  lua_setfield(L, -2, "ties");
  for (const auto& [key, list] : {std::pair<const char*, const std::vector<std::string>*>{"candidates", &cnames},
                                  {"criteria", &inames}, {"warnings", &r.warnings}}) {
    lua_createtable(L, static_cast<int>(list->size()), 0);
    for (std::size_t k = 0; k < list->size(); ++k) {
      lua_pushstring(L, (*list)[k].c_str());
      lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
    }
    lua_setfield(L, -2, key);
  }
  lua::set_string(L, "printable", text);
}

}  // namespace

int decision_matrix(lua_State* L) {
  luaL_checktype(L, 1, LUA_TTABLE);
  lua_settop(L, 1);
  const smi::improve::DecisionOptions opt = decision_matrix_schema().read(L, 1);
  return lua::protect(L, "smi.refine.decision_matrix", [&] {
    if (lua_getfield(L, 1, "candidates") != LUA_TTABLE || lua_rawlen(L, -1) == 0)
      throw InvalidArgument("candidates must be a non-empty list (names, or tables describing each revision)");
    const int cands = lua_gettop(L);
    const int J = static_cast<int>(lua_rawlen(L, cands));
    if (lua_getfield(L, 1, "criteria") != LUA_TTABLE || lua_rawlen(L, -1) == 0)
      throw InvalidArgument("criteria must be a non-empty list of {name =, weight =, magnitude = function(candidate) ... end | values}");
    const int crits = lua_gettop(L);
    const int I = static_cast<int>(lua_rawlen(L, crits));
    const std::vector<std::string> cnames = candidate_names(L, cands, J);
    std::vector<std::string> inames;
    Eigen::MatrixXd M(J, I);
    Eigen::VectorXd w(I);
    read_criteria(L, crits, cands, cnames, inames, M, w);
    const DecisionResult r = smi::improve::decision_matrix(M, w, cnames, inames, opt.tie_tol);
    const std::string text = format_decision(r, cnames, inames, w);

    push_decision(L, r, cands, cnames, inames, w, text);
    luaL_setmetatable(L, kDecisionMeta);
    return 1;
  });
}

void register_decision_meta(lua_State* L) {
  const luaL_Reg meta[] = {{"__tostring", decision_tostring}, {nullptr, nullptr}};
  lua::register_table_type(L, kDecisionMeta, nullptr, meta);
}

}  // namespace smi::bind::improve
