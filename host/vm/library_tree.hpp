// SPDX-License-Identifier: MIT
#pragma once
// A library tree on disk (a project's smi-libs/, or the folder given with --into): one folder
// per library version, <tree>/<name>/<version>/. A library's name and version are data read
// from manifests, lockfiles, archives, tags and the command line; library_dir is the one place
// they become a path, and it refuses anything that is not exactly one plain path component.
//
// LibraryTree is the tree opened for changes (libs add / sync / remove): every target is
// reached with the sandbox's path walk (platform/core/path_walk.hpp), one component at a time
// without following a link, and must be <tree>/<name>/<version> itself; the tree, its name
// folders and its version folders are never symbolic links, so no install, repair or removal
// acts outside the tree.
#include <filesystem>
#include <string>

namespace smi::vm {

/// <tree>/<name>/<version>. Throws smi::Error naming the culprit when `name` is not a library
/// name (vm/manifest.hpp) or `version` not a Semantic Version (vm/semver.hpp): either holds a
/// separator, a dot-segment, NUL or any other character its grammar does not allow.
std::filesystem::path library_dir(const std::filesystem::path& tree, const std::string& name,
                                  const std::string& version);

class LibraryTree {
 public:
  /// Opens `tree` (created with its missing parents when `create`). Throws smi::Error when it
  /// is a symbolic link or not a folder.
  static LibraryTree open(const std::filesystem::path& tree, bool create);

  /// The canonical path of the tree ("" when it does not exist and was not created).
  const std::filesystem::path& path() const { return canonical_; }
  bool exists() const { return !canonical_.empty(); }

  /// The checked folder of name/version (library_dir, then walked without following links).
  /// Throws smi::Error when the name folder or the version folder is a link or not a folder.
  std::filesystem::path target(const std::string& name, const std::string& version) const;
  /// True when name/version is installed (a real folder; a link throws as for target).
  bool has(const std::string& name, const std::string& version) const;
  /// Moves `staged` (a folder inside this tree) to name/version, which must not exist yet.
  void install(const std::filesystem::path& staged, const std::string& name, const std::string& version) const;
  /// Removes name/version (never following a link), and the name folder when left empty.
  void remove(const std::string& name, const std::string& version) const;

 private:
  std::filesystem::path canonical_;
  std::filesystem::path given_;  // as the user or the lockfile wrote it, for messages
};

}  // namespace smi::vm
