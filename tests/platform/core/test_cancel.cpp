// SPDX-License-Identifier: MIT
// The cancellation token: a deadline or an interrupt makes poll() throw smi::Interrupted with
// the reason, from any thread, and reset() lets the next run go on.
#include <catch2/catch.hpp>
#include <thread>

#include "platform/core/cancel.hpp"
#include "platform/core/errors.hpp"
#include "platform/core/machine.hpp"

using namespace smi;

TEST_CASE("no deadline and no interrupt: poll returns") {
  cancel::reset();
  REQUIRE_NOTHROW(cancel::poll());
  REQUIRE(cancel::reason().empty());
}

TEST_CASE("a past deadline throws a timeout naming --timeout") {
  cancel::reset();
  cancel::set_deadline(cancel::Clock::now() - std::chrono::seconds(1), 3);
  REQUIRE(cancel::stop_requested());
  try {
    cancel::poll();
    FAIL("poll did not throw");
  } catch (const Interrupted& e) {
    REQUIRE(std::string(e.what()).rfind("timeout: ", 0) == 0);
    REQUIRE(std::string(e.what()).find("--timeout 3 s") != std::string::npos);
  }
  cancel::reset();
  REQUIRE_NOTHROW(cancel::poll());
}

TEST_CASE("an interrupt from another thread stops a polling loop") {
  cancel::reset();
  std::thread t([] {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    cancel::request_interrupt();
  });
  bool stopped = false;
  std::string what;
  try {
    cancel::Poller poll(16);
    for (;;) poll();
  } catch (const Interrupted& e) {
    stopped = true;
    what = e.what();
  }
  t.join();
  REQUIRE(stopped);
  REQUIRE(what == "interrupted");
  cancel::reset();
}

TEST_CASE("thread counts are capped by the machine") {
  REQUIRE(machine::cores() >= 1);
  REQUIRE(machine::cap_threads(100000) == machine::cores());
  REQUIRE(machine::cap_threads(0) == 1);
  REQUIRE(machine::cap_threads(-5) == 1);
  REQUIRE(machine::cap_threads(1) == 1);
}
