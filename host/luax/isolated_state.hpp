// SPDX-License-Identifier: MIT
#pragma once
// A Lua state of its own for code that must share no object with the study (a command model's
// deck function). Sharing one state, even with a fresh _ENV, leaked the study's objects: the
// string metatable's __index is the study's string table, an upvalue may hold a file handle.
// Here nothing crosses but values: what goes in is copied (numbers, strings, booleans, plain
// tables, Lua functions with their upvalues copied the same way), and what comes out is text.
//
// The state's globals are the pure base functions (no load, require, print, collectgarbage,
// setmetatable), and fresh string (gmatch guarded, no dump), math (without random: a deck is a
// function of its point), table and utf8 tables; any other global name raises an error naming it. Its heap comes from
// the study's allocator, so --max-memory counts it; a count hook polls the run's cancellation
// token, so --timeout and Ctrl-C stop a loop in it.
#include <string>
#include <vector>
#include <lua.hpp>

#include "platform/core/cancel.hpp"

namespace smi::lua {

class IsolatedState {
 public:
  /// A state with `study`'s allocator, polling `token` (may be null: nothing stops it). Throws
  /// smi::Error when no state can be made (out of memory).
  IsolatedState(lua_State* study, const cancel::Token* token);
  ~IsolatedState();
  IsolatedState(const IsolatedState&) = delete;
  IsolatedState& operator=(const IsolatedState&) = delete;

  /// Copies the Lua function at `idx` of `from` into this state by value and keeps it (one
  /// function per state). Its _ENV upvalues (and those of the functions it reaches) become this
  /// state's globals; its other upvalues are copied: nil, booleans, numbers, strings, tables
  /// without a metatable (shared and cyclic tables stay so), Lua functions (the same rule), and
  /// the standard functions of `from`'s string, math, table, utf8 and base (this state's own).
  /// Anything else (a userdata such as a file handle or a smi object, a coroutine, another C
  /// function, a table with a metatable) is refused. Returns "" or the refusal, naming the
  /// upvalue by its path ("'helper' > 'fh' is a file handle").
  std::string adopt_function(lua_State* from, int idx);

  /// One field of the table the kept function is called with.
  struct Field {
    std::string name;
    bool is_number = true;
    double number = 0;
    std::string text;
  };

  /// Calls the kept function with the table {name = value, ...} of `fields` and returns its
  /// result, which must be a string. Throws smi::Error with the function's error (file:line),
  /// the timeout or Ctrl-C, running out of memory, or a result of another type; `what` names
  /// the function in messages of its own.
  std::string call(const std::vector<Field>& fields, const char* what);

 private:
  lua_State* L_ = nullptr;
};

}  // namespace smi::lua
