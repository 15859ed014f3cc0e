#include "platform/core/cancel.hpp"

#include <algorithm>

#include <atomic>
#include <cstdio>

#include "platform/core/errors.hpp"

namespace smi::cancel {
namespace {

// Nanoseconds of Clock's epoch; 0 = no deadline. Atomics so that a watchdog thread, a signal
// handler and kernel worker threads may all read them.
std::atomic<long long> g_deadline_ns{0};
std::atomic<double> g_timeout_s{0};
std::atomic<int> g_interrupted{0};
static_assert(std::atomic<int>::is_always_lock_free, "request_interrupt must be signal-safe");

long long now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch()).count();
}

}  // namespace

void set_deadline(double seconds) {
  if (seconds <= 0) {
    g_deadline_ns.store(0);
    g_timeout_s.store(0);
    return;
  }
  // (capped at 1e9 s: a longer span in nanoseconds overflows the clock's 64 bits)
  set_deadline(Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                  std::chrono::duration<double>(std::min(seconds, 1e9))),
               seconds);
}

void set_deadline(Clock::time_point when, double seconds) {
  g_timeout_s.store(seconds);
  const long long ns = std::chrono::duration_cast<std::chrono::nanoseconds>(when.time_since_epoch()).count();
  g_deadline_ns.store(ns > 0 ? ns : 1);
}

void request_interrupt() noexcept { g_interrupted.store(1, std::memory_order_relaxed); }

void reset() noexcept {
  g_interrupted.store(0);
  g_deadline_ns.store(0);
  g_timeout_s.store(0);
}

bool stop_requested() noexcept {
  if (g_interrupted.load(std::memory_order_relaxed)) return true;
  const long long d = g_deadline_ns.load(std::memory_order_relaxed);
  return d != 0 && now_ns() >= d;
}

bool interrupt_requested() noexcept { return g_interrupted.load(std::memory_order_relaxed) != 0; }

std::string reason() {
  if (g_interrupted.load()) return "interrupted";
  const long long d = g_deadline_ns.load();
  if (d != 0 && now_ns() >= d) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "timeout: the run took longer than --timeout %g s; raise --timeout to allow more",
                  g_timeout_s.load());
    return buf;
  }
  return "";
}

void poll() {
  if (!stop_requested()) return;
  std::string why = reason();
  if (why.empty()) return;  // the deadline was cleared between the two reads
  throw Interrupted(why);
}

}  // namespace smi::cancel
