#pragma once
// The option schema of smi.calibrate (luax/option_schema.hpp): the scalar options are read into
// CalibrateSpec (whose bases hold every default: improve::CalibrationOptions, OptimizerOptions,
// StatisticalOptions); the nested tables and callbacks are listed by_hand and read by
// calibrate_spec.cpp. doc.cpp takes the reference's option list from it.
#include "bindings/improve/calibrate_spec.hpp"
#include "luax/option_schema.hpp"

namespace smi::bind::improve {

const lua::Schema<CalibrateSpec>& calibrate_schema();
/// bootstrap = {...}: read over defaults the binding sets first (the calibration's seed, maxeval
/// and multistart); its reference lines are the bootstrap entry's meaning in calibrate_schema().
const lua::Schema<smi::improve::BootstrapOptions>& bootstrap_schema();

}  // namespace smi::bind::improve
