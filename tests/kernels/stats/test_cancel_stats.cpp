// SPDX-License-Identifier: MIT
// Long stats kernels stop when the run is cancelled: a KDE sum over large
// data and the u-pooling Monte Carlo throw smi::Interrupted with the token's reason, also from
// worker threads, instead of running on (49 s past --timeout 3 before).
#include <catch2/catch.hpp>

#include "kernels/stats/kde.hpp"
#include "kernels/stats/upool.hpp"
#include "platform/core/cancel.hpp"
#include "platform/core/errors.hpp"
#include "platform/core/thread_pool.hpp"

using namespace smi;

namespace {
struct PastDeadline {
  PastDeadline() { cancel::set_deadline(cancel::Clock::now() - std::chrono::seconds(1), 2); }
  ~PastDeadline() { cancel::reset(); }
};
}  // namespace

TEST_CASE("a KDE sum over large data stops at the deadline, on any thread") {
  Eigen::VectorXd data = Eigen::VectorXd::LinSpaced(200000, 0, 1);
  Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(5000, 0, 1).array().square();  // not uniform: direct sums
  PastDeadline d;
  REQUIRE_THROWS_WITH(stats::kde_pdf(data, 0.01, x, 2), Catch::StartsWith("timeout: "));
  REQUIRE_THROWS_AS(stats::kde_pdf(data, 0.01, x, 1), Interrupted);
}

TEST_CASE("the u-pooling Monte Carlo stops when interrupted") {
  cancel::reset();
  cancel::request_interrupt();
  stats::UpoolMcSettings s;
  s.replications = 100000;
  s.seed = 99;  // a sample no other test caches
  REQUIRE_THROWS_WITH(stats::upool_null_sample(5000, s), "interrupted");  // the Monte Carlo (sort path)
  REQUIRE_THROWS_WITH(stats::upool_threshold(40, 0.95, s), "interrupted");  // through the threshold (network path)
  cancel::reset();
}

TEST_CASE("parallel_blocks carries a worker's exception to the caller and caps threads") {
  cancel::reset();
  int calls = 0;
  REQUIRE_THROWS_WITH(pool::parallel_blocks(1000, 100000, 1e9,
                                              [&](Eigen::Index b, Eigen::Index) {
                                                if (b >= 500) throw Error("worker failed");
                                                ++calls;
                                              }),
                      "worker failed");
  // without a cancellation every element is computed exactly once, whatever the split
  std::vector<int> hits(1000, 0);
  pool::parallel_blocks(1000, 3, 1e9, [&](Eigen::Index b, Eigen::Index e) {
    for (Eigen::Index i = b; i < e; ++i) hits[static_cast<std::size_t>(i)]++;
  });
  for (int h : hits) REQUIRE(h == 1);
}
