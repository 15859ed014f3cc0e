// SPDX-License-Identifier: MIT
#include "luax/user_error.hpp"

#include <cstring>

namespace smi::lua {
namespace {

constexpr const char* kMeta = "smi.failure";
constexpr const char* kStdlibKey = "smi.stdlib_source";

int f_tostring(lua_State* L) {
  lua_getfield(L, 1, "message");
  return 1;
}

/// a .. b where either side is a failure: its message takes its place.
int f_concat(lua_State* L) {
  for (int i = 1; i <= 2; ++i) {
    if (is_failure(L, i)) {
      lua_getfield(L, i, "message");
      lua_replace(L, i);
    }
  }
  luaL_tolstring(L, 1, nullptr);
  luaL_tolstring(L, 2, nullptr);
  lua_concat(L, 2);
  return 1;
}

/// e:find(...), e:match(...), e:gsub(...): string methods act on the message.
int f_method(lua_State* L) {
  lua_getfield(L, 1, "message");
  lua_replace(L, 1);
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, lua_gettop(L) - 1, LUA_MULTRET);
  return lua_gettop(L);
}

int f_index(lua_State* L) {
  // stack: [failure, key]
  if (lua_type(L, 2) != LUA_TSTRING) return 0;
  lua_pushliteral(L, "");  // the string library, as strings reach it (whatever the globals hold)
  if (luaL_getmetafield(L, -1, "__index") != LUA_TTABLE) return 0;
  lua_getfield(L, -1, lua_tostring(L, 2));
  if (!lua_isfunction(L, -1)) return 0;
  lua_pushcclosure(L, f_method, 1);
  return 1;
}

void push_metatable(lua_State* L) {
  if (luaL_newmetatable(L, kMeta)) {
    const luaL_Reg mm[] = {{"__tostring", f_tostring}, {"__concat", f_concat}, {"__index", f_index}, {nullptr, nullptr}};
    luaL_setfuncs(L, mm, 0);
    lua_pushstring(L, "smi.failure");
    lua_setfield(L, -2, "__name");
    lua_pushboolean(L, false);  // getmetatable(e) hands out nothing to change
    lua_setfield(L, -2, "__metatable");
  }
}

bool starts_with(const char* s, const char* prefix) { return std::strncmp(s, prefix, std::strlen(prefix)) == 0; }

}  // namespace

void push_failure(lua_State* L, std::string_view message, std::string_view traceback) {
  lua_createtable(L, 0, 2);
  lua_pushlstring(L, message.data(), message.size());
  lua_setfield(L, -2, "message");
  if (!traceback.empty()) {
    lua_pushlstring(L, traceback.data(), traceback.size());
    lua_setfield(L, -2, "traceback");
  }
  push_metatable(L);
  lua_setmetatable(L, -2);
}

bool is_failure(lua_State* L, int idx) {
  if (lua_type(L, idx) != LUA_TTABLE || !lua_getmetatable(L, idx)) return false;
  luaL_getmetatable(L, kMeta);
  const bool same = lua_rawequal(L, -1, -2) != 0;
  lua_pop(L, 2);
  return same;
}

static std::string field(lua_State* L, int idx, const char* name) {
  lua_getfield(L, idx, name);
  std::size_t n = 0;
  const char* s = lua_type(L, -1) == LUA_TSTRING ? lua_tolstring(L, -1, &n) : nullptr;
  std::string out = s ? std::string(s, n) : std::string();
  lua_pop(L, 1);
  return out;
}

std::string failure_message(lua_State* L, int idx) { return field(L, idx, "message"); }
std::string failure_traceback(lua_State* L, int idx) { return field(L, idx, "traceback"); }

void set_stdlib_source(lua_State* L, const std::string& dir) {
  std::string prefix = "@" + dir;
  if (!prefix.empty() && prefix.back() != '/') prefix += '/';
  lua_pushstring(L, prefix.c_str());
  lua_setfield(L, LUA_REGISTRYINDEX, kStdlibKey);
}

bool called_from_stdlib(lua_State* L, int level) {
  lua_Debug ar;
  if (!lua_getstack(L, level, &ar) || !lua_getinfo(L, "S", &ar)) return false;
  if (starts_with(ar.source, "@stdlib/")) return true;
  lua_getfield(L, LUA_REGISTRYINDEX, kStdlibKey);
  const char* dir = lua_tostring(L, -1);
  const bool in_dir = dir && starts_with(ar.source, dir);
  lua_pop(L, 1);
  return in_dir;
}

bool push_stdlib_failure(lua_State* L, int idx, int level) {
  if (lua_type(L, idx) != LUA_TSTRING) return false;
  lua_Debug ar;
  if (!lua_getstack(L, level, &ar) || !lua_getinfo(L, "Sn", &ar)) return false;
  if (std::strcmp(ar.what, "C") != 0 || !ar.name || std::strcmp(ar.name, "error") != 0) return false;
  if (!called_from_stdlib(L, level + 1)) return false;
  const char* msg = lua_tostring(L, idx);
  // "chunk:12: ..." (a position added by error's level): the name before the first ':' holds no
  // newline, and digits then ':' follow it
  const char* colon = std::strchr(msg, ':');
  const char* nl = std::strchr(msg, '\n');
  if (colon && (!nl || colon < nl)) {
    const char* p = colon + 1;
    while (*p >= '0' && *p <= '9') ++p;
    if (p > colon + 1 && *p == ':') return false;
  }
  push_failure(L, msg);
  return true;
}

int l_as_failure(lua_State* L) {
  // level 0 is this function, 1 the Lua handler that calls it, 2 the function that raised
  lua_settop(L, 1);
  if (!push_stdlib_failure(L, 1, 2)) lua_settop(L, 1);
  return 1;
}

int l_fail(lua_State* L) {
  std::size_t tn = 0;
  const char* tb = lua_type(L, 2) == LUA_TSTRING ? lua_tolstring(L, 2, &tn) : "";  // before tolstring pushes
  std::size_t n = 0;
  const char* msg = luaL_tolstring(L, 1, &n);
  push_failure(L, std::string_view(msg, n), std::string_view(tb, tn));
  return lua_error(L);
}

int l_failure(lua_State* L) {
  if (!is_failure(L, 1)) {
    lua_pushnil(L);
    return 1;
  }
  lua_getfield(L, 1, "message");
  return 1;
}

}  // namespace smi::lua
