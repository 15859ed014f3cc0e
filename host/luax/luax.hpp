// SPDX-License-Identifier: MIT
#pragma once
// The helper layer between the Lua-free kernels and Lua (docs/design.md).
//
// Rules every binding follows:
//  * A bound function runs its C++ work inside protect(): a std::exception becomes a Lua error
//    "<function>: <message>" raised *after* the handler, so no exception object is alive when
//    Lua unwinds. We link Debian's C++ build of Lua, where a Lua error is itself a C++ throw of
//    a non-std type: it passes through catch (const std::exception&) untouched and runs
//    destructors on its way. Never write catch (...) around a Lua API call: it would swallow it.
//  * Kernel objects live in a Box {T* p} userdata with a named metatable; __gc and __close
//    delete and null p, and methods on a closed box raise "<type> is closed".
//  * Calling Lua from C++ (objectives, user models) goes through call() below, which uses
//    lua_pcall and turns a Lua error into smi::Error carrying the Lua message.
#include <Eigen/Core>
#include <cstddef>
#include <cstdio>
#include <exception>
#include <initializer_list>
#include <map>
#include <set>
#include <optional>
#include <type_traits>
#include <utility>
#include <vector>
#include <string>
#include <lua.hpp>

#include "platform/core/errors.hpp"

namespace smi::lua {

// ---------------------------------------------------------------------------------------------
// The boundary

/// "<fname>: <what>" into buf; when `what` already holds "<fname>: " (a recursive propagate or
/// calibrate whose model calls it again), the cause comes first whatever the depth:
/// "<fname>: <innermost message> (raised N nested <fname> calls deep)", never a message of
/// prefixes cut off before the cause.
void error_message(char* buf, std::size_t size, const char* fname, const char* what);

/// Raises "<msg>" from a bound function: with the caller's file:line when the caller is the
/// user's code, as a failure (luax/user_error.hpp: one line, no internal path) when the caller is
/// the stdlib, whose checks are about the user's data and declaration.
[[noreturn]] void raise_from_binding(lua_State* L, const char* msg);

/// Runs body() (returns the number of Lua results). A std::exception thrown by it becomes the
/// Lua error "<fname>: <what>" (raise_from_binding).
/// A Lua error met while C++ called into Lua; what() is the Lua message (with traceback when
/// one was asked for). `failure()`: the Lua code raised a failure (smi.fail: an error in the
/// user's data, luax/user_error.hpp), which stays one when it crosses the C++ call back to Lua.
struct LuaError : smi::Error {
  explicit LuaError(const std::string& what, bool failure = false, std::string traceback = {})
      : smi::Error(what), failure_(failure), traceback_(std::move(traceback)) {}
  bool failure() const { return failure_; }
  /// A failure's own traceback (an error in the user's code the stdlib caught and raised again).
  const std::string& traceback() const { return traceback_; }

