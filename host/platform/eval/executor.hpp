// SPDX-License-Identifier: MIT
#pragma once
// Where solver runs execute, below the evaluator: `local` (child processes in their own process
// groups, the Scheduler) or `slurm` (job arrays through sbatch/squeue/sacct/scancel). The
// evaluator builds Jobs, hands them to an Executor, and gets one Outcome per finished attempt on
// its own thread; it alone parses outputs and writes the store. An executor may keep jobs alive
// across a crash of smi-lua (Slurm): it then records them in the store's pending table through
// the PendingTable the evaluator gives it, and a rerun reattaches instead of submitting again.
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "platform/eval/scheduler.hpp"

namespace smi::eval {

class PendingTable;

/// The executor options: --executor/--slurm-opt on the command line. A model's `executor = {...}`
/// may only narrow them (bindings/eval/solver_model.cpp): where runs go and what they ask of a
/// cluster is the user's choice, not the study's.
struct ExecutorConfig {
  std::string kind = "local";                 // "local" | "slurm"
  std::string partition, account, qos;        // -p, -A, -q ("" = the cluster's default)
  std::string time;                           // --time as given ("30" minutes, "1:00:00"); "" = derived
  std::string mem;                            // --mem ("2G")
  int cpus = 0;                               // --cpus-per-task (0 = not given)
  std::vector<std::string> sbatch_args;       // extra sbatch arguments (allow-listed, sbatch_args.hpp)
  int throttle = 50;                          // %N: array tasks running at once
  int max_array = 0;                          // tasks per array (0 = the cluster's MaxArraySize)
  double poll_min = 5, poll_max = 60;         // squeue interval: from poll_min, x1.5 up to poll_max
  double cmd_timeout = 30;                    // seconds one scheduler command may take
  double down_after = 300;                    // seconds of failing scheduler commands before giving up
  double exit_wait = 30;                      // seconds to wait for the exit file of a job that left
  int max_requeues = 5;                       // node failures / preemptions per run before it fails
  bool detach = false;                        // --detach: an interrupted study leaves its jobs running
  std::string bin_dir;                        // where sbatch & co. live ("" = PATH)

  /// Applies "key=value" (the --slurm-opt syntax). Throws InvalidArgument naming the key and
  /// the known keys.
  void set(const std::string& key_value);
  void set(const std::string& key, const std::string& value);
  /// Checks the kind and the values; throws InvalidArgument naming the culprit.
  void validate() const;
};

/// The keys set() knows, for messages and help.
const char* executor_option_keys();

class Executor {
 public:
  virtual ~Executor() = default;
  /// Queues a job (a run's attempt). Job::key names the run for the pending table.
  virtual void submit(Job job) = 0;
  /// Starts no further queued jobs; running ones finish and are reported.
  virtual void stop_launching() = 0;
  /// Runs until nothing is queued or running: on_done once per finished attempt (it may
  /// submit() retries), on_tick about every `tick` seconds (progress, interrupt checks). An
  /// exception from a callback propagates; the executor's destructor then stops (local) or
  /// cancels with one scancel (slurm, unless detached) what still runs.
  virtual void run(const std::function<void(const Outcome&)>& on_done, const std::function<void()>& on_tick,
                   double tick = 0.2) = 0;
  virtual std::size_t running() const = 0;
};

/// The executor for `cfg`. `concurrency` bounds local runs; `pending` (may be null for local)
/// persists submitted Slurm jobs; `runs_dir` holds the Slurm manifests and scripts; `tag` names
/// the study's jobs (smi-<tag>-...).
std::unique_ptr<Executor> make_executor(const ExecutorConfig& cfg, int concurrency, PendingTable* pending,
                                        const std::string& runs_dir, const std::string& tag);

/// --dry-run: the job script and the exact sbatch lines for `runs` runs, with the cost plan
/// (CPU-hours asked for, at most, and expected from stored timings). `mean_seconds` < 0 when
/// unknown. Reads MaxArraySize from the cluster when it answers.
std::string slurm_dry_run(const ExecutorConfig& cfg, std::size_t runs, double timeout, double mean_seconds,
                          const std::string& runs_dir, const std::string& tag);

}  // namespace smi::eval
