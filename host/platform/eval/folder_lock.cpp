// SPDX-License-Identifier: MIT
#include "platform/eval/folder_lock.hpp"

#include <cerrno>
#include <cstring>
#include <ctime>
#include <fcntl.h>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <mutex>
#include <set>
#include <sstream>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include "platform/core/errors.hpp"

namespace smi::eval {
namespace fs = std::filesystem;

namespace {

std::mutex g_mu;
std::set<std::string> g_held;  // folders this process has locked (descriptors stay open)

std::string holder_text() {
  char host[256] = "unknown";
  ::gethostname(host, sizeof host - 1);
  const std::time_t now = std::time(nullptr);
  char when[64];
  std::strftime(when, sizeof when, "%Y-%m-%d %H:%M:%S UTC", std::gmtime(&now));
  std::string cmd;
  std::ifstream in("/proc/self/cmdline", std::ios::binary);
  for (std::string part; std::getline(in, part, '\0');) cmd += (cmd.empty() ? "" : " ") + part;
  if (cmd.size() > 300) cmd = cmd.substr(0, 300) + "...";
  return fmt::format("pid {} on host {}, started {}, running: {}\n", ::getpid(), host, when, cmd);
}

}  // namespace

void lock_output_folder(const std::string& folder) {
  std::error_code ec;
  fs::create_directories(folder, ec);
  const std::string canon = fs::weakly_canonical(folder, ec).string();
  std::lock_guard<std::mutex> lock(g_mu);
  if (g_held.count(canon)) return;
  const std::string path = (fs::path(canon) / ".smi-lock").string();
  // The folder may hold what a study bundle brought along: a link or a hard link planted at
  // .smi-lock would make the truncate and write below land on a file elsewhere. So the lock is
  // opened without following a link, relative to the folder held open, and must be a regular
  // file with no other name.
  const int dir = ::open(canon.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir < 0) throw Error(fmt::format("cannot open the output folder '{}': {}", canon, std::strerror(errno)));
  const int fd = ::openat(dir, ".smi-lock", O_RDWR | O_CREAT | O_NOFOLLOW | O_NONBLOCK | O_NOCTTY | O_CLOEXEC, 0644);
  const int open_errno = errno;
  ::close(dir);
  if (fd < 0 && open_errno == ELOOP)
    throw Error(fmt::format("the lock file '{}' is a symbolic link; smi-lua creates it itself and never writes "
                            "through a link: remove it (it came with the folder's content) and run again",
                            path));
  if (fd < 0) throw Error(fmt::format("cannot open the lock file '{}': {}", path, std::strerror(open_errno)));
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) || st.st_nlink != 1) {
    ::close(fd);
    throw Error(fmt::format("the lock file '{}' is {}; smi-lua writes only files that have no other name: remove "
                            "it and run again",
                            path, S_ISREG(st.st_mode) ? fmt::format("a hard link ({} names)", st.st_nlink)
                                                       : std::string("not a regular file")));
  }
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int e = errno;
    std::string who;
    {  // read through the descriptor checked above, never by name again
      char buf[512];
      const ssize_t n = ::pread(fd, buf, sizeof buf, 0);
      if (n > 0) who.assign(buf, static_cast<std::size_t>(n));
      who = who.substr(0, who.find('\n'));
    }
    ::close(fd);
    if (e != EWOULDBLOCK) throw Error(fmt::format("cannot lock '{}': {}", path, std::strerror(e)));
    throw Error(fmt::format("the output folder '{}' is in use by another smi-lua ({}); two studies in one folder "
                            "would overwrite each other's runs and results. Wait for it to finish, or give this "
                            "one another --out",
                            canon, who.empty() ? "holder unknown" : who));
  }
  // Ours: say who we are (a reader sees the whole line: it is written before anyone can fail
  // to lock, and a failed locker only reads).
  const std::string me = holder_text();
  if (::ftruncate(fd, 0) == 0) {
    ssize_t w = ::pwrite(fd, me.data(), me.size(), 0);
    (void)w;  // the lock itself is what matters; the text is a courtesy
  }
  g_held.insert(canon);  // fd stays open (and locked) until the process exits
}

}  // namespace smi::eval