 private:
  bool failure_;
  std::string traceback_;
};

/// Raises the failure `msg` with `traceback` (may be empty): luax/user_error.hpp.
[[noreturn]] void raise_failure(lua_State* L, const char* msg, const char* traceback);

/// Runs body() (returns the number of Lua results). A std::exception thrown by it becomes the
/// Lua error "<fname>: <what>" (raise_from_binding); a failure raised by a Lua callback that
/// body() called (smi.fail in an objective or a model) is raised again as that failure.
template <class F>
int protect(lua_State* L, const char* fname, F&& body) {
  char msg[2048];  // trivially destructible: nothing to unwind when luaL_error throws
  char traceback[2048] = "";
  bool failure = false;
  try {
    return body();
  } catch (const std::exception& e) {
    const auto* lua_error = dynamic_cast<const LuaError*>(&e);
    failure = lua_error != nullptr && lua_error->failure();
    if (failure) {
      std::snprintf(msg, sizeof msg, "%s", e.what());
      std::snprintf(traceback, sizeof traceback, "%s", lua_error->traceback().c_str());
    } else {
      error_message(msg, sizeof msg, fname, e.what());
    }
  }
  if (failure) raise_failure(L, msg, traceback);
  raise_from_binding(L, msg);
}

/// lua_pcall with a traceback handler; on error pops the message and throws LuaError.
/// Stack: [f, args...] -> [results...].
void call(lua_State* L, int nargs, int nresults);

// ---------------------------------------------------------------------------------------------
// Boxes: userdata holding a pointer to a heap object owned by Lua's GC.
//
// A script must not be able to free what C++ is still using:
//  * every smi metatable has __metatable (a copy without __gc/__close), so getmetatable() never
//    hands out a finalizer or the metatable itself;
//  * __gc and __close check the type of their argument (luaL_checkudata on their own type), so
//    one type's finalizer cannot delete another type's object;
//  * __close (a `<close>` variable) deletes at once only when no C function is running below it
//    on the main thread's stack; otherwise (inside a callback of a bound function: a vec:map
//    function, an option table's __index, a model parser, an objective, or in a coroutine) it
//    only marks the box closed, and the collector deletes the object once nothing reaches it.
//    A bound function keeps the boxes it uses on its own Lua stack (its arguments), so it
//    cannot lose them while it runs; methods on a closed box raise "<type> is closed".

template <class T>
struct Box {
  T* p;
  std::size_t bytes;  // heap bytes counted against --max-memory (memory.hpp), returned on delete
  bool closed;        // closed by __close while in use: p stays valid until __gc
};

/// Counts `bytes` of C++ heap held by a new box (vec, mat, Kriging) against --max-memory and
/// reports them to Lua's collector; raises "memory limit exceeded: <what> ..." beyond the limit.
/// Implemented in memory.cpp. release_bytes returns them when the object is deleted.
void account_bytes(lua_State* L, std::size_t bytes, const char* what);
void release_bytes(lua_State* L, std::size_t bytes);

/// Heap bytes owned by an object (0 when not worth counting). Overloads live beside the types.
template <class T>
std::size_t heap_bytes(const T&) {
  return 0;
}
inline std::size_t heap_bytes(const Eigen::VectorXd& v) { return static_cast<std::size_t>(v.size()) * sizeof(double); }
inline std::size_t heap_bytes(const Eigen::MatrixXd& m) { return static_cast<std::size_t>(m.size()) * sizeof(double); }

/// True when a C function is active below the running __close on this thread, or the thread is
/// a coroutine (whose resumer may be one): then deleting now could free what C++ still uses.
bool close_must_defer(lua_State* L);

template <class T>
void box_delete(lua_State* L, Box<T>* b) {
  T* p = b->p;
  const std::size_t bytes = b->bytes;
  b->p = nullptr;
  b->bytes = 0;
  delete p;
  if (bytes) release_bytes(L, bytes);
}

/// __gc: upvalue 1 is the type name. Called by the collector, the object is unreachable.
template <class T>
int box_gc(lua_State* L) {
  auto* b = static_cast<Box<T>*>(luaL_checkudata(L, 1, lua_tostring(L, lua_upvalueindex(1))));
  if (b->p) box_delete(L, b);
  return 0;
}

/// __close: upvalue 1 is the type name.
template <class T>
int box_close(lua_State* L) {
  auto* b = static_cast<Box<T>*>(luaL_checkudata(L, 1, lua_tostring(L, lua_upvalueindex(1))));
  if (!b->p) return 0;
  if (close_must_defer(L))
    b->closed = true;  // __gc deletes it
  else
    box_delete(L, b);
  return 0;
}

/// Pushes a new, empty box with the metatable `type` (registered with register_type) and
/// returns the slot to fill. The box is consistent (p = nullptr) before anything may fail.
template <class T>
T*& new_box(lua_State* L, const char* type, int user_values = 1) {
  auto* b = static_cast<Box<T>*>(lua_newuserdatauv(L, sizeof(Box<T>), user_values));
  b->p = nullptr;
  b->bytes = 0;
  b->closed = false;
  luaL_setmetatable(L, type);
  return b->p;
}

/// Pushes a box owning `value` (moved in). Its heap bytes count against --max-memory.
template <class T>
T& push_box(lua_State* L, const char* type, T&& value) {
  using V = std::decay_t<T>;
  const std::size_t bytes = heap_bytes(static_cast<const V&>(value));
  if (bytes) account_bytes(L, bytes, type);  // may raise: nothing allocated by us yet
  T*& slot = new_box<V>(L, type);
  auto* b = static_cast<Box<V>*>(lua_touserdata(L, -1));
  b->bytes = bytes;  // returned by __gc even if the copy below fails
  slot = new V(std::move(value));
  return *slot;
}

/// The object in the box at idx if it has metatable `type`, else nullptr. A box of that type
/// that was closed raises "<type> is closed".
template <class T>
T* test_box(lua_State* L, int idx, const char* type) {
  auto* b = static_cast<Box<T>*>(luaL_testudata(L, idx, type));
  if (!b) return nullptr;
  if (!b->p || b->closed) luaL_error(L, "%s is closed", type);
  return b->p;
}

/// The object in the box at idx; raises "bad argument" for another type and "<type> is closed"
/// for a box already collected or closed.
template <class T>
T& check_box(lua_State* L, int idx, const char* type) {
  auto* b = static_cast<Box<T>*>(luaL_checkudata(L, idx, type));
  if (!b->p || b->closed) luaL_error(L, "%s is closed", type);
  return *b->p;
}

/// Getter for fields that are not methods (d.bandwidth): push the value and return 1, or 0.
using FieldGetter = int (*)(lua_State* L);  // stack: [self, key]

/// Creates the metatable `type`: __name, __index (methods, then `getter`), __gc and __close
/// (type-checked closures with the type name as upvalue), __metatable (scripts see a copy
/// without __gc/__close, never the metatable itself), plus `metamethods` (__tostring, __len, arithmetic, ...).
void register_type_raw(lua_State* L, const char* type, const luaL_Reg* methods, const luaL_Reg* metamethods,
                       lua_CFunction gc, lua_CFunction close, FieldGetter getter);

template <class T>
void register_type(lua_State* L, const char* type, const luaL_Reg* methods, const luaL_Reg* metamethods = nullptr,
                   FieldGetter getter = nullptr) {
  register_type_raw(L, type, methods, metamethods, &box_gc<T>, &box_close<T>, getter);
}

/// Registers the metatable of a plain Lua value (a result table such as a verdict) under `type`:
/// __name = type, __index = a table of `methods` (none: no __index), the `metamethods`, then
/// protect_metatable. A second call for the same type changes nothing. Boxes use register_type;
/// these two are the only ways a binding makes a metatable. Stack: unchanged.
void register_table_type(lua_State* L, const char* type, const luaL_Reg* methods, const luaL_Reg* metamethods);

/// Sets __metatable on the metatable at idx (call it when the metatable is complete): getmetatable()
/// then returns a copy without __gc and __close, so a script can read __name and friends but can
/// neither call a finalizer nor change the metatable the host uses.
void protect_metatable(lua_State* L, int idx, const char* type);

// ---------------------------------------------------------------------------------------------
// smi.vec and smi.mat: float64 vectors and column-major matrices, owned by Lua.

inline constexpr const char* kVecType = "smi.vec";
inline constexpr const char* kMatType = "smi.mat";

Eigen::VectorXd& push_vec(lua_State* L, Eigen::VectorXd v);
Eigen::MatrixXd& push_mat(lua_State* L, Eigen::MatrixXd m);
Eigen::VectorXd* test_vec(lua_State* L, int idx);
Eigen::MatrixXd* test_mat(lua_State* L, int idx);

/// A vec, or a sequence table of numbers, copied into a vector. Raises a Lua error that names
/// `what` and the 1-based index of an element that is not a number.
Eigen::VectorXd to_vector(lua_State* L, int idx, const char* what);
/// A mat, a table of rows (each a table or a vec), or a vec (taken as one column).
Eigen::MatrixXd to_matrix(lua_State* L, int idx, const char* what);
/// A sequence table of strings.
std::vector<std::string> to_strings(lua_State* L, int idx, const char* what);

/// For "x is a number -> number; x is a vec or table -> vec" methods: applies f to the values
/// and pushes the result in the caller's shape. f: (const Eigen::VectorXd&) -> Eigen::VectorXd.
template <class F>
int push_mapped(lua_State* L, int idx, const char* fname, F&& f) {
  if (lua_type(L, idx) == LUA_TNUMBER) {
    Eigen::VectorXd x(1);
    x[0] = lua_tonumber(L, idx);
    double y = 0;
    const int r = protect(L, fname, [&] {
      y = f(x)[0];
      return 1;
    });
    lua_pushnumber(L, y);
    return r;
  }
  Eigen::VectorXd x = to_vector(L, idx, "x");
  return protect(L, fname, [&] {
    push_vec(L, f(x));
    return 1;
  });
}

/// Pushes a table {name = vec, ...} in the order given.
void push_named_vectors(lua_State* L, const std::vector<std::string>& names, const Eigen::MatrixXd& columns);

// ---------------------------------------------------------------------------------------------
// Options tables: trailing {key = value} arguments. A bound function declares its options in a
// schema (option_schema.hpp: typed reads, unknown-key check and reference list from one table);
// Options below is left for keys a schema lists as by_hand (nested tables, a number-or-string)
// and presence checks; it has no unknown-key check of its own (the schema's is the one).

/// The option names of every schema built so far in this process, by function name (what
/// smi-lua doc --check compares with the docs).
std::map<std::string, std::set<std::string>> known_options();
/// Adds to known_options() (each option schema does, when it is built).
void record_known_options(const std::string& fname, const std::vector<std::string>& keys);
/// "fname: unknown option 'k' (did you mean 'x'?)" (or with the list of known options) for the
/// first string key of the table at idx, in name order, that is not in `known`; "" if none. The
/// one unknown-key check, the option schemas'.
std::string unknown_option_message(lua_State* L, int idx, const char* fname, const std::vector<std::string>& known);

class Options {
 public:
  /// idx may hold nil/none (all defaults) or a table; anything else raises.
  Options(lua_State* L, int idx, const char* fname);

