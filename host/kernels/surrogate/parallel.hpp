#pragma once
// A minimal deterministic parallel loop: tasks 0..n-1 go to `threads` workers as they free up, and
// each task writes only its own outputs, so results never depend on the thread count. The
// first exception of any worker is rethrown on the caller's thread.
#include <algorithm>
#include <atomic>
#include <exception>
#include <thread>
#include <vector>

#include "kernels/core/cancel.hpp"
#include "kernels/core/machine.hpp"

namespace smi::detail {

template <class F>
void parallel_for(long n, int threads, F&& task) {
  threads = static_cast<int>(std::max(1L, std::min<long>(machine::cap_threads(threads), n)));
  // cancel::poll() before each task: --timeout and Ctrl-C stop a long loop between tasks.
  if (threads <= 1) {
    for (long i = 0; i < n; ++i) {
      cancel::poll();
      task(i);
    }
    return;
  }
  std::vector<std::exception_ptr> errors(threads);
  // Tasks are handed out in order as workers free up (their costs vary: local searches,
  // blocks); which worker runs a task never changes what the task computes.
  std::atomic<long> next{0};
  auto worker = [&](int w) {
    try {
      for (long i = next++; i < n; i = next++) {
        cancel::poll();
        task(i);
      }
    } catch (...) {  // plain C++ only (no Lua here): carried to the caller and rethrown
      errors[w] = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  for (int w = 1; w < threads; ++w) pool.emplace_back(worker, w);
  worker(0);
  for (auto& t : pool) t.join();
  for (auto& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace smi::detail
