#include "vm/runtime.hpp"

#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "modules.hpp"
#include "vm/embedded_stdlib.hpp"

namespace smi::vm {
namespace {

int msghandler(lua_State* L) {
  const char* msg = lua_tostring(L, 1);
  if (!msg) {
    if (luaL_callmeta(L, 1, "__tostring") && lua_type(L, -1) == LUA_TSTRING) return 1;
    msg = lua_pushfstring(L, "(error object is a %s value)", luaL_typename(L, 1));
  }
  luaL_traceback(L, L, msg, 1);
  return 1;
}

/// package.searchers entry: modules compiled into the binary (or read from stdlib_dir).
int embedded_searcher(lua_State* L) {
  const char* name = luaL_checkstring(L, 1);
  for (const EmbeddedModule* m = kEmbeddedModules; m->name; ++m) {
    if (std::strcmp(m->name, name) != 0) continue;
    std::string chunk = std::string("@") + m->path;
    if (luaL_loadbufferx(L, m->data, m->size, chunk.c_str(), "t") != LUA_OK) return lua_error(L);
    lua_pushstring(L, m->path);
    return 2;
  }
  lua_pushfstring(L, "no embedded module '%s'", name);
  return 1;
}

}  // namespace

Runtime::Runtime(Config cfg) : cfg_(std::move(cfg)), L_(luaL_newstate()) {
  if (!L_) throw std::runtime_error("cannot create a Lua state (out of memory)");
  luaL_openlibs(L_);
  // require "smi" and the global smi
  luaL_requiref(L_, "smi", luaopen_smi, 1);
  lua_pushinteger(L_, static_cast<lua_Integer>(cfg_.seed));
  lua_setfield(L_, -2, "seed");
  lua_pop(L_, 1);
  // the embedded stdlib searcher goes right after preload
  lua_getglobal(L_, "package");
  lua_getfield(L_, -1, "searchers");
  const lua_Integer n = luaL_len(L_, -1);
  for (lua_Integer i = n; i >= 2; --i) {
    lua_rawgeti(L_, -1, i);
    lua_rawseti(L_, -2, i + 1);
  }
  lua_pushcfunction(L_, embedded_searcher);
  lua_rawseti(L_, -2, 2);
  lua_pop(L_, 2);
}

Runtime::~Runtime() { lua_close(L_); }

bool Runtime::report(int status) {
  if (status == LUA_OK) return true;
  const char* msg = lua_tostring(L_, -1);
  std::fprintf(stderr, "smi-lua: %s\n", msg ? msg : "(error object is not a string)");
  std::fflush(stderr);
  lua_pop(L_, 1);
  return false;
}

bool Runtime::run_file(const std::string& path, const std::vector<std::string>& args) {
  lua_createtable(L_, static_cast<int>(args.size()), 1);
  lua_pushstring(L_, path.c_str());
  lua_rawseti(L_, -2, 0);
  for (std::size_t i = 0; i < args.size(); ++i) {
    lua_pushstring(L_, args[i].c_str());
    lua_rawseti(L_, -2, static_cast<lua_Integer>(i + 1));
  }
  lua_setglobal(L_, "arg");
  lua_pushcfunction(L_, msghandler);
  const int base = lua_gettop(L_);
  int status = luaL_loadfilex(L_, path.c_str(), "t");
  if (status == LUA_OK) {
    for (const auto& a : args) lua_pushstring(L_, a.c_str());
    status = lua_pcall(L_, static_cast<int>(args.size()), 0, base);
  }
  const bool ok = report(status);
  lua_settop(L_, base - 1);
  return ok;
}

bool Runtime::run_string(const std::string& code, const std::string& chunkname) {
  lua_pushcfunction(L_, msghandler);
  const int base = lua_gettop(L_);
  int status = luaL_loadbufferx(L_, code.data(), code.size(), chunkname.c_str(), "t");
  if (status == LUA_OK) status = lua_pcall(L_, 0, 0, base);
  const bool ok = report(status);
  lua_settop(L_, base - 1);
  return ok;
}

}  // namespace smi::vm
