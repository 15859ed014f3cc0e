// SPDX-License-Identifier: MIT
#include "platform/core/run_record.hpp"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include "platform/core/errors.hpp"
#include "platform/core/path_walk.hpp"
#include "platform/core/sha256.hpp"

namespace smi {

namespace {
/// What a non-regular file is, for the refusal.
const char* file_kind(mode_t m) {
  if (S_ISDIR(m)) return "a folder";
  if (S_ISCHR(m)) return "a character device";
  if (S_ISBLK(m)) return "a block device";
  if (S_ISFIFO(m)) return "a FIFO";
  if (S_ISSOCK(m)) return "a socket";
  return "not a regular file";
}
}  // namespace

FileDigest digest_fd(int fd, const std::string& name) {
  struct stat st;
  if (::fstat(fd, &st) != 0) throw Error(fmt::format("cannot read '{}': {}", name, std::strerror(errno)));
  // Only a regular file has a content of known size: a device (/dev/zero) or a FIFO would be
  // read for ever, a folder not at all.
  if (!S_ISREG(st.st_mode))
    throw Error(fmt::format("cannot read '{}': it is {}, and only regular files are digested", name,
                            file_kind(st.st_mode)));
  FileDigest d;
  d.size = static_cast<std::uintmax_t>(st.st_size);
  d.mtime = static_cast<std::int64_t>(st.st_mtime);
  if (d.size > kLargeFileBytes) {
    d.large = true;  // hashing 1 GB takes seconds to minutes: size and mtime identify it
    return d;
  }
  d.hash = "sha256:" + sha256_fd(fd, name, d.size);  // the size seen: a file still growing ends there
  return d;
}

FileDigest digest_path(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK);
  if (fd < 0) throw Error(fmt::format("cannot read '{}': {}", path, std::strerror(errno)));
  pathwalk::Fd guard(fd);
  return digest_fd(fd, path);
}

namespace {
bool excluded(const std::string& path, const std::vector<std::string>& roots) {
  for (const auto& r : roots)
    if (!r.empty() && pathwalk::within(path, r)) return true;
  return false;
}
}  // namespace

void RunRecord::touch(const std::string& kind, const std::string& path, const FileDigest& d) {
  InputFile& f = files_[path];
  if (f.kind.empty() || (kind == "lua" && f.kind == "data")) f.kind = kind;
  if (f.seq != 0 && (f.digest.hash != d.hash || f.digest.size != d.size || f.digest.mtime != d.mtime))
    f.changed_during_run = true;
  f.digest = d;
  f.seq = ++seq_;
}

void RunRecord::file(const std::string& kind, const std::string& path, int fd) {
  {
    std::lock_guard<std::mutex> lock(mu_);
    if (excluded(path, exclude_roots)) return;
    // The same file read again unchanged (same size and mtime): no second hash.
    if (const auto it = files_.find(path); it != files_.end()) {
      struct stat st;
      if (::fstat(fd, &st) == 0 && static_cast<std::uintmax_t>(st.st_size) == it->second.digest.size &&
          static_cast<std::int64_t>(st.st_mtime) == it->second.digest.mtime) {
        touch(kind, path, it->second.digest);
        return;
      }
    }
  }
  const FileDigest d = digest_fd(fd, path);  // outside the lock: may take a while
  std::lock_guard<std::mutex> lock(mu_);
  touch(kind, path, d);
}

void RunRecord::text(const std::string& kind, const std::string& path, std::string_view bytes) {
  FileDigest d;
  d.size = bytes.size();
  d.hash = "sha256:" + sha256_hex(bytes);
  std::lock_guard<std::mutex> lock(mu_);
  touch(kind, path, d);
}

void RunRecord::path(const std::string& kind, const std::string& path) {
  const FileDigest d = digest_path(path);
  std::lock_guard<std::mutex> lock(mu_);
  touch(kind, path, d);
}

void RunRecord::program(ProgramRun p) {
  std::lock_guard<std::mutex> lock(mu_);
  // also a file of kind "program": the step that made the model has it among its inputs
  if (p.digest.hash != "unreadable") touch("program", p.path, p.digest);
  for (auto& q : programs_)
    if (q.path == p.path && q.version == p.version) {
      q.digest = p.digest;
      if (!p.version_line.empty()) q.version_line = p.version_line;
      return;
    }
  programs_.push_back(std::move(p));
}

void RunRecord::exclude(const std::string& path) {
  std::lock_guard<std::mutex> lock(mu_);
  exclude_roots.push_back(path);
  for (auto it = files_.begin(); it != files_.end();)
    it = pathwalk::within(it->first, path) ? files_.erase(it) : std::next(it);
}

std::map<std::string, InputFile> RunRecord::files() const {
  std::lock_guard<std::mutex> lock(mu_);
  return files_;
}

std::vector<ProgramRun> RunRecord::programs() const {
  std::lock_guard<std::mutex> lock(mu_);
  return programs_;
}

std::uint64_t RunRecord::seq() const {
  std::lock_guard<std::mutex> lock(mu_);
  return seq_;
}

}  // namespace smi
