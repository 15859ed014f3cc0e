// SPDX-License-Identifier: MIT
#include "platform/eval/process.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <dirent.h>
#include <iterator>
#include <mutex>
#include <set>
#include <csignal>
#include <cstring>
#include <ctime>
#include <cmath>
#include <fcntl.h>
#include <poll.h>
#include <fmt/format.h>
#include <filesystem>
#include <fstream>
#include <sys/stat.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include "platform/core/errors.hpp"


extern char** environ;

namespace smi::eval {
namespace {

[[noreturn]] void child_fail(int fd, int err) {
  // Tells the parent why exec did not happen (errno through the CLOEXEC pipe), then leaves.
  while (::write(fd, &err, sizeof err) < 0 && errno == EINTR) {
  }
  ::_exit(127);
}

/// The child after fork: only async-signal-safe calls (the parent may have threads).
[[noreturn]] void exec_child(const SpawnSpec& spec, char* const* argv, char* const* envp, pid_t parent, int errfd) {
  // Die with smi-lua (even by SIGKILL): a solver must not outlive the study that started it. If
  // the parent died between fork and prctl, we were already reparented: leave at once.
  if (spec.die_with_parent) {
    if (::prctl(PR_SET_PDEATHSIG, SIGKILL) != 0) child_fail(errfd, errno);
    if (::getppid() != parent) ::_exit(127);
  }
  // A new process group (pgid = pid), so a timeout or a stop can kill the solver and its helpers.
  if (::setpgid(0, 0) != 0) child_fail(errfd, errno);
  // Default signal handling and an empty mask: a solver does not inherit what the host set.
  struct sigaction dfl {};
  dfl.sa_handler = SIG_DFL;
  for (int sig = 1; sig < NSIG; ++sig)
    if (sig != SIGKILL && sig != SIGSTOP) ::sigaction(sig, &dfl, nullptr);
  sigset_t none;
  sigemptyset(&none);
  ::sigprocmask(SIG_SETMASK, &none, nullptr);
  const int in = ::open("/dev/null", O_RDONLY);
  const int out = spec.stdout_fd >= 0 ? spec.stdout_fd
                                      : ::open(spec.stdout_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW, 0644);
  const int err = spec.stderr_fd >= 0 ? spec.stderr_fd
                                      : ::open(spec.stderr_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW, 0644);
  if (in < 0 || out < 0 || err < 0) child_fail(errfd, errno);
  if (::dup2(in, 0) < 0 || ::dup2(out, 1) < 0 || ::dup2(err, 2) < 0) child_fail(errfd, errno);
  // Descriptors the host holds (files a script opened, the store) are not the solver's business;
  // errfd is close-on-exec, so it stays open until exec succeeds.
  for (int fd : {in, out, err})
    if (fd > 2 && fd != errfd) ::close(fd);
  if (!spec.workdir.empty() && ::chdir(spec.workdir.c_str()) != 0) child_fail(errfd, errno);
  if ((errfd > 3 && ::close_range(3, static_cast<unsigned>(errfd) - 1, 0) != 0) ||
      ::close_range(static_cast<unsigned>(errfd) + 1, ~0u, 0) != 0) {
    const long maxfd = std::min(::sysconf(_SC_OPEN_MAX), 65536L);  // kernels before 5.9
    for (int fd = 3; fd < maxfd; ++fd)
      if (fd != errfd) ::close(fd);
  }
  ::execve(spec.program.c_str(), argv, envp);
  child_fail(errfd, errno);
}

}  // namespace

const char* const kSolverBaseEnv[] = {"PATH", "HOME", "USER", "LOGNAME", "LANG", "LANGUAGE", "LC_ALL", "LC_CTYPE",
                                      "LC_NUMERIC", "LC_MESSAGES", "TZ", "TMPDIR", nullptr};

std::vector<std::string> solver_environment(const std::vector<std::string>& extra) {
  std::vector<std::string> names;
  for (const char* const* n = kSolverBaseEnv; *n; ++n) names.emplace_back(*n);
  names.insert(names.end(), extra.begin(), extra.end());
  std::vector<std::string> env;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string& n = names[i];
    if (n.empty() || n.find('=') != std::string::npos || n == kSolverMarkVar) continue;
    if (std::find(names.begin(), names.begin() + static_cast<std::ptrdiff_t>(i), n) != names.begin() + static_cast<std::ptrdiff_t>(i)) continue;
    if (const char* v = std::getenv(n.c_str())) env.push_back(n + "=" + v);
  }
  return env;
}

