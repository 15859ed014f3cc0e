// SPDX-License-Identifier: MIT
#include "vm/folder_hash.hpp"

#include <cerrno>
#include <climits>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "platform/core/path_walk.hpp"

#include "platform/core/errors.hpp"
#include "platform/core/sha256.hpp"  // the evaluation store's SHA-256 (one implementation in the tree)

namespace smi::vm {
namespace fs = std::filesystem;

std::string combine_file_hashes(const std::map<std::string, std::string>& files) {
  Sha256 h;
  h.field("smi-lib-folder-v1");
  for (const auto& [rel, digest] : files) h.field(rel).field(digest);  // std::map: sorted by path
  return "sha256:" + h.hex();
}

namespace {

/// The digest of one entry, never reading outside `top` (canonical): a regular file by content
/// (opened without following a symlink); a symlink whose target, resolved component-wise, is a
/// regular file inside the library by that file's content (what the module loader reads); any
/// other symlink (out of the library, dangling, to a folder) by its link text, so provenance
/// records that the link changed without hashing what it points to.
/// Returns "" for entries that are left out (FIFOs, sockets, devices, links to folders inside).
std::string entry_digest(const fs::path& p, const std::string& top) {
  struct stat st;
  if (::lstat(p.c_str(), &st) != 0) throw Error("cannot read '" + p.string() + "': " + std::strerror(errno));
  pathwalk::Walk w;
  if (S_ISLNK(st.st_mode)) {
    w = pathwalk::walk(p.string(), true);
    if (!w.error && w.exists && S_ISDIR(w.st.st_mode) && pathwalk::within(w.canonical(), top)) return "";
    if (w.error || !w.exists || !S_ISREG(w.st.st_mode) || !pathwalk::within(w.canonical(), top)) {
      char buf[PATH_MAX + 1];
      const ssize_t n = ::readlink(p.c_str(), buf, PATH_MAX);
      if (n < 0) throw Error("cannot read link '" + p.string() + "': " + std::strerror(errno));
      return "symlink:" + sha256_hex(std::string_view(buf, static_cast<std::size_t>(n)));
    }
  } else if (S_ISREG(st.st_mode)) {
    w = pathwalk::walk(p.string(), false);
    if (w.error || !w.exists || !S_ISREG(w.st.st_mode)) throw Error("cannot read '" + p.string() + "': changed while hashed");
  } else {
    return "";
  }
  const pathwalk::Fd fd(::openat(w.dir.get(), w.leaf.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC));
  struct stat now;
  if (!fd || ::fstat(fd.get(), &now) != 0 || !S_ISREG(now.st_mode))
    throw Error("cannot read '" + p.string() + "': " + std::strerror(fd ? EINVAL : errno));
  return sha256_fd(fd.get(), p.string());
}

}  // namespace

FolderHash hash_folder(const fs::path& folder) {
  FolderHash out;
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) throw Error("library folder '" + folder.string() + "' is not a folder");
  const std::string top = fs::weakly_canonical(fs::absolute(folder, ec), ec).string();
  fs::recursive_directory_iterator it(folder, fs::directory_options::none, ec), end;
  if (ec) throw Error("cannot list library folder '" + folder.string() + "': " + ec.message());
  for (; it != end; it.increment(ec)) {
    if (ec) throw Error("cannot list library folder '" + folder.string() + "': " + ec.message());
    const fs::path& p = it->path();
    const std::string leaf = p.filename().string();
    if (it->is_directory(ec) && !it->is_symlink(ec) && leaf == ".git") {
      it.disable_recursion_pending();
      continue;
    }
    if (leaf == ".git") continue;  // a worktree's or submodule's "gitdir:" file
    const std::string digest = entry_digest(p, top);
    if (!digest.empty()) out.files[p.lexically_relative(folder).generic_string()] = digest;
  }
  out.digest = combine_file_hashes(out.files);
  return out;
}

}  // namespace smi::vm
