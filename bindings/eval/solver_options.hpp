// SPDX-License-Identifier: MIT
#pragma once
// The option schemas of smi.model.command and smi.model.batch (luax/option_schema.hpp):
// solver_model.cpp reads the scalars with them, doc.cpp lists them. The nested tables (inputs,
// outputs, command, files, constants, env, executor, version_args), the parser and a template
// that may be a function are read by solver_model.cpp (by_hand entries here).
#include <string>

#include "luax/option_schema.hpp"
#include "platform/eval/evaluator.hpp"

namespace smi::bind::eval {

/// What the schema reads. Defaults: the evaluator's CommandConfig (name, deck, timeout, retries,
/// on_failure, concurrency, batch_size, reuse_failed, version) and the members below.
struct SolverArgs {
  smi::eval::CommandConfig config;
  std::string template_string;        ///< the deck template's text ("" = not given)
  std::string store;                  ///< the store file ("" = <out>/evaluations.sqlite)
  std::string input_file = "points.csv";  ///< batch: the points file's name (the config's deck_file)
};

/// smi.model.command's (batch = false) or smi.model.batch's.
const lua::Schema<SolverArgs>& solver_schema(bool batch);

}  // namespace smi::bind::eval
