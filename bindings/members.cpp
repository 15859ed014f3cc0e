// SPDX-License-Identifier: MIT
// Misspelt members of the smi module tables: smi.dist.Normal raises "no smi.dist.Normal; did you
// mean smi.dist.normal?" where Lua would say "attempt to call a nil value". Every module table
// (smi.dist, smi.kde, smi.model, ...) gets an __index that names the closest members; the smi
// table itself only for a name that differs from a member by case (smi.Kde): stdlib code probes
// smi.<field> == nil for optional host fields, which must stay nil. smi._closest exposes the
// same suggestion logic (platform/core/closest.hpp) to the stdlib (smi-lua doc NAME, options).
#include <algorithm>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "bindings/modules.hpp"
#include "luax/luax.hpp"
#include "platform/core/closest.hpp"

namespace smi::bind {
namespace {

/// The string keys of the table at `idx` (raw: no __index involved).
std::vector<std::string> keys_of(lua_State* L, int idx) {
  std::vector<std::string> out;
  idx = lua_absindex(L, idx);
  lua_pushnil(L);
  while (lua_next(L, idx)) {
    if (lua_type(L, -2) == LUA_TSTRING) {
      std::string k = lua_tostring(L, -2);
      if (!k.empty() && k[0] != '_') out.push_back(std::move(k));
    }
    lua_pop(L, 1);
  }
  std::sort(out.begin(), out.end());  // closest() breaks ties in this order: the same suggestion every run
  return out;
}

/// __index(t, key): upvalue 1 the table's name ("smi.dist"), upvalue 2 true for the smi table.
int member_index(lua_State* L) {
  if (lua_type(L, 2) != LUA_TSTRING) return 0;
  const std::string key = lua_tostring(L, 2);
  const std::string prefix = lua_tostring(L, lua_upvalueindex(1));
  const bool top = lua_toboolean(L, lua_upvalueindex(2));
  if (!key.empty() && key[0] == '_') return 0;  // private fields are probed freely
  std::string msg;
  {
    const std::vector<std::string> names = keys_of(L, 1);
    std::vector<std::string> near = closest(key, names, 3);
    if (top) {  // only a difference of case on the smi table itself
      std::vector<std::string> same;
      for (const auto& n : near)
        if (name_distance(n, key) == 0) same.push_back(n);
      near = same;
      if (near.empty()) return 0;
    }
    msg = "no " + prefix + "." + key;
    if (!near.empty()) {
      msg += "; did you mean ";
      for (std::size_t i = 0; i < near.size(); ++i) msg += (i ? (i + 1 == near.size() ? " or " : ", ") : "") + prefix + "." + near[i];
      msg += "?";
    } else {
      msg += " (help(" + prefix + ") lists its members)";
    }
  }
  // the user's file:line in front, or, asked by the stdlib, a failure (no internal path)
  lua::raise_from_binding(L, msg.c_str());
}

/// Sets the suggesting __index on the table at the top of the stack (named `name`) and on its
/// module tables below, to `depth` levels; tables that have a metatable keep theirs.
void install(lua_State* L, const std::string& name, bool top, int depth) {
  if (lua_getmetatable(L, -1)) {
    lua_pop(L, 1);
    return;
  }
  if (depth > 0) {
    for (const auto& k : keys_of(L, -1)) {
      lua_getfield(L, -1, k.c_str());
      if (lua_type(L, -1) == LUA_TTABLE) install(L, name + "." + k, false, depth - 1);
      lua_pop(L, 1);
    }
  }
  lua_createtable(L, 0, 2);
  lua_pushstring(L, name.c_str());
  lua_pushboolean(L, top);
  lua_pushcclosure(L, member_index, 2);
  lua_setfield(L, -2, "__index");
  lua_pushboolean(L, 1);
  lua_setfield(L, -2, "__smi_members");  // smi.doc's walk descends into these tables
  lua_setmetatable(L, -2);
}

/// smi._closest(name, {candidates}) -> {closest, ...} (at most 3, nearest first).
int closest_lua(lua_State* L) {
  const std::string name = luaL_checkstring(L, 1);
  luaL_checktype(L, 2, LUA_TTABLE);
  std::vector<std::string> cands;
  const lua_Integer n = luaL_len(L, 2);
  for (lua_Integer i = 1; i <= n; ++i) {
    if (lua_rawgeti(L, 2, i) == LUA_TSTRING) cands.push_back(lua_tostring(L, -1));
    lua_pop(L, 1);
  }
  const auto max = static_cast<std::size_t>(luaL_optinteger(L, 3, 3));
  std::vector<std::string> out;
  try {
    out = closest(name, cands, max);
  } catch (const std::exception& e) {
    return luaL_error(L, "smi._closest: %s", e.what());
  }
  lua_createtable(L, static_cast<int>(out.size()), 0);
  for (std::size_t i = 0; i < out.size(); ++i) {
    lua_pushstring(L, out[i].c_str());
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  return 1;
}

/// smi._known_options() -> {function name = {option, ...}}: the options each function has checked
/// so far in this process (smi-lua doc --check runs every example, then compares with the docs).
int known_options_lua(lua_State* L) {
  std::map<std::string, std::set<std::string>> known;
  try {
    known = lua::known_options();
  } catch (const std::exception& e) {
    return luaL_error(L, "smi._known_options: %s", e.what());
  }
  lua_createtable(L, 0, static_cast<int>(known.size()));
  for (const auto& [fname, keys] : known) {
    lua_createtable(L, static_cast<int>(keys.size()), 0);
    lua_Integer i = 0;
    for (const auto& k : keys) {
      lua_pushstring(L, k.c_str());
      lua_rawseti(L, -2, ++i);
    }
    lua_setfield(L, -2, fname.c_str());
  }
  return 1;
}

}  // namespace

void open_members(lua_State* L) {
  lua_pushcfunction(L, closest_lua);
  lua_setfield(L, -2, "_closest");
  lua_pushcfunction(L, known_options_lua);
  lua_setfield(L, -2, "_known_options");
  install(L, "smi", true, 2);
}

}  // namespace smi::bind
