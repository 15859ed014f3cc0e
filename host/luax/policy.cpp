// SPDX-License-Identifier: MIT
#include "luax/policy.hpp"

#include "luax/load_guard.hpp"

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <fmt/format.h>
#include <unistd.h>

namespace smi::lua {
namespace fs = std::filesystem;

fs::path resolve_path(const std::string& path) {
  std::error_code ec;
  fs::path p = fs::absolute(fs::path(path), ec);
  if (ec) p = fs::path(path);
  // weakly_canonical follows symlinks of the existing prefix and normalises the rest lexically.
  fs::path r = fs::weakly_canonical(p, ec);
  if (ec) r = p.lexically_normal();
  return r;
}

fs::path output_root(const std::string& path) {
  fs::path p = fs::path(path).lexically_normal();
  if (!p.has_filename() && p.has_parent_path()) p = p.parent_path();  // "smi-out/x/"
  std::error_code ec;
  if (p.is_relative()) {
    const fs::path cwd = fs::canonical(fs::current_path(ec), ec);
    return (cwd / p).lexically_normal();
  }
  return resolve_path(p.parent_path().string()) / p.filename();
}

bool path_within(const fs::path& path, const fs::path& root) { return pathwalk::within(path.string(), root.string()); }

namespace {

std::string list_roots(const std::vector<fs::path>& roots) {
  std::string s;
  for (const auto& r : roots) s += (s.empty() ? "" : ", ") + r.string();
  return s.empty() ? "(none)" : s;
}

bool under_any(const std::string& canonical, const std::vector<fs::path>& roots) {
  for (const auto& r : roots)
    if (pathwalk::within(canonical, r.string())) return true;
  return false;
}

/// The path made absolute as text (the working folder resolved, nothing of the path followed).
std::string lexical_absolute(const std::string& path) {
  fs::path p(path);
  std::error_code ec;
  if (p.is_relative()) p = fs::canonical(fs::current_path(ec), ec) / p;
  std::string s = p.lexically_normal().string();
  while (s.size() > 1 && s.back() == '/') s.pop_back();
  return s;
}

/// How a denial shows where `path` led (`where`, canonical). A denial names the path the script
/// gave; where a link on the way led elsewhere (/proc/self/fd/N, /proc/self/cwd, a planted link)
/// the target is not shown: it may name files of the host outside every root.
bool led_elsewhere(const std::string& path, const std::string& where) {
  const std::string lex = lexical_absolute(path);
  return lex != where && !pathwalk::within(lex, where);  // (a walk that stopped early names a prefix)
}

std::string resolved_note(const std::string& path, const std::string& where) {
  return led_elsewhere(path, where) ? " (a link on the way leads outside the folders allowed)"
                                    : fmt::format(" (resolved to '{}')", where);
}

std::string parent_of(const std::string& canonical) {
  const fs::path p(canonical);
  return p.has_parent_path() ? p.parent_path().string() : canonical;
}

[[noreturn]] void os_error(const std::string& path, int e) {
  throw FileError(fmt::format("{}: {}", path, std::strerror(e)), e);
}

/// Opens the last component of a walk that found an existing, non-symlink entry, for reading:
/// O_NOFOLLOW relative to the checked folder, and the same inode as the walk saw (a swap after
/// the walk returns false: the caller walks again).
bool open_leaf_read(const pathwalk::Walk& w, const std::string& shown, pathwalk::Fd& out) {
  if (!S_ISREG(w.st.st_mode)) {
    if (S_ISDIR(w.st.st_mode)) os_error(shown, EISDIR);
    throw FileError(fmt::format("{}: not a regular file (only regular files are opened in the sandbox)", shown), EINVAL);
  }
  const int fd = ::openat(w.dir.get(), w.leaf.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) {
    if (errno == ELOOP || errno == ENOENT || errno == ENXIO) return false;  // changed since the walk
    os_error(shown, errno);
  }
  pathwalk::Fd f(fd);
  struct stat st;
  if (::fstat(fd, &st) != 0) os_error(shown, errno);
  if (st.st_dev != w.st.st_dev || st.st_ino != w.st.st_ino || !S_ISREG(st.st_mode)) return false;
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  out = std::move(f);
  return true;
}

constexpr int kRetries = 16;  // walks per open when the file keeps changing under us

}  // namespace

std::string read_checked(const CheckedFile& f, const std::string& shown) {
  std::string text;
  if (!pathwalk::read_all(f.fd.get(), text)) os_error(shown, errno);
  return text;
}

CheckedFile open_read_within(const std::string& path, const std::vector<fs::path>& roots,
                             const std::string& denial_hint) {
  for (int attempt = 0; attempt < kRetries; ++attempt) {
    pathwalk::Walk w = pathwalk::walk(path, true);
    const std::string where = w.error ? w.where : w.canonical();
    if (!under_any(where, roots))
      throw SandboxDenied(fmt::format("reading '{}'{} is not allowed: {}", path, resolved_note(path, where), denial_hint));
    if (w.error) os_error(path, w.error);
    if (!w.exists) os_error(path, ENOENT);
    pathwalk::Fd fd;
    if (open_leaf_read(w, path, fd)) return {std::move(fd), w.canonical()};
  }
  throw FileError(fmt::format("{}: changed while being opened ({} attempts); try again", path, kRetries), EAGAIN);
}

CheckedFile Policy::open_read(const std::string& path) const {
  CheckedFile f = open_read_unrecorded(path);
  if (record) record->file("data", f.path, f.fd.get());
  return f;
}

CheckedFile Policy::open_read_unrecorded(const std::string& path) const {
  if (unrestricted) {
    std::vector<fs::path> all{"/"};
    return open_read_within(path, all, "");
  }
  std::vector<fs::path> roots = read_roots;
  roots.insert(roots.end(), write_roots.begin(), write_roots.end());
  const std::string resolved = resolve_path(path).string();
  return open_read_within(
      path, roots,
      fmt::format("scripts read only under their own folder, the library folders and --allow-read paths ({}); {}",
                  list_roots(read_roots),
                  led_elsewhere(path, resolved)
                      ? std::string("if the place the link leads to is meant to be read, allow its folder with --allow-read")
                      : fmt::format("run with --allow-read {} to allow it", parent_of(resolved))));
}

fs::path Policy::ensure_out_dir() const {
  const std::string root = out_root.empty() ? output_root(out_dir.string()).string() : out_root.string();
  pathwalk::Fd fd = pathwalk::make_dirs_nofollow(root);
  if (!fd) {
    const int e = errno;
    // Name the link: it sits where smi-lua makes its folders (a study bundle unpacked here can
    // bring one). Its target is not shown: it may lie outside every root.
    fs::path at;
    for (const auto& part : fs::path(root)) {
      at /= part;
      struct stat st;
      if (::lstat(at.c_str(), &st) != 0) break;
      if (S_ISLNK(st.st_mode))
        throw SandboxDenied(fmt::format("the output folder '{}' cannot be used: '{}' is a symbolic link, and smi-lua "
                                        "makes its output folders itself without following links. Remove the link, "
                                        "or give --out a real folder",
                                        out_dir.string(), at.string()));
      if (!S_ISDIR(st.st_mode)) break;
    }
    throw Error(fmt::format("cannot create the output folder '{}' ({}): {}", out_dir.string(), root, std::strerror(e)));
  }
  return root;
}

pathwalk::Walk Policy::walk_write(const std::string& path, const std::string& named) const {
  // The output folder is created on demand: on the first write under it. Deciding that on the
  // text of the path only creates a folder the policy allows anyway.
  // Whether the path lies in it is judged on the text (made absolute, links not followed): a
  // link planted on the way must meet ensure_out_dir, which refuses it by name.
  const std::string root = !out_root.empty() ? out_root.string()
                           : out_dir.empty() ? std::string()
                                             : output_root(out_dir.string()).string();
  if (!root.empty() && (pathwalk::within(output_root(path).string(), root) ||
                        pathwalk::within(resolve_path(path).string(), root)))
    ensure_out_dir();
  pathwalk::Walk w = pathwalk::walk(path, false);
  if (!unrestricted) {
    // The entry's folder must lie under a write root (so a root itself cannot be removed or
    // renamed), or the entry is a root given as a file (--allow-write results.csv).
    bool ok = false;
    if (w.error)
      ok = under_any(w.where, write_roots);
    else if (!w.leaf.empty())
      ok = under_any(w.dir_path, write_roots) ||
           (!(w.exists && S_ISDIR(w.st.st_mode)) &&
            std::any_of(write_roots.begin(), write_roots.end(), [&](const fs::path& r) { return r == w.canonical(); }));
    if (!ok) {
      const std::string shown = w.error ? w.where : w.canonical();
      const bool linked = led_elsewhere(named, shown);
      throw SandboxDenied(fmt::format(
          "writing '{}'{} is not allowed: scripts write only under the output folder "
          "(--out, now {}; smi.out(\"name\") gives a path there) and --allow-write paths ({}); {}",
          named, resolved_note(named, shown), out_dir.string(), list_roots(write_roots),
          linked ? std::string("if the place the link leads to is meant to be written, allow its folder with --allow-write")
                 : fmt::format("run with --allow-write {} to allow it", parent_of(shown))));
    }
  }
  if (w.error) os_error(named, w.error);
  if (w.leaf.empty()) os_error(named, EISDIR);
  return w;
}

CheckedFile Policy::open_write(const std::string& path, int oflags) const {
  std::string p = path;
  int links = 0;
  for (int attempt = 0; attempt < kRetries + 40; ++attempt) {
    pathwalk::Walk w = walk_write(p, path);
    if (w.exists && S_ISLNK(w.st.st_mode)) {
      // A symlink as last component is resolved component-wise like any other, then checked
      // again: its target must lie under a write root too.
      char buf[PATH_MAX + 1];
      const ssize_t n = ::readlinkat(w.dir.get(), w.leaf.c_str(), buf, PATH_MAX);
      if (n <= 0) continue;  // changed: walk again
      const std::string target(buf, static_cast<std::size_t>(n));
      p = target[0] == '/' ? target : w.dir_path + "/" + target;
      if (++links > 40) os_error(path, ELOOP);
      continue;
    }
    const int fd = ::openat(w.dir.get(), w.leaf.c_str(),
                            (oflags & ~O_TRUNC) | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC | O_NOCTTY, 0666);
    if (fd < 0) {
      if (errno == ELOOP) continue;  // a symlink appeared after the walk: walk again
      os_error(path, errno);
    }
    pathwalk::Fd f(fd);
    struct stat st;
    if (::fstat(fd, &st) != 0) os_error(path, errno);
    if (!S_ISREG(st.st_mode))
      throw FileError(fmt::format("{}: not a regular file (only regular files are opened in the sandbox)", path), EINVAL);
    if (st.st_nlink > 1 && !unrestricted)
      throw SandboxDenied(fmt::format(
          "writing '{}' (resolved to '{}') is not allowed: the file has {} hard links, so writing it would change "
          "a file elsewhere; remove it first or write a new file",
          path, w.canonical(), st.st_nlink));
    if ((oflags & O_TRUNC) && ::ftruncate(fd, 0) != 0) os_error(path, errno);
    ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
    return {std::move(f), w.canonical()};
  }
  throw FileError(fmt::format("{}: changed while being opened ({} attempts); try again", path, kRetries), EAGAIN);
}

std::string Policy::checked_write_dir(const std::string& path) const {
  for (int attempt = 0; attempt < 4; ++attempt) {
    pathwalk::Walk w;
    try {
      w = walk_write(path);
    } catch (const FileError& e) {
      // A missing folder on the way: make the parent (checked the same way), then walk again.
      const fs::path parent = fs::path(path).parent_path();
      if (e.err != ENOENT || parent.empty() || parent == fs::path(path) || attempt > 0) throw;
      checked_write_dir(parent.string());
      continue;
    }
    if (!w.exists) {
      if (::mkdirat(w.dir.get(), w.leaf.c_str(), 0777) != 0 && errno != EEXIST) os_error(path, errno);
      continue;
    }
    if (S_ISLNK(w.st.st_mode))
      throw SandboxDenied(fmt::format("writing '{}' (resolved to '{}') is not allowed: it is a symlink, and folders "
                                      "the runtime writes in are not reached through symlinks",
                                      path, w.canonical()));
    if (!S_ISDIR(w.st.st_mode)) os_error(path, ENOTDIR);
    return w.canonical();
  }
  throw FileError(fmt::format("{}: changed while being made; try again", path), EAGAIN);
}

std::string Policy::checked_write_file(const std::string& path) const {
  pathwalk::Walk w = walk_write(path);
  if (w.exists && !S_ISREG(w.st.st_mode))
    throw SandboxDenied(fmt::format("writing '{}' (resolved to '{}') is not allowed: it is not a regular file{}", path,
                                    w.canonical(), S_ISLNK(w.st.st_mode) ? " but a symbolic link" : ""));
  if (w.exists && w.st.st_nlink > 1 && !unrestricted)
    throw SandboxDenied(fmt::format("writing '{}' is not allowed: the file has {} hard links, so writing it would "
                                    "change a file elsewhere; remove it first",
                                    path, w.st.st_nlink));
  return w.canonical();
}

std::string Policy::checked_read_file(const std::string& path) const {
  CheckedFile f = open_read(path);  // checked and a regular file now; the caller opens it by name
  return f.path;
}

fs::path Policy::check_exec(const std::string& program, const char* function) const {
  (void)function;  // named by the caller's protect(), see check_read
  fs::path resolved;
  if (program.find('/') != std::string::npos) {
    resolved = resolve_path(program);
    // a path that names no program fails now, where the model is declared, not at its first run
    struct stat st {};
    if (::stat(resolved.c_str(), &st) != 0)
      throw Error(fmt::format("program '{}' does not exist ({}): check the path{}", program, resolved.string(),
                              program[0] == '/' ? "" : " (relative to the current folder)"));
    if (!S_ISREG(st.st_mode) || ::access(resolved.c_str(), X_OK) != 0)
      throw Error(fmt::format("program '{}' ({}) is not an executable file{}", program, resolved.string(),
                              S_ISREG(st.st_mode) ? ": make it executable (chmod +x) or give the program itself" : ""));
  } else if (const char* env = std::getenv("PATH")) {
    std::string dirs = env;
    std::size_t start = 0;
    while (start <= dirs.size()) {
      const std::size_t end = dirs.find(':', start);
      const std::string dir = dirs.substr(start, end == std::string::npos ? std::string::npos : end - start);
      const fs::path cand = fs::path(dir.empty() ? "." : dir) / program;
      if (::access(cand.c_str(), X_OK) == 0) {
        resolved = resolve_path(cand.string());
        break;
      }
      if (end == std::string::npos) break;
      start = end + 1;
    }
  }
  if (resolved.empty())
    throw SandboxDenied(fmt::format("program '{}' not found on PATH", program));
  if (unrestricted) return resolved;
  for (const auto& allowed : exec_allowed) {
    // By name: "--allow-exec smi-column-fe" allows that program wherever PATH finds it.
    const bool named = (allowed.find('/') == std::string::npos && allowed == program) ||
                       (allowed.find('/') != std::string::npos && resolve_path(allowed) == resolved);
    if (!named) continue;
    // Write or execute, not both: a program the script may rewrite would run the script's code
    // with none of the sandbox's limits.
    for (const auto& root : write_roots)
      if (path_within(resolved, root))
        throw SandboxDenied(fmt::format(
            "running '{}' is not allowed: the program lies under '{}', a folder the script may write, so the script "
            "could replace it before it runs. Install it outside the output folder and the --allow-write folders",
            program, root.string()));
    return resolved;
  }
  throw SandboxDenied(fmt::format(
      "running '{}' ({}) is not allowed: scripts run only programs named by --allow-exec; "
      "run with --allow-exec {} to allow it",
      program, resolved.string(), program));
}

namespace {
const char kPolicyKey = 0;  // its address is the registry key
}

Policy& policy(lua_State* L) {
  lua_rawgetp(L, LUA_REGISTRYINDEX, &kPolicyKey);
  auto* p = static_cast<Policy*>(lua_touserdata(L, -1));
  lua_pop(L, 1);
  if (p) return *p;
  static Policy unrestricted_default = [] {
    Policy d;
    d.unrestricted = true;
    d.out_dir = "smi-out";
    return d;
  }();
  return unrestricted_default;
}

int load_text(lua_State* L, const std::string& text, const std::string& chunkname) {
  std::size_t start = 0;
  if (text.compare(0, 3, "\xEF\xBB\xBF") == 0) start = 3;
  if (start < text.size() && text[start] == '#') {
    const std::size_t nl = text.find('\n', start);
    start = nl == std::string::npos ? text.size() : nl;  // keep the newline: line numbers stay right
  }
  return load_buffer(L, text.data() + start, text.size() - start, chunkname.c_str());
}

void set_policy(lua_State* L, Policy* p) {
  lua_pushlightuserdata(L, p);
  lua_rawsetp(L, LUA_REGISTRYINDEX, &kPolicyKey);
}

void* exit_sentinel() {
  static char tag;
  return &tag;
}


}  // namespace smi::lua
