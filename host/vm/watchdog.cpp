// SPDX-License-Identifier: MIT
#include "vm/watchdog.hpp"

#include <chrono>
#include <cstdio>
#include <string>
#include <unistd.h>

#include "platform/core/cancel.hpp"

namespace smi::vm {

Watchdog::Watchdog(const cancel::Token& token, double grace_s) : token_(token), grace_s_(grace_s) {}

Watchdog::~Watchdog() {
  quit_ = true;
  if (thread_.joinable()) thread_.join();
}

void Watchdog::arm() {
  armed_ = true;
  if (!thread_.joinable()) thread_ = std::thread([this] { loop(); });  // started on first use
}

void Watchdog::disarm() { armed_ = false; }

void Watchdog::loop() {
  using Clock = std::chrono::steady_clock;
  bool seen = false;
  Clock::time_point since{};
  while (!quit_) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    if (!armed_ || !token_.stop_requested()) {
      seen = false;
      continue;
    }
    if (!seen) {
      seen = true;
      since = Clock::now();
      continue;
    }
    if (std::chrono::duration<double>(Clock::now() - since).count() < grace_s_) continue;
    const std::string why = token_.message();
    if (why.empty() || !armed_) {
      seen = false;
      continue;
    }
    const cancel::Reason r = token_.reason();
    const int status = r == cancel::Reason::exit ? token_.detail() : r == cancel::Reason::signal ? 130 : 1;
    char msg[512];
    const int n = std::snprintf(msg, sizeof msg,
                                "smi-lua: %s\nsmi-lua: the run did not stop within %g s of that: it is stuck in code "
                                "that cannot be interrupted (a string pattern that backtracks, a __gc finalizer that "
                                "does not return, or a C function); the process ends here\n",
                                why.c_str(), grace_s_);
    if (n > 0) (void)!::write(2, msg, static_cast<std::size_t>(n < static_cast<int>(sizeof msg) ? n : sizeof msg - 1));
    ::_exit(status);
  }
}

}  // namespace smi::vm
