// SPDX-License-Identifier: MIT
#pragma once
// The content hash of a library folder: SHA-256 of every file (sorted by relative path), and
// one digest over the (path, file digest) pairs. Every file counts, smi-out/ included: a library
// may load or read any file of its folder, so a file left out of the hash could change the
// library's code unseen. Only .git is left out (git's own records, not the library's files).
// `libs add` and `libs pack` do not copy a source folder's smi-out/ (test outputs are no part
// of a release), so an installed library has none and a file added there later is a
// difference. Per-file digests are kept so that `smi-lua verify` and the lockfile check can
// name the file that changed.
#include <filesystem>
#include <map>
#include <string>

namespace smi::vm {

struct FolderHash {
  std::string digest;                        // "sha256:<64 hex>"
  std::map<std::string, std::string> files;  // relative path ('/' separators) -> hex digest
};

/// Throws smi::Error naming the file or folder that cannot be read.
FolderHash hash_folder(const std::filesystem::path& folder);

/// The folder digest of a set of per-file digests (what hash_folder computes from them).
std::string combine_file_hashes(const std::map<std::string, std::string>& files);

}  // namespace smi::vm
