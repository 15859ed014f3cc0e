// SPDX-License-Identifier: MIT
#include "luax/run_context.hpp"

namespace smi::lua {
namespace {
const char kContextKey = 0;  // its address is the registry key
}

RunContext& run_context(lua_State* L) {
  lua_rawgetp(L, LUA_REGISTRYINDEX, &kContextKey);
  auto* c = static_cast<RunContext*>(lua_touserdata(L, -1));
  lua_pop(L, 1);
  if (c) return *c;
  static RunContext outside_a_run = [] {
    RunContext d;
    d.quiet = true;
    return d;
  }();
  return outside_a_run;
}

void set_run_context(lua_State* L, RunContext* ctx) {
  lua_pushlightuserdata(L, ctx);
  lua_rawsetp(L, LUA_REGISTRYINDEX, &kContextKey);
}

const cancel::Token& cancel_token(lua_State* L) {
  static const cancel::Token never;  // outside a run nothing stops a kernel
  const RunContext& ctx = run_context(L);
  return ctx.cancel ? *ctx.cancel : never;
}

void warn(lua_State* L, std::string_view source, std::string_view text) { run_context(L).warnings.warn(source, text); }

void check_stop_now(lua_State* L) {
  // The runtime's hook (vm/limits) reads the token; luax does not know it, Lua does.
  if (lua_Hook h = lua_gethook(L)) lua_sethook(L, h, LUA_MASKCOUNT, 1);
}

void stop_run(lua_State* L, cancel::Reason why, int detail) {
  if (cancel::Token* t = run_context(L).cancel) t->stop(why, detail);
  check_stop_now(L);
}

}  // namespace smi::lua
