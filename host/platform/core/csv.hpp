// SPDX-License-Identifier: MIT
#pragma once
// The one CSV codec of the tree (RFC 4180), Lua-free: smi.csv.read/write (bindings/csv.cpp) and
// the solver-output column reader (eval/text_parsers.hpp, csv_column) both go through it.
//   * fields may be quoted; a quoted field holds the separator, newlines and quotes written ""
//   * records end with LF or CRLF; a UTF-8 byte-order mark at the start is dropped
//   * blank lines are skipped; with ReadOptions::comment, so are lines starting with it
//     (after blanks), as solver output files have
// Errors name the source and line ("r.csv:4: a quoted field never ends ...").
#include <string>
#include <string_view>
#include <vector>

namespace smi::csv {

struct Record {
  std::vector<std::string> fields;  // as written, quotes removed, not trimmed
  long line = 0;                    // the line where the record starts (1-based)
};

struct ReadOptions {
  char sep = ',';
  char comment = 0;  // 0: no comment lines
};

/// The records of CSV text. Throws smi::Error naming `source` and the line for an unterminated
/// quoted field.
std::vector<Record> read(std::string_view text, const std::string& source, const ReadOptions& opts = {});

/// What a file read with separator `sep` really uses, from its first lines: "the file uses ';'
/// between fields: pass sep = ';' or save as CSV" (a tab likewise), with "and ',' as the decimal
/// mark" and decimal = ',' when its numbers are written 31,84. "" when nothing else fits better
/// (the header already splits on `sep` into several columns, or no other separator shows).
std::string sniff(std::string_view text, char sep);

/// True when the cell is a number written with a decimal comma (31,84 or -0,5; no '.').
bool decimal_comma(std::string_view cell);

/// s without leading and trailing blanks (spaces, tabs, CR).
std::string trim(std::string_view s);

/// A cell as a number: the whole trimmed text must be one (strtod syntax); false otherwise.
bool parse_number(std::string_view cell, double& out);

/// A cell as it is written: quoted (with "" for ") when it holds the separator, a quote, CR or LF.
std::string quote(std::string_view cell, char sep = ',');

/// Text of a table: a header row, then one row per index of the columns (cells as given, quoted
/// when needed), each ended by '\n'. The columns must have equal lengths.
std::string write(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& columns,
                  char sep = ',');

}  // namespace smi::csv
