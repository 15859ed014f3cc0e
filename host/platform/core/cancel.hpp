#pragma once
// The run's cancellation token: one per process, Lua-free, set by the host (--timeout, Ctrl-C,
// SIGTERM) and polled by long kernels. Lua's own limits live in an instruction hook that does
// not fire while C++ runs, so every kernel that may run for more than a few milliseconds calls
// cancel::poll() in its outer loops (every few ms: a relaxed atomic load, plus a clock read
// when a deadline is set). poll() throws smi::Interrupted whose message starts with
// "interrupted" or "timeout: ...", which the binding layer turns into a Lua error.
//
// Thread-safe: workers of a parallel kernel poll too (parallel helpers carry the exception to
// the caller). request_interrupt() is async-signal-safe (a lock-free atomic store).
#include <chrono>
#include <string>

namespace smi::cancel {

using Clock = std::chrono::steady_clock;

/// Arms a deadline `seconds` from now (the run's --timeout); seconds <= 0 clears it.
void set_deadline(double seconds);
/// Arms a deadline at `when`, reported as "--timeout <seconds> s".
void set_deadline(Clock::time_point when, double seconds);
/// Asks every polling kernel to stop with "interrupted" (Ctrl-C, SIGTERM). Signal-safe.
void request_interrupt() noexcept;
/// Clears the deadline and the interrupt (the host calls it when a chunk has ended).
void reset() noexcept;

/// "" while work may go on; otherwise the reason: "interrupted" or "timeout: ...".
std::string reason();
/// True once interrupted or past the deadline (cheap; no allocation). Signal-safe.
bool stop_requested() noexcept;
/// True once request_interrupt() was called (and not reset). Signal-safe.
bool interrupt_requested() noexcept;
/// Throws smi::Interrupted with reason() when stop_requested().
void poll();

/// Polls at most once per `every` calls (for loops whose iterations take nanoseconds).
class Poller {
 public:
  explicit Poller(unsigned every = 4096) : every_(every ? every : 1) {}
  void operator()() {
    if (++count_ >= every_) {
      count_ = 0;
      poll();
    }
  }

 private:
  unsigned every_;
  unsigned count_ = 0;
};

}  // namespace smi::cancel
