// SPDX-License-Identifier: MIT
#pragma once
// Reading numbers out of solver output files: the first (or every) match of a regular
// expression, and named columns of a CSV file. Errors name the file, the line and what was
// expected, because a parser failure becomes a failed evaluation record that a person reads.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "platform/core/csv.hpp"
#include "platform/core/errors.hpp"

namespace smi::eval {

/// The output could not be read as expected (missing value, not a number).
struct ParseError : Error {
  using Error::Error;
};

/// Reads a whole file; throws ParseError naming it if it is missing or unreadable.
std::string read_text_file(const std::string& path);

/// The number captured by `pattern` (RE2 syntax, linear time, no recursion; capture group 1 if
/// the pattern has one, else the whole match) at its first match in `text`. `source` names the file in errors.
double regex_number(const std::string& text, const std::string& pattern, const std::string& source);
/// Every match, in order.
Eigen::VectorXd regex_numbers(const std::string& text, const std::string& pattern, const std::string& source);

/// Column `column` (by header name) of a comma-separated table with one header line, read by
/// the one CSV codec (core/csv.hpp: quoted fields, CRLF, BOM); blank lines and lines starting
/// with '#' are skipped.
Eigen::VectorXd csv_column(const std::string& text, const std::string& column, const std::string& source);

/// The blank-separated words of a line of a solver's listing.
std::vector<std::string> split_words(const std::string& line);
/// The line without blanks: listings space out their titles ("E I G E N V A L U E   O U T P U T",
/// "R E A L   E I G E N V A L U E S"), so titles are compared squeezed.
std::string squeeze_blanks(const std::string& line);

/// A whole number from text (strtod over the trimmed text), false if the text is not entirely
/// one: the CSV codec's rule, so a solver's numbers read the same from CSV and from a regex match.
using csv::parse_number;

}  // namespace smi::eval
