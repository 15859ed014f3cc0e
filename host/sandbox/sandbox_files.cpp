// SPDX-License-Identifier: MIT
// The file functions of the sandbox. Each opens its file through the policy (luax/policy.hpp:
// walked component by component, checked, opened relative to the checked folder) and hands
// Lua a file made from that descriptor; nothing is re-opened by name, so the checked path and
// the opened file cannot differ. os.remove and os.rename act on the checked
// folder's descriptor (unlinkat, renameat). A denial is a Lua error naming the function, the
// path, the rule and the flag that allows it; an OS failure is returned as io.open returns it
// (nil, message, errno).
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <string>
#include <unistd.h>

#include "luax/luax.hpp"
#include "luax/policy.hpp"
#include "sandbox/sandbox.hpp"

namespace smi::sandbox {
namespace {

/// Pushes nil, "path: message", errno (the shape of io.open's failure). Returns 3.
int push_failure(lua_State* L, const std::string& msg, int err) {
  luaL_pushfail(L);
  lua_pushstring(L, msg.c_str());
  lua_pushinteger(L, err);
  return 3;
}

int close_stream(lua_State* L) {
  auto* p = static_cast<luaL_Stream*>(luaL_checkudata(L, 1, LUA_FILEHANDLE));
  const int res = std::fclose(p->f);
  return luaL_fileresult(L, res == 0, nullptr);
}

/// The open(2) flags of a Lua mode ("r", "w", "a", "r+", "w+", "a+", each with optional "b").
/// Returns -1 for a mode io.open would reject.
int mode_flags(const char* mode) {
  const char* m = mode;
  int flags = 0;
  switch (*m++) {
    case 'r': flags = O_RDONLY; break;
    case 'w': flags = O_WRONLY | O_CREAT | O_TRUNC; break;
    case 'a': flags = O_WRONLY | O_CREAT | O_APPEND; break;
    default: return -1;
  }
  if (*m == '+') {
    flags = (flags & ~(O_RDONLY | O_WRONLY)) | O_RDWR;
    ++m;
  }
  while (*m == 'b') ++m;
  return *m ? -1 : flags;
}

/// Opens `path` with `mode` through the policy and pushes a Lua file handle. Denials raise
/// (named `fname`); OS failures push nil, message, errno. Returns the number of results.
int open_file(lua_State* L, const char* path, const char* mode, const char* fname) {
  const int flags = mode_flags(mode);
  if (flags < 0) return luaL_error(L, "bad argument #2 to '%s' (invalid mode '%s')", fname, mode);
  pathwalk::Fd fd;
  std::string failure;
  int err = 0;
  lua::protect(L, fname, [&] {
    const lua::Policy& p = lua::policy(L);
    try {
      fd = (flags & (O_WRONLY | O_RDWR)) ? p.open_write(path, flags).fd : p.open_read(path).fd;
    } catch (const lua::FileError& e) {
      failure = e.what();
      err = e.err;
    }
    return 0;
  });
  if (!failure.empty()) return push_failure(L, failure, err);
  auto* s = static_cast<luaL_Stream*>(lua_newuserdatauv(L, sizeof(luaL_Stream), 0));
  s->closef = nullptr;  // "closed" until the FILE exists, so a failure below leaves nothing to close
  luaL_setmetatable(L, LUA_FILEHANDLE);
  s->f = ::fdopen(fd.get(), mode);
  if (!s->f) return luaL_error(L, "%s: cannot make a file of '%s': %s", fname, path, std::strerror(errno));
  fd.release();
  s->closef = close_stream;
  return 1;
}

int io_open(lua_State* L) {
  const char* path = luaL_checkstring(L, 1);
  const char* mode = luaL_optstring(L, 2, "r");
  return open_file(L, path, mode, "io.open");
}

/// The iterator of io.lines(path, ...): upvalue 1 the file, 2.. the formats. Closes the file
/// at the end, as io.lines does.
int lines_next(lua_State* L) {
  const int nfmt = static_cast<int>(lua_tointeger(L, lua_upvalueindex(2)));
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_getfield(L, -1, "read");
  lua_insert(L, -2);  // [read, file]
  for (int i = 0; i < nfmt; ++i) lua_pushvalue(L, lua_upvalueindex(3 + i));
  const int base = lua_gettop(L) - nfmt - 2;
  lua_call(L, nfmt + 1, LUA_MULTRET);
  const int n = lua_gettop(L) - base;
  if (n > 0 && !lua_isnil(L, base + 1)) return n;
  if (n > 1 && lua_type(L, base + 2) == LUA_TSTRING) return luaL_error(L, "%s", lua_tostring(L, base + 2));
  lua_pushvalue(L, lua_upvalueindex(1));  // end of file: close it
  lua_getfield(L, -1, "close");
  lua_insert(L, -2);
  lua_call(L, 1, 0);
  lua_pushnil(L);
  return 1;
}

/// io.lines(): stdin (the original); io.lines(path, ...): a checked read.
int io_lines(lua_State* L) {
  if (lua_isnoneornil(L, 1)) {
    const int n = lua_gettop(L);
    lua_pushvalue(L, lua_upvalueindex(1));
    lua_insert(L, 1);
    lua_call(L, n, LUA_MULTRET);
    return lua_gettop(L);
  }
  const char* path = luaL_checkstring(L, 1);
  const int nfmt = lua_gettop(L) - 1;
  luaL_argcheck(L, nfmt <= 250, 252, "too many arguments");
  if (open_file(L, path, "r", "io.lines") != 1) return luaL_error(L, "%s", lua_tostring(L, -2));
  // stack: [path, fmt..., file]
  lua_pushvalue(L, -1);
  lua_pushinteger(L, nfmt);
  for (int i = 0; i < nfmt; ++i) lua_pushvalue(L, 2 + i);
  lua_pushcclosure(L, lines_next, 2 + nfmt);  // stack: [..., file, iter]
  lua_insert(L, -2);
  lua_pushnil(L);
  lua_insert(L, -2);
  lua_pushnil(L);
  lua_insert(L, -2);  // iter, nil, nil, file (the to-be-closed value)
  return 4;
}

/// io.input(path) / io.output(path) open a checked file and pass it to the original, which
/// makes it the default; io.input() / io.input(file) go to the original unchanged.
int set_default(lua_State* L, const char* mode, const char* fname) {
  if (lua_type(L, 1) == LUA_TSTRING) {
    const char* path = lua_tostring(L, 1);
    if (open_file(L, path, mode, fname) != 1) return luaL_error(L, "%s", lua_tostring(L, -2));
    lua_replace(L, 1);
  }
  const int n = lua_gettop(L);
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, n, LUA_MULTRET);
  return lua_gettop(L);
}

int io_input(lua_State* L) { return set_default(L, "r", "io.input"); }
int io_output(lua_State* L) { return set_default(L, "w", "io.output"); }

/// Runs `call` (unlinkat / renameat on folders the sandbox walked) inside protect(); a FileError
/// of the walk counts as the call failing with its errno. Returns as os.remove/os.rename do.
template <class F>
int checked_entry_result(lua_State* L, const char* fname, const char* shown, F&& call) {
  int rc = 0, err = 0;
  lua::protect(L, fname, [&] {
    try {
      rc = call();
      err = errno;
    } catch (const lua::FileError& e) {
      rc = -1;
      err = e.err;
    }
    return 0;
  });
  errno = err;
  return luaL_fileresult(L, rc == 0, shown);
}

int os_remove(lua_State* L) {
  const char* path = luaL_checkstring(L, 1);
  return checked_entry_result(L, "os.remove", path, [&] {
    const pathwalk::Walk w = lua::policy(L).walk_write(path);
    int rc = ::unlinkat(w.dir.get(), w.leaf.c_str(), 0);
    if (rc != 0 && (errno == EISDIR || errno == EPERM)) rc = ::unlinkat(w.dir.get(), w.leaf.c_str(), AT_REMOVEDIR);
    return rc;
  });
}

int os_rename(lua_State* L) {
  const char* from = luaL_checkstring(L, 1);
  const char* to = luaL_checkstring(L, 2);
  return checked_entry_result(L, "os.rename", from, [&] {
    const lua::Policy& p = lua::policy(L);
    const pathwalk::Walk a = p.walk_write(from);
    const pathwalk::Walk b = p.walk_write(to);
    return ::renameat(a.dir.get(), a.leaf.c_str(), b.dir.get(), b.leaf.c_str());
  });
}

/// Loads the checked file `path` as a text chunk named "@path" (a first "#" line and a UTF-8
/// BOM skipped, as luaL_loadfilex does). Returns the load status; the chunk or the message is
/// on the stack. Denials raise (named `fname`).
int load_checked(lua_State* L, const char* path, const char* fname) {
  std::string text, failure;
  lua::protect(L, fname, [&] {
    try {
      const lua::Policy& pol = lua::policy(L);
      const lua::CheckedFile f = pol.open_read(path);
      if (pol.record) pol.record->file("lua", f.path, f.fd.get());  // provenance: code, not data
      text = lua::read_checked(f, path);
    } catch (const lua::FileError& e) {
      failure = std::string("cannot open ") + e.what();
    }
    return 0;
  });
  if (!failure.empty()) {
    lua_pushstring(L, failure.c_str());
    return LUA_ERRFILE;
  }
  return lua::load_text(L, text, std::string("@") + path);
}

/// loadfile(path [, mode [, env]]): text chunks only. Stack on success: [chunk].
int loadfile(lua_State* L) {
  const char* mode = luaL_optstring(L, 2, "t");
  if (!std::strchr(mode, 't'))
    return luaL_error(L, "loadfile: binary chunks are not allowed in the sandbox (mode '%s'); load source text", mode);
  const bool has_env = !lua_isnone(L, 3);
  const int status =
      lua_isnoneornil(L, 1) ? luaL_loadfilex(L, nullptr, "t") : load_checked(L, luaL_checkstring(L, 1), "loadfile");
  if (status != LUA_OK) {
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
  lua_settop(L, 1);
  const int status =
      lua_isnoneornil(L, 1) ? luaL_loadfilex(L, nullptr, "t") : load_checked(L, luaL_checkstring(L, 1), "dofile");
  if (status != LUA_OK) return lua_error(L);
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
