// SPDX-License-Identifier: MIT
// The script's global environment, built from an allow-list (Redis and LuaSandbox do the same):
// only what is named below is reachable from a script. The standard libraries are opened and
// wrapped first (sandbox.cpp, files.cpp); this copies the listed entries into fresh tables and
// makes them the globals, so the original library tables and the old global table are dropped.
#include <cstddef>
#include <cstring>
#include <string>
#include <vector>

#include "luax/gmatch_guard.hpp"
#include "sandbox/sandbox.hpp"

namespace smi::sandbox {
namespace {

struct Lib {
  const char* name;
  std::vector<const char*> fields;
};

// Base functions and values (the rest of _G: libraries below, and what the host added).
const char* const kBase[] = {"assert",   "collectgarbage", "dofile",   "error",    "getmetatable", "ipairs",
                             "load",     "loadfile",       "next",     "pairs",    "pcall",        "print",
                             "rawequal", "rawget",         "rawlen",   "rawset",   "require",      "select",
                             "setmetatable", "tonumber",   "tostring", "type",     "xpcall",       "warn",
                             "_VERSION", "smi",            "arg"};

const Lib kLibs[] = {
    {"coroutine", {"close", "create", "isyieldable", "resume", "running", "status", "wrap", "yield"}},
    {"table", {"concat", "insert", "move", "pack", "remove", "sort", "unpack"}},
    {"string",
     {"byte", "char", "find", "format", "gmatch", "gsub", "len", "lower", "match", "pack", "packsize", "rep",
      "reverse", "sub", "unpack", "upper"}},
    {"math",
     {"abs",   "acos",  "asin", "atan",  "ceil",       "cos",       "deg",        "exp",  "floor", "fmod",
      "huge",  "log",   "max",  "maxinteger", "min",   "mininteger", "modf",      "pi",   "rad",   "random",
      "randomseed", "sin", "sqrt", "tan", "tointeger", "type",      "ult"}},
    {"utf8", {"char", "charpattern", "codes", "codepoint", "len", "offset"}},
    {"io", {"close", "input", "lines", "open", "output", "read", "stderr", "stdin", "stdout", "type", "write"}},
    {"os", {"clock", "date", "difftime", "exit", "getenv", "remove", "rename", "time"}},
    {"debug", {"traceback"}},
    {"package", {"config", "cpath", "loaded", "path", "preload"}},
};

/// os.getenv(name): upvalue 1 = the original, upvalue 2 = set of allowed names.
int getenv_allowed(lua_State* L) {
  const char* name = luaL_checkstring(L, 1);
  lua_pushvalue(L, 1);
  if (lua_rawget(L, lua_upvalueindex(2)) == LUA_TNIL)
    return luaL_error(L,
                      "os.getenv: the sandbox does not let scripts read the environment variable '%s'; allow it "
                      "with --allow-env %s",
                      name, name);
  lua_pop(L, 1);
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_pushvalue(L, 1);
  lua_call(L, 1, 1);
  return 1;
}

// Lua 5.4.4 resets the C-call count in lua_resetthread, so a __close that closes another
// coroutine whose __close closes another ... recurses on the C stack with a fresh budget of 200
// C calls per level (pcalls inside each __close use it up) until the stack overflows: fixed
// upstream in 5.4.5 by lua/lua commit 1e64c139 ("Bug: stack overflow with nesting of
// coroutine.close"), which carries the caller's count over. A count of nested closes cannot bound
// that (99 levels of 190 pcalls each overflowed under a cap of 100), so the guard measures the C
// stack itself: the distance from the outermost coroutine.close to this one. Each level can add
// at most Lua's own C-call budget on top, far below the rest of an 8 MB stack.
constexpr std::size_t kCloseStackBytes = 1u << 20;
thread_local const char* g_close_base = nullptr;

struct CloseBase {
  bool outermost;
  explicit CloseBase(const char* here) : outermost(g_close_base == nullptr) {
    if (outermost) g_close_base = here;
  }
  ~CloseBase() {  // runs when a Lua error unwinds (Lua is built as C++)
    if (outermost) g_close_base = nullptr;
  }
};

/// coroutine.close(co): upvalue 1 = the original.
int coroutine_close(lua_State* L) {
  // The frame address, not a local's: a sanitizer's fake stack may hold locals on the heap.
  const char* here = static_cast<const char*>(__builtin_frame_address(0));
  if (g_close_base) {
    const std::ptrdiff_t used = g_close_base - here;  // the stack grows down
    if (used > static_cast<std::ptrdiff_t>(kCloseStackBytes))
      return luaL_error(L,
                        "coroutine.close: nested too deep (a __close that closes a coroutine whose __close closes "
                        "another ... used %d KB of C stack); the Lua 5.4.4 in use would overflow the C stack there "
                        "(fixed upstream in Lua 5.4.5, commit 1e64c139)",
                        static_cast<int>(used / 1024));
  }
  CloseBase guard(here);
  const int n = lua_gettop(L);
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, n, LUA_MULTRET);
  return lua_gettop(L);
}

/// Copies t[name] for each name from the table at `from` into the table at the top.
void copy_fields(lua_State* L, int from, const std::vector<const char*>& names) {
  for (const char* n : names) {
    lua_getfield(L, from, n);
    lua_setfield(L, -2, n);
  }
}

}  // namespace

