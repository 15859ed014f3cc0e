// SPDX-License-Identifier: MIT
#pragma once
// A team registry: a git repository (file://, ssh:// or https://; no server of its own) holding
// an index of published library versions, in the manner of Cargo's registry index: one file per
// library, index/<name>, with one JSON line per published version:
//
//   {"name": "refcrit", "version": "1.2.0", "source": "https://git.example.org/refcrit.git",
//    "ref": "v1.2.0", "commit": "<40 hex>", "checksum": "sha256:<folder digest>",
//    "requires": ["unitconv >= 2.0, < 3"], "description": "..."}
//
// The library's files stay in its own repository (`source` at `commit`); the index says which
// versions exist and what their files hash to, so an install is checked against the checksum
// the publisher recorded. Lines are only ever appended: a published version is never replaced.
// Every git call is run_git's (vm/git_process.hpp).
#include <filesystem>
#include <string>
#include <vector>

#include "vm/git_process.hpp"
#include "vm/semver.hpp"

namespace smi::vm {

struct RegistryEntry {
  std::string name, version, source, ref, commit, checksum, description;
  std::vector<std::string> requires_;
};

/// index/<name>: the one place a registry path is made (the name grammar of vm/manifest.hpp).
std::filesystem::path registry_index_file(const std::string& name);

/// A registry cloned into a scratch folder.
class Registry {
 public:
  /// Clones `url` into `place.scratch`/`folder`. Throws smi::Error naming the registry when it
  /// cannot be reached.
  static Registry clone(const std::string& url, const GitPlace& place, const std::string& folder);

  const std::string& url() const { return url_; }
  /// The published versions of `name`, highest first (none when the index has no file for it).
  /// Throws smi::Error naming the index file and line for a malformed line.
  std::vector<RegistryEntry> versions(const std::string& name) const;
  /// Every library name in the index, sorted.
  std::vector<std::string> names() const;
  /// Appends `e` to index/<name>, commits and pushes. Throws smi::Error when the version is
  /// published already (a published version is never replaced) or the push is refused.
  void publish(const RegistryEntry& e) const;

 private:
  std::string url_;
  std::filesystem::path dir_;
  GitPlace place_;
};

}  // namespace smi::vm
