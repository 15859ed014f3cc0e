// SPDX-License-Identifier: MIT
// Entry point of the eval binding area (see modules.hpp): the smi.model table.
//
// THE MODEL INTERFACE (shared by solver models, Lua-function models and surrogates)
// ----------------------------------------------------------------------------------
// A model is an object m with
//   m.inputs    {"x1", "x2", ...}   names, in the column order of X
//   m.outputs   {"f1", ...}         names of what it returns
//   m.name, m.kind                  "command" | "batch" | "lua" (a surrogate may say "surrogate")
//   Y, info = m:evaluate(X)
// X is a smi.mat (rows = points, columns = inputs in the order of m.inputs), a table of rows,
// or a table of named columns {x1 = vec, x2 = vec} ({x1 = 1, x2 = 2} is one point).
// Y is {f1 = smi.vec, ...}: one value per row of X, in row order, whatever the concurrency
// and the order in which runs finished. Rows that did not succeed hold NaN.
// info is a table:
//   info.status    {"ok" | "failed" | "not run", ...}   per row
//   info.ok        smi.vec of 1/0 per row (mask for selecting rows)
//   info.reason    {"" | "exit status 1: ...", ...}     per row
//   info.failures  {{row = i, reason = "..."}, ...}     the failed rows only
//   info.failed    count;  info.launched  processes started;  info.stopped  boolean
//   info.reused    smi.vec of 1/0 (found in the evaluation store);  info.duration  smi.vec (s)
// A model that cannot fail (a surrogate) returns status all "ok", ok all 1, failures = {}.
// m:plan(X) -> {points, reused, runs, eta} tells what evaluate would launch, launching nothing.
// Swapping a solver for a surrogate is one line because nothing else is assumed.
//
// CONSTRUCTORS
//   smi.model.command{name, inputs, outputs, template = "deck.tpl" | template_string = "...",
//       deck = "input.deck", constants = {k = number|string}, files = {...},
//       command = {"program", "{deck}", ...},            -- argv, never a shell; {workdir} too
//       parse = function(dir, h) return {f1 = h.regex("out.txt", "f1 = (\\S+)")} end,
//       version = "...", timeout = s, retries = n, on_failure = "stop"|"skip"|"retry",
//       concurrency = n, reuse_failed = false, store = path}
//   smi.model.batch{...same, input_file = "points.csv", batch_size = n,
//       parse = function(dir, h, n) return {f1 = vec_of_n, ...} end}
//   smi.model.lua{name, inputs, outputs, fn = function(X) return {f1 = vec, ...} end}
// Parser helpers (bound to the run's folder in `h`, free-standing in smi.model.parse):
//   read(file), exists(file), regex(file, pattern), regex_all(file, pattern), csv(file, column),
//   f06(file) -> {mode, cycles, eigenvalue, radians, mass, stiffness, direction, labels,
//                 paper = {[n] = {mode, direction, hz}}, paper_hz}
// smi.model.planned() -> totals of the --dry-run so far {runs, points, reused, eta}.
#include "bindings/eval/model.hpp"
#include "bindings/modules.hpp"
#include "luax/luax.hpp"

namespace smi::bind {

void open_eval(lua_State* L) {
  // stack: [smi]
  eval::register_model_type(L);
  static const luaL_Reg kModel[] = {{"command", eval::model_command}, {"batch", eval::model_batch},
                                    {"lua", eval::model_lua},         {"planned", eval::model_planned},
                                    {nullptr, nullptr}};
  lua_createtable(L, 0, 5);
  luaL_setfuncs(L, kModel, 0);
  eval::push_parse_helpers(L, "");
  lua_setfield(L, -2, "parse");
  lua_setfield(L, -2, "model");
}

}  // namespace smi::bind
