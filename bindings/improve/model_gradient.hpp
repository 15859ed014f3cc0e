// SPDX-License-Identifier: MIT
#pragma once
// The model's Jacobian for smi.calibrate's analytic gradient: per response,
// dY/dX at the CRN inputs. A part that is an smi.kriging gives it in closed form (no Lua call);
// a model object with a gradient method gives m:gradient(X) (an N×k smi.mat for its one output,
// or {output = mat}); a plain function, or an object without one, has none and the calibration
// falls back to finite differences of the objective.
#include <lua.hpp>

#include <string>
#include <vector>

#include "bindings/improve/calibrate_spec.hpp"
#include "bindings/improve/lua_gate.hpp"
#include "kernels/improve/statistical_objective.hpp"

namespace smi::bind::improve {

/// The model without Lua when every response's part is an smi.kriging (per-response parts, or one
/// Kriging for a single response): predict_mean on `threads` threads, the numbers of
/// m:evaluate(X). Empty otherwise. Being Lua-free it may run on several threads at once (starts
/// side by side).
smi::improve::Model kriging_model(lua_State* L, const CalibrateSpec& s, const std::vector<std::string>& responses, int threads);

/// Empty when some response's model has no gradient. A Lua gradient method is called through
/// `gate` (the model's own), so the Jacobian may be asked from several threads.
smi::improve::StatisticalObjective::ModelJacobian model_jacobian(lua_State* L, const CalibrateSpec& s,
                                                                  const std::vector<std::string>& responses, const LuaGate& gate);

}  // namespace smi::bind::improve
