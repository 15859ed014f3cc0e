#include "eval/process.hpp"

#include <cerrno>
#include <csignal>
#include <cstring>
#include <ctime>
#include <fcntl.h>
#include <fmt/format.h>
#include <fstream>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include "core/errors.hpp"

extern char** environ;

namespace smi::eval {
namespace {

/// Owns the posix_spawn attribute objects so every exit path destroys them.
struct SpawnAttrs {
  posix_spawnattr_t attr;
  posix_spawn_file_actions_t actions;
  SpawnAttrs() {
    posix_spawnattr_init(&attr);
    posix_spawn_file_actions_init(&actions);
  }
  ~SpawnAttrs() {
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attr);
  }
  SpawnAttrs(const SpawnAttrs&) = delete;
  SpawnAttrs& operator=(const SpawnAttrs&) = delete;
};

void check(int rc, const char* what) {
  if (rc != 0) throw Error(fmt::format("{} failed: {}", what, std::strerror(rc)));
}

}  // namespace

pid_t spawn_process(const SpawnSpec& spec) {
  if (spec.argv.empty()) throw Error("spawn_process: empty argv");
  SpawnAttrs a;
  // A new process group (pgid = child's pid); default signal handling and an empty mask, so a
  // solver does not inherit whatever the host blocked or ignored.
  sigset_t none, all;
  sigemptyset(&none);
  sigfillset(&all);
  check(posix_spawnattr_setpgroup(&a.attr, 0), "posix_spawnattr_setpgroup");
  check(posix_spawnattr_setsigmask(&a.attr, &none), "posix_spawnattr_setsigmask");
  check(posix_spawnattr_setsigdefault(&a.attr, &all), "posix_spawnattr_setsigdefault");
  check(posix_spawnattr_setflags(&a.attr, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF),
        "posix_spawnattr_setflags");
  check(posix_spawn_file_actions_addopen(&a.actions, 0, "/dev/null", O_RDONLY, 0), "addopen stdin");
  check(posix_spawn_file_actions_addopen(&a.actions, 1, spec.stdout_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW, 0644),
        "addopen stdout");
  check(posix_spawn_file_actions_addopen(&a.actions, 2, spec.stderr_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW, 0644),
        "addopen stderr");
  // Descriptors the host holds (files a script opened, the store) are not the solver's business.
  check(posix_spawn_file_actions_addclosefrom_np(&a.actions, 3), "addclosefrom");
  check(posix_spawn_file_actions_addchdir_np(&a.actions, spec.workdir.c_str()), "addchdir");

  std::vector<char*> argv;
  argv.reserve(spec.argv.size() + 1);
  for (const auto& s : spec.argv) argv.push_back(const_cast<char*>(s.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  // glibc's posix_spawn reports a failed exec (ENOENT, EACCES, ENOEXEC) as its return value.
  const int rc = posix_spawn(&pid, spec.program.c_str(), &a.actions, &a.attr, argv.data(), environ);
  if (rc != 0) throw Error(fmt::format("cannot start '{}': {}", spec.program, std::strerror(rc)));
  return pid;
}

void signal_group(pid_t pgid, int sig) {
  if (pgid > 0) ::kill(-pgid, sig);  // ESRCH: the group is already gone
}

std::string describe_wait_status(int status) {
  if (WIFEXITED(status)) return fmt::format("exit status {}", WEXITSTATUS(status));
  if (WIFSIGNALED(status))
    return fmt::format("killed by signal {} ({})", WTERMSIG(status), strsignal(WTERMSIG(status)));
  return fmt::format("stopped (wait status {})", status);
}

std::string file_tail(const std::string& path, std::size_t max_bytes) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return "";
  const std::streamoff size = in.tellg();
  const std::streamoff start = size > static_cast<std::streamoff>(max_bytes) ? size - static_cast<std::streamoff>(max_bytes) : 0;
  in.seekg(start);
  std::string s(static_cast<std::size_t>(size - start), '\0');
  in.read(s.data(), static_cast<std::streamsize>(s.size()));
  if (start > 0) {
    const auto nl = s.find('\n');
    if (nl != std::string::npos && nl + 1 < s.size()) s.erase(0, nl + 1);
  }
  return s;
}

double monotonic_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

}  // namespace smi::eval
