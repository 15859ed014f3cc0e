// SPDX-License-Identifier: MIT
// smi.rng(seed [, stream]): explicit, seeded generators. The same seed gives the same numbers
// on every run and build (core/rng.hpp).
#include <cmath>

#include "bindings/modules.hpp"
#include "luax/luax.hpp"
#include "luax/memory.hpp"
#include "platform/core/rng.hpp"

namespace smi::bind {
namespace {

constexpr const char* kRngType = "smi.rng";

Rng& self(lua_State* L) { return lua::check_box<Rng>(L, 1, kRngType); }

Eigen::Index check_count(lua_State* L, int arg) {
  const lua_Integer n = luaL_checkinteger(L, arg);
  luaL_argcheck(L, n >= 0 && n <= (lua_Integer(1) << 31), arg, "count must be in 0..2^31");  // literal: the largest count
  lua::check_alloc(L, static_cast<double>(n), sizeof(double), "smi.rng count");
  return static_cast<Eigen::Index>(n);
}

/// Seeds are integers (a float seed would silently lose bits).
std::uint64_t check_seed(lua_State* L, int arg) {
  if (!lua_isinteger(L, arg))
    luaL_error(L, "smi.rng: seed must be an integer, got %s", lua_type(L, arg) == LUA_TNUMBER ? "a float" : luaL_typename(L, arg));
  return static_cast<std::uint64_t>(lua_tointeger(L, arg));
}

int rng_new(lua_State* L) {
  const std::uint64_t seed = check_seed(L, 1);
  std::uint64_t stream = 0;
  if (lua_type(L, 2) == LUA_TSTRING)
    stream = hash_label(lua_tostring(L, 2));
  else if (!lua_isnoneornil(L, 2))
    stream = static_cast<std::uint64_t>(luaL_checkinteger(L, 2));
  lua::push_box(L, kRngType, Rng(seed, stream));
  return 1;
}

/// g:uniform(n [, lo, hi]) -> vec; g:uniform() -> one number in (0, 1).
int rng_uniform(lua_State* L) {
  Rng& g = self(L);
  if (lua_isnoneornil(L, 2)) {
    lua_pushnumber(L, g.uniform01());
    return 1;
  }
  const Eigen::Index n = check_count(L, 2);
  const double lo = luaL_optnumber(L, 3, 0.0), hi = luaL_optnumber(L, 4, 1.0);
  luaL_argcheck(L, std::isfinite(lo) && std::isfinite(hi) && lo < hi, 3, "need finite lo < hi");
  lua::push_vec(L, g.uniform(n, lo, hi));
  return 1;
}

/// g:normal(n [, mean, sd]) -> vec; g:normal() -> one standard normal number.
int rng_normal(lua_State* L) {
  Rng& g = self(L);
  if (lua_isnoneornil(L, 2)) {
    lua_pushnumber(L, g.normal());
    return 1;
  }
  const Eigen::Index n = check_count(L, 2);
  const double mean = luaL_optnumber(L, 3, 0.0), sd = luaL_optnumber(L, 4, 1.0);
  luaL_argcheck(L, std::isfinite(mean), 3, "mean must be finite");
  luaL_argcheck(L, std::isfinite(sd) && sd >= 0, 4, "sd must be finite and >= 0");
  lua::push_vec(L, g.normal(n, mean, sd));
  return 1;
}

/// g:integers(n, lo, hi) -> vec of integers uniform on [lo, hi].
int rng_integers(lua_State* L) {
  Rng& g = self(L);
  const Eigen::Index n = check_count(L, 2);
  const lua_Integer lo = luaL_checkinteger(L, 3), hi = luaL_checkinteger(L, 4);
  luaL_argcheck(L, lo <= hi, 3, "need lo <= hi");
  Eigen::VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i) v[i] = static_cast<double>(g.integer(lo, hi));
  lua::push_vec(L, std::move(v));
  return 1;
}

int rng_tostring(lua_State* L) {
  self(L);
  lua_pushstring(L, "smi.rng");
  return 1;
}

const luaL_Reg kMethods[] = {
    {"uniform", rng_uniform}, {"normal", rng_normal}, {"integers", rng_integers}, {nullptr, nullptr}};
const luaL_Reg kMeta[] = {{"__tostring", rng_tostring}, {nullptr, nullptr}};

}  // namespace

void open_rng(lua_State* L) {
  lua::register_type<Rng>(L, kRngType, kMethods, kMeta);
  lua_pushcfunction(L, rng_new);
  lua_setfield(L, -2, "rng");
}

}  // namespace smi::bind
