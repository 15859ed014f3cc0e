#pragma once
// Tab completion for the REPL: globals, and fields of tables and methods of userdata along a
// dotted path ("smi.k" -> smi.kde, "v:su" -> v:sum). Reads the state without running any Lua
// code (raw lookups only; a userdata's methods come from its metatable's __index table or,
// for smi types, from the methods table the __index closure holds).
#include <string>
#include <vector>
#include <lua.hpp>

namespace smi::repl {

/// Completions of `text` (the word under the cursor), each a full replacement for it, sorted.
std::vector<std::string> complete(lua_State* L, const std::string& text);

}  // namespace smi::repl
