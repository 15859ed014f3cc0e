// SPDX-License-Identifier: MIT
#pragma once
// Reading the table given to smi.calibrate{...} into kernel structures. Runs before any
// optimisation, inside protect(): errors name the field ("inputs.k.mean: ...") and the fix.
// Lua values the calibration calls back (objective, model, metric) are pushed onto the stack
// and their absolute slots recorded, so the callbacks never look anything up by name.
#include <lua.hpp>

#include <optional>
#include <string>
#include <vector>

#include "bindings/improve/lua_callbacks.hpp"
#include "kernels/improve/bootstrap.hpp"
#include "kernels/improve/bounded_optimizer.hpp"
#include "kernels/improve/calibration.hpp"
#include "kernels/improve/design_bounds.hpp"
#include "kernels/improve/directions.hpp"
#include "kernels/improve/identifiability.hpp"
#include "kernels/improve/profile_intervals.hpp"
#include "kernels/improve/statistical_objective.hpp"

namespace smi::bind::improve {

/// One entry of prior = {...}: a normal prior on a parameter (param >= 0) or on a Lua function of
/// the parameters (fn_slot), adding weight * 0.5 ((v - mean) / std)^2 to the objective.
struct PriorSpec {
  std::string label;  ///< the parameter's name, or the entry's name
  int param = -1;
  int fn_slot = 0;
  double mean = 0.0;
  double std = 1.0;
};

/// The table as read: the kernel's options (every default there, calibration.hpp) and problem
/// data, plus the stack slots of the Lua values the calibration calls back.
struct CalibrateSpec : smi::improve::CalibrationOptions {
  std::vector<smi::improve::Parameter> params;
  bool statistical = false;

  // Objective form.
  int objective_slot = 0;

  // Statistical form.
  std::vector<smi::improve::InputSpec> inputs;
  std::vector<smi::improve::ResponseSpec> responses;
  smi::improve::StatisticalOptions stat;
  std::vector<ModelPart> model_parts;  ///< one part, or one per output for {output = model, ...}
  int input_names_slot = 0;   ///< {input names} in column order (second argument of a model function)
  std::vector<std::string> model_input_order;  ///< from model.input_names, when the model object has one
  int data_slot = 0;          ///< the data table as given
  int metric_slot = 0;        ///< a Lua metric function, 0 for "pr"/"loglik"
  int progress_slot = 0;      ///< progress(row) called after each optimiser step (not probes), or 0
  bool progress_line = true;  ///< progress = false: no terminal line either
  int penalty_slot = 0;       ///< penalty(theta) added to the metric (model form), or 0
  std::vector<PriorSpec> priors;  ///< prior = {...} (both forms)
};

/// Reads the spec table at `idx`; pushes the callback values (see slots above).
CalibrateSpec read_calibrate_spec(lua_State* L, int idx);
/// Reads only the model form's model, inputs and data at `idx` into s (params, inputs,
/// responses, model_parts, input_names_slot, data_slot), with the same rules and messages as
/// smi.calibrate; smi.calibrate_bayes reads its population through it. Pushes the same values.
void read_population(lua_State* L, int idx, CalibrateSpec& s);

}  // namespace smi::bind::improve
