#pragma once
// What a script may touch: the sandbox's allow-list, shared by the runtime (which fills it
// from the command line) and the bindings (which check it before opening files or launching
// programs). It lives in the Lua registry so that every bound function can reach it.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>
#include <lua.hpp>

#include "core/errors.hpp"

namespace smi {

/// A path or program the policy does not allow. The message names the path (as given and as
/// resolved), the rule, and the flag that would allow it.
struct SandboxDenied : Error {
  using Error::Error;
};

struct Policy {
  std::vector<std::filesystem::path> read_roots;   // script dir, --lib dirs, --allow-read
  std::vector<std::filesystem::path> write_roots;  // --out dir, --allow-write
  std::vector<std::string> exec_allowed;           // --allow-exec: program names or paths
  std::filesystem::path out_dir;                   // --out (default smi-out/<script>/)
  std::uint64_t seed = 20200214;                   // --seed
  bool quiet = false;                              // --quiet or stdout/stderr not a terminal
  bool unrestricted = false;                       // no sandbox (tests of the kernels only)
  std::string store_path;                          // --store PATH: evaluation store to use (issue 5)
  bool dry_run = false;                            // --dry-run: count solver runs, launch none
  std::string script_path;                         // the study being run ("" for -e / REPL)
  /// Set by the runtime: "" while the run may go on, else why it must stop ("timeout: ...",
  /// "interrupted"). C++ code that waits without running Lua (solver runs) polls it, because
  /// the runtime's checks live in a Lua instruction hook that does not fire while no Lua runs.
  /// Once it is non-empty, the next Lua instruction raises that message as well.
  std::function<std::string()> stop_reason;
  /// Set by the runtime: ends the run quietly with exit status `code` from the next Lua
  /// instruction on (as os.exit does; pcall cannot catch it). --dry-run uses it to stop where a
  /// step needs solver runs that were not made.
  std::function<void(int code)> request_exit;

  /// Resolves `path` (relative to the working directory; "..", symlinks) and returns it if it
  /// lies under a read root (write roots are readable too); throws SandboxDenied otherwise.
  /// The message names the path, the rule and the flag; it does not repeat `function`, which
  /// callers put in front by raising through protect(L, function, ...).
  std::filesystem::path check_read(const std::string& path, const char* function) const;
  /// Same for writing: the path must lie under a write root. A path under out_dir creates
  /// out_dir first (the output folder is made on demand, so a run that writes nothing leaves none).
  std::filesystem::path check_write(const std::string& path, const char* function) const;
  /// Creates out_dir (and its parents) if missing and returns it resolved; throws smi::Error
  /// naming the folder when it cannot be made.
  std::filesystem::path ensure_out_dir() const;
  /// Resolves a program name through PATH (or takes a path) and returns its absolute path if
  /// --allow-exec named it (by name or by path); throws SandboxDenied otherwise.
  std::filesystem::path check_exec(const std::string& program, const char* function) const;
};

/// Resolves a path the way the checks do: absolute, "." and ".." removed, symlinks of the
/// existing prefix followed (so a symlink out of an allowed folder is caught).
std::filesystem::path resolve_path(const std::string& path);

/// True if `path` equals `root` or lies below it (component-wise, both already resolved).
bool path_within(const std::filesystem::path& path, const std::filesystem::path& root);

namespace lua {
/// The policy of this state (installed by the runtime). A state without one gets an
/// unrestricted default, which only kernel-level tests use.
Policy& policy(lua_State* L);
/// Stores `p` (not owned; must outlive the state) in the registry.
void set_policy(lua_State* L, Policy* p);
}  // namespace lua

}  // namespace smi
