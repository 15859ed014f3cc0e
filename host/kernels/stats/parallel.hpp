#pragma once
// Splits [0, n) into `threads` contiguous blocks run on std::threads. Each output element is
// written by exactly one block with the same arithmetic whatever the split, so results do not
// depend on the thread count.
#include <Eigen/Core>
#include <thread>
#include <vector>

namespace smi::detail {

/// Calls body(begin, end) on blocks; runs inline when `work` (a cost estimate) is small.
template <class F>
void parallel_blocks(Eigen::Index n, int threads, double work, F&& body) {
  if (threads <= 1 || work < 2e5 || n < 2) {
    body(Eigen::Index{0}, n);
    return;
  }
  std::vector<std::thread> pool;
  const Eigen::Index per = (n + threads - 1) / threads;
  for (int t = 1; t < threads; ++t) {
    const Eigen::Index b = t * per, e = std::min<Eigen::Index>(n, b + per);
    if (b < e) pool.emplace_back([&body, b, e] { body(b, e); });
  }
  body(Eigen::Index{0}, std::min<Eigen::Index>(n, per));
  for (auto& th : pool) th.join();
}

}  // namespace smi::detail
