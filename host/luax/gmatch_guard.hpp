// SPDX-License-Identifier: MIT
#pragma once
// Lua 5.4.4's gmatch iterator keeps its recursion budget (matchdepth) across calls and resets it
// only when a match ends normally: after "pattern too complex" it stays at -1, so the next call
// never meets the limit and recurses until the C stack overflows (fixed upstream by lua/lua
// commit efddc230, "Bug: wrong initialization in result from 'gmatch'"). The guard: the
// iterator is wrapped, and once it has raised an error it refuses to run again. Used by the
// sandbox's string table and by an isolated state's (isolated_state.hpp).
#include <lua.hpp>

namespace smi::lua {

/// Replaces t.gmatch (t: the string table at `idx`) by the guarded one. Stack: unchanged.
void guard_gmatch(lua_State* L, int idx);

}  // namespace smi::lua
