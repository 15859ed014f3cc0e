// SPDX-License-Identifier: MIT
#pragma once
// Reading CalculiX's .dat results file (ccx 2.20): the "E I G E N V A L U E   O U T P U T" table
// of a *FREQUENCY step, and the result blocks that *NODE PRINT and *EL PRINT write, such as
//    displacements (vx,vy,vz) for set TIP and time  0.1000000E+01
//    stresses (elem, integ.pnt.,sxx,syy,szz,sxy,sxz,syz) for set EALL and time  0.1000000E+01
// each followed by rows of numbers (node blocks start with the node number, which the header
// does not name). In a *FREQUENCY step each block follows its "E I G E N V A L U E    N U M B E R
// n" line, which gives the block's mode. The participation-factor and effective-mass tables are
// skipped. Errors name the file and line.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "platform/eval/text_parsers.hpp"

namespace smi::eval {

struct CcxEigen {
  int mode = 0;
  double eigenvalue = 0, radians = 0, cycles = 0, imaginary = 0;  // lambda, omega (rad/time), Hz, Im(omega)
};

struct CcxBlock {
  std::string name;                  // first word of the header, lower case ("displacements", "stresses")
  std::string set;                   // the node or element set ("TIP"); "" if the header names none
  double time = 0;                   // the header's time (1.0 in a *FREQUENCY step)
  int mode = 0;                      // the eigenmode the block belongs to, 0 outside a *FREQUENCY step
  std::vector<std::string> columns;  // "node" first for node blocks, then the header's names
                                     // ("integ.pnt." -> "integ_pnt")
  Eigen::MatrixXd rows;              // one row per printed line
};

struct CcxDat {
  std::vector<CcxEigen> eigen;   // in file order (every *FREQUENCY step's table)
  std::vector<CcxBlock> blocks;  // in file order
};

/// Parses `text`; `source` names the file in errors. Throws ParseError when the file has neither
/// an eigenvalue table nor a result block (a run that stopped before its output), or a row does
/// not have the fields its table needs (file, line, the row).
CcxDat parse_ccx_dat(const std::string& text, const std::string& source);

}  // namespace smi::eval
