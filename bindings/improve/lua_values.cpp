// SPDX-License-Identifier: MIT
#include "bindings/improve/lua_values.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "luax/luax.hpp"
#include "platform/core/errors.hpp"

namespace smi::bind::improve {

double read_number(lua_State* L, int idx, const std::string& what) {
  if (lua_type(L, idx) != LUA_TNUMBER)
    throw InvalidArgument(fmt::format("{} must be a number, got {}", what, lua_typename(L, lua_type(L, idx))));
  return lua_tonumber(L, idx);
}

Eigen::VectorXd read_vector(lua_State* L, int idx, const std::string& what) {
  idx = lua_absindex(L, idx);
  if (auto* v = lua::test_vec(L, idx)) return *v;
  if (auto* m = lua::test_mat(L, idx)) {
    if (m->cols() == 1) return m->col(0);
    if (m->rows() == 1) return m->row(0).transpose();
    throw InvalidArgument(fmt::format("{} must be a vector, got a {}x{} smi.mat", what, m->rows(), m->cols()));
  }
  if (lua_type(L, idx) != LUA_TTABLE)
    throw InvalidArgument(fmt::format("{} must be a smi.vec or a table of numbers, got {}", what, lua_typename(L, lua_type(L, idx))));
  const auto n = static_cast<lua_Integer>(lua_rawlen(L, idx));
  Eigen::VectorXd out(static_cast<Eigen::Index>(n));
  for (lua_Integer i = 1; i <= n; ++i) {
    lua_rawgeti(L, idx, i);
    const int t = lua_type(L, -1);
    const double x = lua_tonumber(L, -1);
    lua_pop(L, 1);
    if (t != LUA_TNUMBER) throw InvalidArgument(fmt::format("{}[{}] must be a number, got {}", what, i, lua_typename(L, t)));
    out[static_cast<Eigen::Index>(i - 1)] = x;
  }
  return out;
}

std::vector<std::string> sorted_keys(lua_State* L, int idx) {
  idx = lua_absindex(L, idx);
  std::vector<std::string> keys;
  if (lua_type(L, idx) != LUA_TTABLE) return keys;
  lua_pushnil(L);
  while (lua_next(L, idx) != 0) {
    lua_pop(L, 1);
    if (lua_type(L, -1) == LUA_TSTRING) keys.emplace_back(lua_tostring(L, -1));
  }
  std::sort(keys.begin(), keys.end());
  return keys;
}

int raw_field(lua_State* L, int idx, const char* key) {
  idx = lua_absindex(L, idx);
  if (lua_type(L, idx) != LUA_TTABLE) {
    lua_pushnil(L);
    return LUA_TNIL;
  }
  lua_pushstring(L, key);
  return lua_rawget(L, idx);
}

}  // namespace smi::bind::improve
