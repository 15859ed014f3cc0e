#pragma once
// Splits [0, n) into `threads` contiguous blocks run on std::threads. Each output element is
// written by exactly one block with the same arithmetic whatever the split, so results do not
// depend on the thread count.
#include <Eigen/Core>
#include <algorithm>
#include <exception>
#include <thread>
#include <vector>

#include "kernels/core/cancel.hpp"
#include "kernels/core/machine.hpp"

namespace smi::detail {

/// Calls body(begin, end) on blocks; runs inline when `work` (a cost estimate) is small.
/// `threads` is capped by the machine (a script asking for 100,000 aborted the process). The
/// first exception of a block (smi::Interrupted from cancel::poll, bad_alloc) is rethrown here.
/// Each block is run as sub-blocks of about 1e6 work units with cancel::poll() between them
/// (--timeout and Ctrl-C reach a large KDE sum within milliseconds); elements do not depend on
/// the split, so neither do the results.
template <class F>
void parallel_blocks(Eigen::Index n, int threads, double work, F&& body_whole) {
  threads = machine::cap_threads(threads);
  const double per_element = n > 0 ? work / static_cast<double>(n) : 0;
  const Eigen::Index sub = per_element > 0 ? static_cast<Eigen::Index>(std::max(1.0, 1e6 / per_element)) : n;
  auto body = [&body_whole, sub](Eigen::Index b, Eigen::Index e) {
    for (Eigen::Index s = b; s < e; s += sub) {
      cancel::poll();
      body_whole(s, std::min<Eigen::Index>(e, s + sub));
    }
  };
  if (threads <= 1 || work < 2e5 || n < 2) {
    body(Eigen::Index{0}, n);
    return;
  }
  std::vector<std::thread> pool;
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(threads));
  const Eigen::Index per = (n + threads - 1) / threads;
  for (int t = 1; t < threads; ++t) {
    const Eigen::Index b = t * per, e = std::min<Eigen::Index>(n, b + per);
    if (b < e)
      pool.emplace_back([&body, &errors, t, b, e] {
        try {
          body(b, e);
        } catch (...) {  // plain C++ only (no Lua here): carried to the caller
          errors[static_cast<std::size_t>(t)] = std::current_exception();
        }
      });
  }
  try {
    body(Eigen::Index{0}, std::min<Eigen::Index>(n, per));
  } catch (...) {
    errors[0] = std::current_exception();
  }
  for (auto& th : pool) th.join();
  for (auto& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace smi::detail
