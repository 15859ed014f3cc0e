// SPDX-License-Identifier: MIT
#include "vm/library_sources.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <sys/stat.h>
#include <unistd.h>

#include "platform/core/errors.hpp"
#include "platform/core/sha256.hpp"
#include "vm/git_commit.hpp"
#include "vm/git_process.hpp"
#include "vm/tar_gz.hpp"


namespace smi::vm {
namespace fs = std::filesystem;
namespace {

std::string trim(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
  return s;
}

/// Copies the files of a library folder but .git and smi-out/ (a source folder's test outputs
/// are no part of what is installed; vm/folder_hash.hpp). A symbolic link or special file is
/// refused by name: an installed library is plain files.
void copy_library(const fs::path& src, const fs::path& dest, const std::string& what) {
  fs::create_directories(dest);
  std::error_code ec;
  fs::recursive_directory_iterator it(src, fs::directory_options::none, ec), end;
  if (ec) throw Error("cannot list " + what + ": " + ec.message());
  for (; it != end; it.increment(ec)) {
    if (ec) throw Error("cannot list " + what + ": " + ec.message());
    const fs::path& p = it->path();
    const std::string leaf = p.filename().string();
    const fs::path rel = p.lexically_relative(src);
    const auto st = it->symlink_status(ec);
    if (leaf == ".git" || (leaf == "smi-out" && fs::is_directory(st))) {
      if (fs::is_directory(st)) it.disable_recursion_pending();
      continue;
    }
    if (fs::is_symlink(st))
      throw Error(what + " holds a symbolic link, '" + rel.generic_string() +
                  "': an installed library holds only files and folders (replace the link by the file)");
    if (fs::is_directory(st)) {
      fs::create_directories(dest / rel);
    } else if (fs::is_regular_file(st)) {
      fs::copy_file(p, dest / rel, fs::copy_options::none, ec);
      if (ec) throw Error("cannot copy '" + rel.generic_string() + "' of " + what + ": " + ec.message());
    } else {
      throw Error(what + " holds '" + rel.generic_string() + "', which is neither a file nor a folder; remove it");
    }
  }
}

std::string version_list(const std::vector<VersionTag>& tags) {
  std::string s;
  for (const auto& t : tags) s += (s.empty() ? "" : ", ") + t.tag;
  return s.empty() ? "none" : s;
}

/// The tags of a clone, as version tags (highest first).
std::vector<VersionTag> parse_tag_lines(const std::string& text, bool ls_remote) {
  std::vector<VersionTag> out;
  std::stringstream ss(text);
  for (std::string line; std::getline(ss, line);) {
    std::string tag = line;
    if (ls_remote) {
      const std::size_t at = line.find("refs/tags/");
      if (at == std::string::npos) continue;
      tag = line.substr(at + 10);
    }
    Version v;
    if (tag_version(tag, v)) out.push_back({tag, v});
  }
  std::sort(out.begin(), out.end(), [](const VersionTag& a, const VersionTag& b) { return compare(a.version, b.version) > 0; });
  return out;
}

std::string fetch_git(const std::string& source, const std::string& ref, const fs::path& dest, const GitPlace& place) {
  check_git_address(source);
  const fs::path& scratch = place.scratch;
  const fs::path repo = scratch / "repo";
  fs::remove_all(repo);
  GitResult r = run_git({"clone", "--quiet", "--no-checkout", "--template=", "--", source, repo.string()}, place);
  if (r.status != 0)
    throw Error("cannot reach the library source '" + source + "': git clone failed: " + git_reason(r.err) +
                "; check the address (git ls-remote " + source + ") and that you may read it");
  std::string commit;
  const std::string want = ref.empty() ? "HEAD" : ref;
  for (const std::string& cand : {"refs/tags/" + want, "refs/remotes/origin/" + want, want}) {
    r = run_git({"-C", repo.string(), "rev-parse", "--verify", "--quiet", cand + "^{commit}"}, place);
    if (r.status == 0) {
      commit = trim(r.out);
      break;
    }
  }
  if (commit.empty()) {
    const GitResult tags = run_git({"-C", repo.string(), "tag", "-l"}, place);
    throw Error("the library source '" + source + "' has no tag, branch or commit '" + want +
                "'; its version tags: " + version_list(parse_tag_lines(tags.out, false)));
  }
  r = run_git({"-C", repo.string(), "ls-tree", "-r", "-z", "--full-tree", commit}, place);
  if (r.status != 0) throw Error("cannot list commit " + commit + " of '" + source + "': " + git_reason(r.err));
  std::stringstream ss(r.out);
  for (std::string rec; std::getline(ss, rec, '\0');) {
    const std::size_t tab = rec.find('\t');
    if (tab == std::string::npos) continue;
    const std::string mode = rec.substr(0, rec.find(' ')), path = rec.substr(tab + 1);
    if (mode == "120000")
      throw Error("the library source '" + source + "' at " + want + " holds a symbolic link, '" + path +
                  "': an installed library holds only files and folders, so it is refused");
    if (mode == "160000")
      throw Error("the library source '" + source + "' at " + want + " holds a submodule, '" + path +
                  "': submodules are not fetched; make it a library of its own and require it");
  }
  const fs::path work = scratch / "work";
  fs::remove_all(work);
  fs::create_directories(work);
  r = run_git({"--git-dir", (repo / ".git").string(), "--work-tree", work.string(), "checkout", "-q", "-f", commit,
               "--", "."}, place);
  if (r.status != 0) throw Error("cannot check out " + want + " of '" + source + "': " + git_reason(r.err));
  copy_library(work, dest, "the library source '" + source + "' at " + want);
  fs::remove_all(work);
  fs::remove_all(repo);
  return commit;
}

std::string fetch_archive(const std::string& source, const fs::path& dest) {
  const std::vector<TarMember> members = read_tar_gz(source);
  const std::string where = "archive '" + source + "'";
  std::string top;
  for (const TarMember& m : members) {
    const std::string first = m.path.substr(0, m.path.find('/'));
    if (top.empty()) top = first;
    if (first != top || (!m.is_dir && m.path.find('/') == std::string::npos))
      throw Error(where + ": member '" + m.path + "' is not inside the archive's one folder '" + top +
                  "/'; give a .tar.gz made by smi-lua libs pack");
  }
  const TarMember* sums = nullptr;
  for (const TarMember& m : members)
    if (m.path == top + "/" + kPackChecksums) sums = &m;
  if (!sums)
    throw Error(where + " has no " + top + "/" + kPackChecksums + " (the checksums smi-lua libs pack writes); "
                "it was not made by libs pack, or it was altered");
  std::map<std::string, std::string> listed;
  std::stringstream ss(sums->data);
  for (std::string line; std::getline(ss, line);) {
    if (line.empty()) continue;
    if (line.size() < 67 || line.compare(64, 2, "  ") != 0)
      throw Error(where + ": " + kPackChecksums + " has a malformed line '" + line + "' (expected '<sha256>  <file>')");
    listed[line.substr(66)] = line.substr(0, 64);
  }
  std::set<std::string> present;
  for (const TarMember& m : members) {
    if (m.is_dir || &m == sums) continue;
    const std::string rel = m.path.substr(top.size() + 1);
    const auto it = listed.find(rel);
    if (it == listed.end()) throw Error(where + ": file '" + rel + "' is not in " + kPackChecksums + " (added after packing)");
    if (sha256_hex(m.data) != it->second)
      throw Error(where + ": file '" + rel + "' does not match its SHA-256 in " + kPackChecksums + " (altered after packing)");
    present.insert(rel);
  }
  for (const auto& [rel, digest] : listed)
    if (!present.count(rel)) throw Error(where + ": file '" + rel + "', listed in " + kPackChecksums + ", is missing");
  fs::create_directories(dest);
  for (const TarMember& m : members) {
    if (&m == sums || m.path == top) continue;
    const fs::path p = dest / m.path.substr(top.size() + 1);
    if (m.is_dir) {
      fs::create_directories(p);
      continue;
    }
    fs::create_directories(p.parent_path());
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out.write(m.data.data(), static_cast<std::streamsize>(m.data.size()));
    out.close();
    if (!out) throw Error("cannot write '" + p.string() + "'");
    if (m.executable) fs::permissions(p, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec, fs::perm_options::add);
  }
  return "sha256:" + sha256_file(source);
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

bool tag_version(const std::string& tag, Version& out) {
  const std::string t = !tag.empty() && (tag[0] == 'v' || tag[0] == 'V') ? tag.substr(1) : tag;
  try {
    out = Version::parse(t);
    return true;
  } catch (const Error&) {
    return false;
  }
}

std::pair<std::string, std::string> split_source_ref(const std::string& spec) {
  const std::size_t at = spec.rfind('@');
  if (at == std::string::npos || at == 0) return {spec, ""};
  const std::string before = spec.substr(0, at), after = spec.substr(at + 1);
  if (after.empty() || after.find(':') != std::string::npos) return {spec, ""};  // git@host:path
  std::error_code ec;
  // "https://user@host/x": the part after '@' holds '/' and the part before is no repository
  if (after.find('/') != std::string::npos && !ends_with(before, ".git") && !fs::exists(before, ec)) return {spec, ""};
  return {before, after};
}

SourceKind source_kind(const std::string& source, const std::string& ref) {
  if (ends_with(source, ".tar.gz") || ends_with(source, ".tgz")) return SourceKind::archive;
  std::error_code ec;
  if (fs::is_directory(source, ec)) {
    if (!ref.empty() && fs::exists(fs::path(source) / ".git", ec)) return SourceKind::git;
    return SourceKind::folder;
  }
  return SourceKind::git;
}

Fetched fetch_library(const std::string& source, const std::string& ref, const fs::path& dest, const GitPlace& place) {
  Fetched f;
  f.ref = ref;
  // git would read a leading '-' as an option ("--upload-pack=..."): no ref or source starts so
  if (!ref.empty() && ref[0] == '-') throw Error("'" + ref + "' is not a tag, branch or commit name (it starts with '-')");
  check_git_address(source);
  const SourceKind kind = source_kind(source, ref);
  std::string what = "'" + source + "'" + (ref.empty() ? "" : " at " + ref);
  if (kind == SourceKind::git) {
    f.commit = fetch_git(source, ref, dest, place);
  } else if (kind == SourceKind::archive) {
    if (!ref.empty()) throw Error("'" + source + "@" + ref + "': an archive has no refs; give the .tar.gz alone");
    std::error_code ec;
    if (!fs::is_regular_file(source, ec)) throw Error("cannot read the archive '" + source + "': no such file");
    f.commit = fetch_archive(source, dest);
  } else {
    if (!ref.empty())
      throw Error("'" + source + "' is a folder but not a git checkout, so it has no ref '" + ref +
                  "'; give the folder alone, or a git repository");
    copy_library(source, dest, "the library folder '" + source + "'");
    f.commit = git_info(source).commit;
  }
  std::error_code ec;
  if (!fs::is_regular_file(dest / kManifestName, ec))
    throw Error(what + " has no " + kManifestName + " at its top, so it is not an smi-lua library (smi-lua new-lib "
                "makes one)");
  f.manifest = read_manifest(dest / kManifestName);
  f.manifest.file = fs::path(source) / kManifestName;  // messages name where it came from
  Version tv;
  if (!ref.empty() && tag_version(ref, tv) && compare(tv, f.manifest.version) != 0)
    throw Error("the library source '" + source + "' at tag " + ref + " holds " + f.manifest.name + " version " +
                f.manifest.version.text + " in its " + kManifestName + ", not " + tv.text +
                ": the tag and the manifest disagree; ask the library's team to fix the tag or the manifest, or "
                "give a commit instead of the tag");
  f.hash = hash_folder(dest);
  return f;
}

std::vector<VersionTag> version_tags(const std::string& source, const GitPlace& place) {
  const SourceKind kind = source_kind(source, "");
  std::error_code ec;
  if (kind == SourceKind::git || (kind == SourceKind::folder && fs::exists(fs::path(source) / ".git", ec))) {
    check_git_address(source);
    const GitResult r = run_git({"ls-remote", "--tags", "--refs", "--", source}, place);
    if (r.status != 0)
      throw Error("cannot reach the library source '" + source + "': git ls-remote failed: " + git_reason(r.err));
    return parse_tag_lines(r.out, true);
  }
  const fs::path tmp = place.scratch / "peek";
  fs::remove_all(tmp);
  const Fetched f = fetch_library(source, "", tmp, place);
  fs::remove_all(tmp);
  return {{"", f.manifest.version}};
}

}  // namespace smi::vm
