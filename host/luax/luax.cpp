// SPDX-License-Identifier: MIT
#include "luax/luax.hpp"
#include <map>
#include <mutex>
#include <set>
#include "platform/core/closest.hpp"
#include "luax/user_error.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>
#include <string_view>

namespace smi::lua {

namespace {

/// Message handler for call(): the message plus a traceback; non-string errors are described.
int traceback_handler(lua_State* L) {
  if (is_failure(L, 1)) return 1;  // the user's data is at fault: the failure as it is, no traceback
  const char* msg = lua_tostring(L, 1);
  if (!msg) {
    if (luaL_callmeta(L, 1, "__tostring") && lua_type(L, -1) == LUA_TSTRING) return 1;
    msg = lua_pushfstring(L, "(error object is a %s value)", luaL_typename(L, 1));
  }
  luaL_traceback(L, L, msg, 1);
  return 1;
}

/// __index closure: upvalue 1 = methods table, upvalue 2 = light getter pointer or nil.
int index_dispatch(lua_State* L) {
  // stack: [self, key]
  lua_pushvalue(L, 2);
  if (lua_rawget(L, lua_upvalueindex(1)) != LUA_TNIL) return 1;
  lua_pop(L, 1);
  if (lua_type(L, lua_upvalueindex(2)) == LUA_TLIGHTUSERDATA) {
    auto getter = reinterpret_cast<FieldGetter>(lua_touserdata(L, lua_upvalueindex(2)));
    lua_settop(L, 2);
    if (getter(L) > 0) return 1;
  }
  return 0;  // nil, as for a missing table field
}

// The option names each function reads (its schema's, by function name): smi-lua doc --check
// compares them with the documented option lists (known_options()).
std::mutex g_known_mutex;
std::map<std::string, std::set<std::string>>& known_registry() {
  static std::map<std::string, std::set<std::string>> r;
  return r;
}

}  // namespace

void call(lua_State* L, int nargs, int nresults) {
  const int base = lua_gettop(L) - nargs;  // index of the function
  lua_pushcfunction(L, traceback_handler);
  lua_insert(L, base);
  const int status = lua_pcall(L, nargs, nresults, base);
  lua_remove(L, base);
  if (status != LUA_OK) {
    if (is_failure(L, -1)) {
      std::string msg = failure_message(L, -1), traceback = failure_traceback(L, -1);
      lua_pop(L, 1);
      throw LuaError(msg, true, std::move(traceback));
    }
    std::string msg = lua_tostring(L, -1) ? lua_tostring(L, -1) : "(error without message)";
    lua_pop(L, 1);
    throw LuaError(msg);
  }
}

void register_type_raw(lua_State* L, const char* type, const luaL_Reg* methods, const luaL_Reg* metamethods,
                       lua_CFunction gc, lua_CFunction close, FieldGetter getter) {
  luaL_newmetatable(L, type);  // sets __name, used by luaL_typeerror and tostring
  lua_newtable(L);
  if (methods) luaL_setfuncs(L, methods, 0);
  if (getter)
    lua_pushlightuserdata(L, reinterpret_cast<void*>(getter));
  else
    lua_pushnil(L);
  lua_pushcclosure(L, index_dispatch, 2);
  lua_setfield(L, -2, "__index");
  lua_pushstring(L, type);
  lua_pushcclosure(L, gc, 1);
  lua_setfield(L, -2, "__gc");
  lua_pushstring(L, type);
  lua_pushcclosure(L, close, 1);
  lua_setfield(L, -2, "__close");
  if (metamethods) luaL_setfuncs(L, metamethods, 0);
  protect_metatable(L, -1, type);
  lua_pop(L, 1);
}

void register_table_type(lua_State* L, const char* type, const luaL_Reg* methods, const luaL_Reg* metamethods) {
  if (luaL_newmetatable(L, type)) {  // sets __name, used by luaL_typeerror and tostring
    if (methods) {
      lua_newtable(L);
      luaL_setfuncs(L, methods, 0);
      lua_setfield(L, -2, "__index");
    }
    if (metamethods) luaL_setfuncs(L, metamethods, 0);
    protect_metatable(L, -1, type);
  }
  lua_pop(L, 1);
}

void protect_metatable(lua_State* L, int idx, const char* type) {
  // getmetatable(x) returns a copy without __gc and __close: scripts keep reading __name (type
  // checks such as getmetatable(v).__name == "smi.vec") and the other metamethods, but cannot
  // call a finalizer, and changing the copy changes nothing.
  (void)type;
  idx = lua_absindex(L, idx);
  lua_newtable(L);
  lua_pushnil(L);
  while (lua_next(L, idx)) {
    const bool hidden = lua_type(L, -2) == LUA_TSTRING &&
                        (std::strcmp(lua_tostring(L, -2), "__gc") == 0 || std::strcmp(lua_tostring(L, -2), "__close") == 0);
    if (hidden) {
      lua_pop(L, 1);
      continue;
    }
    lua_pushvalue(L, -2);
    lua_insert(L, -2);
    lua_rawset(L, -4);
  }
  lua_setfield(L, idx, "__metatable");
}

bool close_must_defer(lua_State* L) {
  // A coroutine: the function that resumed it may be a bound function using the object.
  if (!lua_pushthread(L)) {
    lua_pop(L, 1);
    return true;
  }
  lua_pop(L, 1);
  // Level 0 is this __close itself; any C function above it (a bound function that called
  // back into Lua, pcall, a metamethod caller) may hold a pointer into the object.
  lua_Debug ar;
  for (int level = 1; lua_getstack(L, level, &ar); ++level) {
    if (!lua_getinfo(L, "S", &ar)) continue;
    if (ar.what && std::strcmp(ar.what, "C") == 0) return true;
  }
  return false;
}

std::vector<std::string> to_strings(lua_State* L, int idx, const char* what) {
  idx = lua_absindex(L, idx);
  if (!lua_istable(L, idx)) luaL_error(L, "%s must be a table of strings, got %s", what, luaL_typename(L, idx));
  const lua_Integer n = luaL_len(L, idx);
  std::vector<std::string> out;
  out.reserve(static_cast<std::size_t>(n));
  for (lua_Integer i = 1; i <= n; ++i) {
    if (lua_rawgeti(L, idx, i) != LUA_TSTRING)
      luaL_error(L, "%s[%d] must be a string, got %s", what, static_cast<int>(i), luaL_typename(L, -1));
    out.emplace_back(lua_tostring(L, -1));
    lua_pop(L, 1);
  }
  return out;
}

void push_named_vectors(lua_State* L, const std::vector<std::string>& names, const Eigen::MatrixXd& columns) {
  lua_createtable(L, 0, static_cast<int>(names.size()));
  for (std::size_t j = 0; j < names.size(); ++j) {
    push_vec(L, columns.col(static_cast<Eigen::Index>(j)));
    lua_setfield(L, -2, names[j].c_str());
  }
}

// ---------------------------------------------------------------------------------------------
// Options

Options::Options(lua_State* L, int idx, const char* fname) : L_(L), idx_(0), fname_(fname) {
  if (lua_isnoneornil(L, idx)) return;
  if (!lua_istable(L, idx))
    luaL_error(L, "%s: options must be a table, got %s", fname, luaL_typename(L, idx));
  idx_ = lua_absindex(L, idx);
}

int Options::push(const char* key) const {
  if (!idx_) {
    lua_pushnil(L_);
    return LUA_TNIL;
  }
  return lua_getfield(L_, idx_, key);
}

bool Options::has(const char* key) const {
  const bool present = push(key) != LUA_TNIL;
  lua_pop(L_, 1);
  return present;
}

void Options::type_error(const char* key, const char* expected) const {
  luaL_error(L_, "%s: option '%s' must be %s, got %s", fname_, key, expected, luaL_typename(L_, -1));
  std::abort();  // not reached: luaL_error does not return
}

std::optional<double> Options::number(const char* key) const {
  const int t = push(key);
  std::optional<double> out;
  if (t == LUA_TNUMBER)
    out = lua_tonumber(L_, -1);
  else if (t != LUA_TNIL)
    type_error(key, "a number");
  lua_pop(L_, 1);
  return out;
}

double Options::number(const char* key, double def) const { return number(key).value_or(def); }

std::optional<lua_Integer> Options::integer(const char* key) const {
  const int t = push(key);
  std::optional<lua_Integer> out;
  if (t == LUA_TNUMBER) {
    int isint = 0;
    const lua_Integer v = lua_tointegerx(L_, -1, &isint);
    if (!isint) type_error(key, "an integer");
    out = v;
  } else if (t != LUA_TNIL) {
    type_error(key, "an integer");
  }
  lua_pop(L_, 1);
  return out;
}

lua_Integer Options::integer(const char* key, lua_Integer def) const { return integer(key).value_or(def); }

std::optional<std::string> Options::string(const char* key) const {
  const int t = push(key);
  std::optional<std::string> out;
  if (t == LUA_TSTRING)
    out = lua_tostring(L_, -1);
  else if (t != LUA_TNIL)
    type_error(key, "a string");
  lua_pop(L_, 1);
  return out;
}

std::string Options::string(const char* key, const std::string& def) const { return string(key).value_or(def); }

bool Options::boolean(const char* key, bool def) const {
  const int t = push(key);
  bool out = def;
  if (t == LUA_TBOOLEAN)
    out = lua_toboolean(L_, -1);
  else if (t != LUA_TNIL)
    type_error(key, "a boolean");
  lua_pop(L_, 1);
  return out;
}

std::map<std::string, std::set<std::string>> known_options() {
  const std::lock_guard<std::mutex> lock(g_known_mutex);
  return known_registry();
}

void record_known_options(const std::string& fname, const std::vector<std::string>& keys) {
  const std::lock_guard<std::mutex> lock(g_known_mutex);
  auto& into = known_registry()[fname];
  into.insert(keys.begin(), keys.end());
}

std::string unknown_option_message(lua_State* L, int idx, const char* fname, const std::vector<std::string>& known) {
  idx = lua_absindex(L, idx);
  // The keys in name order: of several unknown options the one named is the same every run
  // (the table's traversal order changes from process to process).
  std::vector<std::string> keys;
  lua_pushnil(L);
  while (lua_next(L, idx)) {
    lua_pop(L, 1);  // keep the key
    if (lua_type(L, -1) == LUA_TSTRING) keys.emplace_back(lua_tostring(L, -1));  // positional: the caller's
  }
  std::sort(keys.begin(), keys.end());
  const std::string who = fname ? fname : "options";
  for (const std::string& key : keys) {
    if (std::find(known.begin(), known.end(), key) != known.end()) continue;
    // The nearest known key within 2 edits (typos are the usual cause), else the whole list.
    const std::string* best = nullptr;
    std::size_t best_d = 3;
    for (const std::string& k : known)
      if (const std::size_t d = smi::name_distance(k, key); d < best_d) best_d = d, best = &k;
    if (best) return who + ": unknown option '" + key + "' (did you mean '" + *best + "'?)";
    std::string list;
    for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
    return who + ": unknown option '" + key + "'; known options: " + list;
  }
  return {};
}

// ---------------------------------------------------------------------------------------------
// Result setters

void set_number(lua_State* L, const char* key, double v) {
  lua_pushnumber(L, v);
  lua_setfield(L, -2, key);
}
void set_integer(lua_State* L, const char* key, lua_Integer v) {
  lua_pushinteger(L, v);
  lua_setfield(L, -2, key);
}
void set_string(lua_State* L, const char* key, const std::string& v) {
  lua_pushlstring(L, v.data(), v.size());
  lua_setfield(L, -2, key);
}
void set_boolean(lua_State* L, const char* key, bool v) {
  lua_pushboolean(L, v);
  lua_setfield(L, -2, key);
}
void set_vec(lua_State* L, const char* key, Eigen::VectorXd v) {
  push_vec(L, std::move(v));
  lua_setfield(L, -2, key);
}
void set_funcs(lua_State* L, const luaL_Reg* funcs) { luaL_setfuncs(L, funcs, 0); }

void raise_failure(lua_State* L, const char* msg, const char* traceback) {
  push_failure(L, msg, traceback);
  lua_error(L);
  std::abort();  // not reached: lua_error does not return
}

void raise_from_binding(lua_State* L, const char* msg) {
  if (called_from_stdlib(L, 1)) {
    push_failure(L, msg);
    lua_error(L);
  }
  luaL_error(L, "%s", msg);
  std::abort();  // not reached: luaL_error does not return
}

void error_message(char* buf, std::size_t size, const char* fname, const char* what) {
  const std::string mark = std::string(fname) + ": ";
  const std::string w = what;
  int nested = 0;
  std::size_t last = std::string::npos;
  for (std::size_t at = w.find(mark); at != std::string::npos; at = w.find(mark, at + mark.size())) {
    ++nested;
    last = at;
  }
  if (nested == 0) {
    std::snprintf(buf, size, "%s: %s", fname, what);
    return;
  }
  // The cause, without the inner traceback (the outer one, added by the runtime, shows the path).
  std::string cause = w.substr(last + mark.size());
  if (const auto tb = cause.find("\nstack traceback:"); tb != std::string::npos) cause.resize(tb);
  // A level below said how deep it was already: count on from there.
  int depth = nested + 1;
  const std::string tail = std::string(" nested ") + fname + " calls deep)";
  if (cause.size() > tail.size() && cause.compare(cause.size() - tail.size(), tail.size(), tail) == 0) {
    const auto open = cause.rfind(" (raised ");
    if (open != std::string::npos) {
      depth = std::atoi(cause.c_str() + open + 9) + nested;
      cause.resize(open);
    }
  }
  std::snprintf(buf, size, "%s: %s (raised %d nested %s calls deep)", fname, cause.c_str(), depth, fname);
}

}  // namespace smi::lua
