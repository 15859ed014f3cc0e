#include "vm/limits.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "luax/policy.hpp"
#include "platform/core/cancel.hpp"

namespace smi::vm {
namespace {

using Clock = std::chrono::steady_clock;

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
  if (lim.abort == Abort::none) {
    if (lim.interrupted || cancel::interrupt_requested())  // Ctrl-C, or a signal handler elsewhere
      lim.abort = Abort::interrupt;
    else if (lim.timeout_s > 0 && Clock::now() >= lim.deadline)
      lim.abort = Abort::timeout;
    else {
      arm_normal(L, lim);  // a coroutine left with a sticky hook by an earlier chunk
      return;
    }
  }
  arm_sticky(L, lim);
  if (lim.abort == Abort::exit) {
    lua_pushlightuserdata(L, lua::exit_sentinel());
    lua_error(L);
  }
  char buf[256];
  luaL_where(L, 0);  // in a hook, level 0 is the Lua function being run: the script's file:line
  lua_pushstring(L, abort_message(lim, buf, sizeof buf));
  lua_concat(L, 2);
  lua_error(L);
}

Limits* g_sigint_limits = nullptr;  // the run Ctrl-C stops (lua.c's globalL)

constexpr int kStopSignals[] = {SIGINT, SIGTERM, SIGHUP};

extern "C" void on_sigint(int sig) {
  std::signal(sig, SIG_DFL);  // a second signal before the hook runs kills the process
  if (Limits* lim = g_sigint_limits) {
    lim->interrupted = sig;
    cancel::request_interrupt();  // kernels running in C++ see it too
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
    const std::size_t ceiling = lim->mem_limit + (lim->abort == Abort::memory ? kMemorySlack : 0);
    const std::size_t external = lim->external ? *lim->external : 0;
    if (lim->mem_used + external - old + nsize > ceiling) {
      if (lim->abort == Abort::none) {
        lim->abort = Abort::memory;
        if (lim->main) lua_sethook(lim->main, hook, LUA_MASKCOUNT, 1);
      }
      lim->refused = nsize;
      return nullptr;  // Lua raises "not enough memory"
    }
  }
  // Lua answers most refusals with an emergency collection and one retry of the same request:
  // if the retry fits, the live data do not exceed the limit after all, so the abort is lifted
  // (the hook then re-arms itself normally).
  if (lim->refused == nsize && lim->abort == Abort::memory && lim->mem_used - old + nsize <= lim->mem_limit)
    lim->abort = Abort::none;
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
  if (lim.abort != Abort::exit) lim.abort = Abort::none;
  lim.interrupted = 0;
  cancel::reset();
  if (lim.timeout_s > 0) {
    // Capped at 1e9 s (31 years): --timeout 1e10 in nanoseconds overflowed the clock's 64 bits
    // into a deadline in the past, and the run stopped at once "after 1e+10 s".
    lim.deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                      std::chrono::duration<double>(std::min(lim.timeout_s, 1e9)));
    cancel::set_deadline(lim.deadline, lim.timeout_s);
  }
  arm_normal(lim.main, lim);
}

void end_chunk(lua_State*) { cancel::reset(); }

void trip(lua_State* L, Abort why) {
  Limits& lim = limits(L);
  if (lim.abort == Abort::none || why == Abort::exit) lim.abort = why;
  arm_sticky(L, lim);
}

const char* abort_message(const Limits& lim, char* buf, std::size_t size) {
  switch (lim.abort) {
    case Abort::interrupt:
      // Ctrl-C keeps lua.c's word; SIGTERM/SIGHUP (timeout, Slurm, systemd, a closed terminal) say which
      if (lim.interrupted > 0 && lim.interrupted != SIGINT)
        std::snprintf(buf, size, "interrupted by %s", signal_name(lim.interrupted));
      else
        std::snprintf(buf, size, "interrupted!");
      break;
    case Abort::timeout:
      std::snprintf(buf, size, "timeout: the run took longer than --timeout %g s; raise --timeout to allow more",
                    lim.timeout_s);
      break;
    case Abort::memory:
      std::snprintf(buf, size,
                    "memory limit exceeded: the Lua heap would pass --max-memory %zu MB; raise --max-memory to "
                    "allow more",
                    lim.mem_limit >> 20);
      break;
    default:
      return nullptr;
  }
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

const char* signal_name(int sig) {
  switch (sig) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    case SIGHUP: return "SIGHUP";
    default: return "a signal";
  }
}

}  // namespace smi::vm
