// SPDX-License-Identifier: MIT
#include "platform/core/path_walk.hpp"

#include <cerrno>
#include <climits>
#include <cstring>
#include <deque>
#include <dirent.h>
#include <fcntl.h>
#include <unistd.h>

namespace smi::pathwalk {
namespace {

constexpr int kMaxLinks = 40;        // the kernel's own limit (MAXSYMLINKS)
constexpr std::size_t kMaxDepth = 128;
constexpr std::size_t kMaxComponents = 4096;
constexpr std::size_t kMaxPathText = 64 * 1024;

/// Splits on '/', dropping empty components. `trailing` tells whether the text ends in '/'.
void split(const std::string& s, std::deque<std::string>& out, bool front) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (start <= s.size()) {
    const std::size_t end = s.find('/', start);
    const std::size_t stop = end == std::string::npos ? s.size() : end;
    if (stop > start) parts.emplace_back(s.substr(start, stop - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  if (front)
    out.insert(out.begin(), parts.begin(), parts.end());
  else
    out.insert(out.end(), parts.begin(), parts.end());
}

std::string join(const std::vector<std::string>& names) {
  if (names.empty()) return "/";
  std::string s;
  for (const auto& n : names) s += "/" + n;
  return s;
}

/// The canonical part reached plus the components not yet walked, normalised as text: only
/// for messages ("resolved to ..."), never opened.
std::string describe(const std::vector<std::string>& names, const std::deque<std::string>& rest) {
  std::vector<std::string> v = names;
  for (const auto& c : rest) {
    if (c == ".") continue;
    if (c == "..") {
      if (!v.empty()) v.pop_back();
      continue;
    }
    v.push_back(c);
  }
  return join(v);
}

int open_path(int dirfd, const char* name, int extra = 0) {
  int fd;
  do fd = ::openat(dirfd, name, O_PATH | O_NOFOLLOW | O_CLOEXEC | extra);
  while (fd < 0 && errno == EINTR);
  return fd;
}

// The components to walk, in todo: the working folder's (for a relative path) then the path's.
// false (and w.error, w.where set) when the path text is empty, too long, holds a NUL or has
// too many components. must_be_dir: the path ends in "/", "." or ".." (a trailing "/" also
// follows a last link, as the kernel does).
bool components_to_walk(const std::string& path, bool& follow_last, bool& must_be_dir, std::deque<std::string>& todo,
                        Walk& w) {
  if (path.empty() || path.size() > kMaxPathText || path.find('\0') != std::string::npos) {
    // (a NUL would end the name the kernel sees while the walk's text went on)
    w.error = path.empty() ? ENOENT : path.size() > kMaxPathText ? ENAMETOOLONG : EINVAL;
    w.where = path;
    return false;
  }
  must_be_dir = path.back() == '/';
  if (must_be_dir) follow_last = true;  // as the kernel: "link/" names what the link points to
  if (path[0] != '/') {
    char buf[PATH_MAX];
    if (!::getcwd(buf, sizeof buf)) {
      w.error = errno;
      w.where = path;
      return false;
    }
    split(buf, todo, false);
  }
  split(path, todo, false);
  if (todo.size() > kMaxComponents) {
    w.error = ENAMETOOLONG;
    w.where = path;
    return false;
  }
  if (!todo.empty() && (todo.back() == "." || todo.back() == "..")) must_be_dir = true;
  return true;
}

// The walk reached its end: a path naming a folder is expressed as (its parent, its name); the
// result holds the parent's descriptor and canonical text, or ENOTDIR when the path asked for a
// folder and names something else.
void finish_walk(Walk& w, std::vector<std::string>& names, std::vector<Fd>& fds, bool must_be_dir) {
  if (w.leaf.empty() && !names.empty()) {
    w.leaf = names.back();
    names.pop_back();
    Fd self = std::move(fds.back());
    fds.pop_back();
    w.exists = ::fstat(self.get(), &w.st) == 0;
  } else if (w.leaf.empty()) {
    w.exists = ::fstat(fds[0].get(), &w.st) == 0;
  }
  if (must_be_dir && w.exists && !S_ISDIR(w.st.st_mode) && !S_ISLNK(w.st.st_mode)) {
    w.error = ENOTDIR;
    w.where = describe(names, {w.leaf});
    return;
  }
  w.dir_path = join(names);
  w.dir = std::move(fds.back());
  w.where = w.canonical();
}

}  // namespace

void Fd::reset() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

std::string Walk::canonical() const {
  if (leaf.empty()) return dir_path;
  return dir_path == "/" ? "/" + leaf : dir_path + "/" + leaf;
}

bool within(const std::string& path, const std::string& root) {
  if (root.empty()) return false;
  if (root == "/") return !path.empty() && path[0] == '/';
  std::string r = root;
  while (r.size() > 1 && r.back() == '/') r.pop_back();
  if (path.compare(0, r.size(), r) != 0) return false;
  return path.size() == r.size() || path[r.size()] == '/';
}

// long: one loop over the queue of components, whose cases (".", "..", a link spliced into the
// queue, a folder descended into, the leaf) all move the same state (the queue, the open folder
// descriptors and their names, the link count); its entry and exit are in the helpers above.
Walk walk(const std::string& path, bool follow_last) {
  Walk w;
  std::deque<std::string> todo;
  bool must_be_dir = false;
  if (!components_to_walk(path, follow_last, must_be_dir, todo, w)) return w;

  std::vector<Fd> fds;              // fds[0] = "/", fds[i] = names[i-1]
  std::vector<std::string> names;   // canonical components of the folder reached
  fds.emplace_back(open_path(AT_FDCWD, "/", O_DIRECTORY));
  if (!fds[0]) {
    w.error = errno;
    return w;
  }
  int links = 0;
  std::size_t steps = 0;
  auto fail = [&](int err) {
    w.error = err;
    w.where = describe(names, todo);
    return std::move(w);
  };
  while (!todo.empty()) {
    if (++steps > kMaxComponents * 4) return fail(ELOOP);
    std::string c = std::move(todo.front());
    todo.pop_front();
    if (c == ".") continue;
    if (c == "..") {
      if (!names.empty()) {
        names.pop_back();
        fds.pop_back();
      }
      continue;
    }
    if (c.size() > NAME_MAX) {
      todo.push_front(c);
      return fail(ENAMETOOLONG);
    }
    const bool last = todo.empty();
    if (last && !follow_last) {
      w.leaf = c;
      struct stat st;
      if (::fstatat(fds.back().get(), c.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0) {
        w.exists = true;
        w.st = st;
      } else if (errno != ENOENT) {
        todo.push_front(c);
        return fail(errno);
      }
      break;
    }
    Fd fd(open_path(fds.back().get(), c.c_str()));
    if (!fd) {
      const int e = errno;
      if (last && e == ENOENT) {
        w.leaf = c;
        break;
      }
      todo.push_front(c);
      return fail(e);
    }
    struct stat st;
    if (::fstat(fd.get(), &st) != 0) {
      todo.push_front(c);
      return fail(errno);
    }
    if (S_ISLNK(st.st_mode)) {
      if (++links > kMaxLinks) {
        todo.push_front(c);
        return fail(ELOOP);
      }
      char buf[PATH_MAX + 1];
      const ssize_t n = ::readlinkat(fd.get(), "", buf, PATH_MAX);
      if (n <= 0) {
        todo.push_front(c);
        return fail(n == 0 ? ENOENT : errno);
      }
      const std::string target(buf, static_cast<std::size_t>(n));
      if (target.size() && target.back() == '/' && last) must_be_dir = true;
      split(target, todo, true);
      if (todo.size() > kMaxComponents) return fail(ENAMETOOLONG);
      if (target[0] == '/') {
        names.clear();
        fds.resize(1);
      }
      continue;
    }
    if (S_ISDIR(st.st_mode)) {
      if (fds.size() > kMaxDepth) {
        todo.push_front(c);
        return fail(ENAMETOOLONG);
      }
      names.push_back(c);
      fds.push_back(std::move(fd));
      continue;
    }
    if (!last) {
      todo.push_front(c);
      return fail(ENOTDIR);
    }
    w.leaf = c;
    w.exists = true;
    w.st = st;
    break;
  }
  finish_walk(w, names, fds, must_be_dir);
  return w;
}

Fd make_dirs_nofollow(const std::string& dir) {
  std::deque<std::string> parts;
  split(dir, parts, false);
  Fd cur(open_path(AT_FDCWD, "/", O_DIRECTORY));
  if (!cur) return cur;
  for (const auto& c : parts) {
    if (c == "." || c == "..") {
      errno = EINVAL;
      return Fd();
    }
    int fd = open_path(cur.get(), c.c_str(), O_DIRECTORY);
    if (fd < 0 && errno == ENOENT) {
      if (::mkdirat(cur.get(), c.c_str(), 0777) != 0 && errno != EEXIST) return Fd();
      fd = open_path(cur.get(), c.c_str(), O_DIRECTORY);
    }
    if (fd < 0) return Fd();  // ENOTDIR also for a symlink (O_PATH|O_NOFOLLOW|O_DIRECTORY)
    cur = Fd(fd);
  }
  return cur;
}

bool read_all(int fd, std::string& out, std::size_t limit) {
  out.clear();
  char buf[65536];
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    if (n == 0) return true;
    if (out.size() + static_cast<std::size_t>(n) > limit) {
      errno = EFBIG;
      return false;
    }
    out.append(buf, static_cast<std::size_t>(n));
  }
}

bool write_all(int fd, const std::string& data) {
  std::size_t done = 0;
  while (done < data.size()) {
    const ssize_t n = ::write(fd, data.data() + done, data.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    done += static_cast<std::size_t>(n);
  }
  return true;
}

bool remove_tree_at(int dirfd, const std::string& name) {
  if (::unlinkat(dirfd, name.c_str(), 0) == 0 || errno == ENOENT) return true;
  if (errno != EISDIR && errno != EPERM) return false;
  const int fd = ::openat(dirfd, name.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) return false;
  DIR* d = ::fdopendir(fd);
  if (!d) {
    ::close(fd);
    return false;
  }
  bool ok = true;
  std::vector<std::string> entries;
  while (dirent* e = ::readdir(d)) {
    const std::string n = e->d_name;
    if (n != "." && n != "..") entries.push_back(n);
  }
  for (const auto& n : entries) ok = remove_tree_at(::dirfd(d), n) && ok;
  ::closedir(d);
  if (!ok) return false;
  return ::unlinkat(dirfd, name.c_str(), AT_REMOVEDIR) == 0 || errno == ENOENT;
}

}  // namespace smi::pathwalk
