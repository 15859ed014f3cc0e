// SPDX-License-Identifier: MIT
// smi._docs(): hands the compiled-in reference texts of the C++ side to stdlib/smi/doc.lua,
// with the methods table of every smi userdata type (found in the registry), so that the doc
// module can walk the public API at run time. The texts of the smi module's values set from the
// command line and of the host functions registered by library_lua.cpp (smi.libraries,
// smi.provenance) are here; the run-level functions' are in bindings/run_doc.cpp.
#include <cstring>
#include <exception>
#include <string>

#include "app/docs.hpp"
#include "app/runtime.hpp"
#include "luax/luax.hpp"

namespace smi::app {
namespace {

const char* const kHostDoc = R"(
@ module smi
The smi-lua runtime: every kernel is a field of this table (help() lists them).
Values set by the command line: smi.seed (--seed, default ${seed}), smi.quiet (--quiet, or
output not a terminal), smi.out_dir (--out, default smi-out/<script>), smi.script_dir (the
script's folder), smi.version (the program's version), smi.dry_run (--dry-run), smi.pdf (--pdf:
a study also prints its report to PDF).

@ smi.libraries() -> list
The libraries a study sees (--lib, SMI_PATH), as the manifests declare them.
returns: a list of {name =, version =, path =, description =, commit =} (commit when the
  folder is a git checkout)
errors: none (a bad library stops the run before the script starts)
example:
  print(#smi.libraries() >= 0)

@ smi.provenance([opts]) -> table
What this run's numbers depend on so far: every file it read (Lua modules, dofile/loadfile
chunks, data, priors, templates, the embedded stdlib modules), each with its SHA-256 taken from
the bytes read (files over 1 GB: size and mtime, marked large); every program a model runs (path,
SHA-256, declared version); the command line, the script's arguments and smi-lua's options that
change results (seed, executor, --slurm-opt, --timeout, --max-memory, --store); the version and
build of smi-lua (compiler, Lua, Eigen, NLopt, SQLite, RE2, nettle, fmt); every library's version,
content hash and git commit. smi.study records it in results.json after every step (schema 2,
docs/provenance.md); `smi-lua verify results.json` hashes it all again.
options:
  files = true  -- include each library file's SHA-256 (false: only the folder hash)
returns: {smi_lua =, lua =, build = {compiler =, eigen =, ...}, seed =, command = {...}, cwd =,
  arguments = {...}, options = {seed =, executor =, ...}, script = {path =, hash =},
  files = {[path] = {kind = "lua" | "data" | "stdlib" | "program" | "script", hash =, size =
  [, large = true, mtime =]}}, programs = {{name =, path =, hash =, size =, version =}, ...},
  libraries = {{name =, version =, path =, hash =, commit =, source =, files = {...}}, ...}}
  (source and commit of a library of the project's tree come from smi-lock.json: where `smi-lua
  libs add` fetched it and what it resolved)
errors: a library file that cannot be read
example:
  local p = smi.provenance{files = false}
  print(p.smi_lua ~= nil, p.seed == smi.seed)
)";

/// Pushes {methods table by type name} for every registry metatable named "smi.*".
void push_types(lua_State* L) {
  lua_newtable(L);
  const int out = lua_gettop(L);
  lua_pushnil(L);
  while (lua_next(L, LUA_REGISTRYINDEX)) {  // [out, key, value]
    if (lua_type(L, -2) == LUA_TSTRING && lua_istable(L, -1) && std::strncmp(lua_tostring(L, -2), "smi.", 4) == 0) {
      lua_getfield(L, -1, "__index");  // [out, key, mt, index]
      bool pushed = false;
      if (lua_istable(L, -1)) {
        pushed = true;
      } else if (lua_iscfunction(L, -1) && lua_getupvalue(L, -1, 1)) {  // smi types: methods upvalue
        if (lua_istable(L, -1)) {
          lua_remove(L, -2);
          pushed = true;
        } else {
          lua_pop(L, 1);
        }
      }
      if (pushed) {
        lua_pushvalue(L, -3);  // key
        lua_insert(L, -2);
        lua_settable(L, out);
      } else {
        lua_pop(L, 1);
      }
    }
    lua_pop(L, 1);
  }
}

using BindingDocs = std::vector<lua::DocText> (*)();

int smi_docs(lua_State* L) {
  std::vector<lua::DocText> texts;
  // The bindings' list came with the closure (install_docs), in a userdata upvalue.
  const auto* source = static_cast<const BindingDocs*>(lua_touserdata(L, lua_upvalueindex(1)));
  const int r = lua::protect(L, "smi._docs", [&] {
    texts = (*source)();
    texts.push_back({"host/app/docs.cpp", lua::fill(kHostDoc, {{"seed", std::to_string(kDefaultSeed)}})});
    return 0;
  });
  lua_createtable(L, 0, 2);
  lua_createtable(L, static_cast<int>(texts.size()), 0);
  int i = 0;
  for (const auto& t : texts) {
    lua_createtable(L, 0, 2);
    lua_pushstring(L, t.source);
    lua_setfield(L, -2, "source");
    lua_pushlstring(L, t.text.data(), t.text.size());
    lua_setfield(L, -2, "text");
    lua_rawseti(L, -2, ++i);
  }
  lua_setfield(L, -2, "texts");
  push_types(L);
  lua_setfield(L, -2, "types");
  return r + 1;
}

}  // namespace

void install_docs(lua_State* L, BindingDocs binding_docs) {
  // stack: [smi] -> [smi]. The pointer lives in a full userdata (a function pointer is no
  // void*): [smi, ud] -> [smi, closure].
  auto* slot = static_cast<BindingDocs*>(lua_newuserdatauv(L, sizeof(BindingDocs), 0));
  *slot = binding_docs;
  lua_pushcclosure(L, smi_docs, 1);
  lua_setfield(L, -2, "_docs");
}

}  // namespace smi::app
