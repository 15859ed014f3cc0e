// SPDX-License-Identifier: MIT
// The option schemas of the solver models (solver_options.hpp). Defaults: the structs'.
#include "bindings/eval/solver_options.hpp"

#include <vector>

namespace smi::bind::eval {

using namespace smi::lua;
namespace se = smi::eval;

namespace {

using S = SolverArgs;

std::string on_failure_name(se::OnFailure f) {
  return f == se::OnFailure::Skip ? "skip" : f == se::OnFailure::Retry ? "retry" : "stop";
}

/// Both forms' options in reference order; the command form's deck keys or the batch form's.
std::vector<Option<S>> solver_options(bool batch) {
  std::vector<Option<S>> o{
      string<S>("name", [](auto& s) -> auto& { return s.config.name; }, {},
                "names the runs folder <out>/runs/<name> and the progress line"),
      by_hand<S>("inputs", "(required)", "input names, in the column order of X"),
      by_hand<S>("outputs", "(required)", "output names, the keys parse returns")};
  if (!batch) {
    o.push_back(by_hand<S>("template", "nil", "the deck template file, or a function(p) -> deck text (or template_string)"));
    o.push_back(string<S>("template_string", &S::template_string, {}, "the deck template text", "nil"));
    o.push_back(string<S>("deck", [](auto& s) -> auto& { return s.config.deck_file; }, {},
                          "the deck's file name in the work folder ({deck} in command)"));
    o.push_back(by_hand<S>("constants", "{}", "more placeholder values {name = number | string}"));
  } else {
    o.push_back(string<S>("input_file", &S::input_file, {}, "the CSV file of points in the work folder ({deck} in command)"));
  }
  o.push_back(by_hand<S>("files", "{}", "files copied into every work folder"));
  o.push_back(by_hand<S>("command", "(required)",
                         "argv {program, arg, ...}: \"{deck}\" and \"{workdir}\" are replaced;\n"
                         "the program must be allowed with --allow-exec"));
  o.push_back(by_hand<S>("parse", "(required)", batch ? "function(dir, h, n) returning {output = vec of n, ...}"
                                                     : "function(dir, h) returning {output = number, ...}"));
  o.push_back(string<S>("version", [](auto& s) -> auto& { return s.config.version; }, {},
                        "the solver's version in the store key (\"\" = the program's SHA-256)"));
  o.push_back(by_hand<S>("version_args", "nil",
                         "e.g. {\"--version\"}: run the program once with these arguments when\n"
                         "the model is made; the first line it prints is recorded in the\n"
                         "provenance (results.json, the report) as its version line"));
  o.push_back(number<S>("timeout", [](auto& s) -> auto& { return s.config.timeout; }, at_least(0),
                        "seconds per run, 0 = none; the process group is killed"));
  o.push_back(integer<S>("retries", [](auto& s) -> auto& { return s.config.retries; }, at_least(0),
                         "extra attempts after a failure"));
  o.push_back(parsed<S>("on_failure", [](auto& s) -> auto& { return s.config.on_failure; }, se::parse_on_failure, on_failure_name,
                        "\"stop\" (raise after the batch), \"skip\" (NaN, reported in info),\nor \"retry\""));
  o.push_back(integer<S>("concurrency", [](auto& s) -> auto& { return s.config.concurrency; }, at_least(1), "processes at once"));
  if (batch)
    o.push_back(integer<S>("batch_size", [](auto& s) -> auto& { return s.config.batch_size; }, at_least(0),
                           "points per run; 0 = all pending points in one run"));
  o.push_back(boolean<S>("reuse_failed", [](auto& s) -> auto& { return s.config.reuse_failed; },
                         "also reuse stored failures (default: run them again)"));
  o.push_back(string<S>("store", &S::store, {},
                        "the store file (default <out>/evaluations.sqlite); a missing folder\n"
                        "is made (under --out or an --allow-write path only)",
                        "nil"));
  o.push_back(by_hand<S>("executor", "nil",
                         "where the runs execute, overriding --executor: {kind = \"slurm\",\n"
                         "partition =, account =, time =, ...} (the --slurm-opt keys)"));
  o.push_back(by_hand<S>("env", "nil",
                         "{NAME = \"value\"}: variables the solver needs (OMP_NUM_THREADS, a\n"
                         "licence server), each allowed by the user with --allow-env NAME;\n"
                         "loader and interpreter hooks (LD_*, BASH_ENV, PATH, HOME, PYTHON*,\n"
                         "JAVA*, ...) are refused even then. Part of the store key"));
  return o;
}

}  // namespace

const Schema<SolverArgs>& solver_schema(bool batch) {
  static const Schema<S> command("smi.model.command", solver_options(false));
  static const Schema<S> batch_form("smi.model.batch", solver_options(true));
  return batch ? batch_form : command;
}

}  // namespace smi::bind::eval
