// SPDX-License-Identifier: MIT
#pragma once
// The REPL's value printer: tables, vecs and mats shown in full when small and cut short when
// large (entry, depth and character budgets), so printing a million numbers costs one line.
#include <string>
#include <lua.hpp>

namespace smi::repl {

struct PrintLimits {
  int max_entries = 24;     // per table
  int max_depth = 3;        // nested tables deeper than this print as {...}
  std::size_t max_chars = 2000;
  std::size_t wrap = 78;    // longer renderings of a table go one entry per line
};

/// Renders the value at idx. May run __tostring metamethods, so call it in protected mode.
/// Top-level strings are rendered raw (as print does); nested ones quoted.
std::string describe(lua_State* L, int idx, const PrintLimits& lim = {});

/// lua_CFunction: prints every argument with describe(), tab-separated, then a newline.
int print_values(lua_State* L);

}  // namespace smi::repl
