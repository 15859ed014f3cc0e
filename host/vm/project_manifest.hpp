// SPDX-License-Identifier: MIT
#pragma once
// smi-project.json: what a study project asks for, as its team wrote it: each library it uses
// directly, with a version range and where it comes from (a source or a registry), and the team
// registries (vm/registry.hpp) it looks names up in. `libs add` writes it, `libs update` moves
// within its ranges, `libs sync` reads it; smi-lock.json stays the exact record of what was
// resolved (every library, direct or not, by commit and file hashes).
//
//   {"project": 1,
//    "registries": {"team": "file:///srv/smi-registry.git"},
//    "requires": {"refcrit": {"version": "^1.2.0", "source": "https://git.example.org/refcrit.git"},
//                 "unitconv": {"version": ">= 2.0, < 3", "registry": "team"}}}
//
// A range is written as in a manifest's `requires` without the name ("^1.2.0", ">= 2.0, < 3";
// "" for any version). Names and ranges are checked with the library grammars when read.
#include <filesystem>
#include <map>
#include <string>

#include "vm/semver.hpp"

namespace smi::vm {

inline constexpr const char* kProjectManifestName = "smi-project.json";

struct DirectRequirement {
  std::string name;
  std::string range;     // constraint text; "" = any version
  std::string source;    // a git URL, folder or .tar.gz; "" when found through a registry
  std::string registry;  // a name of ProjectManifest::registries; "" when `source` is given

  Requirement requirement() const;  // "name range", parsed
};

struct ProjectManifest {
  std::map<std::string, std::string> registries;           // name -> git URL of the index
  std::map<std::string, DirectRequirement> requires_;      // by library name
  bool exists = false;                                      // read from a file
};

/// Reads `file`; a missing file is an empty manifest. Throws smi::Error naming the file, the
/// field and the fix for malformed JSON, a bad library name or range, or an unknown registry.
ProjectManifest read_project_manifest(const std::filesystem::path& file);
/// Writes `file` whole or not at all (platform/core/atomic_file.hpp).
void write_project_manifest(const ProjectManifest& m, const std::filesystem::path& file);

}  // namespace smi::vm
