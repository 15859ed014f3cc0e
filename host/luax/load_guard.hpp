// SPDX-License-Identifier: MIT
#pragma once
// Source text the Lua in use (Debian 12's 5.4.4) would compile into wrong code, refused at load.
//
// Lua 5.4.0-5.4.4 miscompile a binary bitwise operator (& | ~ << >>) whose first operand is an
// integer constant once the function holds more than 255 constants: `1 ~ (2 or 3)` returns 0.
// Silent wrong arithmetic, fixed upstream in 5.4.5 by lua/lua commit c764ca71 ("Bug: Wrong code
// generation in bitwise operations"). The host cannot patch the system library's code
// generator, and deciding exactly which operations are affected needs Lua's parser and its
// constant folding (`K ~ x` with `local K <const> = 1`, `(1 + 1) ~ x`). So the rule is coarse and
// safe: a chunk that may hold 255 constants or more in one function (counted from its tokens
// as an upper bound: distinct names and strings, every numeral, true/false/nil) and that uses a
// binary bitwise operator is refused, naming the line and the fix. Studies rarely use bitwise
// operators; a large generated table with them is split into smaller chunks.
#include <cstddef>
#include <string>
#include <string_view>
#include <lua.hpp>

namespace smi::lua {

/// "" when `text` is safe to compile, else the reason (with "line N:").
std::string lua544_refusal(std::string_view text);

/// luaL_loadbufferx in text mode, after lua544_refusal: a refused chunk pushes
/// "<chunkname>:<line>: ..." and returns LUA_ERRSYNTAX, as a syntax error would.
int load_buffer(lua_State* L, const char* data, std::size_t size, const char* chunkname);

}  // namespace smi::lua
