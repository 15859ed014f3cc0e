// SPDX-License-Identifier: MIT
#pragma once
// Talking to Slurm through its command-line tools (sbatch --parsable, squeue, sacct, scancel,
// scontrol): never libslurm, whose ABI changes every release. Each call is a child process with
// a time limit; a call that fails in a way that looks transient (timeout, controller not
// answering) is retried with backoff until `down_after` seconds have passed, and then the
// scheduler is declared down with a message that names the command and its error. The parsers
// are pure functions so the kernel tests check them on recorded output.
#include <map>
#include <string>
#include <vector>

#include "platform/core/errors.hpp"

namespace smi::eval {

/// Slurm did not answer for too long: the study stops (finished runs are stored).
struct SchedulerDown : Error {
  using Error::Error;
};

struct CommandResult {
  int status = -1;          // exit status; -1 when it timed out or could not start
  bool timed_out = false;
  std::string out, err;
};

/// Runs argv[0] (looked up in `bin_dir`, else PATH) with a time limit; output captured.
CommandResult run_command(const std::vector<std::string>& argv, double timeout, const std::string& bin_dir = "");

/// True for errors worth retrying: timeouts, "Unable to contact slurm controller", socket
/// errors, "Resource temporarily unavailable", "Try again".
bool transient_failure(const CommandResult& r);

/// The lifecycle of one array task as squeue shows it (%T).
enum class TaskState { Pending, Running, Completed, Failed, Timeout, OutOfMemory, Cancelled, NodeFail, Preempted,
                       BootFail, Requeued, Unknown };
TaskState parse_task_state(const std::string& s);
bool is_final(TaskState s);
/// Node failure, preemption, boot failure: the infrastructure's fault, requeued without counting.
bool is_infrastructure(TaskState s);

struct QueueEntry {
  std::string array_job_id;  // "123" (the %A of an array)
  int index = -1;            // the array task index, -1 when not an array task
  TaskState state = TaskState::Unknown;
  std::string state_text, reason;
  std::string raw_id;        // the task's own job id (%A): `sacct -c` knows array tasks only by it
};

/// Parses `squeue -h -r -t all -o '%i|%T|%r|%A'` lines. Lines it cannot read are skipped.
std::vector<QueueEntry> parse_squeue(const std::string& out);

/// Parses `sacct -n -P -X -o JobID,State,ExitCode` (or `sacct -c`): task "123_4" -> state text.
std::map<std::string, std::string> parse_sacct(const std::string& out);

/// MaxArraySize from `scontrol show config` (0 when absent).
int parse_max_array_size(const std::string& out);

/// The job id sbatch --parsable prints ("123" or "123;cluster").
std::string parse_sbatch_id(const std::string& out);

/// Whole minutes of a Slurm --time value ("30", "1:30:00", "2-00:00:00", "45:00"); -1 if unreadable.
double slurm_time_minutes(const std::string& t);

}  // namespace smi::eval