void restrict_globals(lua_State* L, const std::vector<std::string>& allowed_env) {
  lua_pushglobaltable(L);
  const int old_g = lua_gettop(L);
  lua_newtable(L);  // the new globals
  const int env = lua_gettop(L);
  for (const char* n : kBase) {
    lua_getfield(L, old_g, n);
    lua_setfield(L, env, n);
  }
  luaL_getsubtable(L, LUA_REGISTRYINDEX, LUA_LOADED_TABLE);
  const int loaded = lua_gettop(L);
  for (const Lib& lib : kLibs) {
    if (lua_getfield(L, old_g, lib.name) != LUA_TTABLE) {
      lua_pop(L, 1);
      continue;
    }
    const int orig = lua_gettop(L);
    lua_createtable(L, 0, static_cast<int>(lib.fields.size()));
    copy_fields(L, orig, lib.fields);
    if (std::strcmp(lib.name, "os") == 0) {
      lua_getfield(L, orig, "getenv");
      lua_createtable(L, 0, static_cast<int>(allowed_env.size()));
      for (const auto& e : allowed_env) {
        lua_pushboolean(L, 1);
        lua_setfield(L, -2, e.c_str());
      }
      lua_pushcclosure(L, getenv_allowed, 2);
      lua_setfield(L, -2, "getenv");
    } else if (std::strcmp(lib.name, "coroutine") == 0) {
      lua_getfield(L, orig, "close");
      lua_pushcclosure(L, coroutine_close, 1);
      lua_setfield(L, -2, "close");
    } else if (std::strcmp(lib.name, "string") == 0) {
      lua::guard_gmatch(L, -1);  // Lua 5.4.4's gmatch bug (gmatch_guard.hpp)
      // Strings' methods ("x"):upper() come from the string metatable's __index: the new table.
      lua_pushliteral(L, "");
      if (lua_getmetatable(L, -1)) {
        lua_pushvalue(L, -3);
        lua_setfield(L, -2, "__index");
        lua_pop(L, 1);
      }
      lua_pop(L, 1);
    }
    lua_pushvalue(L, -1);
    lua_setfield(L, env, lib.name);
    lua_setfield(L, loaded, lib.name);  // require "string" gives the restricted table
    lua_pop(L, 1);                      // the original
  }
  lua_pushvalue(L, env);
  lua_setfield(L, env, "_G");
  lua_pushvalue(L, env);
  lua_setfield(L, loaded, "_G");
  lua_pushvalue(L, env);
  lua_rawseti(L, LUA_REGISTRYINDEX, LUA_RIDX_GLOBALS);
  lua_settop(L, old_g - 1);
}

}  // namespace smi::sandbox
