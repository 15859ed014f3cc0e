// SPDX-License-Identifier: MIT
#include "platform/eval/f06.hpp"

#include <fmt/format.h>
#include <sstream>

#include "platform/eval/text_parsers.hpp"

namespace smi::eval {
namespace {

bool is_int(const std::string& s, int& out) {
  double v = 0;
  if (!parse_number(s, v) || v != static_cast<double>(static_cast<int>(v))) return false;
  out = static_cast<int>(v);
  return true;
}

enum class Block { None, Eigen, Labels };

struct F06Parser {
  const std::string& source;
  int line = 0;
  F06Result r;

  [[noreturn]] void bad(const std::string& what, const std::string& text) const {
    throw ParseError(fmt::format("'{}' line {}: {}: '{}'", source, line, what, text));
  }

  double num(const std::string& s, const char* field, const std::string& text) const {
    double v = 0;
    if (!parse_number(s, v)) bad(fmt::format("{} '{}' is not a number", field, s), text);
    return v;
  }

  void eigen_row(const std::vector<std::string>& f, const std::string& text) {
    if (f.size() != 7) bad(fmt::format("eigenvalue row has {} fields, expected 7", f.size()), text);
    F06Eigen e;
    if (!is_int(f[0], e.mode) || !is_int(f[1], e.order)) bad("mode and extraction order must be integers", text);
    e.eigenvalue = num(f[2], "EIGENVALUE", text);
    e.radians = num(f[3], "RADIANS", text);
    e.cycles = num(f[4], "CYCLES", text);
    e.mass = num(f[5], "GENERALIZED MASS", text);
    e.stiffness = num(f[6], "GENERALIZED STIFFNESS", text);
    r.eigen.push_back(e);
  }

  void label_row(const std::vector<std::string>& f, const std::string& text) {
    if (f.size() != 10) bad(fmt::format("mode label row has {} fields, expected 10", f.size()), text);
    F06Label l;
    if (!is_int(f[0], l.mode)) bad("MODE must be an integer", text);
    l.cycles = num(f[1], "CYCLES", text);
    l.direction = f[2];
    if (f[3] != "-" && !is_int(f[3], l.paper)) bad("PAPER must be an integer or '-'", text);
    for (int k = 0; k < 6; ++k) l.participation[k] = num(f[4 + k], "participation", text);
    r.labels.push_back(l);
  }

  // "PAPER MODE 1  VERTICAL      MODE   1  2.963724E+01 HZ"
  void paper_line(const std::vector<std::string>& f, const std::string& text) {
    if (f.size() != 8 || f[4] != "MODE" || f[7] != "HZ") bad("expected 'PAPER MODE n DIRECTION MODE m f HZ'", text);
    F06PaperMode p;
    if (!is_int(f[2], p.paper) || !is_int(f[5], p.mode)) bad("paper and solver mode numbers must be integers", text);
    p.direction = f[3];
    p.hz = num(f[6], "frequency", text);
    r.paper.push_back(p);
  }
};

}  // namespace

F06Result parse_f06(const std::string& text, const std::string& source) {
  F06Parser p{source, 0, {}};
  std::istringstream in(text);
  std::string raw;
  Block block = Block::None;
  bool saw_eigen_title = false;
  while (std::getline(in, raw)) {
    ++p.line;
    if (!raw.empty() && raw.back() == '\r') raw.pop_back();
    const std::string sq = squeeze_blanks(raw);
    if (sq == "REALEIGENVALUES") {
      block = Block::Eigen;
      saw_eigen_title = true;
      continue;
    }
    if (sq == "MODELABELS") {
      block = Block::Labels;
      continue;
    }
    // Carriage-control column: '1' starts a page, '0' is a spacer; both end a table block.
    if (!raw.empty() && (raw[0] == '1' || raw[0] == '0')) {
      block = Block::None;
      continue;
    }
    const auto f = split_words(raw);
    if (f.empty()) continue;
    if (f.size() >= 2 && f[0] == "PAPER" && f[1] == "MODE") {
      p.paper_line(f, raw);
      continue;
    }
    int first = 0;
    if (!is_int(f[0], first)) continue;  // column headings ("MODE  EXTRACTION ...", "NO.  ORDER")
    if (block == Block::Eigen) p.eigen_row(f, raw);
    else if (block == Block::Labels) p.label_row(f, raw);
  }
  if (!saw_eigen_title)
    throw ParseError(fmt::format("'{}': no 'R E A L   E I G E N V A L U E S' table (is this the .f06 of a normal-modes run?)",
                                 source));
  if (p.r.eigen.empty()) throw ParseError(fmt::format("'{}': the REAL EIGENVALUES table has no rows", source));
  return p.r;
}

}  // namespace smi::eval
