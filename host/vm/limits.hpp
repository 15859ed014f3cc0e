#pragma once
// Limits a run cannot escape: --timeout, --max-memory, Ctrl-C and os.exit.
//
// Each works the way lua.c handles Ctrl-C: something sets a flag and arms an instruction hook
// that raises an error. Unlike lua.c the flag is sticky: once tripped, the hook is re-armed to
// fire at every instruction (on the thread that tripped it and on the main thread), so a
// script that wraps the loop in pcall gets the error again at its very next instruction and
// unwinds to the host. The host clears the flag when the chunk has ended (REPL: next prompt).
#include <chrono>
#include <csignal>
#include <cstddef>
#include <lua.hpp>

namespace smi::vm {

enum class Abort { none, timeout, interrupt, memory, exit };

struct Limits {
  lua_State* main = nullptr;
  // --timeout (0 = none): deadline of the running chunk, checked every kCheckEvery instructions
  double timeout_s = 0;
  std::chrono::steady_clock::time_point deadline{};
  // --max-memory (0 = none): bytes of Lua heap in use and the ceiling
  std::size_t mem_limit = 0;
  std::size_t mem_used = 0;
  const std::size_t* external = nullptr;  // C++ heap held by boxes (luax/memory.hpp), same ceiling
  std::size_t refused = 0;  // size of a request refused once (Lua collects garbage and retries)
  // set asynchronously by SIGINT, SIGTERM or SIGHUP: the signal's number (0 = none)
  volatile std::sig_atomic_t interrupted = 0;
  Abort abort = Abort::none;
  int exit_code = 0;  // for Abort::exit

  static constexpr int kCheckEvery = 10000;
};

/// The allocator handed to lua_newstate (ud = Limits*): refuses growth beyond mem_limit (Lua then
/// raises "not enough memory") and trips Abort::memory; shrinking never fails, as Lua requires.
void* limited_alloc(void* ud, void* ptr, std::size_t osize, std::size_t nsize);

/// Stores `lim` in the state's extra space (inherited by coroutines) and arms the count hook.
void install_limits(lua_State* L, Limits* lim);
Limits& limits(lua_State* L);

/// Starts a chunk: clears a previous abort (unless it was os.exit), sets the deadline, re-arms,
/// and arms smi::cancel (core/cancel.hpp) with the same deadline for kernels.
void begin_chunk(lua_State* L);
/// Ends a chunk: clears smi::cancel so kernels called later (REPL, next chunk) run.
void end_chunk(lua_State* L);
/// Trips an abort from C++ (os.exit): the hook raises from the next instruction on.
void trip(lua_State* L, Abort why);
/// The message an abort raises ("interrupted!", "timeout: ..."); nullptr for none and exit.
const char* abort_message(const Limits& lim, char* buf, std::size_t size);

/// SIGINT, SIGTERM and SIGHUP handling while a chunk runs (lua.c's laction): the handler records
/// the signal and arms the hook; a second signal before the hook ran kills the process, as in
/// lua.c. All three stop a run the same way (what `timeout`, Slurm and systemd send is SIGTERM;
/// a closed terminal sends SIGHUP): the solver process groups are killed, stored runs are kept.
void catch_sigint(lua_State* L);
void release_sigint();
/// "SIGINT", "SIGTERM", "SIGHUP".
const char* signal_name(int sig);

}  // namespace smi::vm
