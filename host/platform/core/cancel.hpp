// SPDX-License-Identifier: MIT
#pragma once
// The run's one cancellation token: Lua-free, set by whatever must stop the run and read by
// everything that runs long. Setters: the signal handler (Ctrl-C, SIGTERM, SIGHUP), the
// deadline of --timeout (armed by the runtime, noticed by the first reader past it), Lua's
// allocator at --max-memory, and os.exit / --dry-run (reason exit with the status). Readers:
// the Lua instruction hook (vm/limits), the kernels (poll() in their outer loops, every few ms:
// a relaxed atomic load, plus a clock read when a deadline is armed), the evaluator between
// solver runs, and the watchdog. Nothing is called back: a reader only reads the reason and
// throws smi::Interrupted with its message (the binding layer turns that into a Lua error).
//
// The first reason wins: a Ctrl-C after the deadline passed still reports the timeout, an
// os.exit after a Ctrl-C still exits 130. Thread-safe; stop() is async-signal-safe (a lock-free
// compare-and-swap), so the signal handler calls it.
#include <chrono>
#include <cstdint>
#include <string>
#include <atomic>
#include <csignal>

namespace smi::cancel {

using Clock = std::chrono::steady_clock;

/// Why a run must stop. `detail` carries the signal number (signal), the exit status (exit) or
/// the ceiling in MB (memory).
enum class Reason : int { none = 0, signal = 1, timeout = 2, memory = 3, exit = 4 };

class Token {
 public:
  /// Sets the reason unless one is set already (the first wins); true if this call set it.
  /// Async-signal-safe.
  bool stop(Reason why, int detail = 0) noexcept;
  /// Clears `why` if it is the reason set (Lua's allocator: a refused request that fitted
  /// after a garbage collection).
  void lift(Reason why) noexcept;
  /// Arms the deadline `seconds` from now (capped at 1e9 s); seconds <= 0 clears it.
  void arm_deadline(double seconds) noexcept;
  /// Arms the deadline at `when`, reported as "--timeout <seconds> s".
  void arm_deadline(Clock::time_point when, double seconds) noexcept;
  void clear_deadline() noexcept;
  /// Clears the reason and the deadline (a new chunk starts); an exit request is kept when
  /// `keep_exit` (os.exit ends the run, whatever chunk comes next).
  void reset(bool keep_exit = false) noexcept;

  /// The reason set, without reading the clock (Lua's allocator asks at every allocation).
  Reason raised() const noexcept { return static_cast<Reason>(state_.load(std::memory_order_relaxed) & 0xff); }
  /// The reason, the deadline included: a passed deadline sets `timeout` (if nothing else was).
  Reason reason() const noexcept;
  int detail() const noexcept { return static_cast<int>(state_.load(std::memory_order_relaxed) >> 8); }
  bool stop_requested() const noexcept { return reason() != Reason::none; }
  /// The seconds of --timeout armed (0 = none).
  double timeout_seconds() const noexcept { return timeout_s_.load(std::memory_order_relaxed); }
  /// "" while the run may go on; else what stopped it: "interrupted", "interrupted by SIGTERM",
  /// "timeout: the run took longer than --timeout 3 s; ...", "memory limit exceeded: ...".
  std::string message() const;
  /// Throws smi::Interrupted with message() once a reason is set.
  void poll() const;

 private:
  // The reason in the low byte, its detail above: one word, so a reader never sees a reason
  // with another's detail, and the first reason wins by one compare-and-swap.
  mutable std::atomic<std::int64_t> state_{0};
  std::atomic<long long> deadline_ns_{0};  // of Clock's epoch; 0 = none
  std::atomic<double> timeout_s_{0};
};

/// The process's token: the one the signal handler reaches, and the one a runtime's
/// RunContext (core/run_context.hpp) hands to the bindings and kernels.
Token& process_token() noexcept;

/// "SIGINT", "SIGTERM", "SIGHUP" ("a signal" for others).
const char* signal_name(int sig) noexcept;

// Shorthands on process_token() for the kernels' loops (and their tests).

/// Arms a deadline `seconds` from now (the run's --timeout); seconds <= 0 clears it.
inline void set_deadline(double seconds) { process_token().arm_deadline(seconds); }
inline void set_deadline(Clock::time_point when, double seconds) { process_token().arm_deadline(when, seconds); }
/// Stops the run as SIGINT would (a test's Ctrl-C). Signal-safe.
inline void request_interrupt() noexcept { process_token().stop(Reason::signal, SIGINT); }
/// Clears the reason and the deadline.
inline void reset() noexcept { process_token().reset(); }
/// "" while work may go on; otherwise the reason's message.
inline std::string reason() { return process_token().message(); }
/// True once a reason is set or the deadline passed (cheap; no allocation).
inline bool stop_requested() noexcept { return process_token().stop_requested(); }
/// Throws smi::Interrupted with the reason's message once stop_requested().
inline void poll() { process_token().poll(); }

/// Polls a token at most once per `every` calls (for loops whose iterations take nanoseconds).
class Poller {
 public:
  explicit Poller(unsigned every = 4096, const Token& token = process_token())
      : token_(token), every_(every ? every : 1) {}
  void operator()() {
    if (++count_ >= every_) {
      count_ = 0;
      token_.poll();
    }
  }

 private:
  const Token& token_;
  unsigned every_;
  unsigned count_ = 0;
};

}  // namespace smi::cancel
