// SPDX-License-Identifier: MIT
#pragma once
// The Lua VM of one smi-lua run: a state with limited memory, the standard libraries behind the
// sandbox, the smi module, the module searchers, and the protected calls every chunk goes
// through (message handler with traceback, Ctrl-C, --timeout, os.exit).
#include <cstdint>
#include <string>
#include <vector>
#include <lua.hpp>

#include "luax/doc_text.hpp"
#include "luax/memory.hpp"
#include "luax/policy.hpp"
#include "platform/core/run_context.hpp"
#include "platform/core/defaults.hpp"
#include "platform/core/run_record.hpp"
#include "vm/libraries.hpp"
#include "vm/limits.hpp"
#include "vm/searchers.hpp"
#include "vm/watchdog.hpp"

namespace smi::app {

using smi::kDefaultSeed;  // core/defaults.hpp

struct Config {
  std::uint64_t seed = kDefaultSeed;  // --seed; recorded in results as smi.seed
  bool quiet = false;                 // --quiet, or set by the CLI when output is not a terminal
  std::string stdlib_dir;             // --stdlib-dir / SMI_STDLIB_DIR; empty = embedded
  std::string script;                 // script path, "-" for stdin, "" for none (-e, REPL)
  std::vector<std::string> allow_read, allow_write, allow_exec;
  std::vector<std::string> allow_env;  // --allow-env: names os.getenv may read
  std::vector<std::string> lib_dirs;  // --lib, then SMI_PATH entries
  std::string out_dir;                // --out; empty = smi-out/<script name>/
  std::string store_path;             // --store
  bool dry_run = false;               // --dry-run
  std::string executor;               // --executor ("" = local)
  std::vector<std::string> slurm_opts;  // --slurm-opt KEY=VALUE, in order
  bool detach = false;                // --detach
  bool traceback = false;             // --traceback: a Lua traceback under failures too
  bool pdf = false;                   // --pdf: a study also prints its report to PDF
  double timeout_s = 0;               // --timeout; 0 = none
  std::size_t max_memory_mb = 0;      // --max-memory; 0 = none
  bool sandbox = true;                // false only in tests of the runtime itself
};

/// What the runtime takes from the bindings, handed in by the program's composition root
/// (cli/bindings_root.cpp): app never includes bindings/, so no arrow points back up the layers.
struct Bindings {
  lua_CFunction open_smi = nullptr;               // luaopen_smi: the smi module table
  std::vector<lua::DocText> (*docs)() = nullptr;  // the bindings' reference texts (smi._docs)
};

/// The default output folder for a script: smi-out/<script name without .lua>.
std::string default_out_dir(const std::string& script);

class Runtime {
 public:
  Runtime(Config cfg, Bindings bindings);
  ~Runtime();
  Runtime(const Runtime&) = delete;
  Runtime& operator=(const Runtime&) = delete;

  lua_State* state() const { return L_; }
  const Config& config() const { return cfg_; }
  const lua::Policy& policy() const { return policy_; }
  const RunContext& context() const { return context_; }
  const Bindings& bindings() const { return bindings_; }

  /// Sets the global `arg` as lua.c does: argv[script_index] at 0, the script's arguments at
  /// 1..n, the interpreter and its options at negative indices.
  void set_arg(int argc, char** argv, int script_index);

  /// Each returns an exit status: 0 on success, 1 after printing the error with its traceback
  /// on stderr, or the code given to os.exit.
  int run_file(const std::string& path, const std::vector<std::string>& args);  // "-" = stdin
  int run_string(const std::string& code, const std::string& chunkname);
  /// -l mod / -l g=mod: global g (default mod) = require(mod).
  int require_global(const std::string& spec);

  /// Calls the function below `nargs` arguments in protected mode with the message handler,
  /// Ctrl-C and the limits armed. Returns the Lua status; the error value is left on the stack.
  int docall(int nargs, int nresults);
  /// Prints the error at the top of the stack (pops it) unless it is an os.exit request;
  /// returns the exit status for `status`.
  int report(int status);
  /// The REPL's errors: one line, without a traceback (--traceback brings it back).
  void set_one_line_errors(bool on) { one_line_ = on; }
  bool one_line_errors() const { return one_line_; }
  /// True once os.exit was called; the host must stop running chunks.
  bool exit_requested() const { return context_.cancel->raised() == cancel::Reason::exit; }

 private:
  void build_policy();
  void build_context();
  Config cfg_;
  Bindings bindings_;
  lua::Policy policy_;    // what the script may touch
  RunContext context_;    // how the run goes: seed, quiet, limits, executor, sinks, the token
  vm::Limits limits_;
  lua::MemoryBudget memory_;  // vec/mat/Kriging bytes under --max-memory
  vm::Watchdog watchdog_{cancel::process_token()};  // ends a run stuck in C code past --timeout or Ctrl-C
  vm::ModuleSearch modules_;
  lua_State* L_;
  bool one_line_ = false;  // set_one_line_errors
  vm::LibrarySet libs_;  // --lib / SMI_PATH libraries, checked before anything runs
  RunRecord record_;  // what the run read and ran: smi.provenance()

 public:
  const vm::LibrarySet& libraries() const { return libs_; }
  const RunRecord& record() const { return record_; }
};

}  // namespace smi::app
