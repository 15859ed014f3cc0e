// SPDX-License-Identifier: MIT
#pragma once
// Path resolution as the kernel does it, but one component at a time through descriptors, so
// that what is checked is what is opened.
//
// walk() starts at "/" (a relative path is taken from the working directory's canonical path)
// and opens every component with openat(O_PATH | O_NOFOLLOW). A symlink is never followed by
// the kernel: its text is read from the link itself (readlinkat on the O_PATH descriptor) and
// spliced into the components still to walk, so a link is resolved component-wise again; ".."
// goes back to the folder descriptor held one level up (the kernel's ".." after a link goes to
// the link target's parent too). The result is an O_PATH descriptor of the folder holding the
// last component, and the canonical path by which it was reached; a caller checks that path
// against its roots and then opens the last component relative to that descriptor with
// O_NOFOLLOW, so a symlink swapped in after the walk fails the open instead of being followed.
//
// No openat2(RESOLVE_BENEATH): the roots of a sandboxed script are several unrelated folders and
// a link may lead from one to another, which RESOLVE_BENEATH (one root per call) refuses; the
// walk above gives the same guarantee on every kernel. Limits: 40 symlinks per walk (as the
// kernel), 128 folders deep, 4096 components, 64 KiB of path text.
#include <string>
#include <vector>
#include <sys/stat.h>

namespace smi::pathwalk {

/// An owned file descriptor.
class Fd {
 public:
  Fd() = default;
  explicit Fd(int fd) : fd_(fd) {}
  Fd(Fd&& o) noexcept : fd_(o.release()) {}
  Fd& operator=(Fd&& o) noexcept {
    if (this != &o) {
      reset();
      fd_ = o.release();
    }
    return *this;
  }
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  ~Fd() { reset(); }
  int get() const { return fd_; }
  explicit operator bool() const { return fd_ >= 0; }
  int release() {
    const int f = fd_;
    fd_ = -1;
    return f;
  }
  void reset();

 private:
  int fd_ = -1;
};

struct Walk {
  int error = 0;          // 0, or the errno that stopped the walk before the last component
  Fd dir;                 // O_PATH descriptor of the folder holding `leaf` (when error == 0)
  std::string dir_path;   // canonical path of that folder ("/" for the root)
  std::string leaf;       // the last component ("" when the path names "/"); never "." or ".."
  bool exists = false;    // the last component exists (with follow_last: and is no symlink)
  struct stat st {};      // of the last component, when it exists
  std::string where;      // for messages: the canonical part reached, then the rest as text

  /// dir_path joined with leaf.
  std::string canonical() const;
};

/// Walks `path` as described above. With follow_last, a symlink as last component is resolved
/// too; without, the last component is left as it is (remove, rename act on the link itself).
/// A missing last component is not an error (exists = false); a missing folder before it is.
Walk walk(const std::string& path, bool follow_last);

/// True if `path` equals `root` or lies below it, both canonical ("/a/b" is not within "/a/bc").
bool within(const std::string& path, const std::string& root);

/// Opens (creating what is missing, mode 0777 & umask) the folder at the canonical path `dir`,
/// refusing any symlink on the way. Sets errno and returns an invalid Fd on failure.
Fd make_dirs_nofollow(const std::string& dir);

/// Reads everything from `fd` (from its current offset), at most `limit` bytes (more sets
/// errno = EFBIG and returns false).
bool read_all(int fd, std::string& out, std::size_t limit = static_cast<std::size_t>(1) << 34);

/// Writes all of `data`; false with errno set on failure.
bool write_all(int fd, const std::string& data);

/// Removes `name` in folder `dirfd` and, if it is a folder, everything below it, never
/// following a symlink (a link is removed, not its target). Missing is success.
bool remove_tree_at(int dirfd, const std::string& name);

}  // namespace smi::pathwalk
