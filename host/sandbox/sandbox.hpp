// SPDX-License-Identifier: MIT
#pragma once
// The sandbox: the globals a script sees, built by allow-list (as Redis, LuaSandbox and LÖVE do).
//
// The state is made for one run and restricted before any script code runs, so the standard
// libraries' dangerous entries are never reachable: removed, or replaced by wrappers that check
// smi::Policy and keep the original only as a C upvalue (no debug library to dig it out).
//   io.open io.lines io.input io.output dofile loadfile os.remove os.rename  checked by the policy
//   load, loadfile, dofile, require                                         text chunks only
//   os.execute io.popen io.tmpfile os.tmpname os.setlocale package.loadlib
//   package.searchpath string.dump debug.* (but traceback)                  gone
//   os.exit                  raises an uncatchable request; the host closes the state and exits
//   math.random              seeded with --seed; math.randomseed() without argument reseeds it
#include <string>
#include <vector>
#include <lua.hpp>

namespace smi::sandbox {

/// Restricts the globals of a state whose standard libraries are open. Uses lua::policy(L)
/// (paths) and lua::run_context(L) (seed; the token os.exit stops). Stack: unchanged.
void install(lua_State* L);

/// The last step of making a state (after the host added smi, searchers and libraries):
/// replaces the global table by a new one built from an allow-list of names (fresh library
/// tables holding only the listed functions, copied from the wrapped ones), so anything not
/// named (a function a new Lua version adds, one a removal forgot) is unreachable. os.getenv
/// answers only for the names in `allowed_env` (--allow-env) and raises for any other.
/// coroutine.close refuses nesting deeper than the C stack allows (Lua 5.4.4 bug).
void restrict_globals(lua_State* L, const std::vector<std::string>& allowed_env);

/// Checked file functions (files.cpp): io.open, io.lines, io.input, io.output, dofile, loadfile,
/// os.remove, os.rename. Stack: unchanged.
void install_file_functions(lua_State* L);

/// Replaces `lib[name]` by the C closure `fn` whose upvalue 1 is the original. Stack: unchanged.
void wrap(lua_State* L, const char* lib, const char* name, lua_CFunction fn);

}  // namespace smi::sandbox
