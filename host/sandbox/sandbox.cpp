// SPDX-License-Identifier: MIT
#include "sandbox/sandbox.hpp"

#include <cstring>
#include <string>
#include <string_view>

#include "luax/load_guard.hpp"
#include "luax/policy.hpp"
#include "luax/run_context.hpp"

namespace smi::sandbox {
namespace {

/// Sets lib[name] = nil for each name. Stack: unchanged.
void remove(lua_State* L, const char* lib, std::initializer_list<const char*> names) {
  if (lua_getglobal(L, lib) == LUA_TTABLE)
    for (const char* n : names) {
      lua_pushnil(L);
      lua_setfield(L, -2, n);
    }
  lua_pop(L, 1);
}

/// load(chunk [, chunkname [, mode [, env]]]) with the mode forced to text. A reader function
/// is drained first (its pieces joined), so the text goes through the guard against Lua 5.4.4's
/// code-generation bug (luax/load_guard.hpp) like every other chunk.
int load(lua_State* L) {
  const char* mode = luaL_optstring(L, 3, "t");
  if (!std::strchr(mode, 't'))
    return luaL_error(L, "load: binary chunks are not allowed in the sandbox (mode '%s'); load source text", mode);
  const int n = lua_gettop(L) < 4 ? 3 : 4;  // keep an explicit env (even nil), as load does
  lua_settop(L, n);
  if (lua_type(L, 1) == LUA_TFUNCTION) {
    luaL_Buffer b;
    luaL_buffinit(L, &b);  // (pushes onto the stack: pieces go below it through the buffer)
    for (;;) {
      lua_pushvalue(L, 1);
      if (lua_pcall(L, 0, 1, 0) != LUA_OK) {  // load returns the reader's error, it does not raise it
        lua_pushnil(L);
        lua_insert(L, -2);
        return 2;
      }
      if (lua_isnil(L, -1) || (lua_type(L, -1) == LUA_TSTRING && lua_rawlen(L, -1) == 0)) {
        lua_pop(L, 1);
        break;
      }
      if (lua_type(L, -1) != LUA_TSTRING) {
        lua_pushnil(L);
        lua_pushliteral(L, "reader function must return a string");
        return 2;
      }
      luaL_addvalue(&b);
    }
    luaL_pushresult(&b);
    lua_replace(L, 1);
    if (lua_isnil(L, 2)) {  // load's own name for a reader's chunk
      lua_pushliteral(L, "=(load)");
      lua_replace(L, 2);
    }
  }
  if (lua_type(L, 1) == LUA_TSTRING) {
    std::size_t len = 0;
    const char* text = lua_tolstring(L, 1, &len);
    const std::string why = lua::lua544_refusal(std::string_view(text, len));
    if (!why.empty()) {
      lua_pushnil(L);
      luaL_where(L, 1);
      lua_pushfstring(L, "load: chunk refused, %s", why.c_str());
      lua_concat(L, 2);
      return 2;
    }
  }
  lua_pushliteral(L, "t");
  lua_replace(L, 3);
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, n, LUA_MULTRET);
  return lua_gettop(L);
}

/// os.exit([code [, close]]): asks the host to end the run with `code` after closing the state
/// (so __gc/__close handlers and open files are finished). Raised as an error no pcall keeps.
int os_exit(lua_State* L) {
  int code = 0;
  if (lua_isboolean(L, 1))
    code = lua_toboolean(L, 1) ? 0 : 1;
  else
    code = static_cast<int>(luaL_optinteger(L, 1, 0));
  lua::stop_run(L, cancel::Reason::exit, code);  // the token says exit: no pcall keeps running
  lua_pushlightuserdata(L, lua::exit_sentinel());
  return lua_error(L);
}

/// math.randomseed(): without arguments reseeds with --seed instead of the clock, so a run
/// stays reproducible; with arguments it is the standard function.
int randomseed(lua_State* L) {
  if (lua_gettop(L) == 0) lua_pushinteger(L, static_cast<lua_Integer>(lua::run_context(L).seed));
  const int n = lua_gettop(L);
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, n, LUA_MULTRET);
  return lua_gettop(L);
}

}  // namespace

void wrap(lua_State* L, const char* lib, const char* name, lua_CFunction fn) {
  lua_getglobal(L, lib);           // stack: [lib]
  lua_getfield(L, -1, name);       // stack: [lib, original]
  lua_pushcclosure(L, fn, 1);      // stack: [lib, wrapper]
  lua_setfield(L, -2, name);
  lua_pop(L, 1);
}

void install(lua_State* L) {
  install_file_functions(L);

  // load: text only. The original becomes an upvalue of the wrapper.
  lua_getglobal(L, "load");
  lua_pushcclosure(L, load, 1);
  lua_setglobal(L, "load");

  remove(L, "os", {"execute", "tmpname", "setlocale"});
  wrap(L, "os", "exit", os_exit);
  remove(L, "io", {"popen", "tmpfile"});
  remove(L, "string", {"dump"});
  remove(L, "package", {"loadlib", "searchpath"});

  // debug: only traceback survives (tests and error handlers use it; it reads, never writes).
  lua_getglobal(L, "debug");        // stack: [debug]
  lua_createtable(L, 0, 1);         // stack: [debug, safe]
  lua_getfield(L, -2, "traceback");
  lua_setfield(L, -2, "traceback");
  lua_pushvalue(L, -1);
  lua_setglobal(L, "debug");
  luaL_getsubtable(L, LUA_REGISTRYINDEX, LUA_LOADED_TABLE);  // stack: [debug, safe, loaded]
  lua_insert(L, -2);
  lua_setfield(L, -2, "debug");
  lua_pop(L, 2);

  // math.random: seeded from --seed (Lua 5.4 seeds from the clock otherwise).
  wrap(L, "math", "randomseed", randomseed);
  lua_getglobal(L, "math");
  lua_getfield(L, -1, "randomseed");
  lua_call(L, 0, 0);
  lua_pop(L, 1);
}

}  // namespace smi::sandbox