std::string declared_env_refusal(const std::string& name) {
  if (name.empty() || !(std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_'))
    return "a variable name starts with a letter or '_'";
  for (const char ch : name)
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_'))
      return "a variable name holds only letters, digits and '_'";
  if (name == kSolverMarkVar) return "smi-lua sets it itself to find its solvers' processes";
  // Whole families: the loader's, and interpreters that read many start-up variables (Python's
  // PYTHONWARNINGS can import a module, Java's JDK_JAVA_OPTIONS adds an agent, R_PROFILE runs a
  // file, GIT_SSH runs a program, a folder in XDG_CONFIG_HOME holds start-up files).
  static const char* const kFamilies[] = {"LD_",   "BASH_FUNC_", "DYLD_",  "PYTHON", "PERL", "RUBY", "GEM_",
                                          "NODE_", "NPM_",       "LUA_",   "JAVA",   "_JAVA", "JDK_", "TCL",
                                          "TK_",   "GIT_",       "XDG_",   "R_",     "JULIA_", "OCTAVE", "MATLAB",
                                          "PHP",   "GCONV_",     "MALLOC_", "OMP_TOOL", "OMPI_", "PMIX_", nullptr};
  for (const char* const* f = kFamilies; *f; ++f)
    if (name.rfind(*f, 0) == 0) return "it makes the program load or run other code";
  static const char* const kHooks[] = {
      "PATH", "BASH_ENV", "ENV", "SHELLOPTS", "BASHOPTS", "PS4", "PROMPT_COMMAND", "IFS", "CDPATH", "GLIBC_TUNABLES",
      "LOCPATH", "NLSPATH", "HOSTALIASES", "RESOLV_HOST_CONF", "CLASSPATH", "HOME", "ZDOTDIR", "INPUTRC", "BROWSER",
      "EDITOR", "VISUAL", "PAGER", "MANPAGER", "LESSOPEN", "LESSCLOSE", "SSH_ASKPASS", "SUDO_ASKPASS", "OPENSSL_CONF",
      "OPENSSL_ENGINES", "TERMINFO", "TERMINFO_DIRS", "TMPDIR", "SHELL", nullptr};
  for (const char* const* h = kHooks; *h; ++h)
    if (name == *h) {
      if (name == "PATH") return "a study could put a folder it writes first; give the solver's absolute path instead";
      if (name == "HOME" || name == "TMPDIR" || name == "ZDOTDIR")
        return "programs read start-up files from there (Python's user site, shell and tool settings)";
      return "it makes the program load or run other code";
    }
  return "";
}

void apply_declared_env(std::vector<std::string>& env, const std::vector<std::pair<std::string, std::string>>& set) {
  for (const auto& [name, value] : set) {
    const std::string prefix = name + "=";
    env.erase(std::remove_if(env.begin(), env.end(), [&](const std::string& e) { return e.rfind(prefix, 0) == 0; }),
              env.end());
    env.push_back(prefix + value);
  }
}

namespace {
std::mutex g_live_mu;
std::set<pid_t> g_live;  // solvers started and not yet waited for by their scheduler

bool is_live_solver(pid_t pid) {
  std::lock_guard<std::mutex> lock(g_live_mu);
  return g_live.count(pid) > 0;
}
}  // namespace

void solver_reaped(pid_t pid) {
  std::lock_guard<std::mutex> lock(g_live_mu);
  g_live.erase(pid);
}

pid_t spawn_process(const SpawnSpec& spec) {
  if (spec.argv.empty()) throw Error("spawn_process: empty argv");
  std::vector<char*> argv;
  argv.reserve(spec.argv.size() + 1);
  for (const auto& s : spec.argv) argv.push_back(const_cast<char*>(s.c_str()));
  argv.push_back(nullptr);
  // The environment plus a mark naming this smi-lua: descendants that escape the process group
  // (setsid) and are reparented to us (the child subreaper) are recognised by it and killed.
  const std::string mark = std::string(kSolverMarkVar) + "=" + std::to_string(::getpid());
  std::vector<char*> envp;
  for (const auto& e : spec.env)
    if (e.rfind(std::string(kSolverMarkVar) + "=", 0) != 0) envp.push_back(const_cast<char*>(e.c_str()));
  if (spec.solver_mark) envp.push_back(const_cast<char*>(mark.c_str()));
  envp.push_back(nullptr);

  int pipefd[2];
  if (::pipe2(pipefd, O_CLOEXEC) != 0) throw Error(fmt::format("pipe failed: {}", std::strerror(errno)));
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) {
    const int e = errno;
    ::close(pipefd[0]);
    ::close(pipefd[1]);
    throw SpawnError(fmt::format("cannot start '{}': fork failed: {}", spec.program, std::strerror(e)), e);
  }
  if (pid == 0) {
    ::close(pipefd[0]);
    exec_child(spec, argv.data(), envp.data(), parent, pipefd[1]);
  }
  ::close(pipefd[1]);
  {
    std::lock_guard<std::mutex> lock(g_live_mu);
    g_live.insert(pid);
  }
  // Also set the group from this side, so a kill(-pid) right after we return cannot miss it.
  ::setpgid(pid, pid);
  int err = 0;
  ssize_t r;
  while ((r = ::read(pipefd[0], &err, sizeof err)) < 0 && errno == EINTR) {
  }
  ::close(pipefd[0]);
  if (r == static_cast<ssize_t>(sizeof err)) {  // exec failed: reap the child, report why
    int st = 0;
    while (::waitpid(pid, &st, 0) < 0 && errno == EINTR) {
    }
    solver_reaped(pid);
    throw SpawnError(fmt::format("cannot start '{}': {}", spec.program, std::strerror(err)), err);
  }
  return pid;
}

CapturedRun run_captured(SpawnSpec spec, double timeout) {
  CapturedRun r;
  int out[2], err[2];
  if (::pipe2(out, O_CLOEXEC) != 0) throw Error(fmt::format("pipe: {}", std::strerror(errno)));
  if (::pipe2(err, O_CLOEXEC) != 0) {
    const int e = errno;
    ::close(out[0]);
    ::close(out[1]);
    throw Error(fmt::format("pipe: {}", std::strerror(e)));
  }
  spec.stdout_fd = out[1];
  spec.stderr_fd = err[1];
  pid_t pid = -1;
  try {
    pid = spawn_process(spec);
  } catch (const Error&) {
    for (int fd : {out[0], out[1], err[0], err[1]}) ::close(fd);
    throw;
  }
  ::close(out[1]);
  ::close(err[1]);
  const double deadline = timeout > 0 ? monotonic_seconds() + timeout : 0;
  pollfd fds[2] = {{out[0], POLLIN, 0}, {err[0], POLLIN, 0}};
  std::string* sink[2] = {&r.out, &r.err};
  int open_fds = 2;
  char buf[4096];
  while (open_fds > 0) {
    const double left = timeout > 0 ? deadline - monotonic_seconds() : 1.0;
    if (left <= 0) {
      r.timed_out = true;
      signal_group(pid, SIGKILL);
      break;
    }
    const int n = ::poll(fds, 2, static_cast<int>(std::ceil(std::min(left, 1.0) * 1000)));
    if (n < 0 && errno != EINTR) break;
    for (int i = 0; i < 2; ++i) {
      if (fds[i].fd < 0 || !(fds[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      const ssize_t got = ::read(fds[i].fd, buf, sizeof buf);
      if (got > 0) {
        sink[i]->append(buf, static_cast<std::size_t>(got));
      } else if (got == 0 || errno != EINTR) {
        ::close(fds[i].fd);
        fds[i].fd = -1;
        --open_fds;
      }
    }
  }
  for (auto& f : fds)
    if (f.fd >= 0) ::close(f.fd);
  int st = 0;
  while (::waitpid(pid, &st, 0) < 0 && errno == EINTR) {
  }
  solver_reaped(pid);
  if (!r.timed_out) r.status = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + (WIFSIGNALED(st) ? WTERMSIG(st) : 0);
  return r;
}

std::string find_program(const std::string& program) {
  if (program.empty()) return "";
  if (program.find('/') != std::string::npos) return program;
  const char* path = std::getenv("PATH");
  const std::string dirs = path ? path : "/usr/local/bin:/usr/bin:/bin";  // execvp's default
  for (std::size_t a = 0; a <= dirs.size();) {
    std::size_t b = dirs.find(':', a);
    if (b == std::string::npos) b = dirs.size();
    const std::string dir = b > a ? dirs.substr(a, b - a) : ".";  // an empty entry is the working folder
    const std::string cand = dir + "/" + program;
    struct stat st {};
    if (::stat(cand.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(cand.c_str(), X_OK) == 0) return cand;
    a = b + 1;
  }
  return "";
}

std::vector<std::string> current_environment() {
  std::vector<std::string> env;
  for (char** e = environ; e && *e; ++e) env.emplace_back(*e);
  return env;
}

void become_subreaper() { ::prctl(PR_SET_CHILD_SUBREAPER, 1); }

namespace {

/// The whole of a small /proc file, or "" when it cannot be read. A process can exit between
/// readdir and read: read(2) then fails (ESRCH), and std::ifstream read through an
/// istreambuf_iterator turns that into an exception that nothing catches (it aborted a study
/// in CI). Plain read(2), every error meaning "nothing there".
std::string read_proc_file(const std::string& path) {
  std::string out;
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return out;
  char buf[4096];
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n > 0) {
      out.append(buf, static_cast<std::size_t>(n));
      if (out.size() > (1u << 20)) break;  // /proc files of interest are far smaller
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) out.clear();
    break;
  }
  ::close(fd);
  return out;
}

/// Children of this process (parent pid field of /proc/<pid>/stat).
std::vector<pid_t> own_children() {
  std::vector<pid_t> out;
  const pid_t me = ::getpid();
  DIR* d = ::opendir("/proc");
  if (!d) return out;
  while (dirent* e = ::readdir(d)) {
    char* end = nullptr;
    const long pid = std::strtol(e->d_name, &end, 10);
    if (pid <= 0 || *end) continue;
    const std::string text = read_proc_file(fmt::format("/proc/{}/stat", pid));
    const auto rp = text.rfind(')');  // the command name may hold spaces and parentheses
    if (rp == std::string::npos) continue;
    char state = 0;
    long ppid = 0;
    if (std::sscanf(text.c_str() + rp + 1, " %c %ld", &state, &ppid) == 2 && ppid == me)
      out.push_back(static_cast<pid_t>(pid));
  }
  ::closedir(d);
  return out;
}

/// True if `pid`'s environment holds kSolverMarkVar=<our pid>. A zombie's environ reads empty:
/// it is ours to reap either way if it is not one we track (the caller passes those in keep).
bool marked_as_ours(pid_t pid, bool& zombie) {
  const std::string text = read_proc_file(fmt::format("/proc/{}/environ", pid));
  zombie = text.empty();  // also a process that exited while we looked: waitpid(WNOHANG) is harmless
  const std::string mark = std::string(kSolverMarkVar) + "=" + std::to_string(::getpid());
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t nul = text.find('\0', at);
    if (text.compare(at, (nul == std::string::npos ? text.size() : nul) - at, mark) == 0) return true;
    if (nul == std::string::npos) break;
    at = nul + 1;
  }
  return false;
}

}  // namespace

int reap_escaped_descendants(const std::vector<pid_t>& keep) {
  int killed = 0;
  for (int round = 0; round < 50; ++round) {  // each round's victims' children come to us next
    std::vector<pid_t> victims;
    for (pid_t pid : own_children()) {
      if (std::find(keep.begin(), keep.end(), pid) != keep.end() || is_live_solver(pid)) continue;
      bool zombie = false;
      if (marked_as_ours(pid, zombie)) victims.push_back(pid);
      else if (zombie) {
        // An exited orphan of a solver (only marked processes are reparented to us while we
        // run solvers; popen children of a script are waited for by Lua): reap it if it is
        // a zombie, never block on a live process we do not know.
        int st = 0;
        ::waitpid(pid, &st, WNOHANG);
      }
    }
    if (victims.empty()) break;
    for (pid_t pid : victims) {
      ::kill(pid, SIGKILL);
      if (::getpgid(pid) == pid) ::kill(-pid, SIGKILL);  // a group it leads (after setsid)
    }
    for (pid_t pid : victims) {
      int st = 0;
      while (::waitpid(pid, &st, 0) < 0 && errno == EINTR) {
      }
    }
    killed += static_cast<int>(victims.size());
  }
  return killed;
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
  // A solver's log, shown in a failure message: the solver may have left a link (or a FIFO) in
  // its place. The run folder is opened without following a link, the log relative to it with
  // O_NOFOLLOW|O_NONBLOCK, and only a regular file is read: a link shows as "" (nothing read).
  const std::filesystem::path p(path);
  const std::string folder = p.has_parent_path() ? p.parent_path().string() : ".";
  const int dir = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (dir < 0) return "";
  const int fd = ::openat(dir, p.filename().c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  ::close(dir);
  if (fd < 0) return "";
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    return "";
  }
  const auto size = static_cast<std::size_t>(st.st_size);
  const std::size_t start = size > max_bytes ? size - max_bytes : 0;
  std::string s(size - start, '\0');
  std::size_t got = 0;
  while (got < s.size()) {
    const ssize_t n = ::pread(fd, s.data() + got, s.size() - got, static_cast<off_t>(start + got));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    got += static_cast<std::size_t>(n);
  }
  ::close(fd);
  s.resize(got);
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
