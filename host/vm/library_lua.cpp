// SPDX-License-Identifier: MIT
#include "vm/library_lua.hpp"

#include <string>

#include "luax/luax.hpp"
#include "luax/policy.hpp"
#include "platform/core/sha256.hpp"
#include "vm/provenance_lua.hpp"
#include "vm/searchers.hpp"

namespace smi::vm {
namespace fs = std::filesystem;
namespace {

const LibrarySet& libs_of(lua_State* L) {
  return *static_cast<const LibrarySet*>(lua_touserdata(L, lua_upvalueindex(1)));
}

void set_string(lua_State* L, const char* key, const std::string& v) {
  lua_pushlstring(L, v.data(), v.size());
  lua_setfield(L, -2, key);
}

/// package.searchers entry: modules of libraries. Returns nothing for names whose first
/// component is no library, so the next searcher takes over without noise in the message.
int library_searcher(lua_State* L) {
  const std::string name = luaL_checkstring(L, 1);
  const LibrarySet& set = libs_of(L);
  const std::size_t dot = name.find('.');
  const Library* lib = set.find(name.substr(0, dot));
  if (!lib) return 0;
  std::string tried, found, text;
  lua::protect(L, "require", [&] {
    std::vector<fs::path> cands;
    if (dot == std::string::npos) {
      cands.push_back(lib->folder / "init.lua");
    } else {
      const fs::path rel = module_relpath(name.c_str() + dot + 1);
      fs::path rel_lua = rel;
      rel_lua += ".lua";
      cands.push_back(lib->folder / rel_lua);
      cands.push_back(lib->folder / rel / "init.lua");
    }
    const lua::Policy& pol = lua::policy(L);
    for (const fs::path& c : cands) {
      try {
        // opened through the policy like io.open: a module reached through a symlink out of
        // the library folders is refused, and the file read is the file checked
        const lua::CheckedFile f = pol.open_read(c.string());
        if (pol.record) pol.record->file("lua", f.path, f.fd.get());  // provenance: every module loaded
        text = lua::read_checked(f, c.string());
        found = c.string();
        return 0;
      } catch (const lua::FileError&) {
        tried += (tried.empty() ? "" : "\n\t") + ("no file '" + c.string() + "'");
      }
    }
    tried += " (library " + lib->name() + " " + lib->manifest.version.text + ")";
    return 0;
  });
  if (found.empty()) {
    lua_pushstring(L, tried.c_str());
    return 1;
  }
  if (lua::load_text(L, text, "@" + found) != LUA_OK)
    return luaL_error(L, "error loading module '%s' from file '%s':\n\t%s", name.c_str(), found.c_str(),
                      lua_tostring(L, -1));
  lib->used = true;
  lua_pushstring(L, found.c_str());
  return 2;
}

}  // namespace

/// The common fields of one library; stack: [..., t].
void push_library_fields(lua_State* L, const Library& l) {
  set_string(L, "name", l.name());
  set_string(L, "version", l.manifest.version.text);
  set_string(L, "path", l.folder.string());
  if (!l.git.commit.empty()) set_string(L, "commit", l.git.commit);
  if (!l.git.branch.empty()) set_string(L, "branch", l.git.branch);
  if (!l.source.empty()) set_string(L, "source", l.source);  // smi-lock.json: where libs add fetched it
  lua_pushboolean(L, l.used);
  lua_setfield(L, -2, "used");
}

namespace {

int smi_libraries(lua_State* L) {
  const LibrarySet& set = libs_of(L);
  lua_createtable(L, static_cast<int>(set.all().size()), 0);
  int i = 0;
  for (const Library& l : set.all()) {
    lua_newtable(L);
    push_library_fields(L, l);
    if (!l.manifest.description.empty()) set_string(L, "description", l.manifest.description);
    lua_createtable(L, static_cast<int>(l.manifest.requires_.size()), 0);
    int k = 0;
    for (const auto& r : l.manifest.requires_) {
      lua_pushstring(L, r.text.c_str());
      lua_rawseti(L, -2, ++k);
    }
    lua_setfield(L, -2, "requires");
    lua_rawseti(L, -2, ++i);
  }
  return 1;
}

}  // namespace

void install_libraries(lua_State* L, const LibrarySet* libs) {
  void* ud = const_cast<LibrarySet*>(libs);
  lua_getglobal(L, "package");
  lua_getfield(L, -1, "searchers");  // [package, searchers]
  const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L, -1));
  for (lua_Integer i = n; i >= 3; --i) {  // shift the path searcher(s) up by one
    lua_rawgeti(L, -1, i);
    lua_rawseti(L, -2, i + 1);
  }
  lua_pushlightuserdata(L, ud);
  lua_pushcclosure(L, library_searcher, 1);
  lua_rawseti(L, -2, 3);
  lua_pop(L, 2);

  lua_getglobal(L, "smi");
  lua_pushlightuserdata(L, ud);
  lua_pushcclosure(L, smi_libraries, 1);
  lua_setfield(L, -2, "libraries");
  lua_pop(L, 1);
  install_provenance(L, libs);  // smi.provenance (vm/provenance_lua.cpp)
}

}  // namespace smi::vm
