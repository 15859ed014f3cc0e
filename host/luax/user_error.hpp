// SPDX-License-Identifier: MIT
#pragma once
// Errors in the user's data, options or declaration ("failures"), as opposed to errors in code.
//
// A failure is a Lua error whose value is a table {message = "...", traceback = nil | "..."} with
// one shared metatable (__tostring gives the message; string methods such as e:find work on it,
// and `..` concatenates its message). smi-lua prints a failure as one line, with no Lua
// traceback (--traceback adds it); an error in code (a string, a runtime error) keeps its
// traceback. smi's own checks raise failures: smi.fail(message) in the stdlib, and any error of a
// bound function called by the stdlib (protect() in luax.hpp). A failure that carries a
// traceback (smi.fail(message, traceback)) is an error in the user's code caught by the stdlib
// (a study step) and raised again: its original traceback is printed.
#include <string>
#include <string_view>
#include <lua.hpp>

namespace smi::lua {

/// Pushes a failure with `message` (and `traceback` when not empty). Stack: [] -> [failure].
void push_failure(lua_State* L, std::string_view message, std::string_view traceback = {});
/// Whether the value at idx is a failure.
bool is_failure(lua_State* L, int idx);
/// The failure's message and traceback ("" when none); idx must be a failure.
std::string failure_message(lua_State* L, int idx);
std::string failure_traceback(lua_State* L, int idx);

/// Whether the Lua function `level` frames up the stack is a stdlib chunk (embedded, or loaded
/// from --stdlib-dir: see set_stdlib_source). Level 1 is the caller of the running C function.
bool called_from_stdlib(lua_State* L, int level = 1);
/// The chunk-name prefix of stdlib modules loaded from a folder ("@DIR/"); the embedded ones are
/// "@stdlib/...".
void set_stdlib_source(lua_State* L, const std::string& dir);

/// Called by a message handler while the stack is as the error left it: when the error value at
/// `idx` is a string raised by `error(message, 0)` in a stdlib chunk (the raising function, `level`
/// frames up, is `error`, its caller a stdlib chunk, and the message carries no file:line), a
/// failure with that message is pushed and true returned: the stdlib's own messages for the user.
/// An error the stdlib raised with a position (error(msg, 2): the user's line) stays an error in code.
bool push_stdlib_failure(lua_State* L, int idx, int level);

/// smi._as_failure(e): inside an xpcall handler (smi.study's), e as a failure when the stdlib raised
/// it with error(message, 0), else e unchanged.
int l_as_failure(lua_State* L);

/// smi.fail(message [, traceback]): raises a failure. Bound as smi.fail.
int l_fail(lua_State* L);
/// smi.failure(e) -> message | nil: the message of a failure, nil for any other value.
int l_failure(lua_State* L);

}  // namespace smi::lua
