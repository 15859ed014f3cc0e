#pragma once
// The helper layer between the Lua-free kernels and Lua (shared/conventions.md §3.4-3.6, 3.11).
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
#include <cstdio>
#include <exception>
#include <initializer_list>
#include <optional>
#include <type_traits>
#include <utility>
#include <vector>
#include <string>
#include <lua.hpp>

#include "core/errors.hpp"

namespace smi::lua {

// ---------------------------------------------------------------------------------------------
// The boundary

/// Runs body() (returns the number of Lua results). A std::exception thrown by it becomes the
/// Lua error "<fname>: <what>" carrying the caller's file:line.
template <class F>
int protect(lua_State* L, const char* fname, F&& body) {
  char msg[2048];  // trivially destructible: nothing to unwind when luaL_error throws
  try {
    return body();
  } catch (const std::exception& e) {
    std::snprintf(msg, sizeof msg, "%s: %s", fname, e.what());
  }
  return luaL_error(L, "%s", msg);
}

/// A Lua error met while C++ called into Lua; what() is the Lua message (with traceback when
/// one was asked for).
struct LuaError : smi::Error {
  using smi::Error::Error;
};

/// lua_pcall with a traceback handler; on error pops the message and throws LuaError.
/// Stack: [f, args...] -> [results...].
void call(lua_State* L, int nargs, int nresults);

// ---------------------------------------------------------------------------------------------
// Boxes: userdata holding a pointer to a heap object owned by Lua's GC.

template <class T>
struct Box {
  T* p;
};

template <class T>
int box_gc(lua_State* L) {
  auto* b = static_cast<Box<T>*>(lua_touserdata(L, 1));
  if (b && b->p) {
    delete b->p;
    b->p = nullptr;
  }
  return 0;
}

/// Pushes a new, empty box with the metatable `type` (registered with register_type) and
/// returns the slot to fill. The box is consistent (p = nullptr) before anything may fail.
template <class T>
T*& new_box(lua_State* L, const char* type) {
  auto* b = static_cast<Box<T>*>(lua_newuserdatauv(L, sizeof(Box<T>), 1));
  b->p = nullptr;
  luaL_setmetatable(L, type);
  return b->p;
}

/// Pushes a box owning `value` (moved in).
template <class T>
T& push_box(lua_State* L, const char* type, T&& value) {
  T*& slot = new_box<std::decay_t<T>>(L, type);
  slot = new std::decay_t<T>(std::move(value));
  return *slot;
}

template <class T>
T* test_box(lua_State* L, int idx, const char* type) {
  auto* b = static_cast<Box<T>*>(luaL_testudata(L, idx, type));
  return b ? b->p : nullptr;
}

/// The object in the box at idx; raises "bad argument" for another type and "<type> is closed"
/// for a box already collected or closed.
template <class T>
T& check_box(lua_State* L, int idx, const char* type) {
  auto* b = static_cast<Box<T>*>(luaL_checkudata(L, idx, type));
  if (!b->p) luaL_error(L, "%s is closed", type);
  return *b->p;
}

/// Getter for fields that are not methods (d.bandwidth): push the value and return 1, or 0.
using FieldGetter = int (*)(lua_State* L);  // stack: [self, key]

/// Creates the metatable `type`: __name, __index (methods, then `getter`), __gc and __close
/// (delete the object), plus `metamethods` (__tostring, __len, arithmetic, ...).
void register_type_raw(lua_State* L, const char* type, const luaL_Reg* methods, const luaL_Reg* metamethods,
                       lua_CFunction gc, FieldGetter getter);

template <class T>
void register_type(lua_State* L, const char* type, const luaL_Reg* methods, const luaL_Reg* metamethods = nullptr,
                   FieldGetter getter = nullptr) {
  register_type_raw(L, type, methods, metamethods, &box_gc<T>, getter);
}

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
// Options tables: trailing {key = value} arguments.

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
  /// Raises for a key not in `known`, naming the closest known key (typos are the usual cause).
  void check_known(std::initializer_list<const char*> known) const;
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
