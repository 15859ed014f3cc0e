// SPDX-License-Identifier: MIT
#pragma once
// Starting a process, the one way smi-lua does it (solvers, their version line, the Slurm
// commands): fork + exec of an argv vector (never a shell), in its own process group so that a
// timeout can kill it and everything it started, with default signal handling, stdin from
// /dev/null, stdout/stderr to files or to pipes the caller reads (run_captured), and exactly the
// environment it is given.
// The solver dies with smi-lua (PR_SET_PDEATHSIG), and carries kSolverMarkVar in its
// environment so that descendants escaping its group (setsid) can be found and killed
// (reap_escaped_descendants, with smi-lua a child subreaper).
#include <string>
#include <sys/types.h>
#include <vector>

#include "platform/core/errors.hpp"

namespace smi::eval {

struct SpawnSpec {
  std::string program;            // absolute path of the executable (already checked by the sandbox)
  std::vector<std::string> argv;  // argv[0] included
  std::string workdir;            // current directory of the child
  std::string stdout_path;        // absolute paths of the capture files
  std::string stderr_path;
  std::vector<std::string> env;   // the child's whole environment ("NAME=value"), see solver_environment
  // What run_captured and the Slurm commands change (a solver keeps the defaults):
  int stdout_fd = -1;             // >= 0: the child's stdout/stderr are these descriptors (pipes),
  int stderr_fd = -1;             //   not stdout_path/stderr_path
  bool solver_mark = true;        // carry kSolverMarkVar (sbatch would hand it on to the job)
  bool die_with_parent = true;    // PR_SET_PDEATHSIG: a solver dies with smi-lua; an sbatch or
                                  //   scancel under way is left to finish
};

/// A process that could not be started: the program and the system's reason (errno in `err`).
struct SpawnError : Error {
  SpawnError(const std::string& msg, int e) : Error(msg), err(e) {}
  int err;
};

/// The variables every solver gets from smi-lua's environment when they are set (the locale, the
/// user, PATH, HOME, TMPDIR, TZ); nothing else reaches a solver unless named.
extern const char* const kSolverBaseEnv[];

/// "NAME=value" for the base variables and for `extra` (--allow-env), from this process's
/// environment: a solver's environment is a list, never an inheritance (what a study cannot read
/// with os.getenv must not come back to it through a solver's output).
std::vector<std::string> solver_environment(const std::vector<std::string>& extra);

/// Why a model may never set the solver variable `name` itself ("" when it may, if --allow-env
/// names it: the binding checks that). A study sets such variables with values of its own
/// choosing, so the ones that make a program load or run other code are refused even then: the
/// dynamic loader's (LD_*, GCONV_PATH, ...), whole interpreter families (PYTHON*, PERL*, JAVA*,
/// JDK_*, LUA_*, NODE_*, TCL*, R_*, GIT_*, ...), the shells' start-up hooks (BASH_ENV, ENV, ...),
/// programs run by name (BROWSER, EDITOR, PAGER, SSH_ASKPASS), folders start-up files come from
/// (HOME, XDG_*, TMPDIR), PATH (a script could put a folder it writes first) and smi-lua's own
/// mark. Names are [A-Za-z_][A-Za-z0-9_]*. A list of names is only a second guard: the first is
/// that the user allows each name.
std::string declared_env_refusal(const std::string& name);

/// `env` ("NAME=value" entries) with each declared variable set, replacing an inherited one of
/// the same name.
void apply_declared_env(std::vector<std::string>& env, const std::vector<std::pair<std::string, std::string>>& set);

/// Starts the process with exactly spec.env (plus kSolverMarkVar); returns its pid, which is also its process-group id. Throws SpawnError
/// with the program and the system's reason when it cannot be started (missing, not executable).
pid_t spawn_process(const SpawnSpec& spec);

/// What a short command printed and how it ended (run_captured).
struct CapturedRun {
  int status = -1;          // exit status (128 + signal when killed); -1 when it timed out
  bool timed_out = false;
  std::string out, err;
};

/// Runs `spec` (its stdout/stderr fields ignored) to its end with both outputs captured through
/// pipes; at `timeout` seconds (<= 0: none) its process group is killed (SIGKILL) and timed_out is set.
/// Throws SpawnError when it cannot be started.
CapturedRun run_captured(SpawnSpec spec, double timeout);

/// The absolute path of `program` found through $PATH as execvp would (a name with a '/' is
/// returned as it is); "" when no folder of PATH holds an executable of that name.
std::string find_program(const std::string& program);

/// This process's environment as "NAME=value" entries (for a command that inherits it all).
std::vector<std::string> current_environment();

/// Environment variable set in every solver's environment to smi-lua's pid.
inline constexpr const char* kSolverMarkVar = "SMI_LUA_SOLVER_OF";

/// Makes this process the child subreaper (PR_SET_CHILD_SUBREAPER): orphans of the solvers it
/// starts are reparented to it instead of to init, so they can be found and reaped.
void become_subreaper();
/// Kills (SIGKILL) and reaps every child of this process that carries kSolverMarkVar with our
/// pid but is not in `keep` (a solver's setsid escape, reparented to us), repeating until none
/// is left (their own children are reparented to us in turn). Returns how many it killed.
int reap_escaped_descendants(const std::vector<pid_t>& keep = {});

/// Every scheduler's solvers are registered from spawn_process until their scheduler has waited
/// for them (solver_reaped): a nested evaluation (a parser that evaluates another model) cleaning
/// up after itself must not kill, nor reap, the outer model's solvers, which carry the same mark.
void solver_reaped(pid_t pid);

/// Sends `sig` to the whole process group `pgid` (ignores an already empty group).
void signal_group(pid_t pgid, int sig);

/// "exit status 3", "killed by signal 11 (Segmentation fault)", from a waitpid status.
std::string describe_wait_status(int status);

/// The last `max_bytes` bytes of a file ("" if it does not exist), cut to whole lines when it can.
std::string file_tail(const std::string& path, std::size_t max_bytes);

/// Seconds on the monotonic clock.
double monotonic_seconds();

}  // namespace smi::eval
