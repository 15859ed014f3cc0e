// SPDX-License-Identifier: MIT
#include "vm/git_commit.hpp"

#include <cctype>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "platform/core/path_walk.hpp"
#include <sstream>

namespace smi::vm {
namespace fs = std::filesystem;
namespace {

constexpr std::size_t kLineMax = 4096;               // HEAD, refs, commondir, gitdir files
constexpr std::size_t kPackedMax = 64u << 20;        // packed-refs

/// The text of a regular file reached from `file` without leaving `top` (canonical), at most
/// `limit` bytes; "" otherwise. The walk and open are the sandbox's (core/path_walk.hpp): a
/// .git file, commondir or symlink pointing out of the checkout is not followed, and a FIFO or
/// device (which would hang or never end) is not read.
std::string read_within(const fs::path& file, const std::string& top, std::size_t limit) {
  const pathwalk::Walk w = pathwalk::walk(file.string(), true);
  if (w.error || !w.exists || !S_ISREG(w.st.st_mode) || !pathwalk::within(w.canonical(), top)) return {};
  const pathwalk::Fd fd(::openat(w.dir.get(), w.leaf.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC));
  struct stat st;
  if (!fd || ::fstat(fd.get(), &st) != 0 || st.st_ino != w.st.st_ino || st.st_dev != w.st.st_dev) return {};
  std::string text;
  if (!pathwalk::read_all(fd.get(), text, limit)) return {};
  return text;
}

std::string first_line(const fs::path& file, const std::string& top) {
  std::string line = read_within(file, top, kLineMax);
  if (const std::size_t nl = line.find('\n'); nl != std::string::npos) line.resize(nl);
  while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
  return line;
}

bool is_sha(const std::string& s) {
  if (s.size() != 40 && s.size() != 64) return false;  // sha1 or sha256 object format
  for (char c : s)
    if (!std::isxdigit(static_cast<unsigned char>(c))) return false;
  return true;
}

/// The git directory of a checkout at `top`: .git itself, or the target of a "gitdir: x" file
/// (read only if it stays inside `top`: see read_within).
fs::path git_dir_of(const fs::path& top) {
  const fs::path dot = top / ".git";
  struct stat st;
  if (::lstat(dot.c_str(), &st) != 0) return {};
  if (S_ISDIR(st.st_mode)) return dot;
  if (S_ISREG(st.st_mode)) {
    const std::string line = first_line(dot, top.string());
    if (line.rfind("gitdir:", 0) == 0) {
      std::string p = line.substr(7);
      while (!p.empty() && p.front() == ' ') p.erase(p.begin());
      fs::path g(p);
      return g.is_absolute() ? g : top / g;
    }
  }
  return {};
}

/// Resolves a ref name ("refs/heads/main") in a git dir and its common dir; "" if unknown.
std::string resolve_ref(const fs::path& gitdir, const fs::path& common, const std::string& ref, const std::string& top,
                        int depth = 0) {
  if (depth > 5) return {};
  // A ref is a name under refs/ ("refs/heads/main"), never a path climbing out of the git dir.
  if (ref.rfind("refs/", 0) != 0 || ref.find("..") != std::string::npos) return {};
  for (const fs::path& d : {gitdir, common}) {
    const std::string v = first_line(d / ref, top);
    if (v.rfind("ref:", 0) == 0) {
      std::string next = v.substr(4);
      while (!next.empty() && next.front() == ' ') next.erase(next.begin());
      return resolve_ref(gitdir, common, next, top, depth + 1);
    }
    if (is_sha(v)) return v;
  }
  std::istringstream packed(read_within(common / "packed-refs", top, kPackedMax));
  std::string line;
  while (std::getline(packed, line)) {
    if (line.empty() || line[0] == '#' || line[0] == '^') continue;
    std::istringstream ls(line);
    std::string sha, name;
    if (ls >> sha >> name && name == ref && is_sha(sha)) return sha;
  }
  return {};
}

}  // namespace

GitInfo git_info(const fs::path& folder) {
  GitInfo info;
  std::error_code ec;
  fs::path dir = fs::weakly_canonical(fs::absolute(folder, ec), ec);
  for (; !dir.empty(); dir = dir.parent_path()) {
    const fs::path gitdir = git_dir_of(dir);
    if (!gitdir.empty()) {
      info.repo_root = dir;
      const std::string top = dir.string();
      fs::path common = gitdir;
      if (const std::string c = first_line(gitdir / "commondir", top); !c.empty())
        common = fs::path(c).is_absolute() ? fs::path(c) : gitdir / c;
      const std::string head = first_line(gitdir / "HEAD", top);
      if (head.rfind("ref:", 0) == 0) {
        std::string ref = head.substr(4);
        while (!ref.empty() && ref.front() == ' ') ref.erase(ref.begin());
        if (ref.rfind("refs/heads/", 0) == 0) info.branch = ref.substr(11);
        info.commit = resolve_ref(gitdir, common, ref, top);
      } else if (is_sha(head)) {
        info.commit = head;
      }
      return info;
    }
    if (dir == dir.root_path()) break;
  }
  return info;
}

}  // namespace smi::vm
