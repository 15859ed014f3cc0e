#pragma once
// The content hash of a library folder: SHA-256 of every file (sorted by relative path), and
// one digest over the (path, file digest) pairs. .git folders and smi-out output folders are
// left out (they change without the code changing). Per-file digests are kept so that
// `smi-lua verify` can name the file that changed.
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
