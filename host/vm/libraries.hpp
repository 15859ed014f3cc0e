// SPDX-License-Identifier: MIT
#pragma once
// The libraries a study sees: folders with a smi-lib.lua manifest, found in the --lib folders
// and SMI_PATH entries. An entry is a library itself (it holds smi-lib.lua) or a folder of
// libraries (each subfolder holding smi-lib.lua is one). Entries without any manifest stay plain
// module folders for the path searcher.
//
// A library tree (what `smi-lua libs add` fills: <tree>/<name>/<version>/smi-lib.lua) may hold
// several versions of a library side by side; a study sees one of them: the version the
// project's smi-lock.json pins when there is one, else the highest version that satisfies every
// requirement of the other libraries it sees. The project folder is the current folder: its
// smi-libs/ (or the tree its smi-lock.json names) is searched after --lib and SMI_PATH.
//
// Before a study starts the set is checked: one version per library name, every `requires`
// met, and every library the lockfile pins holding exactly the files the lockfile records (a
// file changed, added or removed stops the study, naming the file and `smi-lua libs sync`).
// Each problem is reported with which library, where, and how to fix it.
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "vm/folder_hash.hpp"
#include "vm/git_commit.hpp"
#include "vm/lockfile.hpp"
#include "vm/manifest.hpp"

namespace smi::vm {

/// One library-path entry and where it came from ("--lib" or "SMI_PATH"), for messages.
struct LibraryRoot {
  std::string dir;
  std::string origin;
};

struct Library {
  Manifest manifest;
  std::filesystem::path folder;  // resolved, absolute
  LibraryRoot root;              // the entry it was found through
  GitInfo git;                   // for a library of a tree: commit from smi-lock.json, no branch
  std::string source;            // where `libs add` fetched it (smi-lock.json), "" otherwise
  mutable bool used = false;                     // a module of it was loaded in this run
  mutable std::optional<FolderHash> hash_cache;  // computed on first use

  const std::string& name() const { return manifest.name; }
  const FolderHash& hash() const;
  /// "refcrit 1.2.0 at /x/refcrit (--lib /x)"
  std::string describe() const;
};

/// The library tree and lockfile of a project folder.
struct ProjectLibraries {
  std::filesystem::path lockfile;  // <dir>/smi-lock.json when it exists, else empty
  std::optional<Lockfile> lock;
  std::filesystem::path tree;      // the lockfile's tree, or <dir>/smi-libs; empty when neither exists
  /// The lockfile names a tree outside the project folder: it is no read root of a study and is
  /// searched only when the user gives the same folder with --lib or SMI_PATH.
  bool tree_outside = false;
};
/// Reads <dir>/smi-lock.json (throws smi::Error for a malformed or hand-edited one). Throws
/// smi::Error, naming it, when the project's tree is a symbolic link or passes through one.
ProjectLibraries project_libraries(const std::filesystem::path& dir);

class LibrarySet {
 public:
  /// Reads the manifests under `roots` (in order). Throws smi::Error for a manifest that does
  /// not load or is malformed (naming the file); conflicts are left for problems()/check().
  /// With `project`, its tree is searched last and its lockfile chooses among side-by-side versions.
  static LibrarySet discover(const std::vector<LibraryRoot>& roots, const ProjectLibraries* project = nullptr);

  const std::vector<Library>& all() const { return libs_; }
  const std::vector<LibraryRoot>& roots() const { return roots_; }
  /// The first library named `name`, or nullptr.
  const Library* find(const std::string& name) const;

  /// Two copies of one library, reserved names, unmet requirements: one message each.
  std::vector<std::string> problems() const;
  /// Throws smi::Error listing every problem (nothing when there is none).
  void check() const;

 private:
  std::string seen_versions(const std::string& name) const;
  std::vector<LibraryRoot> roots_;
  std::vector<Library> libs_;
  std::vector<std::string> tree_problems_;                     // a locked version not installed
  std::map<std::string, std::vector<std::string>> versions_;  // name -> versions seen in trees
};

/// The library-path entries of a run: the --lib folders, then SMI_PATH (':'-separated).
std::vector<LibraryRoot> library_roots(const std::vector<std::string>& lib_dirs, const char* smi_path_env);

/// The smi-lua version libraries can require as "smi-lua >= 0.1".
const char* host_version();

}  // namespace smi::vm
