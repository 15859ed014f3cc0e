// SPDX-License-Identifier: MIT
#pragma once
// The Lua face of the library set:
//   require "name.module"   a searcher (before the plain path searcher) that maps the first
//                           component to a library folder: name.a.b -> <folder>/a/b.lua or
//                           <folder>/a/b/init.lua; "name" alone -> <folder>/init.lua
//   smi.libraries()         {{name=, version=, description=, path=, commit=, used=}, ...}
//   smi.provenance([opts])  what a results file records so the study can be rerun exactly
//                           (vm/provenance_lua.hpp, installed from here)
// Library modules load as text chunks after the sandbox's read check, like any module.
#include <lua.hpp>

#include "vm/libraries.hpp"

namespace smi::vm {

/// Adds the searcher (as package.searchers[3]) and smi.libraries / smi.provenance. `libs`
/// must outlive the state. Call after install_searchers. Stack: unchanged.
void install_libraries(lua_State* L, const LibrarySet* libs);

/// The fields of one library shared by smi.libraries and smi.provenance: name, version, path,
/// commit, branch, used. Stack: [..., t] -> [..., t].
void push_library_fields(lua_State* L, const Library& l);

}  // namespace smi::vm
