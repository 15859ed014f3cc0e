// SPDX-License-Identifier: MIT
#include "vm/searchers.hpp"

#include <cstring>
#include <optional>
#include <string>

#include "luax/luax.hpp"
#include "luax/policy.hpp"
#include "platform/core/errors.hpp"
#include "vm/embedded_stdlib.hpp"
#include "vm/internal_functions.hpp"

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

/// A module file found and read through a checked descriptor: its text and the path shown.
struct Found {
  std::string path, text;
};

/// Tries dir/rel.lua and dir/rel/init.lua, each opened by `open` (a checked open: a denial
/// raises, a missing file adds "\n\tno file 'x'" to `tried`). Returns the first that opens.
template <class Open>
std::optional<Found> find_in(const fs::path& dir, const fs::path& rel, std::string& tried, RunRecord* record,
                             Open&& open) {
  fs::path rel_lua = rel;
  rel_lua += ".lua";
  for (const fs::path& cand : {dir / rel_lua, dir / rel / "init.lua"}) {
    try {
      const lua::CheckedFile f = open(cand.string());
      if (RunRecord* r = record) r->file("lua", f.path, f.fd.get());  // provenance: every module loaded
      return Found{cand.string(), lua::read_checked(f, cand.string())};
    } catch (const lua::FileError&) {
      tried += (tried.empty() ? "" : "\n\t") + ("no file '" + cand.string() + "'");
    }
  }
  return std::nullopt;
}

/// Loads `f` as a text chunk named "@path" and pushes [chunk, path] (2 results), or raises.
int load_found(lua_State* L, const Found& f) {
  if (lua::load_text(L, f.text, "@" + f.path) != LUA_OK)
    return luaL_error(L, "error loading module '%s' from file '%s':\n\t%s", lua_tostring(L, 1), f.path.c_str(),
                      lua_tostring(L, -1));
  lua_pushstring(L, f.path.c_str());
  return 2;
}

/// The loader of a stdlib module (upvalue 1: its chunk): require calls it with (name, path); the
/// chunk gets (name, path, internal), internal being the functions meant for the stdlib only
/// (internal_functions.hpp), which reach no script this way.
int stdlib_loader(lua_State* L) {
  lua_settop(L, 2);
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  push_internal_functions(L);
  lua_call(L, 3, 1);
  return 1;
}

/// [chunk, path] of a stdlib module -> [loader, path].
int stdlib_found(lua_State* L) {
  lua_pushvalue(L, -2);
  lua_pushcclosure(L, stdlib_loader, 1);
  lua_replace(L, -3);
  return 2;
}

/// searcher 2: the stdlib, from disk when a stdlib dir is set (development), else embedded.
/// The stdlib folder is a root of this searcher only: scripts' read roots do not grow with it
///, and a file reached through a symlink out of it is refused.
int stdlib_searcher(lua_State* L) {
  const char* name = luaL_checkstring(L, 1);
  const ModuleSearch& ms = search(L);
  std::string tried;
  if (!ms.stdlib_dir.empty()) {
    std::optional<Found> found;
    lua::protect(L, "require", [&] {
      const fs::path rel = module_relpath(name);
      const std::vector<fs::path> roots{lua::resolve_path(ms.stdlib_dir.string())};
      found = find_in(ms.stdlib_dir, rel, tried, lua::policy(L).record, [&](const std::string& p) {
        return lua::open_read_within(p, roots, "the stdlib is loaded only from inside --stdlib-dir " + roots[0].string());
      });
      return 0;
    });
    if (found) {
      load_found(L, *found);
      return stdlib_found(L);
    }
  }
  for (const EmbeddedModule* m = kEmbeddedModules; m->name; ++m) {
    if (std::strcmp(m->name, name) != 0) continue;
    const std::string chunk = std::string("@") + m->path;
    if (RunRecord* r = lua::policy(L).record) {  // provenance: the embedded module's own bytes
      lua::protect(L, "require", [&] {
        r->text("stdlib", std::string("embedded:") + m->path, std::string_view(m->data, m->size));
        return 0;
      });
    }
    if (luaL_loadbufferx(L, m->data, m->size, chunk.c_str(), "t") != LUA_OK) return lua_error(L);
    lua_pushstring(L, m->path);
    return stdlib_found(L);
  }
  tried += (tried.empty() ? "" : "\n\t") + std::string("no embedded stdlib module '") + name + "'";
  lua_pushstring(L, tried.c_str());
  return 1;
}

/// searcher 3: Lua files under the script folder, --lib folders and SMI_PATH, opened through
/// the policy like io.open (a symlink out of the library folders is refused).
int path_searcher(lua_State* L) {
  const char* name = luaL_checkstring(L, 1);
  const ModuleSearch& ms = search(L);
  std::string tried;
  std::optional<Found> found;
  lua::protect(L, "require", [&] {
    const fs::path rel = module_relpath(name);
    const lua::Policy& pol = lua::policy(L);
    for (const fs::path& root : ms.candidate_roots(name)) {
      found = find_in(root, rel, tried, pol.record, [&](const std::string& p) { return pol.open_read(p); });
      if (found) break;
    }
    return 0;
  });
  if (found) return load_found(L, *found);
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
