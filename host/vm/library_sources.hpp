// SPDX-License-Identifier: MIT
#pragma once
// Where `smi-lua libs add` and `libs sync` get a library: a git repository (any URL the git
// program clones, file:// included, or a local checkout given with @REF), a local folder, or a
// .tar.gz made by `libs pack`. Fetching copies files and never runs code from the library.
//
// git runs as vm/git_process.hpp says (no configuration, no hooks, file/https/ssh only, a time
// limit); a tree holding a symbolic link or a submodule is refused, naming the entry. A pack
// must carry smi-pack.sha256, and every member must match it.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "vm/folder_hash.hpp"
#include "vm/git_process.hpp"
#include "vm/manifest.hpp"
#include "vm/semver.hpp"

namespace smi::vm {

inline constexpr const char* kPackChecksums = "smi-pack.sha256";

enum class SourceKind { git, folder, archive };

/// "URL@REF" -> {URL, REF}. The '@' of "git@host:path" or "https://user@host/x" is no ref.
std::pair<std::string, std::string> split_source_ref(const std::string& spec);

/// What `source` is: a name ending in .tar.gz/.tgz is an archive; an existing folder is a
/// folder, unless a ref is given and it is a git checkout; anything else is for git.
SourceKind source_kind(const std::string& source, const std::string& ref);

struct Fetched {
  Manifest manifest;
  std::string commit;   // git commit, "sha256:<archive digest>", or the folder's checkout commit
  std::string ref;      // as asked ("" for the default branch or a folder)
  FolderHash hash;      // of the fetched files
};

/// Copies the library at `ref` of `source` into `dest` (which must not exist yet), using
/// `place.scratch` (an existing empty folder) for git's clone and home. Checks the manifest against
/// `ref` when ref names a version ("v1.2.0" or "1.2.0"). Throws smi::Error naming the source
/// and what is wrong: unreachable, no such ref, a link or submodule in it, a bad pack.
Fetched fetch_library(const std::string& source, const std::string& ref, const std::filesystem::path& dest,
                      const GitPlace& place);

struct VersionTag {
  std::string tag;
  Version version;
};

/// The tags of `source` that name versions, highest first (a folder or archive: its manifest's
/// version, with tag ""). Throws smi::Error saying that the source cannot be reached.
std::vector<VersionTag> version_tags(const std::string& source, const GitPlace& place);

/// The version a tag names ("v1.2.0" -> 1.2.0), or false.
bool tag_version(const std::string& tag, Version& out);

}  // namespace smi::vm
