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

struct CalibrateSpec {
  smi::improve::OptimizerOptions optimizer;
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
  int penalty_slot = 0;       ///< penalty(theta) added to the metric (model form), or 0
  std::vector<smi::improve::DesignRange> design;
  std::vector<PriorSpec> priors;  ///< prior = {...} (both forms)
  double prior_weight = 1.0;
  /// "auto": analytic when the model has a gradient (Kriging, m:gradient) and the metric is PR or
  /// loglik, else differences; "analytic" requires it; "differences" never uses it.
  std::string gradient = "auto";
  bool overlap_start = true;  ///< move a start where PR saturates at 2 (overlap_start = false: keep it)
  bool moment_start = false;  ///< move every start by Levenberg-Marquardt on the responses' moments (kept when better)

  // Diagnostics.
  bool identifiability = true;
  bool identifiability_directions = true;  ///< identifiability = {directions = false} skips them (and near_optimal)
  smi::improve::IdentifiabilityOptions ident;
  smi::improve::DirectionsOptions directions;
  /// identifiability.tolerance as given, or 0: then chosen by the metric at run time (PR: 0.01
  /// per response; loglik: 1.92 = half the 95 % chi-square quantile; otherwise 1e-6 max(1, |f*|)).
  double directions_tolerance = 0.0;
  std::optional<smi::improve::BootstrapOptions> bootstrap;
  /// intervals = true | {level = 0.9, delta =}: per-parameter profile intervals.
  std::optional<smi::improve::ProfileOptions> intervals;
  double interval_level = 0.9;  ///< 0 when delta was given instead
};

/// Reads the spec table at `idx`; pushes the callback values (see slots above).
CalibrateSpec read_calibrate_spec(lua_State* L, int idx);

}  // namespace smi::bind::improve
