// SPDX-License-Identifier: MIT
#pragma once
// What a script may touch: the sandbox's allow-list, shared by the runtime (which fills it
// from the command line) and the bindings (which check it before opening files or launching
// programs). It lives in the Lua registry so that every bound function can reach it.
#include <filesystem>
#include <string>
#include <vector>
#include <lua.hpp>

#include "platform/core/errors.hpp"
#include "platform/core/path_walk.hpp"
#include "platform/core/run_record.hpp"

namespace smi::lua {

/// A path or program the policy does not allow. The message names the path (as given and as
/// resolved), the rule, and the flag that would allow it.
struct SandboxDenied : Error {
  using Error::Error;
};

/// An OS failure opening a file the policy allows (missing, permissions, not a regular file).
struct FileError : Error {
  FileError(const std::string& msg, int e) : Error(msg), err(e) {}
  int err;
};

/// A file opened through the sandbox: the descriptor, and the canonical path it was reached by.
struct CheckedFile {
  pathwalk::Fd fd;
  std::string path;
};

/// The whole content of a checked file (throws FileError naming `shown` on a read error).
std::string read_checked(const CheckedFile& f, const std::string& shown);

/// Opens `path` for reading only if its canonical path lies under one of `roots` (canonical);
/// the walk, check and open of Policy::open_read, for readers with roots of their own (the
/// stdlib folder, a library folder). Throws SandboxDenied / FileError like it.
CheckedFile open_read_within(const std::string& path, const std::vector<std::filesystem::path>& roots,
                             const std::string& denial_hint);

struct Policy {
  std::vector<std::filesystem::path> read_roots;   // script dir, --lib dirs, --allow-read
  std::vector<std::filesystem::path> write_roots;  // --out dir, --allow-write
  std::vector<std::string> exec_allowed;           // --allow-exec: program names or paths
  std::filesystem::path out_dir;                   // --out (default smi-out/<script>/)
  bool unrestricted = false;                       // no sandbox (tests of the kernels only)
  std::vector<std::string> allow_env;              // --allow-env: variables scripts and solvers may see
  // The run's settings (seed, quiet, store, executor, the cancellation token, ...) are not the
  // sandbox's: they are in the RunContext (core/run_context.hpp, luax/run_context.hpp).

  std::filesystem::path out_root;                  // output_root(out_dir) at start (made on demand, no symlinks)
  /// What the run read and ran (provenance); set by the runtime, null in kernel tests.
  /// open_read records every file it opens here (hashed from the opened descriptor).
  RunRecord* record = nullptr;

  // Files a script names are opened only through these: the path is walked
  // one component at a time through descriptors (core/path_walk.hpp), the canonical path reached
  // is checked against the roots, and the file is opened relative to the folder descriptor that
  // was checked, with O_NOFOLLOW. Nothing is re-opened by name afterwards. Symlinks are followed
  // only component-wise (so one that leads out of every root is refused, wherever it sits), and
  // only regular files are opened. Denials throw SandboxDenied; OS failures (missing file,
  // permissions) throw FileError carrying errno. Messages leave out the function name, which
  // callers put in front by raising through protect(L, function, ...).

  /// Opens `path` for reading: it must lie under a read root (write roots are readable too).
  CheckedFile open_read(const std::string& path) const;
  /// The same check and open without recording the file as an input of the run (provenance's
  /// own re-hashing of recorded files).
  CheckedFile open_read_unrecorded(const std::string& path) const;
  /// Opens `path` for writing with open(2) flags `oflags` (O_WRONLY or O_RDWR, O_CREAT, O_APPEND,
  /// O_TRUNC): its folder must lie under a write root. A file with other hard links is refused
  /// (writing it would change a file elsewhere); O_TRUNC is applied after that check. A path
  /// under out_dir creates out_dir first (made on demand, so a run that writes nothing leaves none).
  CheckedFile open_write(const std::string& path, int oflags) const;
  /// The checked folder of an entry that is written without being opened (os.remove,
  /// os.rename, folders made by the evaluator): the last component is not followed.
  pathwalk::Walk walk_write(const std::string& path) const { return walk_write(path, path); }
  /// The same, naming `shown` (what the script wrote) in messages.
  pathwalk::Walk walk_write(const std::string& path, const std::string& shown) const;
  /// A folder under a write root, made if missing; its canonical path (for the evaluator, which
  /// makes its run folders below it refusing symlinks, see eval/work_dir.hpp).
  std::string checked_write_dir(const std::string& path) const;
  /// A file path under a write root for a program that opens it by name (SQLite): the folder is
  /// checked and the file must not be a symlink; the canonical path is returned. Residual race:
  /// a folder on that path swapped after the check (README, Sandbox).
  std::string checked_write_file(const std::string& path) const;
  /// Same for reading (a shared store opened read-only by SQLite).
  std::string checked_read_file(const std::string& path) const;
  /// Creates out_dir (and its parents) if missing, refusing symlinks on the way, and returns
  /// it resolved; throws smi::Error naming the folder when it cannot be made.
  std::filesystem::path ensure_out_dir() const;
  /// Resolves a program name through PATH (or takes a path) and returns its absolute path if
  /// --allow-exec named it (by name or by path); throws SandboxDenied otherwise.
  std::filesystem::path check_exec(const std::string& program, const char* function) const;
};

/// A path made absolute, symlinks of the existing prefix followed, the rest normalised as text.
/// For roots given on the command line (resolved once at start) and for messages only: never
/// to decide whether a script may open something (that is Policy::open_read/open_write).
std::filesystem::path resolve_path(const std::string& path);

/// The output folder as an absolute path with no link in it followed: the working folder
/// (resolved) joined with a relative --out, or an absolute --out's resolved parent and its name.
/// Links planted where smi-lua makes its folders are then refused by name when it makes them
/// (Policy::ensure_out_dir), instead of being followed to wherever they point.
std::filesystem::path output_root(const std::string& path);

/// True if `path` equals `root` or lies below it (component-wise, both already resolved).
bool path_within(const std::filesystem::path& path, const std::filesystem::path& root);

/// The policy of this state (installed by the runtime). A state without one gets an
/// unrestricted default, which only kernel-level tests use.
Policy& policy(lua_State* L);
/// Stores `p` (not owned; must outlive the state) in the registry.
void set_policy(lua_State* L, Policy* p);
/// The error value that ends a run quietly (os.exit, --dry-run: a token stopped with reason exit): a light userdata the
/// runtime's message handler recognises. Raised by the sandbox's os.exit and the limits' hook.
void* exit_sentinel();
/// Loads the text of a checked file as a text chunk named `chunkname` ("@path"), skipping a
/// UTF-8 BOM and a first "#" line as luaL_loadfilex does. Returns the load status; pushes the
/// chunk or the message.
int load_text(lua_State* L, const std::string& text, const std::string& chunkname);

}  // namespace smi::lua
