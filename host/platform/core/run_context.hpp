// SPDX-License-Identifier: MIT
#pragma once
// The settings of one run, apart from the sandbox's Policy (luax/policy.hpp: what a script may
// touch). The runtime builds one RunContext from the command line (app::Config) and hands it
// down explicitly: the bindings reach it through lua::run_context(L) (luax/run_context.hpp),
// the kernels get what they need of it as arguments (a seed, the cancellation token; never the
// sinks below, which are the bindings' business). Lua-free, so it lives in platform/core.
//
// Following a setting from the command line to the kernel: docs/design.md, "Following a setting".
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "platform/core/cancel.hpp"
#include "platform/core/defaults.hpp"

namespace smi {

/// Where the run's warnings go: collected for the result (smi.warnings(), and the functions
/// that return theirs in a `warnings` field), and printed on stderr as "<source>: warning: <text>"
/// only when the run prints (not --quiet, stderr a terminal). Bindings warn through it, never
/// with fprintf(stderr): a warning then neither vanishes nor reaches stderr behind --quiet.
class WarningSink {
 public:
  /// Warnings kept (and printed) in full; past them each is only counted, so that a warning in
  /// a loop of a million calls neither fills the memory nor the terminal. collected() ends with
  /// a line saying how many were counted.
  static constexpr std::size_t kKept = 1000;

  explicit WarningSink(bool print = false) : print_(print) {}
  WarningSink(const WarningSink& o) : print_(o.print_) {
    const std::lock_guard<std::mutex> lock(o.mu_);
    collected_ = o.collected_;
    counted_ = o.counted_;
  }
  WarningSink& operator=(const WarningSink& o);
  void warn(std::string_view source, std::string_view text);
  /// Every warning of the run so far, as "<source>: <text>", in order.
  std::vector<std::string> collected() const;
  bool prints() const { return print_; }

 private:
  bool print_;
  mutable std::mutex mu_;  // parallel kernels' bindings may warn from workers
  std::vector<std::string> collected_;
  std::size_t counted_ = 0;  // warnings past kKept
};

/// Whether live progress lines are drawn (on stderr, redrawn in place): only when the run
/// prints (not --quiet) and stderr is a terminal.
struct ProgressSink {
  bool live = false;
  /// What the lines belong to ("[study] step 4/7 calibrate"): set by smi.progress_label (smi.study
  /// sets it per step), written in front of every progress line; "" for none.
  std::string label;
  /// "label: " or "".
  std::string prefix() const { return label.empty() ? std::string() : label + ": "; }
};

struct RunContext {
  std::uint64_t seed = kDefaultSeed;  // --seed: every kernel's default seed (smi.seed)
  bool quiet = false;                 // --quiet, or output not a terminal (smi.quiet)
  bool dry_run = false;               // --dry-run: count solver runs, launch none (smi.dry_run)
  double timeout_s = 0;               // --timeout (0 = none): armed on `cancel` per chunk
  std::size_t memory_bytes = 0;       // --max-memory (0 = none): Lua heap plus boxes
  std::string store_path;             // --store: evaluation store read for hits ("" = none)
  std::string script_path;            // the study being run ("" for -e, stdin, the REPL)
  std::string executor;               // --executor: where solver runs go ("" = local)
  std::vector<std::string> slurm_opts;  // --slurm-opt KEY=VALUE, in order
  bool detach = false;                // --detach: leave Slurm jobs running when stopped
  ProgressSink progress;
  WarningSink warnings;
  /// The run's one cancellation token (cancel::process_token() under a runtime, which the signal
  /// handler reaches); null outside a run (kernel tests), where nothing stops.
  cancel::Token* cancel = nullptr;
};

}  // namespace smi
