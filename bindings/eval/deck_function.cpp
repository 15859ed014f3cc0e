// A command model's deck made by a Lua function of the point (template = function(p) ... end): the function
// runs with no I/O so that a deck can compute (per-node stiffnesses,
// log-scaled inputs) without the study's evaluation depending on anything but the point.
//  * The model keeps a copy of the function whose _ENV is a fresh table holding only the pure
//    globals (string, math, table, utf8 and the base functions that touch nothing outside Lua);
//    any other global name raises an error naming it. Its other upvalues (local helpers, tables
//    of constants) are copied by value when the model is made.
//  * While it runs, the sandbox policy refuses every file and program access (Policy::io_barred),
//    which also holds for the helper functions it calls through its upvalues.
#include <cstring>
#include <fmt/format.h>

#include "bindings/eval/model.hpp"
#include "luax/luax.hpp"
#include "luax/policy.hpp"

namespace smi::bind::eval {
namespace {

constexpr const char* kBarred =
    "a deck function runs without I/O (no files, no programs); give it what it needs through the point "
    "or the model's constants";

const char* const kPureBase[] = {"assert", "error",  "ipairs",   "next",     "pairs",    "pcall",  "rawequal",
                                 "rawget", "rawlen", "rawset",   "select",   "setmetatable", "getmetatable",
                                 "tonumber", "tostring", "type", "xpcall", "_VERSION"};
const char* const kPureLibs[] = {"string", "math", "table", "utf8"};

int dump_writer(lua_State*, const void* p, size_t sz, void* ud) {
  static_cast<std::string*>(ud)->append(static_cast<const char*>(p), sz);
  return 0;
}

/// __index of the pure environment: a global the deck function may not see.
int missing_global(lua_State* L) {
  const char* k = lua_tostring(L, 2);
  return luaL_error(L, "deck function: global '%s' is not available: %s (it sees string, math, table, utf8 and "
                       "the pure base functions)", k ? k : "?", kBarred);
}

/// Pushes the pure environment, copying its libraries from `src` (the function's own _ENV).
void push_pure_env(lua_State* L, int src) {
  src = lua_absindex(L, src);
  lua_newtable(L);
  const bool have = lua_istable(L, src);
  for (const char* name : kPureBase) {
    if (!have) break;
    lua_getfield(L, src, name);
    lua_setfield(L, -2, name);
  }
  for (const char* name : kPureLibs) {
    if (!have || lua_getfield(L, src, name) != LUA_TTABLE) {
      if (have) lua_pop(L, 1);
      continue;
    }
    lua_newtable(L);  // a copy: the deck function cannot change the study's string table
    lua_pushnil(L);
    while (lua_next(L, -3)) {
      lua_pushvalue(L, -2);
      lua_insert(L, -2);
      lua_rawset(L, -4);
    }
    lua_setfield(L, -3, name);
    lua_pop(L, 1);
  }
  lua_createtable(L, 0, 1);
  lua_pushcfunction(L, missing_global);
  lua_setfield(L, -2, "__index");
  lua_setmetatable(L, -2);
}

/// Runs under lua::call: [fn, point] -> [deck text]. The policy bars I/O around the call; the
/// barrier is lifted before any error goes on (the inner pcall catches it first).
int deck_trampoline(lua_State* L) {
  lua::Policy& pol = lua::policy(L);
  const char* before = pol.io_barred;
  pol.io_barred = kBarred;
  const int status = lua_pcall(L, 1, 1, 0);
  pol.io_barred = before;
  if (status != LUA_OK) return lua_error(L);
  if (lua_type(L, -1) != LUA_TSTRING)
    return luaL_error(L, "the deck function must return the deck text (a string), got %s", luaL_typename(L, -1));
  return 1;
}

}  // namespace

void push_pure_function(lua_State* L, int idx, const char* fname) {
  idx = lua_absindex(L, idx);
  if (lua_type(L, idx) != LUA_TFUNCTION || lua_iscfunction(L, idx))
    luaL_error(L, "%s: option 'template' as a function must be a Lua function(p) returning the deck text", fname);
  std::string code;
  lua_pushvalue(L, idx);
  const int dumped = lua_dump(L, dump_writer, &code, 0);
  lua_pop(L, 1);
  if (dumped != 0) luaL_error(L, "%s: the template function could not be copied", fname);
  if (luaL_loadbufferx(L, code.data(), code.size(), "=(deck function)", "b") != LUA_OK) lua_error(L);
  const int copy = lua_gettop(L);
  for (int i = 1;; ++i) {
    const char* name = lua_getupvalue(L, idx, i);
    if (!name) break;
    if (std::strcmp(name, "_ENV") == 0) {
      push_pure_env(L, -1);
      lua_remove(L, -2);
    } else if (*name == 0 || std::strcmp(name, "(no name)") == 0) {
      luaL_error(L, "%s: the template function has no debug information (stripped), so its environment cannot "
                    "be replaced; define it in the study's source", fname);
    }
    lua_setupvalue(L, copy, i);
  }
}

DeckFunctionScope::DeckFunctionScope(lua_State* L, int model_idx, Model& m) : m_(m) {
  if (!m.ev || !m.ev->config().deck_function) return;
  lua_getiuservalue(L, model_idx, 2);
  const int fn = lua_gettop(L);
  const auto* cfg = &m.ev->config();
  m.ev->set_deck_function([L, fn, cfg](const Eigen::VectorXd& x) {
    lua_pushcfunction(L, deck_trampoline);
    lua_pushvalue(L, fn);
    lua_createtable(L, 0, static_cast<int>(cfg->inputs.size() + cfg->constants.size()));
    for (const auto& [k, v] : cfg->constants) {
      if (v.is_number) lua_pushnumber(L, v.number);
      else lua_pushlstring(L, v.text.data(), v.text.size());
      lua_setfield(L, -2, k.c_str());
    }
    for (std::size_t j = 0; j < cfg->inputs.size(); ++j) {
      lua_pushnumber(L, x[static_cast<Eigen::Index>(j)]);
      lua_setfield(L, -2, cfg->inputs[j].c_str());
    }
    lua::call(L, 2, 1);
    std::size_t n = 0;
    const char* s = lua_tolstring(L, -1, &n);
    std::string deck(s, n);
    lua_pop(L, 1);
    return deck;
  });
  active_ = true;
}

DeckFunctionScope::~DeckFunctionScope() {
  if (active_) m_.ev->set_deck_function({});
}

}  // namespace smi::bind::eval
