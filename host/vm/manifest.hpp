// SPDX-License-Identifier: MIT
#pragma once
// smi-lib.lua, the manifest that makes a folder a library:
//
//   name = "refcrit"                       -- what `require "refcrit.x"` starts with
//   version = "1.2.0"                      -- semver MAJOR.MINOR.PATCH
//   description = "Refinement criteria shared by the chassis team"
//   requires = {"kdetools >= 1.2", "smi-lua >= 0.1"}
//   sources = {kdetools = "https://git.example.org/kdetools.git"}  -- where `libs add` finds them
//
// (or the same fields in a returned table). A manifest is data, not code: it is loaded as text
// in a fresh Lua state with no libraries, an empty environment, an instruction budget and a
// memory ceiling, so a manifest can neither reach the study nor hang or exhaust the host.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "vm/semver.hpp"

namespace smi::vm {

inline constexpr const char* kManifestName = "smi-lib.lua";

struct Manifest {
  std::string name;
  Version version;
  std::string description;
  std::vector<Requirement> requires_;
  /// Where `smi-lua libs add` fetches each required library (a git URL, a folder or a .tar.gz),
  /// by library name. Only read by `libs add`; a study never fetches anything.
  std::map<std::string, std::string> sources;
  std::filesystem::path file;  // the smi-lib.lua read
};

/// True for names a library may take: a Lua identifier ([A-Za-z_][A-Za-z0-9_]*), since it is
/// the first component of module names.
bool valid_library_name(const std::string& name);

/// `s` with each NUL byte written as \0, for messages about a name or version that holds one
/// (printed as a C string, the text would end at the NUL).
std::string visible_text(const std::string& s);

/// Reads and checks `file`. Throws smi::Error naming the file, the field and the fix.
Manifest read_manifest(const std::filesystem::path& file);
/// The manifest of the library folder `dir` (`smi-lua test`, `libs pack`); a folder without one
/// is an error naming it and `smi-lua new-lib`.
Manifest read_library_folder(const std::filesystem::path& dir);
/// Same from text (chunk named after `file`).
Manifest parse_manifest(const std::string& text, const std::filesystem::path& file);

}  // namespace smi::vm
