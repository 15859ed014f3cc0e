#include "vm/git_commit.hpp"

#include <cctype>
#include <fstream>
#include <sstream>

namespace smi::vm {
namespace fs = std::filesystem;
namespace {

std::string first_line(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  if (!in || !std::getline(in, line)) return {};
  while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
  return line;
}

bool is_sha(const std::string& s) {
  if (s.size() != 40 && s.size() != 64) return false;  // sha1 or sha256 object format
  for (char c : s)
    if (!std::isxdigit(static_cast<unsigned char>(c))) return false;
  return true;
}

/// The git directory of a checkout at `top`: .git itself, or the target of a "gitdir: x" file.
fs::path git_dir_of(const fs::path& top) {
  const fs::path dot = top / ".git";
  std::error_code ec;
  if (fs::is_directory(dot, ec)) return dot;
  if (fs::is_regular_file(dot, ec)) {
    const std::string line = first_line(dot);
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
std::string resolve_ref(const fs::path& gitdir, const fs::path& common, const std::string& ref, int depth = 0) {
  if (depth > 5) return {};
  for (const fs::path& d : {gitdir, common}) {
    std::error_code ec;
    const fs::path loose = d / ref;
    if (fs::is_regular_file(loose, ec)) {
      const std::string v = first_line(loose);
      if (v.rfind("ref:", 0) == 0) {
        std::string next = v.substr(4);
        while (!next.empty() && next.front() == ' ') next.erase(next.begin());
        return resolve_ref(gitdir, common, next, depth + 1);
      }
      if (is_sha(v)) return v;
    }
  }
  std::ifstream packed(common / "packed-refs");
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
      fs::path common = gitdir;
      if (const std::string c = first_line(gitdir / "commondir"); !c.empty())
        common = fs::path(c).is_absolute() ? fs::path(c) : gitdir / c;
      const std::string head = first_line(gitdir / "HEAD");
      if (head.rfind("ref:", 0) == 0) {
        std::string ref = head.substr(4);
        while (!ref.empty() && ref.front() == ' ') ref.erase(ref.begin());
        if (ref.rfind("refs/heads/", 0) == 0) info.branch = ref.substr(11);
        info.commit = resolve_ref(gitdir, common, ref);
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
