#pragma once
// The model's Jacobian for smi.calibrate's analytic gradient (issue 11 item 1): per response,
// dY/dX at the CRN inputs. A part that is an smi.kriging gives it in closed form (no Lua call);
// a model object with a gradient method gives m:gradient(X) (an N×k smi.mat for its one output,
// or {output = mat}); a plain function, or an object without one, has none and the calibration
// falls back to finite differences of the objective.
#include <lua.hpp>

#include <string>
#include <vector>

#include "bindings/improve/calibrate_spec.hpp"
#include "kernels/improve/statistical_objective.hpp"

namespace smi::bind::improve {

/// Empty when some response's model has no gradient.
smi::improve::StatisticalObjective::ModelJacobian model_jacobian(lua_State* L, const CalibrateSpec& s,
                                                                  const std::vector<std::string>& responses);

}  // namespace smi::bind::improve
