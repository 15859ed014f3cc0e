// SPDX-License-Identifier: MIT
#pragma once
// Host functions meant for the stdlib only (the run's record of files read, re-hashing a
// recorded file, marking the results file as an output). A field of smi would be reachable by
// every script, and one of them let a script take its data out of the provenance. They live in
// a table in the registry, which the stdlib searcher hands to each stdlib module as the third
// argument of its chunk (`local _, _, internal = ...`: never through a global function, which
// a script may have replaced); no global, field or upvalue a script can reach holds it.
#include <lua.hpp>

namespace smi::vm {

/// Adds `f` as internal.`name`. Stack: unchanged.
void set_internal_function(lua_State* L, const char* name, lua_CFunction f);
/// Pushes the table of internal functions (made empty on first use).
void push_internal_functions(lua_State* L);

}  // namespace smi::vm
