// SPDX-License-Identifier: MIT
#pragma once
// Helpers shared by the smi-column-fe tests.
#include <cmath>

#include "solve.hpp"

namespace fe_test {

/// Half a unit in the last of `digits` significant digits of ref: the agreement "to the printed
/// digits" of the spec's tables.
inline double half_unit(double ref, int digits) {
  return 0.5 * std::pow(10.0, std::floor(std::log10(std::abs(ref))) - (digits - 1));
}

/// Frequencies (Hz) of paper modes 1..4.
inline std::array<double, 4> paper_hz(const cfe::Inputs& in) { return cfe::run_model(in).paper_hz; }

/// The §8 corner: the lateral mode comes first.
inline cfe::Inputs corner(cfe::Airbag a) {
  cfe::Inputs in = cfe::nominal_inputs(a);
  in.set("column_frame_E", 307500);
  in.set("ecu_bracket_thickness", 4.8);
  in.set("wheel_cover_rho", 0.5e-9);
  in.set("wheel_cover_thickness", 2.75);
  return in;
}

}  // namespace fe_test
