#pragma once
// smi.calibrate{...}: running a calibration described by a CalibrateSpec and pushing its result.
#include <lua.hpp>

#include <optional>
#include <string>
#include <vector>

#include "bindings/improve/calibrate_spec.hpp"
#include "kernels/improve/bootstrap.hpp"
#include "kernels/improve/bounded_optimizer.hpp"
#include "kernels/improve/directions.hpp"
#include "kernels/improve/identifiability.hpp"
#include "kernels/improve/start_agreement.hpp"
#include "kernels/improve/statistical_objective.hpp"

namespace smi::bind::improve {

struct CalibrationOutcome {
  smi::improve::OptimizationResult opt;
  std::vector<std::string> part_names;  ///< labels of Evaluation::parts (responses)
  std::optional<smi::improve::IdentifiabilityResult> ident;
  std::optional<smi::improve::DirectionsResult> directions;
  std::optional<smi::improve::ProfileResult> profile;
  std::optional<smi::improve::BootstrapResult> boot;
  std::optional<smi::improve::StartAgreement> agreement;  ///< with multistart > 1
  std::optional<smi::improve::StatisticalObjective> stat;
  std::vector<std::string> warnings;  ///< everything worth telling, optimiser's included
  bool analytic_gradient = false;     ///< SLSQP ran on the analytic gradient
};

/// Runs optimisation and diagnostics. Calls back into Lua through the spec's slots.
CalibrationOutcome run_calibration(lua_State* L, const CalibrateSpec& s);
/// Pushes the result table. Stack: [] -> [result].
void push_calibration_result(lua_State* L, const CalibrateSpec& s, const CalibrationOutcome& out);

/// The Lua function smi.calibrate.
int calibrate(lua_State* L);

}  // namespace smi::bind::improve
