// SPDX-License-Identifier: MIT
#include "platform/eval/work_dir.hpp"

#include <cerrno>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>

#include "platform/core/errors.hpp"

namespace smi::eval {
namespace fs = std::filesystem;

void write_text_file(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw Error(fmt::format("cannot write '{}': {}", path, std::strerror(errno)));
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  out.close();
  if (!out) throw Error(fmt::format("error writing '{}' (disk full?)", path));
}

namespace {

/// Creates `name` in folder `dir` (O_EXCL, O_NOFOLLOW: never through a link planted there).
pathwalk::Fd create_in(int dir, const std::string& name, const std::string& shown) {
  const int fd = ::openat(dir, name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
  if (fd < 0) throw Error(fmt::format("cannot write '{}': {}", shown, std::strerror(errno)));
  return pathwalk::Fd(fd);
}

void copy_fd(int from, int to, const std::string& shown) {
  char buf[1 << 16];
  off_t off = 0;
  for (;;) {
    const ssize_t n = ::pread(from, buf, sizeof buf, off);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw Error(fmt::format("cannot copy '{}': {}", shown, std::strerror(errno)));
    if (n == 0) return;
    if (!pathwalk::write_all(to, std::string(buf, static_cast<std::size_t>(n))))
      throw Error(fmt::format("cannot copy '{}': {}", shown, std::strerror(errno)));
    off += n;
  }
}

}  // namespace

void prepare_work_dir(const std::string& dir, const std::string& deck_name, const std::string& deck_text,
                      const std::vector<std::string>& files,
                      const std::vector<std::shared_ptr<const pathwalk::Fd>>& fds) {
  // The runs folder is opened refusing every symlink on its path, and everything below it is
  // made relative to its descriptor: a link planted in the output folder is never followed,
  // and clearing a leftover removes links rather than what they point to.
  const fs::path d = fs::absolute(fs::path(dir)).lexically_normal();
  const std::string leaf = d.filename().string();
  pathwalk::Fd parent = pathwalk::make_dirs_nofollow(d.parent_path().string());
  if (!parent)
    throw Error(fmt::format("cannot create work directory '{}': {}{}", dir, std::strerror(errno),
                            errno == ENOTDIR ? " (a symlink or a file on its path)" : ""));
  if (!pathwalk::remove_tree_at(parent.get(), leaf))
    throw Error(fmt::format("cannot clear work directory '{}': {}", dir, std::strerror(errno)));
  if (::mkdirat(parent.get(), leaf.c_str(), 0777) != 0)
    throw Error(fmt::format("cannot create work directory '{}': {}", dir, std::strerror(errno)));
  const pathwalk::Fd run(::openat(parent.get(), leaf.c_str(), O_PATH | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC));
  if (!run) throw Error(fmt::format("cannot open work directory '{}': {}", dir, std::strerror(errno)));
  if (!deck_name.empty()) {
    const pathwalk::Fd out = create_in(run.get(), deck_name, (d / deck_name).string());
    if (!pathwalk::write_all(out.get(), deck_text))
      throw Error(fmt::format("error writing '{}' (disk full?)", (d / deck_name).string()));
  }
  for (std::size_t i = 0; i < files.size(); ++i) {
    const std::string name = fs::path(files[i]).filename().string();
    const pathwalk::Fd out = create_in(run.get(), name, (d / name).string());
    if (i < fds.size() && fds[i]) {
      copy_fd(fds[i]->get(), out.get(), files[i]);
    } else {  // kernel use without a sandbox: the caller's own path
      const pathwalk::Fd in(::open(files[i].c_str(), O_RDONLY | O_CLOEXEC));
      if (!in) throw Error(fmt::format("cannot copy '{}' into '{}': {}", files[i], dir, std::strerror(errno)));
      copy_fd(in.get(), out.get(), files[i]);
    }
  }
}

}  // namespace smi::eval
