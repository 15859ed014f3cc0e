// SPDX-License-Identifier: MIT
// The run's one cancellation token: it carries the reason and its detail, the first
// reason wins, a passed deadline becomes the reason only if nothing came first, and the readers
// (a kernel's loop through the thread pool, a Poller given the token) stop with the reason's
// message. The old token knew only "interrupted" and "timeout" and had no detail: the memory
// and exit cases below, and the signal's name, did not exist.
#include <catch2/catch.hpp>
#include <csignal>
#include <thread>

#include "platform/core/cancel.hpp"
#include "platform/core/errors.hpp"
#include "platform/core/run_context.hpp"
#include "platform/core/thread_pool.hpp"

using namespace smi;
using cancel::Reason;

TEST_CASE("the token carries the reason and its detail") {
  cancel::Token t;
  REQUIRE(t.reason() == Reason::none);
  REQUIRE(t.message().empty());
  REQUIRE_NOTHROW(t.poll());

  REQUIRE(t.stop(Reason::signal, SIGTERM));
  REQUIRE(t.reason() == Reason::signal);
  REQUIRE(t.detail() == SIGTERM);
  REQUIRE(t.message() == "interrupted by SIGTERM");

  cancel::Token c;
  c.stop(Reason::signal, SIGINT);
  REQUIRE(c.message() == "interrupted");  // Ctrl-C keeps its short word

  cancel::Token m;
  m.stop(Reason::memory, 64);
  REQUIRE(m.message() ==
          "memory limit exceeded: the Lua heap would pass --max-memory 64 MB; raise --max-memory to allow more");

  cancel::Token e;
  e.stop(Reason::exit, 3);
  REQUIRE(e.reason() == Reason::exit);
  REQUIRE(e.detail() == 3);
  e.stop(Reason::exit, -1);  // a later exit does not change the status
  REQUIRE(e.detail() == 3);
}

TEST_CASE("the first reason wins") {
  cancel::Token t;
  REQUIRE(t.stop(Reason::signal, SIGINT));
  REQUIRE_FALSE(t.stop(Reason::exit, 7));
  REQUIRE_FALSE(t.stop(Reason::memory, 1));
  REQUIRE(t.reason() == Reason::signal);
  REQUIRE(t.detail() == SIGINT);

  // a passed deadline is the reason only when nothing came first...
  cancel::Token d;
  d.arm_deadline(cancel::Clock::now() - std::chrono::seconds(1), 3);
  REQUIRE(d.raised() == Reason::none);  // not noticed until read
  REQUIRE(d.reason() == Reason::timeout);
  REQUIRE(d.message() == "timeout: the run took longer than --timeout 3 s; raise --timeout to allow more");
  REQUIRE_FALSE(d.stop(Reason::signal, SIGINT));  // ...and then a Ctrl-C does not replace it
  REQUIRE(d.reason() == Reason::timeout);

  cancel::Token s;
  s.stop(Reason::exit, 0);
  s.arm_deadline(cancel::Clock::now() - std::chrono::seconds(1), 3);
  REQUIRE(s.reason() == Reason::exit);
}

TEST_CASE("memory is lifted when Lua's retry fits; a new chunk keeps an exit request") {
  cancel::Token t;
  t.stop(Reason::memory, 8);
  t.lift(Reason::signal);  // not the reason set: nothing happens
  REQUIRE(t.reason() == Reason::memory);
  t.lift(Reason::memory);
  REQUIRE(t.reason() == Reason::none);

  t.stop(Reason::exit, 4);
  t.reset(/*keep_exit=*/true);
  REQUIRE(t.reason() == Reason::exit);
  REQUIRE(t.detail() == 4);
  t.reset();
  REQUIRE(t.reason() == Reason::none);
  REQUIRE(t.detail() == 0);
}

TEST_CASE("kernels read the token: a pool's loop and a Poller stop with its reason") {
  // The process token (the one a runtime hands to kernels) stopped from another thread, as the
  // signal handler does: the thread pool, which polls before every task, throws its message.
  cancel::reset();
  std::thread setter([] {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    cancel::process_token().stop(Reason::signal, SIGHUP);
  });
  std::string what;
  try {
    pool::parallel_for(1L << 40, 2, [](long) { std::this_thread::sleep_for(std::chrono::microseconds(50)); });
  } catch (const Interrupted& e) {
    what = e.what();
  }
  setter.join();
  REQUIRE(what == "interrupted by SIGHUP");
  cancel::reset();
  REQUIRE_NOTHROW(cancel::poll());

  // A token of one's own, read through a Poller: memory stops a loop as a signal does.
  cancel::Token mine;
  cancel::Poller poll(4, mine);
  for (int i = 0; i < 10; ++i) poll();
  mine.stop(Reason::memory, 16);
  REQUIRE_THROWS_WITH([&] { for (;;) poll(); }(), Catch::StartsWith("memory limit exceeded"));
}

TEST_CASE("a run's warning sink collects every warning, printing only when asked") {
  WarningSink quiet(false);
  quiet.warn("smi.kde_bd", "2 data point(s) lie outside [0, 1]");
  quiet.warn("smi.csv.read", "x.csv: 1 duplicated data row");
  const auto w = quiet.collected();
  REQUIRE(w.size() == 2);
  REQUIRE(w[0] == "smi.kde_bd: 2 data point(s) lie outside [0, 1]");
  REQUIRE(w[1] == "smi.csv.read: x.csv: 1 duplicated data row");
  REQUIRE_FALSE(quiet.prints());
}
