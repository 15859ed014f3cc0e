// SPDX-License-Identifier: MIT
#include "platform/core/atomic_file.hpp"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fmt/format.h>
#include <unistd.h>

#include "platform/core/errors.hpp"

namespace smi {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& tmp, const char* what, int err) {
  ::unlink(tmp.c_str());
  throw Error(fmt::format("cannot write '{}': {} failed: {}{}; the previous file (if any) is unchanged", path, what,
                          std::strerror(err), err == ENOSPC || err == EDQUOT ? " (the disk is full: free space and run again)" : ""));
}

}  // namespace

void write_file_atomic(const std::string& path, std::string_view data, unsigned mode) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  fs::path dir = target.parent_path();
  if (dir.empty()) dir = ".";
  // Unique per process: two writers never share a temporary file.
  const std::string tmp = (dir / fmt::format(".{}.tmp-{}", target.filename().string(), ::getpid())).string();
  // A leftover of a crashed run with the same pid is removed; O_EXCL | O_NOFOLLOW then refuses a
  // symlink planted under the temporary name (the write must land in the checked folder).
  ::unlink(tmp.c_str());
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, static_cast<mode_t>(mode));
  if (fd < 0) {
    const int e = errno;
    throw Error(fmt::format("cannot write '{}': {} (does the folder exist and may smi-lua write there?)", path,
                            std::strerror(e)));
  }
  std::size_t done = 0;
  while (done < data.size()) {
    const std::size_t chunk = data.size() - done;
    const ssize_t w = ::write(fd, data.data() + done, chunk);
    if (w < 0) {
      if (errno == EINTR) continue;
      const int e = errno;
      ::close(fd);
      fail(path, tmp, "write", e);
    }
    done += static_cast<std::size_t>(w);
  }
  if (::fsync(fd) != 0) {
    const int e = errno;
    ::close(fd);
    fail(path, tmp, "fsync", e);
  }
  if (::close(fd) != 0) fail(path, tmp, "close", errno);
  if (::rename(tmp.c_str(), path.c_str()) != 0) fail(path, tmp, "rename", errno);
  // The rename is durable once the folder's entry is on disk.
  const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {
    ::fsync(dfd);
    ::close(dfd);
  }
}

}  // namespace smi
