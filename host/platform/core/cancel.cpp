// SPDX-License-Identifier: MIT
#include "platform/core/cancel.hpp"

#include <algorithm>
#include <cstdio>

#include "platform/core/errors.hpp"

namespace smi::cancel {
namespace {

static_assert(std::atomic<std::int64_t>::is_always_lock_free, "Token::stop must be async-signal-safe");

std::int64_t pack(Reason why, int detail) noexcept {
  return static_cast<std::int64_t>(static_cast<std::uint64_t>(static_cast<std::int64_t>(detail)) << 8) | static_cast<int>(why);
}

long long now_ns() noexcept {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch()).count();
}

}  // namespace

bool Token::stop(Reason why, int detail) noexcept {
  std::int64_t none = 0;
  return state_.compare_exchange_strong(none, pack(why, detail));
}

void Token::lift(Reason why) noexcept {
  std::int64_t s = state_.load();
  if ((s & 0xff) == static_cast<int>(why)) state_.compare_exchange_strong(s, 0);
}

void Token::arm_deadline(double seconds) noexcept {
  if (seconds <= 0) {
    clear_deadline();
    return;
  }
  // (capped at 1e9 s: --timeout 1e10 in nanoseconds overflowed the clock's 64 bits into a
  // deadline in the past, and the run stopped at once "after 1e+10 s")
  arm_deadline(Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                  std::chrono::duration<double>(std::min(seconds, 1e9))),
               seconds);
}

void Token::arm_deadline(Clock::time_point when, double seconds) noexcept {
  timeout_s_.store(seconds);
  const long long ns = std::chrono::duration_cast<std::chrono::nanoseconds>(when.time_since_epoch()).count();
  deadline_ns_.store(ns > 0 ? ns : 1);
}

void Token::clear_deadline() noexcept {
  deadline_ns_.store(0);
  timeout_s_.store(0);
}

void Token::reset(bool keep_exit) noexcept {
  clear_deadline();
  if (keep_exit && raised() == Reason::exit) return;
  state_.store(0);
}

Reason Token::reason() const noexcept {
  const Reason r = raised();
  if (r != Reason::none) return r;
  const long long d = deadline_ns_.load(std::memory_order_relaxed);
  if (d == 0 || now_ns() < d) return Reason::none;
  // the deadline passed: it becomes the reason, unless another came first
  std::int64_t none = 0;
  state_.compare_exchange_strong(none, pack(Reason::timeout, 0));
  return raised();
}

std::string Token::message() const {
  char buf[200];
  switch (reason()) {
    case Reason::none:
      return "";
    case Reason::signal:
      // Ctrl-C is "interrupted"; SIGTERM/SIGHUP (timeout, Slurm, systemd, a closed terminal) say which
      if (detail() > 0 && detail() != SIGINT) return std::string("interrupted by ") + signal_name(detail());
      return "interrupted";
    case Reason::timeout:
      std::snprintf(buf, sizeof buf, "timeout: the run took longer than --timeout %g s; raise --timeout to allow more",
                    timeout_seconds());
      return buf;
    case Reason::memory:
      std::snprintf(buf, sizeof buf,
                    "memory limit exceeded: the Lua heap would pass --max-memory %d MB; raise --max-memory to "
                    "allow more",
                    detail());
      return buf;
    case Reason::exit:
      return "interrupted";  // os.exit (or --dry-run) while C++ waits: stop as Ctrl-C would
  }
  return "";
}

void Token::poll() const {
  if (!stop_requested()) return;
  const std::string why = message();
  if (why.empty()) return;  // lifted between the two reads
  throw Interrupted(why);
}

Token& process_token() noexcept {
  static Token token;
  return token;
}

const char* signal_name(int sig) noexcept {
  switch (sig) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    case SIGHUP: return "SIGHUP";
    default: return "a signal";
  }
}

}  // namespace smi::cancel
