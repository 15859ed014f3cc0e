// The file functions of the sandbox: each resolves its path (absolute, "..", symlinks), asks the
// policy, and only then calls the original library function (upvalue 1) with the resolved path.
// A denial is a Lua error naming the function, the path, the rule and the flag that allows it.
#include <cstring>
#include <string>

#include "luax/luax.hpp"
#include "luax/policy.hpp"
#include "sandbox/sandbox.hpp"

namespace smi::sandbox {
namespace {

enum class Access { read, write };

/// Replaces the path argument at `idx` by its checked, resolved form. May raise.
void check_arg(lua_State* L, int idx, Access access, const char* fname) {
  const char* path = luaL_checkstring(L, idx);
  std::string resolved;
  lua::protect(L, fname, [&] {
    const Policy& p = lua::policy(L);
    resolved = (access == Access::read ? p.check_read(path, fname) : p.check_write(path, fname)).string();
    return 0;
  });
  lua_pushstring(L, resolved.c_str());
  lua_replace(L, idx);
}

/// Calls upvalue 1 with every argument; returns all its results.
int call_original(lua_State* L) {
  const int n = lua_gettop(L);
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, n, LUA_MULTRET);
  return lua_gettop(L);
}

bool mode_writes(const char* mode) {
  return std::strchr(mode, 'w') || std::strchr(mode, 'a') || std::strchr(mode, '+');
}

int io_open(lua_State* L) {
  const char* mode = luaL_optstring(L, 2, "r");
  check_arg(L, 1, mode_writes(mode) ? Access::write : Access::read, "io.open");
  return call_original(L);
}

/// io.lines(): stdin; io.lines(path, ...): a checked read.
int io_lines(lua_State* L) {
  if (!lua_isnoneornil(L, 1)) check_arg(L, 1, Access::read, "io.lines");
  return call_original(L);
}

/// io.input(path) opens for reading; io.input() / io.input(file) are unchecked.
int io_input(lua_State* L) {
  if (lua_type(L, 1) == LUA_TSTRING) check_arg(L, 1, Access::read, "io.input");
  return call_original(L);
}

int io_output(lua_State* L) {
  if (lua_type(L, 1) == LUA_TSTRING) check_arg(L, 1, Access::write, "io.output");
  return call_original(L);
}

int os_remove(lua_State* L) {
  check_arg(L, 1, Access::write, "os.remove");
  return call_original(L);
}

int os_rename(lua_State* L) {
  check_arg(L, 1, Access::write, "os.rename");
  check_arg(L, 2, Access::write, "os.rename");
  return call_original(L);
}

/// loadfile(path [, mode [, env]]): text chunks only. Stack on success: [chunk].
int loadfile(lua_State* L) {
  const char* mode = luaL_optstring(L, 2, "t");
  if (!std::strchr(mode, 't'))
    return luaL_error(L, "loadfile: binary chunks are not allowed in the sandbox (mode '%s'); load source text", mode);
  const bool has_env = !lua_isnone(L, 3);
  const char* path = nullptr;
  if (!lua_isnoneornil(L, 1)) {
    check_arg(L, 1, Access::read, "loadfile");
    path = lua_tostring(L, 1);
  }
  if (luaL_loadfilex(L, path, "t") != LUA_OK) {
    luaL_pushfail(L);
    lua_insert(L, -2);
    return 2;  // fail, message
  }
  if (has_env) {
    lua_pushvalue(L, 3);
    if (!lua_setupvalue(L, -2, 1)) lua_pop(L, 1);  // the chunk's _ENV
  }
  return 1;
}

/// dofile([path]): text chunks only; errors propagate.
int dofile(lua_State* L) {
  const char* path = nullptr;
  if (!lua_isnoneornil(L, 1)) {
    check_arg(L, 1, Access::read, "dofile");
    path = lua_tostring(L, 1);
  }
  lua_settop(L, 1);
  if (luaL_loadfilex(L, path, "t") != LUA_OK) return lua_error(L);
  lua_call(L, 0, LUA_MULTRET);
  return lua_gettop(L) - 1;
}

}  // namespace

void install_file_functions(lua_State* L) {
  wrap(L, "io", "open", io_open);
  wrap(L, "io", "lines", io_lines);
  wrap(L, "io", "input", io_input);
  wrap(L, "io", "output", io_output);
  wrap(L, "os", "remove", os_remove);
  wrap(L, "os", "rename", os_rename);
  lua_register(L, "loadfile", loadfile);
  lua_register(L, "dofile", dofile);
}

}  // namespace smi::sandbox
