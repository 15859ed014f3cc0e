// SPDX-License-Identifier: MIT
#include "platform/eval/scheduler.hpp"

#include "platform/core/machine.hpp"

#include <algorithm>
#include <cmath>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <ctime>
#include <fmt/format.h>
#include <fcntl.h>
#include <poll.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include "platform/core/errors.hpp"

namespace smi::eval {
namespace {

void sleep_seconds(double s) {
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(s);
  ts.tv_nsec = static_cast<long>((s - static_cast<double>(ts.tv_sec)) * 1e9);
  nanosleep(&ts, nullptr);
}

/// A descriptor that becomes readable when `pid` exits, or -1 where the kernel has no pidfd_open.
int open_pidfd(pid_t pid) {
#ifdef SYS_pidfd_open
  const long fd = ::syscall(SYS_pidfd_open, pid, 0);
  if (fd >= 0) {
    ::fcntl(static_cast<int>(fd), F_SETFD, FD_CLOEXEC);
    return static_cast<int>(fd);
  }
#else
  (void)pid;
#endif
  return -1;
}

}  // namespace

Scheduler::Scheduler(int concurrency, double kill_grace) : concurrency_(concurrency), grace_(kill_grace) {
  if (concurrency < 1) throw InvalidArgument(fmt::format("concurrency must be >= 1, got {}", concurrency));
  // Local solver processes at once: no more than the machine has cores (200 ran at once).
  concurrency_ = machine::cap_threads(concurrency);
}

Scheduler::~Scheduler() { kill_all(); }

void Scheduler::kill_all() {
  for (const Running& r : running_) signal_group(r.pid, SIGKILL);
  for (const Running& r : running_) {
    int st = 0;
    while (::waitpid(r.pid, &st, 0) < 0 && errno == EINTR) {
    }
    if (r.pidfd >= 0) ::close(r.pidfd);
    solver_reaped(r.pid);
  }
  running_.clear();
  // Solver descendants that left their process group (setsid) and were reparented to us.
  reap_escaped_descendants();
}

void Scheduler::submit(Job job) { queue_.push_back(std::move(job)); }

void Scheduler::launch_ready(const std::function<void(const Outcome&)>& on_done) {
  while (!stopping_ && !queue_.empty() && running_.size() < static_cast<std::size_t>(concurrency_)) {
    Job job = std::move(queue_.front());
    queue_.pop_front();
    const double t0 = monotonic_seconds();
    pid_t pid = -1;
    std::string error;
    try {
      if (job.prepare) job.prepare();
      pid = spawn_process(job.spec);
    } catch (const std::exception& e) {
      error = e.what();
    }
    if (pid < 0) {
      Outcome o;
      o.id = job.id;
      o.kind = Outcome::SpawnFailed;
      o.reason = error;
      on_done(o);
      continue;
    }
    running_.push_back({std::move(job), pid, t0, 0, open_pidfd(pid)});
    peak_ = std::max(peak_, running_.size());
  }
}

bool Scheduler::reap(const std::function<void(const Outcome&)>& on_done) {
  bool any = false;
  const double now = monotonic_seconds();
  for (std::size_t i = 0; i < running_.size();) {
    Running& r = running_[i];
    int st = 0;
    const pid_t w = ::waitpid(r.pid, &st, WNOHANG);
    if (w == 0) {
      // Still running: enforce the timeout on the whole group, SIGTERM first so a solver can
      // flush, SIGKILL after the grace period.
      if (r.job.timeout > 0 && now - r.started > r.job.timeout) {
        if (r.term_sent == 0) {
          signal_group(r.pid, SIGTERM);
          r.term_sent = now;
        } else if (now - r.term_sent > grace_) {
          signal_group(r.pid, SIGKILL);
        }
      }
      ++i;
      continue;
    }
    if (w < 0 && errno == EINTR) continue;
    // The leader is gone; anything it left in its group goes too (a solver's helper processes
    // must not outlive the evaluation they belong to).
    signal_group(r.pid, SIGKILL);
    Outcome o;
    o.id = r.job.id;
    o.seconds = now - r.started;
    o.wait_status = st;
    if (w < 0) {
      o.kind = Outcome::Signaled;
      o.reason = fmt::format("lost track of process {}: {}", r.pid, std::strerror(errno));
    } else if (r.term_sent != 0) {
      o.kind = Outcome::TimedOut;
      o.reason = fmt::format("timeout after {:g} s (process group killed)", r.job.timeout);
    } else if (WIFEXITED(st)) {
      o.kind = Outcome::Exited;
      o.exit_code = WEXITSTATUS(st);
      if (o.exit_code != 0) o.reason = describe_wait_status(st);
    } else {
      o.kind = Outcome::Signaled;
      o.reason = describe_wait_status(st);
    }
    if (r.pidfd >= 0) ::close(r.pidfd);
    solver_reaped(r.pid);
    running_.erase(running_.begin() + static_cast<std::ptrdiff_t>(i));
    any = true;
    on_done(o);
  }
  return any;
}

void Scheduler::wait_for_event(double max_wait) {
  const double now = monotonic_seconds();
  double wait = max_wait;
  bool all_fds = true;
  std::vector<pollfd> fds;
  for (const Running& r : running_) {
    if (r.job.timeout > 0)  // wake up for the timeout, then for the end of the grace period
      wait = std::min(wait, r.term_sent == 0 ? r.started + r.job.timeout - now : r.term_sent + grace_ - now);
    if (r.pidfd < 0) all_fds = false;
    fds.push_back({r.pidfd, POLLIN, 0});
  }
  wait = std::max(wait, 0.0005);  // a SIGKILLed process may take a moment to be reapable
  if (all_fds && !fds.empty()) {
    // Woken by the kernel the moment a process exits: no polling latency, no busy waiting.
    ::poll(fds.data(), fds.size(), static_cast<int>(std::ceil(wait * 1000)));
  } else {
    // No pidfd: short naps (2 ms at most keeps a trivial solver's added latency small and
    // costs a few hundred waitpid calls a second while a long run goes on).
    sleep_seconds(std::min(wait, 0.002));
  }
}

void Scheduler::run(const std::function<void(const Outcome&)>& on_done, const std::function<void()>& on_tick,
                    double tick) {
  double last_tick = monotonic_seconds();
  launch_ready(on_done);
  while (!running_.empty() || (!stopping_ && !queue_.empty())) {
    const bool event = reap(on_done);
    launch_ready(on_done);
    const double now = monotonic_seconds();
    if (event || now - last_tick >= tick) {
      if (on_tick) on_tick();
      last_tick = now;
    }
    if (event) continue;
    wait_for_event(std::max(0.0, last_tick + tick - now));
  }
}

}  // namespace smi::eval
