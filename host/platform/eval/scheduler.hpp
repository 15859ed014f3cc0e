// SPDX-License-Identifier: MIT
#pragma once
// Runs solver processes, at most `concurrency` at a time, on the calling thread. Completion is
// reported through a callback on that same thread, so the caller (the Lua binding) can parse
// outputs and write the store without locks; results are placed by job id, so the order in
// which processes finish never changes what a study computes.
// No threads here: a solver slot is a child process waited for with poll/waitpid on the caller's
// thread, a different job from the kernels' thread pool (core/thread_pool.hpp).
#include <cstddef>
#include <deque>
#include <functional>
#include <string>
#include <sys/types.h>
#include <vector>

#include "platform/eval/process.hpp"

namespace smi::eval {

struct Job {
  std::size_t id = 0;   // the caller's handle (a row index)
  std::string key;      // the run's store key (an executor that outlives smi-lua records it)
  int attempt = 1;      // 1 for the first attempt, 2 for the first retry, ...
  SpawnSpec spec;
  double timeout = 0;   // seconds; 0 = none
  /// Called just before the launch (prepares the work directory); an exception makes the job
  /// end as SpawnFailed with the exception's message as reason.
  std::function<void()> prepare;
};

struct Outcome {
  enum Kind { Exited, Signaled, TimedOut, SpawnFailed };
  std::size_t id = 0;
  Kind kind = Exited;
  int exit_code = 0;     // Exited
  int wait_status = 0;   // raw waitpid status (Exited, Signaled)
  double seconds = 0;    // wall time from launch to reaping
  std::string reason;    // "" for exit status 0, else why it failed, ready for a record
  bool ok() const { return kind == Exited && exit_code == 0; }
};

class Scheduler {
 public:
  /// `kill_grace`: seconds between SIGTERM and SIGKILL to a timed-out process group.
  explicit Scheduler(int concurrency, double kill_grace = 1.0);
  /// Kills (SIGKILL) and reaps every process group still running, then every solver descendant
  /// that escaped its group and was reparented to us (see become_subreaper): an exception or a
  /// Lua error unwinding through the caller, or a plain end, leaves no solver process behind.
  ~Scheduler();
  Scheduler(const Scheduler&) = delete;
  Scheduler& operator=(const Scheduler&) = delete;

  /// Queues a job; jobs start in the order submitted.
  void submit(Job job);
  /// Launches no further queued jobs (running ones finish and are reported).
  void stop_launching() { stopping_ = true; }

  /// Runs until no job is queued or running. on_done(outcome) is called once per job as it ends
  /// and may submit() more (retries) or stop_launching(); on_tick() is called about every
  /// `tick` seconds and after each event (progress display). An exception from either callback
  /// propagates; the Scheduler's destructor then kills the process groups still running.
  void run(const std::function<void(const Outcome&)>& on_done, const std::function<void()>& on_tick,
           double tick = 0.2);

  std::size_t running() const { return running_.size(); }
  std::size_t queued() const { return queue_.size(); }
  /// Most processes that ever ran at the same time (tests use it to see overlap).
  std::size_t peak_running() const { return peak_; }

 private:
  struct Running {
    Job job;
    pid_t pid;
    double started;
    double term_sent = 0;  // when SIGTERM went to the group after a timeout (0 = not yet)
    int pidfd = -1;        // readable when the process exits (Linux >= 5.3), -1 if unavailable
  };
  /// Sleeps until a running process may have exited, a timeout or grace period is due, or
  /// `max_wait` seconds have passed.
  void wait_for_event(double max_wait);
  void launch_ready(const std::function<void(const Outcome&)>& on_done);
  bool reap(const std::function<void(const Outcome&)>& on_done);
  void kill_all();

  int concurrency_;
  double grace_;
  bool stopping_ = false;
  std::deque<Job> queue_;
  std::vector<Running> running_;
  std::size_t peak_ = 0;
};

}  // namespace smi::eval
