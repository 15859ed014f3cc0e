// SPDX-License-Identifier: MIT
#pragma once
// smi-lock.json: exactly which libraries a project uses, where they came from and what their
// files hold, so that `smi-lua libs sync` restores them byte for byte and a study run in the
// project folder sees those versions and no others.
//
//   {"lockfile": 1, "tree": "smi-libs", "checksum": "sha256:...",
//    "libraries": [{"name": "unitconv", "version": "1.2.0", "source": "https://.../unitconv.git",
//                   "ref": "v1.2.0", "commit": "<40 hex>", "requires": ["..."],
//                   "hash": "sha256:...", "files": {"init.lua": "<64 hex>", ...},
//                   "checksum": "sha256:..."}]}
//
// The file is written by `libs add` / `libs remove` only. Each entry carries a checksum of its
// own fields and the file one over the entries, so an entry changed, added or removed by hand
// (or by a bad merge) is refused naming the library instead of restoring something nobody
// resolved. "commit" is the git commit for a git source, "sha256:<archive digest>" for a pack,
// and the checkout's commit (or "") for a folder.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace smi::vm {

inline constexpr const char* kLockfileName = "smi-lock.json";
inline constexpr const char* kTreeName = "smi-libs";

struct LockEntry {
  std::string name, version, source, ref, commit;
  std::vector<std::string> requires_;
  std::string hash;                          // folder digest (combine_file_hashes of files)
  std::map<std::string, std::string> files;  // relative path -> hex SHA-256
};

struct Lockfile {
  std::string tree = kTreeName;  // the library tree, relative to the lockfile's folder (or absolute)
  std::vector<LockEntry> libs;   // sorted by name; one version per name

  const LockEntry* find(const std::string& name) const;
  /// Adds or replaces the entry of e.name, keeping the list sorted.
  void put(LockEntry e);
  bool erase(const std::string& name);
};

/// Reads and checks `file`. Throws smi::Error naming the file, the library and the fix for
/// malformed JSON, a missing field, or an entry whose checksum says it was edited by hand.
Lockfile read_lockfile(const std::filesystem::path& file);
/// Writes atomically (a temporary file renamed over `file`), with fresh checksums.
void write_lockfile(const Lockfile& lock, const std::filesystem::path& file);

/// The library tree a lockfile names, resolved against the lockfile's folder.
std::filesystem::path lock_tree(const Lockfile& lock, const std::filesystem::path& lockfile);

/// True when a tree as a lockfile writes it ("smi-libs") lies inside the lockfile's folder: a
/// relative path without "..". A tree elsewhere is read or changed only when the user names it
/// (--lib for a study, --into for libs), never because a lockfile says so.
bool tree_inside_project(const std::string& tree);

/// Each file that differs between a lock entry's files and `have` (a folder hash's files), one
/// line each: "file 'init.lua' differs from smi-lock.json (...)", "... is missing",
/// "... is not in smi-lock.json".
std::vector<std::string> lock_differences(const std::map<std::string, std::string>& want,
                                          const std::map<std::string, std::string>& have);

}  // namespace smi::vm