  bool has(const char* key) const;
  double number(const char* key, double def) const;
  std::optional<double> number(const char* key) const;
  lua_Integer integer(const char* key, lua_Integer def) const;
  std::optional<lua_Integer> integer(const char* key) const;
  std::string string(const char* key, const std::string& def) const;
  std::optional<std::string> string(const char* key) const;
  bool boolean(const char* key, bool def) const;
  /// Pushes the raw field value (nil if absent); returns its Lua type.
  int push(const char* key) const;
  int index() const { return idx_; }
  bool present() const { return idx_ != 0; }

 private:
  [[noreturn]] void type_error(const char* key, const char* expected) const;
  lua_State* L_;
  int idx_;  // absolute stack index, 0 if no table
  const char* fname_;
};

// Small setters for result tables. Stack: [t] -> [t].
void set_number(lua_State* L, const char* key, double v);
void set_integer(lua_State* L, const char* key, lua_Integer v);
void set_string(lua_State* L, const char* key, const std::string& v);
void set_boolean(lua_State* L, const char* key, bool v);
void set_vec(lua_State* L, const char* key, Eigen::VectorXd v);

/// Sets funcs into the table at the top of the stack.
void set_funcs(lua_State* L, const luaL_Reg* funcs);

}  // namespace smi::lua
