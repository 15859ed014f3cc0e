// SPDX-License-Identifier: MIT
#pragma once
// Batch mode: many solutions in one process (`smi-column-fe --batch POINTS.csv --base DECK -o OUT.csv`),
// so that screening 46 inputs over hundreds of samples costs solves, not process launches.
// POINTS.csv: a header of input names (any of the 46 inputs and airbag_stiffness), then one row of
// numbers per point; every input a row does not name keeps its value from the base deck (which
// also fixes airbag_model and mesh_refinement). OUT.csv: one row per point, in order:
//   point,mode1_hz,mode2_hz,mode3_hz,mode4_hz   (paper modes; "nan" when a label is absent)
// A bad header or value is an error naming the file, the row, the column and the value (nothing
// is written then), checked before any solution starts.
#include <iosfwd>
#include <string>
#include <vector>

#include "inputs.hpp"

namespace cfe {

struct BatchPoints {
  std::vector<std::string> names;           // header, in column order
  std::vector<std::vector<double>> rows;    // one per point
};

/// Parses POINTS.csv text; `file` only names it in messages. Throws DeckError.
BatchPoints parse_points(const std::string& text, const std::string& file);

/// The inputs of point `i`: `base` with the point's values set; values checked as in a deck (§9).
Inputs point_inputs(const Inputs& base, const BatchPoints& pts, std::size_t i, const std::string& file);

/// Solves every point and writes OUT.csv to `os` (header first). `threads` > 1 solves points
/// concurrently (results are identical: each solution is independent).
void run_batch(const Inputs& base, const BatchPoints& pts, const std::string& file, std::ostream& os, int threads = 1);

}  // namespace cfe
