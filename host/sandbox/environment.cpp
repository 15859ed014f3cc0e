// The script's global environment, built from an allow-list (Redis and LuaSandbox do the same):
// only what is named below is reachable from a script. The standard libraries are opened and
// wrapped first (sandbox.cpp, files.cpp); this copies the listed entries into fresh tables and
// makes them the globals, so the original library tables and the old global table are dropped.
#include <cstring>
#include <string>
#include <vector>

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
// coroutine whose __close closes another ... recurses on the C stack until it overflows
// (fixed upstream in 5.4.5). Nested closes beyond this depth raise instead.
constexpr int kMaxCloseDepth = 100;
thread_local int g_close_depth = 0;

struct CloseDepth {
  CloseDepth() { ++g_close_depth; }
  ~CloseDepth() { --g_close_depth; }  // runs when a Lua error unwinds (Lua is built as C++)
};

/// coroutine.close(co): upvalue 1 = the original.
int coroutine_close(lua_State* L) {
  if (g_close_depth >= kMaxCloseDepth)
    return luaL_error(L,
                      "coroutine.close: nested more than %d deep (a __close that closes a coroutine whose __close "
                      "closes another ...); the Lua 5.4.4 in use would overflow the C stack",
                      kMaxCloseDepth);
  CloseDepth guard;
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
