// SPDX-License-Identifier: MIT
#pragma once
// Evaluating a design matrix with an external solver: render one deck per point (or one input
// file per batch of points), look every point up in the evaluation store, run the missing ones
// through the Scheduler, parse and store each result the moment its run ends, and return the
// outputs in input order. Failures (non-zero exit, signal, timeout, missing or unparsable
// output) are results too: a failed record with its reason, a NaN row, and a status.
#include <Eigen/Core>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "platform/core/cancel.hpp"
#include "platform/core/path_walk.hpp"
#include "platform/eval/deck_template.hpp"
#include "platform/eval/executor.hpp"
#include "platform/eval/store.hpp"

namespace smi::eval {

enum class OnFailure { Stop, Skip, Retry };
OnFailure parse_on_failure(const std::string& s);  // "stop" | "skip" | "retry"

struct CommandConfig {
  std::string name = "model";               // names the runs folder and the progress line
  std::vector<std::string> inputs, outputs;
  std::shared_ptr<const DeckTemplate> deck;   // per-point deck (nullptr in batch mode)
  bool deck_function = false;                 // decks come from Evaluator::set_deck_function instead
  std::string deck_file = "input.deck";       // its file name in the work directory
  DeckValues constants;                       // extra placeholder values (numbers or strings)
  std::vector<std::string> files;             // absolute paths copied into every work directory
  // Their descriptors, opened by the sandbox when it checked them (same order; may be empty):
  // hashed and copied from these, never re-opened by name.
  std::vector<std::shared_ptr<const pathwalk::Fd>> file_fds;
  std::string program;                        // absolute path (checked by the sandbox)
  std::string program_name;                   // as the study wrote it; goes into the key
  std::vector<std::string> args;              // argv[1..]: "{deck}" -> deck_file, "{workdir}" -> the folder
  std::vector<std::string> env_names;         // --allow-env: variables solvers get besides the base set
  // Declared by the model (env = {NAME = "value"}): set in every run's environment, checked by
  // declared_env_refusal, part of the store key (they can change a run's result).
  std::vector<std::pair<std::string, std::string>> env_set;
  std::string script_hash;                    // "sha256:..." of the study script ("" for -e, stdin, REPL)
  std::string version;                        // "" -> "sha256:" + hash of the program file
  double timeout = 0;                         // seconds per run; 0 = none
  int retries = 0;                            // extra attempts after a failure
  OnFailure on_failure = OnFailure::Stop;
  int concurrency = 1;
  bool reuse_failed = false;                  // also reuse stored failures (default: run again)
  std::string runs_dir;                       // <out>/runs/<name>
  std::string store_path;                     // the local store (written)
  std::string shared_store_path;              // --store: read for hits only ("" = none)
  // Batch mode: one run takes `batch_size` points (0 = all pending) written as CSV to deck_file.
  bool batch = false;
  int batch_size = 0;
  ExecutorConfig executor;                    // where runs execute: local (default) or slurm
};

enum class Status { Ok, Failed, NotRun };

struct EvalResult {
  Eigen::MatrixXd Y;                 // rows = points, columns = outputs; NaN where not Ok
  std::vector<Status> status;
  std::vector<std::string> reason;   // "" when Ok
  Eigen::VectorXd duration;          // run seconds (stored duration for reused points)
  std::vector<bool> reused;          // found in a store, no run
  std::size_t launched = 0;          // processes started (retries included)
  std::size_t failed = 0;            // points that ended Failed
  bool stopped = false;              // on_failure = stop ended the evaluation early
};

struct Progress {
  std::size_t total = 0;     // runs needed (points not in a store)
  std::size_t done = 0;      // runs finished (ok or failed), this evaluation
  std::size_t failed = 0;
  std::size_t running = 0;
  double mean_seconds = 0;   // of finished runs (stored timing before the first)
  double eta_seconds = -1;   // -1 = unknown
};

struct Plan {
  std::size_t points = 0;    // rows of X
  std::size_t unique = 0;    // distinct keys
  std::size_t reused = 0;    // distinct keys found in a store
  std::size_t runs = 0;      // solver processes that would start (batches count once)
  Timing timing;             // stored timings of this program and version
  double eta_seconds = -1;   // -1 when no timing is stored
};

/// Reads the outputs of a finished run from its work directory: one value per name, in any
/// order (command mode). Throws (any std::exception) when the output is missing or unparsable.
using ParseFn = std::function<NamedValues(const std::string& workdir)>;
/// Batch mode: a matrix with one row per point of the batch (in the order written) and one
/// column per output, in the order of CommandConfig::outputs.
using ParseBatchFn = std::function<Eigen::MatrixXd(const std::string& workdir, std::size_t points)>;
using ProgressFn = std::function<void(const Progress&, bool final)>;

class Evaluator {
 public:
  explicit Evaluator(CommandConfig cfg);
  ~Evaluator();

  /// Runs what the stores do not hold. X: rows = points, columns = cfg.inputs. With
  /// launch = false (--dry-run) only stored results are filled in; the rest are NotRun.
  EvalResult evaluate(const Eigen::MatrixXd& X, const ParseFn& parse, const ParseBatchFn& parse_batch,
                      const ProgressFn& progress, bool launch = true);
  /// What evaluate(X) would run, without running anything (--dry-run).
  Plan plan(const Eigen::MatrixXd& X);
  /// --dry-run with a Slurm executor: the job script, the sbatch lines and the cost plan for
  /// `plan` ("" for the local executor).
  std::string executor_plan(const Plan& plan);

  /// The run's cancellation token, read while runs go on (every tick and after each run): once
  /// it carries a reason (signal, timeout, memory, exit), evaluate() kills the running process
  /// groups and throws smi::Interrupted with the reason's message. Records of the runs that
  /// finished are in the store already, so running the study again resumes. Null: never stops.
  void set_cancel(const cancel::Token* token) { cancel_ = token; }

  /// With CommandConfig::deck_function: the function that makes the deck text of a point (the
  /// binding sets it when the model is made, see bindings/eval/deck_function.cpp). It is called
  /// on the calling thread only, while the points are keyed, never by the scheduler's workers.
  /// The deck text goes into the key, as a rendered template's does.
  void set_deck_function(std::function<std::string(const Eigen::VectorXd&)> fn) { deck_fn_ = std::move(fn); }

  /// The content key of row `x` (tests and reports).
  std::string key(const Eigen::VectorXd& x) const;
  /// The deck text for `x` (command mode).
  std::string render(const Eigen::VectorXd& x) const;
  const CommandConfig& config() const { return cfg_; }
  const std::string& version() const { return cfg_.version; }
  Store& store();

 private:
  struct Point;
  struct Run;  // one call of evaluate(): its tasks, retries, records and progress
  std::vector<Point> points_of(const Eigen::MatrixXd& X) const;
  std::string key_of(const Eigen::VectorXd& x, const std::string& deck) const;
  bool lookup(Point& p);
  CommandConfig cfg_;
  std::string key_prefix_;  // hash state of everything but the point, as text fed first
  std::unique_ptr<Store> store_, shared_;
  const cancel::Token* cancel_ = nullptr;
  std::function<std::string(const Eigen::VectorXd&)> deck_fn_;
};

}  // namespace smi::eval
