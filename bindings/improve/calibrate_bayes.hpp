// SPDX-License-Identifier: MIT
#pragma once
// smi.calibrate_bayes{...}: the posterior of calibrated parameters and the log evidence by
// TMCMC (kernels/improve/tmcmc.hpp), on a Lua log-likelihood (objective form) or on the
// population likelihood of a model, its unknown inputs and the specimens' data (model form,
// kernels/improve/population_likelihood.hpp).
#include <lua.hpp>

namespace smi::bind::improve {

/// The Lua function smi.calibrate_bayes.
int calibrate_bayes(lua_State* L);
/// Registers the result's metatable (its __tostring).
void register_bayes_meta(lua_State* L);

}  // namespace smi::bind::improve
