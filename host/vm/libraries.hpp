#pragma once
// The libraries a study sees: folders with a smi-lib.lua manifest, found in the --lib folders
// and SMI_PATH entries. An entry is a library itself (it holds smi-lib.lua) or a folder of
// libraries (each subfolder holding smi-lib.lua is one). Entries without any manifest stay plain
// module folders for the path searcher.
//
// Before a study starts the set is checked: one version per library name, and every `requires`
// met. Each problem is reported with which library, where, and how to fix it.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "vm/folder_hash.hpp"
#include "vm/git_commit.hpp"
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
  GitInfo git;
  mutable bool used = false;                     // a module of it was loaded in this run
  mutable std::optional<FolderHash> hash_cache;  // computed on first use

  const std::string& name() const { return manifest.name; }
  const FolderHash& hash() const;
  /// "refcrit 1.2.0 at /x/refcrit (--lib /x)"
  std::string describe() const;
};

class LibrarySet {
 public:
  /// Reads the manifests under `roots` (in order). Throws smi::Error for a manifest that does
  /// not load or is malformed (naming the file); conflicts are left for problems()/check().
  static LibrarySet discover(const std::vector<LibraryRoot>& roots);

  const std::vector<Library>& all() const { return libs_; }
  const std::vector<LibraryRoot>& roots() const { return roots_; }
  /// The first library named `name`, or nullptr.
  const Library* find(const std::string& name) const;

  /// Two copies of one library, reserved names, unmet requirements: one message each.
  std::vector<std::string> problems() const;
  /// Throws smi::Error listing every problem (nothing when there is none).
  void check() const;

 private:
  std::vector<LibraryRoot> roots_;
  std::vector<Library> libs_;
};

/// The library-path entries of a run: the --lib folders, then SMI_PATH (':'-separated).
std::vector<LibraryRoot> library_roots(const std::vector<std::string>& lib_dirs, const char* smi_path_env);

/// The smi-lua version libraries can require as "smi-lua >= 0.1".
const char* host_version();

}  // namespace smi::vm
