// SPDX-License-Identifier: MIT
#pragma once
// The .f06-like results file of spec §10, and a reader for it (tests, tools).
#include <array>
#include <iosfwd>
#include <string>
#include <vector>

#include "eigen_solve.hpp"
#include "inputs.hpp"
#include "labels.hpp"

namespace cfe {

struct ModeRow {
  int mode = 0;
  double eigenvalue = 0, radians = 0, cycles = 0, gen_mass = 0, gen_stiffness = 0;
  std::string direction;
  int paper = 0;  // 1..4, or 0 for '-'
  std::array<double, 6> p{};
};

struct Results {
  std::string airbag;  // "RIGID" / "SPRING"
  int dof = 0;
  std::vector<ModeRow> modes;
  std::array<double, 4> paper_hz{};  // NaN when the label was not found
  std::array<int, 4> paper_mode{};   // 1-based mode number, 0 when not found
};

/// Collect what the file reports from a solution.
Results make_results(Airbag airbag, int dof, const Modes& modes, const Labels& labels, const Eigen::MatrixXd& M);

void write_results(std::ostream& os, const Results& r);
/// Parse a results file; throws std::runtime_error naming `file` and the line on malformed input.
Results read_results(std::istream& is, const std::string& file);

}  // namespace cfe
