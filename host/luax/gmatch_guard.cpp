// SPDX-License-Identifier: MIT
#include "luax/gmatch_guard.hpp"

namespace smi::lua {
namespace {

/// The wrapped iterator: upvalue 1 = Lua's iterator, upvalue 2 = true once it raised.
int gmatch_step(lua_State* L) {
  if (lua_toboolean(L, lua_upvalueindex(2)))
    return luaL_error(L, "string.gmatch: this iterator already failed (\"pattern too complex\" or another error) and "
                         "cannot be resumed; call string.gmatch again for a new one");
  lua_settop(L, 0);
  lua_pushvalue(L, lua_upvalueindex(1));
  if (lua_pcall(L, 0, LUA_MULTRET, 0) != LUA_OK) {
    lua_pushboolean(L, 1);
    lua_replace(L, lua_upvalueindex(2));
    return lua_error(L);  // the same error, raised on
  }
  return lua_gettop(L);
}

/// string.gmatch(s, pattern [, init]): upvalue 1 = the original.
int gmatch(lua_State* L) {
  const int n = lua_gettop(L);
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, n, 1);
  lua_pushboolean(L, 0);
  lua_pushcclosure(L, gmatch_step, 2);
  return 1;
}

}  // namespace

void guard_gmatch(lua_State* L, int idx) {
  idx = lua_absindex(L, idx);
  lua_getfield(L, idx, "gmatch");
  lua_pushcclosure(L, gmatch, 1);
  lua_setfield(L, idx, "gmatch");
}

}  // namespace smi::lua
