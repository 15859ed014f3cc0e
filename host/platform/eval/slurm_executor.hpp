// SPDX-License-Identifier: MIT
#pragma once
// Solver runs as Slurm job arrays. Each batch of queued runs becomes one array per chunk of at
// most MaxArraySize tasks, throttled with %N; a manifest maps the array index to the run's work
// folder and a job wrapper (job.sh) runs the solver there under smi-lua's own per-run timeout and
// writes .smi/exit atomically. That file decides the outcome; one squeue call per polling cycle
// (5 s backing off to 60 s, reset on change) follows every live job, and sacct is asked only why
// a job left the queue without an exit file. Node failures and preemptions are requeued without
// counting against the run. Submitted jobs are recorded in the store's pending table, so a rerun
// reattaches to them instead of submitting again.
#include <deque>
#include <map>
#include <string>
#include <vector>

#include "platform/eval/executor.hpp"
#include "platform/eval/slurm_cli.hpp"

namespace smi::eval {

class SlurmExecutor final : public Executor {
 public:
  SlurmExecutor(ExecutorConfig cfg, PendingTable* pending, std::string runs_dir, std::string tag);
  /// Cancels every live job with one scancel (unless detached); their pending rows go too.
  ~SlurmExecutor() override;
  void submit(Job job) override { queue_.push_back(std::move(job)); }
  void stop_launching() override { stopping_ = true; }
  void run(const std::function<void(const Outcome&)>& on_done, const std::function<void()>& on_tick,
           double tick) override;
  std::size_t running() const override;

  /// Scheduler commands issued so far (bench/, tests).
  struct Calls {
    long sbatch = 0, squeue = 0, sacct = 0, scancel = 0, scontrol = 0;
  };
  const Calls& calls() const { return calls_; }
  std::size_t submitted() const { return submitted_; }    // array tasks sbatch'ed
  std::size_t reattached() const { return reattached_; }  // runs found in the pending table
  std::size_t requeued() const { return requeued_; }      // infrastructure failures resubmitted

  /// The wrapper every array task runs (also printed by --dry-run).
  static std::string job_script();
  /// The sbatch argv for one array chunk (without the script and its arguments).
  static std::vector<std::string> sbatch_argv(const ExecutorConfig& cfg, const std::string& job_name,
                                              std::size_t tasks, double timeout, const std::string& log_dir);
  /// --time in minutes for runs with smi-lua's own `timeout`: that plus a margin (Slurm checks
  /// limits about every 30 s and rounds to minutes), or the configured time; -1 = none.
  static double time_limit_minutes(const ExecutorConfig& cfg, double timeout);

 private:
  struct Task {
    Job job;
    std::string job_name, job_id;
    int index = 0;
    TaskState state = TaskState::Unknown;
    std::string state_text, reason, raw_id;
    double gone_since = -1;   // when squeue stopped listing it (or showed it final) without an exit file
    int requeues = 0;         // infrastructure failures so far (not counted against the run)
  };

  void submit_queued(const std::function<void(const Outcome&)>& on_done);
  void submit_chunk(std::vector<Task> chunk);
  bool scan_exit_files(const std::function<void(const Outcome&)>& on_done);
  bool poll_queue(const std::function<void(const Outcome&)>& on_done);  // true on a change
  void judge_gone(const std::function<void(const Outcome&)>& on_done);
  void finish(std::size_t i, Outcome o, const std::function<void(const Outcome&)>& on_done);
  void requeue(std::size_t i, const std::string& why, const std::function<void(const Outcome&)>& on_done);
  void cancel_pending_tasks();
  /// Runs a scheduler command, retrying transient failures until down_after; throws
  /// SchedulerDown then. With `harvest`, runs that end while it waits are reported (exit files
  /// need no scheduler) and on_tick keeps running, so Ctrl-C works and finished runs are stored.
  CommandResult call(const std::vector<std::string>& argv, const char* what, bool harvest = false);
  int max_array();

  ExecutorConfig cfg_;
  PendingTable* pending_;
  std::string runs_dir_, tag_, slurm_dir_;
  std::deque<Job> queue_;
  std::vector<Task> live_;
  std::map<std::string, int> requeues_;  // key -> infrastructure requeues so far
  bool stopping_ = false, stop_done_ = false, down_ = false;
  Calls calls_;
  const std::function<void(const Outcome&)>* on_done_ = nullptr;  // set while run() runs
  const std::function<void()>* on_tick_ = nullptr;
  std::size_t submitted_ = 0, reattached_ = 0, requeued_ = 0;
  int max_array_ = 0;
  int chunks_ = 0;
  double interval_ = 0;
};

}  // namespace smi::eval
