// SPDX-License-Identifier: MIT
#pragma once
// The .tar.gz of `smi-lua libs pack` and `libs add ARCHIVE`: a small ustar reader and writer
// over zlib's gzip (zlib1g: no tar program is run, so nothing depends on which tar is installed
// and no archive member is ever interpreted by another program).
//
// Only regular files and folders are written or read. Reading refuses, naming the member, every
// other type (symbolic and hard links, devices, FIFOs, pax and GNU extension headers), absolute
// names, names with a ".." component, duplicate names, and archives over the size limits below
// (a gzip bomb stops at the limit, not at the end of the disk).
//
// Writing is byte-reproducible: members in the order given, mode 0644 (0755 for executables and
// folders), owner 0:0 without names, modification time 0, gzip header without a time stamp.
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace smi::vm {

struct TarMember {
  std::string path;  // '/' separators, relative, no trailing '/'
  bool is_dir = false;
  bool executable = false;
  std::string data;  // file contents (empty for a folder)
};

inline constexpr std::size_t kTarMaxBytes = std::size_t(256) << 20;  // unpacked size accepted
inline constexpr std::size_t kTarMaxMembers = 20000;

/// Writes `members` as a gzip-compressed ustar archive to `file` (replacing it). Throws
/// smi::Error naming a member whose name does not fit ustar (more than 255 bytes).
void write_tar_gz(const std::filesystem::path& file, const std::vector<TarMember>& members);

/// Reads every member of `file`. Throws smi::Error naming the archive and the culprit member.
std::vector<TarMember> read_tar_gz(const std::filesystem::path& file);

}  // namespace smi::vm
