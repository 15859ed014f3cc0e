// SPDX-License-Identifier: MIT
#include "vm/limits.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "luax/policy.hpp"
#include "platform/core/cancel.hpp"

namespace smi::vm {
namespace {

/// Once the memory ceiling was hit, error handling (messages, tracebacks) may still allocate
/// this much more, so the error can reach the host.
constexpr std::size_t kMemorySlack = 4u << 20;

Limits** slot(lua_State* L) { return static_cast<Limits**>(lua_getextraspace(L)); }

void hook(lua_State* L, lua_Debug*);

/// The hook of a chunk in normal running: every kCheckEvery instructions (a negligible cost),
/// always, because coroutines inherit it when they are created: that is how a timeout or a
/// Ctrl-C reaches a loop running inside a coroutine (the SIGINT handler arms the main thread).
void arm_normal(lua_State* L, const Limits&) { lua_sethook(L, hook, LUA_MASKCOUNT, Limits::kCheckEvery); }

/// After an abort: fire at every instruction, here and on the main thread, so pcall cannot
/// swallow the error for more than one instruction.
void arm_sticky(lua_State* L, const Limits& lim) {
  lua_sethook(L, hook, LUA_MASKCOUNT, 1);
  if (lim.main && lim.main != L) lua_sethook(lim.main, hook, LUA_MASKCOUNT, 1);
}

void hook(lua_State* L, lua_Debug*) {
  Limits& lim = limits(L);
  const cancel::Reason why = lim.token ? lim.token->reason() : cancel::Reason::none;
  if (why == cancel::Reason::none) {
    arm_normal(L, lim);  // a coroutine left with a sticky hook by an earlier chunk
    return;
  }
  arm_sticky(L, lim);
  if (why == cancel::Reason::exit) {
    lua_pushlightuserdata(L, lua::exit_sentinel());
    lua_error(L);
  }
  char buf[256];
  luaL_where(L, 0);  // in a hook, level 0 is the Lua function being run: the script's file:line
  lua_pushstring(L, abort_message(*lim.token, buf, sizeof buf));
  lua_concat(L, 2);
  lua_error(L);
}

Limits* g_sigint_limits = nullptr;  // the run Ctrl-C stops (lua.c's globalL)

constexpr int kStopSignals[] = {SIGINT, SIGTERM, SIGHUP};

extern "C" void on_sigint(int sig) {
  std::signal(sig, SIG_DFL);  // a second signal before the hook runs kills the process
  if (Limits* lim = g_sigint_limits) {
    if (lim->token) lim->token->stop(cancel::Reason::signal, sig);  // kernels in C++ read it too
    lua_sethook(lim->main, hook, LUA_MASKCALL | LUA_MASKRET | LUA_MASKLINE | LUA_MASKCOUNT, 1);
  }
}

}  // namespace

void* limited_alloc(void* ud, void* ptr, std::size_t osize, std::size_t nsize) {
  auto* lim = static_cast<Limits*>(ud);
  const std::size_t old = ptr ? osize : 0;  // for a new block osize is the object's type
  if (nsize == 0) {
    std::free(ptr);
    lim->mem_used -= old;
    return nullptr;
  }
  if (lim->mem_limit && nsize > old) {
    const bool tripped = lim->token && lim->token->raised() == cancel::Reason::memory;
    const std::size_t ceiling = lim->mem_limit + (tripped ? kMemorySlack : 0);
    const std::size_t external = lim->external ? *lim->external : 0;
    if (lim->mem_used + external - old + nsize > ceiling) {
      if (lim->token && lim->token->stop(cancel::Reason::memory, static_cast<int>(lim->mem_limit >> 20)) && lim->main)
        lua_sethook(lim->main, hook, LUA_MASKCOUNT, 1);
      lim->refused = nsize;
      return nullptr;  // Lua raises "not enough memory"
    }
  }
  // Lua answers most refusals with an emergency collection and one retry of the same request:
  // if the retry fits, the live data do not exceed the limit after all, so the abort is lifted
  // (the hook then re-arms itself normally).
  if (lim->refused == nsize && lim->token && lim->token->raised() == cancel::Reason::memory &&
      lim->mem_used - old + nsize <= lim->mem_limit)
    lim->token->lift(cancel::Reason::memory);
  lim->refused = 0;
  void* p = std::realloc(ptr, nsize);
  if (!p) return nullptr;
  lim->mem_used = lim->mem_used - old + nsize;
  return p;
}

void install_limits(lua_State* L, Limits* lim) {
  *slot(L) = lim;
  lim->main = L;
  arm_normal(L, *lim);
}

Limits& limits(lua_State* L) { return **slot(L); }

void begin_chunk(lua_State* L) {
  Limits& lim = limits(L);
  if (lim.token) {
    lim.token->reset(/*keep_exit=*/true);
    if (lim.timeout_s > 0) lim.token->arm_deadline(lim.timeout_s);
  }
  arm_normal(lim.main, lim);
}

void end_chunk(lua_State* L) {
  if (Limits& lim = limits(L); lim.token) lim.token->clear_deadline();
}

const char* abort_message(const cancel::Token& token, char* buf, std::size_t size) {
  const cancel::Reason why = token.reason();
  if (why == cancel::Reason::none || why == cancel::Reason::exit) return nullptr;
  // Ctrl-C keeps lua.c's word; SIGTERM/SIGHUP say which (the token's message)
  const bool ctrl_c = why == cancel::Reason::signal && (token.detail() <= 0 || token.detail() == SIGINT);
  std::snprintf(buf, size, "%s", ctrl_c ? "interrupted!" : token.message().c_str());
  return buf;
}

void catch_sigint(lua_State* L) {
  g_sigint_limits = &limits(L);
  for (int sig : kStopSignals) std::signal(sig, on_sigint);
}

void release_sigint() {
  for (int sig : kStopSignals) std::signal(sig, SIG_DFL);
  g_sigint_limits = nullptr;
}


}  // namespace smi::vm
