#include "vm/searchers.hpp"

#include <cstring>
#include <string>

#include "core/errors.hpp"
#include "luax/luax.hpp"
#include "luax/policy.hpp"
#include "vm/embedded_stdlib.hpp"

namespace smi::vm {
namespace fs = std::filesystem;

std::vector<fs::path> ModuleSearch::candidate_roots(const char*) const { return roots; }

fs::path module_relpath(const char* name) {
  std::string s = name;
  if (s.empty()) throw Error("module name is empty");
  for (char c : s)
    if (c == '/' || c == '\\' || c == '\0')
      throw Error("module name '" + s + "' may not contain '/' or '\\\\' (use dots: require \"a.b\")");
  if (s.front() == '.' || s.back() == '.' || s.find("..") != std::string::npos)
    throw Error("module name '" + s + "' has an empty component");
  for (char& c : s)
    if (c == '.') c = '/';
  return fs::path(s);
}

namespace {

const ModuleSearch& search(lua_State* L) {
  return *static_cast<const ModuleSearch*>(lua_touserdata(L, lua_upvalueindex(1)));
}

/// Loads `file` as a text chunk named "@file" and pushes [chunk, file] (2 results), or raises.
int load_found(lua_State* L, const fs::path& file) {
  const std::string f = file.string();
  if (luaL_loadfilex(L, f.c_str(), "t") != LUA_OK)
    return luaL_error(L, "error loading module '%s' from file '%s':\n\t%s", lua_tostring(L, 1), f.c_str(),
                      lua_tostring(L, -1));
  lua_pushstring(L, f.c_str());
  return 2;
}

/// Tries dir/rel.lua and dir/rel/init.lua; returns the first that exists, or "" after adding
/// "\n\tno file 'x'" lines to `tried`.
fs::path find_in(const fs::path& dir, const fs::path& rel, std::string& tried) {
  fs::path rel_lua = rel;
  rel_lua += ".lua";
  for (const fs::path& cand : {dir / rel_lua, dir / rel / "init.lua"}) {
    std::error_code ec;
    if (fs::is_regular_file(cand, ec)) return cand;
    tried += (tried.empty() ? "" : "\n\t") + ("no file '" + cand.string() + "'");
  }
  return {};
}

/// searcher 2: the stdlib, from disk when a stdlib dir is set (development), else embedded.
int stdlib_searcher(lua_State* L) {
  const char* name = luaL_checkstring(L, 1);
  const ModuleSearch& ms = search(L);
  std::string tried;
  if (!ms.stdlib_dir.empty()) {
    fs::path rel, found;
    lua::protect(L, "require", [&] {
      rel = module_relpath(name);
      found = find_in(ms.stdlib_dir, rel, tried);
      if (!found.empty()) lua::policy(L).check_read(found.string(), "require");  // symlinks out
      return 0;
    });
    if (!found.empty()) return load_found(L, found);
  }
  for (const EmbeddedModule* m = kEmbeddedModules; m->name; ++m) {
    if (std::strcmp(m->name, name) != 0) continue;
    const std::string chunk = std::string("@") + m->path;
    if (luaL_loadbufferx(L, m->data, m->size, chunk.c_str(), "t") != LUA_OK) return lua_error(L);
    lua_pushstring(L, m->path);
    return 2;
  }
  tried += (tried.empty() ? "" : "\n\t") + std::string("no embedded stdlib module '") + name + "'";
  lua_pushstring(L, tried.c_str());
  return 1;
}

/// searcher 3: Lua files under the script folder, --lib folders and SMI_PATH.
int path_searcher(lua_State* L) {
  const char* name = luaL_checkstring(L, 1);
  const ModuleSearch& ms = search(L);
  std::string tried;
  fs::path found;
  lua::protect(L, "require", [&] {
    const fs::path rel = module_relpath(name);
    for (const fs::path& root : ms.candidate_roots(name)) {
      found = find_in(root, rel, tried);
      if (found.empty()) continue;
      // a file reached through a symlink out of the library folders is refused like io.open
      lua::policy(L).check_read(found.string(), "require");
      break;
    }
    return 0;
  });
  if (!found.empty()) return load_found(L, found);
  if (tried.empty()) tried = "(no script folder, --lib or SMI_PATH folder to search)";
  lua_pushstring(L, tried.c_str());
  return 1;
}

}  // namespace

void install_searchers(lua_State* L, const ModuleSearch* ms) {
  lua_getglobal(L, "package");  // stack: [package]
  lua_getfield(L, -1, "searchers");
  lua_rawgeti(L, -1, 1);  // the preload searcher: keep it
  lua_createtable(L, 3, 0);  // stack: [package, old, preload, new]
  lua_insert(L, -2);
  lua_rawseti(L, -2, 1);
  lua_pushlightuserdata(L, const_cast<ModuleSearch*>(ms));
  lua_pushcclosure(L, stdlib_searcher, 1);
  lua_rawseti(L, -2, 2);
  lua_pushlightuserdata(L, const_cast<ModuleSearch*>(ms));
  lua_pushcclosure(L, path_searcher, 1);
  lua_rawseti(L, -2, 3);
  lua_setfield(L, -3, "searchers");
  lua_pop(L, 1);
  // The standard path strings are not used by any searcher; empty them so they do not mislead.
  lua_pushliteral(L, "");
  lua_setfield(L, -2, "path");
  lua_pushliteral(L, "");
  lua_setfield(L, -2, "cpath");
  lua_pop(L, 1);
}

}  // namespace smi::vm
