// SPDX-License-Identifier: MIT
#pragma once
// The one thread pool of the kernels: parallel loops whose results never depend on the thread
// count (each task writes only its own outputs, with the same arithmetic whatever the split).
//   * the calling thread works too; threads are capped by the machine (machine::cap_threads)
//   * the run's cancel token (an argument, by default the process's) is polled before every task,
//     so --timeout and Ctrl-C stop a loop between tasks
//   * the first exception of any task (smi::Interrupted, bad_alloc, a kernel error) stops the
//     handing out of further tasks and is rethrown on the calling thread after every worker has
//     joined: never std::terminate, never a task still running after the call returns.
// Plain C++ only: a task calls Lua only through a gate that runs each call alone, protected on
// its own thread (bindings/improve/lua_gate.hpp), so no Lua error crosses the pool.
// Not used by eval's Scheduler: its solver slots are processes reaped on the calling thread.
#include <Eigen/Core>
#include <algorithm>
#include <functional>

#include "platform/core/cancel.hpp"
#include "platform/core/machine.hpp"

namespace smi::pool {

/// Runs task(i) for every i in [0, n), handed out in order as threads free up (for tasks of
/// varying cost). With threads <= 1 (or n <= 1) it runs inline, polling between tasks.
void run_tasks(long n, int threads, const std::function<void(long)>& task,
               const cancel::Token& stop = cancel::process_token());

/// run_tasks for any callable.
template <class F>
void parallel_for(long n, int threads, F&& task, const cancel::Token& stop = cancel::process_token()) {
  run_tasks(n, threads, std::function<void(long)>(std::ref(task)), stop);
}

/// Calls body(begin, end) on contiguous blocks covering [0, n): one block per thread, each cut
/// into sub-blocks of about 1e6 work units (`work` estimates the whole loop's cost) with a
/// cancel poll between them, so a large sum stops within milliseconds. Small loops (work < 2e5)
/// run inline on the calling thread.
template <class F>
void parallel_blocks(Eigen::Index n, int threads, double work, F&& body,
                     const cancel::Token& stop = cancel::process_token()) {
  if (n <= 0) return;
  threads = machine::cap_threads(threads);
  const double per_element = work / static_cast<double>(n);
  const Eigen::Index sub = per_element > 0 ? static_cast<Eigen::Index>(std::max(1.0, 1e6 / per_element)) : n;
  const Eigen::Index blocks = (threads <= 1 || work < 2e5 || n < 2) ? 1 : std::min<Eigen::Index>(threads, n);
  const Eigen::Index per = (n + blocks - 1) / blocks;
  const Eigen::Index subs_per_block = (per + sub - 1) / sub;
  // Task t is sub-block t % subs_per_block of block t / subs_per_block: tasks are handed out
  // in order, so each thread tends to walk one block; which thread runs a task changes nothing.
  run_tasks(static_cast<long>(blocks * subs_per_block), static_cast<int>(blocks), [&](long t) {
    const Eigen::Index blk = t / subs_per_block, s = t % subs_per_block;
    const Eigen::Index b = blk * per + s * sub;
    const Eigen::Index e = std::min({n, blk * per + per, b + sub});
    if (b < e) body(b, e);
  }, stop);
}

}  // namespace smi::pool
