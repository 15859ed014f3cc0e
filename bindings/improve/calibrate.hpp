// SPDX-License-Identifier: MIT
#pragma once
// smi.calibrate{...}: running a calibration described by a CalibrateSpec and pushing its result.
#include <lua.hpp>

#include <optional>
#include <string>
#include <vector>

#include "bindings/improve/calibrate_spec.hpp"
#include "kernels/improve/bounded_optimizer.hpp"
#include "kernels/improve/calibration.hpp"
#include "kernels/improve/directions.hpp"
#include "kernels/improve/identifiability.hpp"
#include "kernels/improve/start_agreement.hpp"
#include "kernels/improve/statistical_objective.hpp"

namespace smi::bind::improve {

using smi::improve::CalibrationOutcome;

/// The kernel's problem from the spec: Lua callbacks wrapped as capabilities (they call through
/// the spec's slots, so the spec and its stack must outlive the problem).
smi::improve::CalibrationProblem calibration_problem(lua_State* L, const CalibrateSpec& s);
/// Runs the kernel's pipeline (smi::improve::calibrate) on the spec.
CalibrationOutcome run_calibration(lua_State* L, const CalibrateSpec& s);
/// Pushes the result table. Stack: [] -> [result].
void push_calibration_result(lua_State* L, const CalibrateSpec& s, const CalibrationOutcome& out);

/// The Lua function smi.calibrate.
int calibrate(lua_State* L);

}  // namespace smi::bind::improve
