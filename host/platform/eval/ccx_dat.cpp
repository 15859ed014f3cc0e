// SPDX-License-Identifier: MIT
#include "platform/eval/ccx_dat.hpp"

#include <cctype>
#include <fmt/format.h>
#include <sstream>

#include "platform/eval/text_parsers.hpp"

namespace smi::eval {
namespace {

/// A header's column name as a Lua-friendly key: lower case, runs of other characters -> '_'.
std::string column_key(const std::string& raw) {
  std::string s;
  for (char c : raw) {
    if (std::isalnum(static_cast<unsigned char>(c))) s += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    else if (!s.empty() && s.back() != '_') s += '_';
  }
  while (!s.empty() && s.back() == '_') s.pop_back();
  return s;
}

bool blank(const std::string& line) { return line.find_first_not_of(" \t\r") == std::string::npos; }

struct Parser {
  const std::string& source;
  int line = 0;
  CcxDat r;

  [[noreturn]] void bad(const std::string& what, const std::string& text) const {
    throw ParseError(fmt::format("'{}' line {}: {}: '{}'", source, line, what, text));
  }

  /// Fields that are numbers, in order; stops at the first that is not (ccx appends element
  /// labels such as "_shell_0000000001" to some rows).
  std::vector<double> numbers(const std::vector<std::string>& f) const {
    std::vector<double> v;
    for (const auto& s : f) {
      double x = 0;
      if (!parse_number(s, x)) break;
      v.push_back(x);
    }
    return v;
  }

  void eigen_row(const std::vector<std::string>& f, const std::string& text) {
    const std::vector<double> v = numbers(f);
    if (v.size() != 5 || f.size() != 5)
      bad(fmt::format("eigenvalue row has {} fields, expected 5 (mode, eigenvalue, rad/time, cycles/time, imaginary)",
                      f.size()), text);
    CcxEigen e;
    e.mode = static_cast<int>(v[0]);
    if (e.mode != v[0] || e.mode < 1) bad("the mode number must be a positive integer", text);
    e.eigenvalue = v[1];
    e.radians = v[2];
    e.cycles = v[3];
    e.imaginary = v[4];
    r.eigen.push_back(e);
  }

  /// "<name> (<columns>) for set <SET> and time <t>" -> a new block, or false if not a header.
  bool block_header(const std::string& text, int mode) {
    const auto open = text.find('('), close = text.find(')');
    const auto for_set = text.find(" for set ");
    if (open == std::string::npos || close == std::string::npos || close < open || for_set == std::string::npos ||
        for_set < close)
      return false;
    const std::vector<std::string> words = split_words(text.substr(0, open));
    if (words.empty()) return false;
    CcxBlock b;
    b.mode = mode;
    for (const auto& w : words) b.name += (b.name.empty() ? "" : " ") + w;
    for (auto& c : b.name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    std::string cols = text.substr(open + 1, close - open - 1);
    std::istringstream in(cols);
    for (std::string c; std::getline(in, c, ',');)
      if (const std::string k = column_key(c); !k.empty()) b.columns.push_back(k);
    const std::vector<std::string> tail = split_words(text.substr(for_set + 9));
    if (!tail.empty()) b.set = tail[0];
    for (std::size_t i = 0; i + 1 < tail.size(); ++i)
      if (tail[i] == "time" && !parse_number(tail[i + 1], b.time)) bad("the block's time is not a number", text);
    r.blocks.push_back(std::move(b));
    return true;
  }

  void block_row(CcxBlock& b, std::vector<std::vector<double>>& rows, const std::vector<std::string>& f,
                 const std::string& text) {
    const std::vector<double> v = numbers(f);
    if (rows.empty() && b.columns.size() + 1 == v.size()) b.columns.insert(b.columns.begin(), "node");
    if (v.size() != b.columns.size())
      bad(fmt::format("a row of '{}' has {} numbers, the block's columns are {} ({})", b.name, v.size(),
                      b.columns.size(), fmt::join(b.columns, ", ")), text);
    rows.push_back(v);
  }
};

void finish_block(CcxBlock& b, const std::vector<std::vector<double>>& rows) {
  b.rows.resize(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(b.columns.size()));
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (std::size_t j = 0; j < rows[i].size(); ++j) b.rows(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = rows[i][j];
}

}  // namespace

CcxDat parse_ccx_dat(const std::string& text, const std::string& source) {
  Parser p{source, 0, {}};
  enum class In { None, EigenHeader, EigenRows, BlockHeader, BlockRows } state = In::None;
  int mode = 0;  // the current "E I G E N V A L U E    N U M B E R n"
  std::vector<std::vector<double>> rows;
  auto close_block = [&] {
    if (state == In::BlockHeader || state == In::BlockRows) finish_block(p.r.blocks.back(), rows);
    rows.clear();
    state = In::None;
  };
  std::istringstream in(text);
  for (std::string s; std::getline(in, s);) {
    ++p.line;
    if (!s.empty() && s.back() == '\r') s.pop_back();
    const std::string sq = squeeze_blanks(s);
    if (sq == "EIGENVALUEOUTPUT") {
      close_block();
      state = In::EigenHeader;
      continue;
    }
    if (sq.rfind("EIGENVALUENUMBER", 0) == 0) {
      close_block();
      double n = 0;
      if (!parse_number(sq.substr(16), n) || n < 1) p.bad("the eigenvalue number is not a positive integer", s);
      mode = static_cast<int>(n);
      continue;
    }
    if (blank(s)) {
      if (state == In::EigenRows || state == In::BlockRows) close_block();
      continue;
    }
    const std::vector<std::string> f = split_words(s);
    double first = 0;
    const bool numeric = parse_number(f[0], first);
    switch (state) {
      case In::EigenHeader:
        if (numeric) {
          state = In::EigenRows;
          p.eigen_row(f, s);
        }
        break;  // the column titles
      case In::EigenRows:
        p.eigen_row(f, s);
        break;
      case In::BlockHeader:
      case In::BlockRows:
        if (!numeric) {  // the next header, no blank line between
          close_block();
          if (p.block_header(s, mode)) state = In::BlockHeader;
          break;
        }
        state = In::BlockRows;
        p.block_row(p.r.blocks.back(), rows, f, s);
        break;
      case In::None:
        if (!numeric && p.block_header(s, mode)) state = In::BlockHeader;
        break;  // other tables (participation factors, effective mass) and titles
    }
  }
  close_block();
  if (p.r.eigen.empty() && p.r.blocks.empty())
    throw ParseError(fmt::format("'{}' has no E I G E N V A L U E   O U T P U T table and no result block (did the "
                                 "ccx run stop early? see its .sta and stdout)", source));
  return p.r;
}

}  // namespace smi::eval
