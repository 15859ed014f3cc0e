// SPDX-License-Identifier: MIT
#pragma once
// The terminal line of a calibration's long stages, drawn by the same
// show_progress/format_duration as the solver runs' line (platform/eval/progress_line.hpp):
//   calibration: start 2/4, 137 evaluations, best 0.2881, ETA 0:42
//   bootstrap: 12/100 replicates, 1234 evaluations, ETA 3:10
//   near-optimal: 45 evaluations, ETA 5 s
// Nothing when stderr is not a terminal, with --quiet, or with progress = false.
#include <lua.hpp>

#include <string>

#include "kernels/improve/calibration.hpp"

namespace smi::bind::improve {

/// The text of one row (testable without a terminal).
std::string format_progress_row(const smi::improve::ProgressRow& r);

/// The line for this run, or empty when it must stay silent.
smi::improve::ProgressLine terminal_progress_line(lua_State* L, bool wanted);

}  // namespace smi::bind::improve
