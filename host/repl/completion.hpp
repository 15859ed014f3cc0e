// SPDX-License-Identifier: MIT
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

/// Completion with the line before the word: after `help("` (or `help "`, `help '`) and after a
/// leading `?`, the words are the names of the reference (smi.kde, smi.vec:mean, smi.report.new),
/// asked of stdlib/smi/doc.lua in protected mode; elsewhere as complete().
std::vector<std::string> complete_line(lua_State* L, const std::string& text, const std::string& before);

}  // namespace smi::repl
