// SPDX-License-Identifier: MIT
#pragma once
// Choosing and fetching library versions for `libs add`, `libs update`, `libs sync` (a
// requirement of smi-project.json the lockfile does not meet) and `smi-lua test` (a library's
// own requirements). Versions are found at a source (its version tags: vm/library_sources.hpp)
// or in the team registries a project names (vm/registry.hpp); a version found in a registry is
// fetched from the source the registry records and must match the recorded commit and checksum.
//
// resolve() is greedy: each library gets the highest version that satisfies every requirement
// on it from the libraries planned, fetched into the scratch folder (nothing is installed
// here). Where a requirement's library comes from, in order: the requiring library's `sources`,
// the source already planned or locked, the project's registries.
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "vm/library_sources.hpp"
#include "vm/lockfile.hpp"
#include "vm/registry.hpp"

namespace smi::vm {

/// One version of a library that can be fetched.
struct Candidate {
  Version version;
  std::string source, ref;       // fetch_library(source, ref)
  std::string commit, checksum;  // from a registry: what the fetched files must be ("" at a source)
  std::string registry;          // the registry's URL, "" for a source's tag
};

class VersionFinder {
 public:
  /// `registries`: (name, git URL) in the order they are searched.
  VersionFinder(GitPlace place, std::vector<std::pair<std::string, std::string>> registries)
      : place_(std::move(place)), registries_(std::move(registries)) {}

  const GitPlace& place() const { return place_; }
  bool has_registries() const { return !registries_.empty(); }
  /// The versions tagged at `source`, highest first.
  const std::vector<Candidate>& at_source(const std::string& source);
  /// The versions of `name` published in the registries (only `registry` when given), highest
  /// first; a version in two registries is taken from the first.
  std::vector<Candidate> in_registries(const std::string& name, const std::string& registry = "");
  /// Fetches `c` into `dest`; checks the library's name, and a registry's commit and checksum.
  Fetched fetch(const Candidate& c, const std::string& name, const std::filesystem::path& dest);
  /// The registries searched, for messages ("team (file:///...), ...").
  std::string registries_text() const;

 private:
  const Registry& registry(const std::string& name, const std::string& url);
  GitPlace place_;
  std::vector<std::pair<std::string, std::string>> registries_;
  std::map<std::string, std::vector<Candidate>> tags_;  // by source
  std::map<std::string, Registry> clones_;              // by registry name
};

/// One library to install: fetched into `staged`, to be moved to tree/name/version.
struct Planned {
  LockEntry entry;
  std::vector<Requirement> requires_;
  std::map<std::string, std::string> sources;  // the manifest's
  std::filesystem::path staged;                // empty: already locked, nothing to install
  std::string why;                             // "" for what the user asked, else "required by x"
  bool pinned = false;                         // what the user asked for: never swapped for another version
};

/// The lock entry of a fetched library.
LockEntry entry_of(const Fetched& f, const std::string& source);

/// The highest of `cands` that every requirement in `on` accepts, or nullptr.
const Candidate* best_candidate(const std::vector<Candidate>& cands, const std::vector<const Requirement*>& on);

/// Completes `plan` until every requirement of every planned library is met (see above);
/// fetched folders are named scratch/lib<N> with `counter`. Throws smi::Error naming the
/// requiring library, the requirement, where versions were looked for, and the fix.
void resolve(std::map<std::string, Planned>& plan, VersionFinder& finder, int& counter);

}  // namespace smi::vm
