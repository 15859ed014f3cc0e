// SPDX-License-Identifier: MIT
#include "luax/isolated_state.hpp"

#include <cstdio>
#include <cstring>
#include <initializer_list>

#include "luax/gmatch_guard.hpp"
#include "platform/core/errors.hpp"

namespace smi::lua {
namespace {

constexpr int kCheckEvery = 1000;  // instructions between two looks at the token
constexpr int kMaxDepth = 64;      // nesting of copied tables and functions

// What the state's globals hold: an allow-list, as the sandbox's (a function a new Lua adds is
// not there). No setmetatable: nothing in the state gets a __gc or __close to run outside a call.
const char* const kPureBase[] = {"assert", "error",    "ipairs",   "next",   "pairs",    "pcall",
                                 "rawequal", "rawget", "rawlen",   "rawset", "select",   "getmetatable",
                                 "tonumber", "tostring", "type",   "xpcall", "_VERSION"};

struct Lib {
  const char* name;
  std::initializer_list<const char*> fields;
};

// string without dump; math without random and randomseed (a deck is a function of its point).
const Lib kPureLibs[] = {
    {"string",
     {"byte", "char", "find", "format", "gmatch", "gsub", "len", "lower", "match", "pack", "packsize", "rep",
      "reverse", "sub", "unpack", "upper"}},
    {"math",
     {"abs", "acos", "asin", "atan", "ceil", "cos", "deg", "exp", "floor", "fmod", "huge", "log", "max",
      "maxinteger", "min", "mininteger", "modf", "pi", "rad", "sin", "sqrt", "tan", "tointeger", "type", "ult"}},
    {"table", {"concat", "insert", "move", "pack", "remove", "sort", "unpack"}},
    {"utf8", {"char", "charpattern", "codes", "codepoint", "len", "offset"}},
};

const char kFunctionKey = 0;  // registry key of the adopted function

// ---- the state ------------------------------------------------------------------------------

const cancel::Token*& token_slot(lua_State* L) { return *static_cast<const cancel::Token**>(lua_getextraspace(L)); }

void stop_hook(lua_State* L, lua_Debug*) {
  const cancel::Token* t = token_slot(L);
  if (!t || !t->stop_requested()) return;
  lua_sethook(L, stop_hook, LUA_MASKCOUNT, 1);  // at every instruction now: a pcall cannot swallow it
  char msg[256];
  std::snprintf(msg, sizeof msg, "%s", t->message().c_str());
  luaL_error(L, "%s", msg);
}

/// __index of the globals: a name the state does not have.
int missing_global(lua_State* L) {
  const char* k = lua_tostring(L, 2);
  return luaL_error(L,
                    "global '%s' is not available: a deck function runs without I/O, in a Lua state of its own (it "
                    "sees string, math without random, table, utf8 and the pure base functions); give it what it "
                    "needs through the point or the model's constants",
                    k ? k : "?");
}

/// Opens the libraries and replaces the globals by the allow-listed ones (protected).
int setup(lua_State* L) {
  luaL_requiref(L, "_G", luaopen_base, 1);
  luaL_requiref(L, "string", luaopen_string, 1);
  luaL_requiref(L, "math", luaopen_math, 1);
  luaL_requiref(L, "table", luaopen_table, 1);
  luaL_requiref(L, "utf8", luaopen_utf8, 1);
  lua_settop(L, 0);
  lua_pushglobaltable(L);  // 1: the full globals
  lua_newtable(L);         // 2: the state's globals
  for (const char* n : kPureBase) {
    lua_getfield(L, 1, n);
    lua_setfield(L, 2, n);
  }
  for (const Lib& lib : kPureLibs) {
    lua_getfield(L, 1, lib.name);  // 3: the library
    lua_createtable(L, 0, static_cast<int>(lib.fields.size()));  // 4: the state's copy
    for (const char* f : lib.fields) {
      lua_getfield(L, 3, f);
      lua_setfield(L, 4, f);
    }
    if (std::strcmp(lib.name, "string") == 0) {
      guard_gmatch(L, 4);
      lua_pushliteral(L, "");  // strings' methods ("x"):upper() come from this copy
      if (lua_getmetatable(L, -1)) {
        lua_pushvalue(L, 4);
        lua_setfield(L, -2, "__index");
        lua_pop(L, 1);
      }
      lua_pop(L, 1);
    }
    lua_setfield(L, 2, lib.name);
    lua_pop(L, 1);
  }
  lua_createtable(L, 0, 1);
  lua_pushcfunction(L, missing_global);
  lua_setfield(L, -2, "__index");
  lua_setmetatable(L, 2);
  lua_pushvalue(L, 2);
  lua_rawseti(L, LUA_REGISTRYINDEX, LUA_RIDX_GLOBALS);
  return 0;
}

// ---- the copy -------------------------------------------------------------------------------

/// One copy from `from` into the isolated state. Only trivially destructible members: a Lua
/// error (out of memory) in the isolated state unwinds through the functions that use it.
struct Copy {
  lua_State* from = nullptr;
  int pure = 0;  // in `from`: {[function] = "lib.name" | "name"}, its standard functions
  int memo = 0;  // in the isolated state: {[pointer in from] = copy}
  int depth = 0;
  char path[400] = {0};  // where the copy is, for a refusal: "'helper' > 'fh'"
  char error[600] = {0};
};

/// Appends a component to c.path; returns the old length (to restore it).
std::size_t enter(Copy& c, const char* component) {
  const std::size_t n = std::strlen(c.path);
  std::snprintf(c.path + n, sizeof c.path - n, "%s%s", n ? " > " : "", component);
  return n;
}

bool refuse(Copy& c, const char* what) {
  std::snprintf(c.error, sizeof c.error, "%s %s", c.path[0] ? c.path : "the function", what);
  return false;
}

/// What a value that cannot be copied is, for the refusal.
bool refuse_value(Copy& c, int i) {
  char what[160];
  if (lua_type(c.from, i) == LUA_TUSERDATA) {
    if (luaL_testudata(c.from, i, LUA_FILEHANDLE)) {
      std::snprintf(what, sizeof what, "is a file handle");
    } else if (lua_getmetatable(c.from, i)) {
      lua_getfield(c.from, -1, "__name");
      const char* n = lua_type(c.from, -1) == LUA_TSTRING ? lua_tostring(c.from, -1) : nullptr;
      std::snprintf(what, sizeof what, "is a userdata%s%s%s", n ? " (" : "", n ? n : "", n ? ")" : "");
      lua_pop(c.from, 2);
    } else {
      std::snprintf(what, sizeof what, "is a userdata");
    }
  } else {
    std::snprintf(what, sizeof what, "is a %s", luaL_typename(c.from, i));
  }
  return refuse(c, what);
}

bool copy_value(lua_State* to, Copy& c, int i);

bool copy_table(lua_State* to, Copy& c, int i) {
  if (lua_getmetatable(c.from, i)) {
    lua_pop(c.from, 1);
    return refuse(c, "is a table with a metatable");
  }
  if (c.depth >= kMaxDepth || !lua_checkstack(c.from, 4) || !lua_checkstack(to, 6))
    return refuse(c, "is nested too deeply");
  ++c.depth;
  lua_newtable(to);
  const int t = lua_gettop(to);
  lua_pushvalue(to, t);
  lua_rawsetp(to, c.memo, lua_topointer(c.from, i));  // a table met again (a cycle) is this copy
  lua_pushnil(c.from);
  while (lua_next(c.from, i)) {
    char field[80];
    if (lua_type(c.from, -2) == LUA_TSTRING) std::snprintf(field, sizeof field, "field '%.60s'", lua_tostring(c.from, -2));
    else std::snprintf(field, sizeof field, "a field");
    const std::size_t back = enter(c, field);
    const int key = lua_absindex(c.from, -2);
    if (!copy_value(to, c, key) || !copy_value(to, c, lua_gettop(c.from))) {
      lua_pop(c.from, 2);
      return false;
    }
    lua_rawset(to, t);
    lua_pop(c.from, 1);
    c.path[back] = 0;
  }
  --c.depth;
  return true;
}

/// A C function: one of `from`'s standard functions becomes the isolated state's own.
bool copy_cfunction(lua_State* to, Copy& c, int i) {
  lua_pushvalue(c.from, i);
  if (lua_rawget(c.from, c.pure) != LUA_TSTRING) {
    lua_pop(c.from, 1);
    return refuse(c, "is a C function that is not one of the standard string, math, table, utf8 or base functions");
  }
  char name[120];
  std::snprintf(name, sizeof name, "%s", lua_tostring(c.from, -1));
  lua_pop(c.from, 1);
  lua_pushglobaltable(to);
  char* dot = std::strchr(name, '.');
  if (dot) {
    *dot = 0;
    lua_pushstring(to, name);
    if (lua_rawget(to, -2) == LUA_TTABLE) {
      lua_pushstring(to, dot + 1);
      lua_rawget(to, -2);
    } else {
      lua_pushnil(to);
    }
    lua_remove(to, -2);
    *dot = '.';
  } else {
    lua_pushstring(to, name);
    lua_rawget(to, -2);
  }
  lua_remove(to, -2);
  if (lua_type(to, -1) != LUA_TFUNCTION) {
    lua_pop(to, 1);
    char what[200];
    std::snprintf(what, sizeof what, "is %s, which a deck function does not have", name);
    return refuse(c, what);
  }
  return true;
}

int dump_writer(lua_State*, const void* p, size_t sz, void* ud) {
  luaL_addlstring(static_cast<luaL_Buffer*>(ud), static_cast<const char*>(p), sz);
  return 0;
}

/// A Lua function: its code (dumped and loaded: a function compiled from text in this process)
/// with each upvalue copied, _ENV being the isolated state's globals.
bool copy_lua_function(lua_State* to, Copy& c, int i) {
  if (c.depth >= kMaxDepth || !lua_checkstack(c.from, 4) || !lua_checkstack(to, 8))
    return refuse(c, "is nested too deeply");
  ++c.depth;
  luaL_Buffer b;
  luaL_buffinit(to, &b);
  lua_pushvalue(c.from, i);
  const int dumped = lua_dump(c.from, dump_writer, &b, 0);
  lua_pop(c.from, 1);
  luaL_pushresult(&b);
  if (dumped != 0) return refuse(c, "could not be copied");
  std::size_t n = 0;
  const char* code = lua_tolstring(to, -1, &n);
  if (luaL_loadbufferx(to, code, n, "=(deck function)", "b") != LUA_OK) {
    lua_pop(to, 2);
    return refuse(c, "could not be copied");
  }
  lua_remove(to, -2);  // the code
  const int f = lua_gettop(to);
  lua_pushvalue(to, f);
  lua_rawsetp(to, c.memo, lua_topointer(c.from, i));  // a recursive local function refers to itself
  for (int u = 1;; ++u) {
    const char* name = lua_getupvalue(c.from, i, u);
    if (!name) break;
    if (*name == 0 || std::strcmp(name, "(no name)") == 0) {
      lua_pop(c.from, 1);
      return refuse(c, "has no debug information (stripped), so its upvalues cannot be told apart; define it in "
                       "the study's source");
    }
    if (std::strcmp(name, "_ENV") == 0) {
      lua_pushglobaltable(to);
    } else {
      char component[80];
      std::snprintf(component, sizeof component, "'%.60s'", name);
      const std::size_t back = enter(c, component);
      if (!copy_value(to, c, lua_gettop(c.from))) {
        lua_pop(c.from, 1);
        return false;
      }
      c.path[back] = 0;
    }
    lua_setupvalue(to, f, u);
    lua_pop(c.from, 1);
  }
  --c.depth;
  return true;
}

bool copy_value(lua_State* to, Copy& c, int i) {
  i = lua_absindex(c.from, i);
  switch (lua_type(c.from, i)) {
    case LUA_TNIL: lua_pushnil(to); return true;
    case LUA_TBOOLEAN: lua_pushboolean(to, lua_toboolean(c.from, i)); return true;
    case LUA_TNUMBER:
      if (lua_isinteger(c.from, i)) lua_pushinteger(to, lua_tointeger(c.from, i));
      else lua_pushnumber(to, lua_tonumber(c.from, i));
      return true;
    case LUA_TSTRING: {
      std::size_t n = 0;
      const char* s = lua_tolstring(c.from, i, &n);
      lua_pushlstring(to, s, n);
      return true;
    }
    case LUA_TTABLE:
    case LUA_TFUNCTION:
      if (lua_rawgetp(to, c.memo, lua_topointer(c.from, i)) != LUA_TNIL) return true;
      lua_pop(to, 1);
      if (lua_type(c.from, i) == LUA_TTABLE) return copy_table(to, c, i);
      return lua_iscfunction(c.from, i) ? copy_cfunction(to, c, i) : copy_lua_function(to, c, i);
    default: return refuse_value(c, i);
  }
}

/// In the isolated state (protected): [Copy*] -> [function] or [nil] with c.error set.
int copy_entry(lua_State* to) {
  Copy& c = *static_cast<Copy*>(lua_touserdata(to, 1));
  lua_newtable(to);
  c.memo = lua_gettop(to);
  if (!copy_value(to, c, lua_gettop(c.from))) {
    lua_pushnil(to);
    return 1;
  }
  return 1;
}

/// In `from` (protected): [] -> [{[function] = name}] of its globals' standard functions.
int pure_index(lua_State* L) {
  lua_newtable(L);
  const int t = lua_gettop(L);
  lua_pushglobaltable(L);
  const int g = lua_gettop(L);
  for (const char* n : kPureBase) {
    lua_pushstring(L, n);
    if (lua_rawget(L, g) == LUA_TFUNCTION) {
      lua_pushstring(L, n);
      lua_rawset(L, t);
    } else {
      lua_pop(L, 1);
    }
  }
  for (const Lib& l : kPureLibs) {
    const char* lib = l.name;
    lua_pushstring(L, lib);
    if (lua_rawget(L, g) != LUA_TTABLE) {
      lua_pop(L, 1);
      continue;
    }
    lua_pushnil(L);
    while (lua_next(L, -2)) {
      if (lua_type(L, -1) == LUA_TFUNCTION && lua_type(L, -2) == LUA_TSTRING) {
        lua_pushfstring(L, "%s.%s", lib, lua_tostring(L, -2));
        lua_rawset(L, t);  // t[function] = "lib.name"
      } else {
        lua_pop(L, 1);
      }
    }
    lua_pop(L, 1);
  }
  lua_settop(L, t);
  return 1;
}

}  // namespace

IsolatedState::IsolatedState(lua_State* study, const cancel::Token* token) {
  void* ud = nullptr;
  const lua_Alloc alloc = lua_getallocf(study, &ud);
  L_ = lua_newstate(alloc, ud);
  if (!L_) throw Error("cannot make a Lua state for the deck function: not enough memory");
  token_slot(L_) = token;
  lua_pushcfunction(L_, setup);
  if (lua_pcall(L_, 0, 0, 0) != LUA_OK) {
    lua_close(L_);
    L_ = nullptr;
    throw Error("cannot make a Lua state for the deck function: not enough memory");
  }
}

IsolatedState::~IsolatedState() {
  if (L_) lua_close(L_);
}

std::string IsolatedState::adopt_function(lua_State* from, int idx) {
  idx = lua_absindex(from, idx);
  if (!lua_checkstack(from, 8)) return "the function could not be copied (the Lua stack is full)";
  lua_pushcfunction(from, pure_index);
  if (lua_pcall(from, 0, 1, 0) != LUA_OK) {
    lua_pop(from, 1);
    return "the function could not be copied (not enough memory)";
  }
  Copy c;
  c.from = from;
  c.pure = lua_gettop(from);
  lua_pushvalue(from, idx);  // copy_entry copies the value on top of `from`
  lua_settop(L_, 0);
  lua_pushcfunction(L_, copy_entry);
  lua_pushlightuserdata(L_, &c);
  const int status = lua_pcall(L_, 1, 1, 0);
  std::string error;
  if (status != LUA_OK) {
    const char* m = lua_tostring(L_, -1);
    error = std::string("the function could not be copied: ") + (m ? m : "not enough memory");
  } else if (lua_isnil(L_, -1)) {
    error = c.error;
  } else {
    lua_rawsetp(L_, LUA_REGISTRYINDEX, &kFunctionKey);
  }
  lua_settop(L_, 0);
  lua_settop(from, c.pure - 1);
  return error;
}

std::string IsolatedState::call(const std::vector<Field>& fields, const char* what) {
  lua_settop(L_, 0);
  lua_sethook(L_, stop_hook, LUA_MASKCOUNT, kCheckEvery);  // normal pace again after a stop
  struct Args {
    const std::vector<Field>* fields;
    const char* what;
  } args{&fields, what};
  lua_pushcfunction(L_, [](lua_State* L) -> int {
    const Args& a = *static_cast<const Args*>(lua_touserdata(L, 1));
    if (lua_rawgetp(L, LUA_REGISTRYINDEX, &kFunctionKey) != LUA_TFUNCTION)
      return luaL_error(L, "%s: no function was given", a.what);
    lua_createtable(L, 0, static_cast<int>(a.fields->size()));
    for (const Field& f : *a.fields) {
      if (f.is_number) lua_pushnumber(L, f.number);
      else lua_pushlstring(L, f.text.data(), f.text.size());
      lua_setfield(L, -2, f.name.c_str());
    }
    lua_call(L, 1, 1);
    if (lua_type(L, -1) != LUA_TSTRING)
      return luaL_error(L, "%s must return the deck text (a string), got %s", a.what, luaL_typename(L, -1));
    return 1;
  });
  lua_pushlightuserdata(L_, &args);
  const int status = lua_pcall(L_, 1, 1, 0);
  std::size_t n = 0;
  // an error value that is not a string is not converted (its __tostring would run unprotected)
  const char* s = lua_type(L_, -1) == LUA_TSTRING ? lua_tolstring(L_, -1, &n) : nullptr;
  std::string out = s ? std::string(s, n)
                      : std::string(what) + " raised an error that is not a string (a " + luaL_typename(L_, -1) + ")";
  lua_settop(L_, 0);
  lua_gc(L_, LUA_GCCOLLECT);  // what the call made is garbage now: give it back to the study's budget
  if (status != LUA_OK) throw Error(out);
  return out;
}

}  // namespace smi::lua
