// SPDX-License-Identifier: MIT
#pragma once
// Limits a run cannot escape: --timeout, --max-memory, Ctrl-C and os.exit.
//
// Each works the way lua.c handles Ctrl-C: something sets a flag and arms an instruction hook
// that raises an error. The flag is the run's cancellation token (core/cancel.hpp), which kernels,
// the evaluator and the watchdog read too. Unlike lua.c the flag is sticky: once tripped, the hook is re-armed to
// fire at every instruction (on the thread that tripped it and on the main thread), so a
// script that wraps the loop in pcall gets the error again at its very next instruction and
// unwinds to the host. The host clears the flag when the chunk has ended (REPL: next prompt).
#include <cstddef>
#include <lua.hpp>

#include "platform/core/cancel.hpp"

namespace smi::vm {

struct Limits {
  lua_State* main = nullptr;
  /// The run's one cancellation token (core/cancel.hpp): the signal handler, the allocator and
  /// os.exit set it, the hook reads it (and the deadline of --timeout it carries).
  cancel::Token* token = nullptr;
  // --timeout (0 = none): armed on the token when a chunk starts, checked every kCheckEvery instructions
  double timeout_s = 0;
  // --max-memory (0 = none): bytes of Lua heap in use and the ceiling
  std::size_t mem_limit = 0;
  std::size_t mem_used = 0;
  const std::size_t* external = nullptr;  // C++ heap held by boxes (luax/memory.hpp), same ceiling
  std::size_t refused = 0;  // size of a request refused once (Lua collects garbage and retries)

  static constexpr int kCheckEvery = 10000;
};

/// The allocator handed to lua_newstate (ud = Limits*): refuses growth beyond mem_limit (Lua then
/// raises "not enough memory") and stops the token with reason memory; shrinking never fails, as
/// Lua requires.
void* limited_alloc(void* ud, void* ptr, std::size_t osize, std::size_t nsize);

/// Stores `lim` in the state's extra space (inherited by coroutines) and arms the count hook.
void install_limits(lua_State* L, Limits* lim);
Limits& limits(lua_State* L);

/// Starts a chunk: clears the token (but an os.exit request), arms its deadline with --timeout,
/// re-arms the hook.
void begin_chunk(lua_State* L);
/// Ends a chunk: clears the deadline (kernels called later, REPL, run); the reason stays for
/// the host's report until the next chunk starts.
void end_chunk(lua_State* L);
/// The message the hook raises for the token's reason ("interrupted!", "timeout: ..."); nullptr
/// for none and exit.
const char* abort_message(const cancel::Token& token, char* buf, std::size_t size);

/// SIGINT, SIGTERM and SIGHUP handling while a chunk runs (lua.c's laction): the handler stops
/// the token with the signal and arms the hook; a second signal before the hook ran kills the
/// process, as in lua.c. All three stop a run the same way (what `timeout`, Slurm and systemd
/// send is SIGTERM; a closed terminal sends SIGHUP): the solver process groups are killed, stored
/// runs are kept.
void catch_sigint(lua_State* L);
void release_sigint();
/// "SIGINT", "SIGTERM", "SIGHUP".
inline const char* signal_name(int sig) { return cancel::signal_name(sig); }

}  // namespace smi::vm
