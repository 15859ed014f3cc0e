// SPDX-License-Identifier: MIT
// The one thread pool (core/thread_pool.hpp): a worker's exception reaches the caller (never
// std::terminate), a failure or a cancel stops the handing out of tasks, and every element is
// computed exactly once whatever the thread count.
#include <catch2/catch.hpp>
#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include "platform/core/cancel.hpp"
#include "platform/core/errors.hpp"
#include "platform/core/thread_pool.hpp"

using namespace smi;

TEST_CASE("a task's exception thrown on a worker thread is rethrown on the caller's") {
  cancel::reset();
  const auto caller = std::this_thread::get_id();
  std::atomic<int> thrown_elsewhere{0};
  // Every task not on the caller's thread throws; with one core everything runs inline and the
  // last task throws instead, so the test holds on any machine.
  REQUIRE_THROWS_WITH(pool::parallel_for(64, 2,
                                         [&](long i) {
                                           std::this_thread::sleep_for(std::chrono::microseconds(200));
                                           if (std::this_thread::get_id() != caller) {
                                             ++thrown_elsewhere;
                                             throw Error("worker failed at " + std::to_string(i));
                                           }
                                           if (i == 63) throw Error("worker failed at 63");
                                         }),
                      Catch::StartsWith("worker failed at"));
}

TEST_CASE("after the first failure no further task starts") {
  cancel::reset();
  std::atomic<long> started{0};
  REQUIRE_THROWS_AS(pool::parallel_for(2000, 2,
                                       [&](long i) {
                                         ++started;
                                         if (i == 0) throw InvalidArgument("bad input");
                                         std::this_thread::sleep_for(std::chrono::microseconds(500));
                                       }),
                    InvalidArgument);
  CHECK(started.load() < 100);  // the old loops ran all 2000 tasks (about a second) before rethrowing
}

TEST_CASE("a cancel (Ctrl-C, --timeout) stops the loop between tasks with Interrupted") {
  cancel::reset();
  std::atomic<long> done{0};
  REQUIRE_THROWS_WITH(pool::parallel_for(100000, 2,
                                         [&](long i) {
                                           if (i == 10) cancel::request_interrupt();
                                           ++done;
                                         }),
                      Catch::StartsWith("interrupted"));
  CHECK(done.load() < 1000);
  cancel::reset();
  cancel::set_deadline(0.05);
  std::atomic<long> blocks{0};
  REQUIRE_THROWS_WITH(pool::parallel_blocks(1000000, 2, 1e13,
                                            [&](Eigen::Index, Eigen::Index) {
                                              ++blocks;
                                              std::this_thread::sleep_for(std::chrono::milliseconds(1));
                                            }),
                      Catch::StartsWith("timeout"));
  CHECK(blocks.load() < 1000000);
  cancel::reset();
}

TEST_CASE("every element once, whatever the thread count") {
  cancel::reset();
  for (int threads : {1, 2, 3, 100000}) {
    std::vector<int> hits(10007, 0);
    pool::parallel_blocks(static_cast<Eigen::Index>(hits.size()), threads, 1e9, [&](Eigen::Index b, Eigen::Index e) {
      for (Eigen::Index i = b; i < e; ++i) hits[static_cast<std::size_t>(i)]++;
    });
    for (int h : hits) REQUIRE(h == 1);
    std::vector<int> once(513, 0);
    pool::parallel_for(513, threads, [&](long i) { once[static_cast<std::size_t>(i)]++; });
    for (int h : once) REQUIRE(h == 1);
  }
}
