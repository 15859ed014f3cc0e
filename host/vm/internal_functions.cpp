// SPDX-License-Identifier: MIT
#include "vm/internal_functions.hpp"

namespace smi::vm {
namespace {
const char kInternalKey = 0;  // registry key of the table
}  // namespace

void push_internal_functions(lua_State* L) {
  if (lua_rawgetp(L, LUA_REGISTRYINDEX, &kInternalKey) == LUA_TTABLE) return;
  lua_pop(L, 1);
  lua_newtable(L);
  lua_pushvalue(L, -1);
  lua_rawsetp(L, LUA_REGISTRYINDEX, &kInternalKey);
}

void set_internal_function(lua_State* L, const char* name, lua_CFunction f) {
  push_internal_functions(L);
  lua_pushcfunction(L, f);
  lua_setfield(L, -2, name);
  lua_pop(L, 1);
}

}  // namespace smi::vm
