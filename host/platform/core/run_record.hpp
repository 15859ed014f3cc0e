// SPDX-License-Identifier: MIT
#pragma once
// What a run's numbers depend on, recorded while it runs: every file the script read
// (data, priors, templates, Lua modules), every program it ran, its arguments and the options of
// smi-lua that change results. Each file is hashed (SHA-256) when it is read, from the descriptor
// that was read, so the digest is the one of the bytes the run used. smi.provenance() turns this
// into the "provenance" of results.json and `smi-lua verify` re-hashes it.
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

namespace smi {

/// Files above this size are not hashed (minutes of reading): size and mtime stand for them.
inline constexpr std::uintmax_t kLargeFileBytes = std::uintmax_t{1} << 30;

/// The digest of one file as provenance records it: "sha256:<hex>", or, for a file over
/// kLargeFileBytes, no hash and `large` set (size and mtime then identify it).
struct FileDigest {
  std::string hash;            // "sha256:..." ("" when large)
  std::uintmax_t size = 0;
  std::int64_t mtime = 0;      // seconds since the epoch
  bool large = false;
};

/// Digest of an open regular file (read with pread up to the size fstat gives; the offset is not
/// moved); throws smi::Error naming `name` for a device, FIFO, folder or socket.
FileDigest digest_fd(int fd, const std::string& name);
/// Digest of a regular file by name (verify, the script itself); throws smi::Error naming it.
FileDigest digest_path(const std::string& path);

/// One file the run read. kind: "script", "lua" (a module or a dofile/loadfile chunk), "stdlib"
/// (a module embedded in the binary; path "embedded:smi/x.lua"), "program" (a solver a model
/// runs; also listed in programs()), "data" (anything else read).
struct InputFile {
  std::string kind;
  FileDigest digest;
  std::uint64_t seq = 0;          // when it was last read (RunRecord::seq), for per-step inputs
  bool changed_during_run = false;  // read twice with different contents
};

/// One program the run may start (smi.model.command / batch).
struct ProgramRun {
  std::string name;     // as the study wrote it
  std::string path;     // absolute
  FileDigest digest;
  std::string version;       // the model's declared version ("" = none)
  std::string version_line;  // the first line the program printed for the model's version_args
};

class RunRecord {
 public:
  /// A file read through `fd` (canonical path); hashed unless a read of the same size and mtime
  /// was hashed already. A "lua" record upgrades an earlier "data" one of the same file.
  void file(const std::string& kind, const std::string& path, int fd);
  /// A chunk read as text (the embedded stdlib): hashed from the bytes.
  void text(const std::string& kind, const std::string& path, std::string_view bytes);
  /// A file read by name (the script, which Lua loads itself).
  void path(const std::string& kind, const std::string& path);
  void program(ProgramRun p);
  /// `path` (canonical; a file or a folder) is an output of the run, not an input: reads of it
  /// are not recorded, and a record already made is dropped (smi.study's results file).
  void exclude(const std::string& path);

  /// Files read so far, by path.
  std::map<std::string, InputFile> files() const;
  std::vector<ProgramRun> programs() const;
  /// A counter bumped by every read: files with seq > n were read after seq() returned n.
  std::uint64_t seq() const;

  // Set once by the runtime before any script code runs.
  std::vector<std::string> command_line;   // argv as given (smi-lua, options, script, args)
  std::vector<std::string> script_args;    // the script's own arguments
  std::string cwd;                         // where the command was run from
  std::vector<std::pair<std::string, std::string>> options;  // smi-lua options that change results
  std::vector<std::string> exclude_roots;  // folders whose reads are outputs, not inputs (--out)

 private:
  void touch(const std::string& kind, const std::string& path, const FileDigest& d);
  mutable std::mutex mu_;
  std::map<std::string, InputFile> files_;
  std::vector<ProgramRun> programs_;
  std::uint64_t seq_ = 0;
};

}  // namespace smi
