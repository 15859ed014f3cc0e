// SPDX-License-Identifier: MIT
#pragma once
// Reading the results of a normal-modes run in Nastran's .f06 layout, as written by the
// steering-column solver (docs/spec/steering-column.md §10): the REAL EIGENVALUES table, the
// MODE LABELS table and the "PAPER MODE n" lines that map the paper's modes to solver modes.
// Page headers (lines starting with '1') and spacer lines ('0') between blocks are skipped,
// and a table continued on a later page (its title repeated) is appended.
#include <string>
#include <vector>

#include "platform/eval/text_parsers.hpp"

namespace smi::eval {

struct F06Eigen {
  int mode = 0, order = 0;
  double eigenvalue = 0, radians = 0, cycles = 0, mass = 0, stiffness = 0;
};

struct F06Label {
  int mode = 0;
  double cycles = 0;
  std::string direction;
  int paper = 0;              // paper mode number, 0 for '-'
  double participation[6]{};  // translations a, l, v then rotations a, l, v
};

struct F06PaperMode {
  int paper = 0;
  std::string direction;
  int mode = 0;
  double hz = 0;
};

struct F06Result {
  std::vector<F06Eigen> eigen;        // in file order
  std::vector<F06Label> labels;       // empty when the file has no MODE LABELS table
  std::vector<F06PaperMode> paper;    // empty when the file has no PAPER MODE lines
};

/// Parses `text`; `source` names the file in errors. Throws ParseError when there is no REAL
/// EIGENVALUES table, or a row of a table does not have the expected fields (file and line).
F06Result parse_f06(const std::string& text, const std::string& source);

}  // namespace smi::eval
