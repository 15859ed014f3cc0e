// SPDX-License-Identifier: MIT
#pragma once
// The last resort behind --timeout and Ctrl-C. The instruction hook stops Lua code and kernels
// poll the run's cancellation token, but some code can do neither: one string.find with a pathological pattern
// (C code, no hook), a __gc finalizer (Lua turns hooks off inside it), a C++ call that does not
// poll. A thread watches the run; once the cancellation token has said stop and the chunk has
// not ended `grace` seconds later, it prints why on stderr and ends the process (exit status 1
// for a timeout, 130 for Ctrl-C): the only safe way to stop a thread stuck in C code.
#include <atomic>
#include <thread>

#include "platform/core/cancel.hpp"

namespace smi::vm {

class Watchdog {
 public:
  /// Reads `token` (the run's); it must outlive the watchdog.
  explicit Watchdog(const cancel::Token& token, double grace_s = 2.0);
  ~Watchdog();
  Watchdog(const Watchdog&) = delete;
  Watchdog& operator=(const Watchdog&) = delete;

  /// While armed, a stop request that is not honoured within the grace ends the process.
  void arm();
  void disarm();

 private:
  void loop();
  const cancel::Token& token_;
  double grace_s_;
  std::atomic<bool> armed_{false};
  std::atomic<bool> quit_{false};
  std::thread thread_;
};

}  // namespace smi::vm
