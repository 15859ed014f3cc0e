// SPDX-License-Identifier: MIT
#pragma once
// What smi.propagate and smi.screen accept as `model`, turned into one C++ callable on whole
// matrices: an smi.kriging (mean prediction), a table of them by output name, a Lua function
// taking the sample matrix (returning a vec, or {name = vec}), or any object with the model
// interface m:evaluate(X) -> {name = vec} (smi.model objects).
#include <string>
#include <vector>
#include <lua.hpp>

#include "kernels/surrogate/propagate.hpp"
#include "luax/luax.hpp"

namespace smi::bind::surrogate {

struct ModelArg {
  smi::surrogate::propagate::MatrixModel fn;
  /// Output names; for Lua functions and objects, filled by the first call.
  std::shared_ptr<std::vector<std::string>> outputs;
  /// Column order the model expects, when it says (Kriging `inputs`, smi.model's m.inputs).
  std::vector<std::string> input_names;
};

/// The value at absolute index idx must stay on the stack while fn is used.
ModelArg to_model(lua_State* L, int idx, const char* fname);

/// Reads `inputs` (at absolute index idx): either an array {{"name", dist|number}, ...} or a
/// map {name = dist|number}; a map is ordered by `order` when given, else by the model's input
/// names, else by sorted names.
std::vector<smi::surrogate::propagate::Input> to_inputs(lua_State* L, int idx, const std::vector<std::string>& order,
                                        const char* fname);

/// The `model`, `order` and `inputs` fields shared by smi.propagate and smi.screen, read from
/// the options table `o`. The model value is left on the stack (at model_idx) for as long as
/// the caller uses model.fn.
struct ModelAndInputs {
  ModelArg model;
  int model_idx;
  std::vector<smi::surrogate::propagate::Input> inputs;
};
ModelAndInputs read_model_and_inputs(lua_State* L, const lua::Options& o, const char* fname);

}  // namespace smi::bind::surrogate
