#pragma once
// Where `smi-lua libs add` and `libs sync` get a library: a git repository (any URL the git
// program clones, file:// included, or a local checkout given with @REF), a local folder, or a
// .tar.gz made by `libs pack`. Fetching copies files and never runs code from the library.
//
// git runs with a minimal environment: HOME is an empty temporary folder, no system or global
// configuration (GIT_CONFIG_NOSYSTEM, GIT_CONFIG_GLOBAL=/dev/null), no hooks
// (core.hooksPath=/dev/null, an empty --template), no terminal prompt, the ext:: transport off,
// and symlinks checked out as plain files; a tree holding a symbolic link or a submodule is
// refused, naming the entry. Only PATH, LANG=C, SSH_AUTH_SOCK and the proxy variables are
// passed on. A pack must carry smi-pack.sha256, and every member must match it.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "vm/folder_hash.hpp"
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
/// `scratch` (an existing empty folder) for git's clone and home. Checks the manifest against
/// `ref` when ref names a version ("v1.2.0" or "1.2.0"). Throws smi::Error naming the source
/// and what is wrong: unreachable, no such ref, a link or submodule in it, a bad pack.
Fetched fetch_library(const std::string& source, const std::string& ref, const std::filesystem::path& dest,
                      const std::filesystem::path& scratch);

struct VersionTag {
  std::string tag;
  Version version;
};

/// The tags of `source` that name versions, highest first (a folder or archive: its manifest's
/// version, with tag ""). Throws smi::Error saying that the source cannot be reached.
std::vector<VersionTag> version_tags(const std::string& source, const std::filesystem::path& scratch);

/// The version a tag names ("v1.2.0" -> 1.2.0), or false.
bool tag_version(const std::string& tag, Version& out);

}  // namespace smi::vm
