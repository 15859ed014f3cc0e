// SPDX-License-Identifier: MIT
#pragma once
// The option schema of smi.calibrate (luax/option_schema.hpp): the scalar options are read into
// CalibrateSpec (whose bases hold every default: improve::CalibrationOptions, OptimizerOptions,
// StatisticalOptions); the nested tables and callbacks are listed by_hand and read by
// calibrate_spec.cpp. doc.cpp takes the reference's option list from it.
#include <limits>
#include <string>

#include "bindings/improve/calibrate_spec.hpp"
#include "luax/option_schema.hpp"

namespace smi::bind::improve {

const lua::Schema<CalibrateSpec>& calibrate_schema();
/// bootstrap = {...}: read over defaults the binding sets first (the calibration's seed, maxeval
/// and multistart); its reference lines are the bootstrap entry's meaning in calibrate_schema().
const lua::Schema<smi::improve::BootstrapOptions>& bootstrap_schema();
/// identifiability = {...}: read into the spec (s.ident, s.directions, the directions' switch
/// and tolerance), over what it holds; the caller copies points to s.directions.points.
const lua::Schema<CalibrateSpec>& identifiability_schema();

/// intervals = {...}: what was given (NaN / 0: not given); read_intervals checks that level and
/// delta do not come together and that observations goes with level.
struct IntervalsArgs {
  double level = std::numeric_limits<double>::quiet_NaN();  ///< NaN: the spec's interval_level
  double delta = std::numeric_limits<double>::quiet_NaN();  ///< NaN: from the level
  int observations = 0;                                     ///< 0: the large-sample delta
};
const lua::Schema<IntervalsArgs>& intervals_schema();

/// An entry of prior = {...}: param (a calibrated parameter) or name with fn (read by hand, it
/// stays on the stack), and the normal prior's mean and std (NaN until given).
struct PriorArgs {
  std::string param, name;
  double mean = std::numeric_limits<double>::quiet_NaN();
  double std = std::numeric_limits<double>::quiet_NaN();
};
/// Read with the entry's name ("prior[2]") in its messages.
const lua::Schema<PriorArgs>& prior_schema();

}  // namespace smi::bind::improve
