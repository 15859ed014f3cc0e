#pragma once
// Launching one solver process: posix_spawn of an argv vector (never a shell), in its own
// process group so that a timeout can kill the solver and everything it started, with the
// work directory as its current directory, stdin from /dev/null and stdout/stderr to files.
#include <string>
#include <sys/types.h>
#include <vector>

namespace smi::eval {

struct SpawnSpec {
  std::string program;            // absolute path of the executable (already checked by the sandbox)
  std::vector<std::string> argv;  // argv[0] included
  std::string workdir;            // current directory of the child
  std::string stdout_path;        // absolute paths of the capture files
  std::string stderr_path;
};

/// Starts the process; returns its pid, which is also its process-group id. Throws smi::Error
/// with the program and the system's reason when it cannot be started (missing, not executable).
pid_t spawn_process(const SpawnSpec& spec);

/// Sends `sig` to the whole process group `pgid` (ignores an already empty group).
void signal_group(pid_t pgid, int sig);

/// "exit status 3", "killed by signal 11 (Segmentation fault)", from a waitpid status.
std::string describe_wait_status(int status);

/// The last `max_bytes` bytes of a file ("" if it does not exist), cut to whole lines when it can.
std::string file_tail(const std::string& path, std::size_t max_bytes);

/// Seconds on the monotonic clock.
double monotonic_seconds();

}  // namespace smi::eval
