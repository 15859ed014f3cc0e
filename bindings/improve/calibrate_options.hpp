#pragma once
// The option schema of smi.calibrate (luax/option_schema.hpp): the scalar options are read into
// CalibrateSpec (whose bases hold every default: improve::CalibrationOptions, OptimizerOptions,
// StatisticalOptions); the nested tables and callbacks are listed by_hand and read by
// calibrate_spec.cpp. doc.cpp takes the reference's option list from it.
#include "bindings/improve/calibrate_spec.hpp"
#include "luax/option_schema.hpp"

namespace smi::bind::improve {

const lua::Schema<CalibrateSpec>& calibrate_schema();

}  // namespace smi::bind::improve
