// SPDX-License-Identifier: MIT
#include "platform/core/thread_pool.hpp"

#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "platform/core/cancel.hpp"
#include "platform/core/machine.hpp"

namespace smi::pool {

void run_tasks(long n, int threads, const std::function<void(long)>& task, const cancel::Token& stop) {
  if (n <= 0) return;
  threads = static_cast<int>(std::max(1L, std::min<long>(machine::cap_threads(threads), n)));
  if (threads <= 1) {
    for (long i = 0; i < n; ++i) {
      stop.poll();
      task(i);
    }
    return;
  }
  std::atomic<long> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr first;
  std::mutex first_mutex;
  auto worker = [&] {
    try {
      for (long i = next++; i < n && !failed.load(std::memory_order_relaxed); i = next++) {
        stop.poll();
        task(i);
      }
    } catch (...) {  // plain C++ only (no Lua here): carried to the caller and rethrown
      const std::lock_guard<std::mutex> lock(first_mutex);
      if (!first) first = std::current_exception();
      failed = true;
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(static_cast<std::size_t>(threads - 1));
  try {
    for (int w = 1; w < threads; ++w) pool.emplace_back(worker);
  } catch (...) {  // a thread that cannot start (resource limits): the started ones and the caller finish the loop
  }
  worker();
  for (auto& t : pool) t.join();
  if (first) std::rethrow_exception(first);
}

}  // namespace smi::pool
