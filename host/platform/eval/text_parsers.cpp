// SPDX-License-Identifier: MIT
#include "platform/eval/text_parsers.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fmt/format.h>
#include <fstream>
#include <memory>
#include <re2/re2.h>
#include <string_view>
#include <sstream>

#include "platform/core/csv.hpp"

namespace smi::eval {
namespace {

/// RE2 runs in time linear in the text with no recursion (std::regex recursed per character
/// and overflowed the stack on a 200 KB line, even inside pcall). It has no backreferences or
/// lookaround; such a pattern is refused here with the reason and the pattern named.
std::unique_ptr<RE2> compile(const std::string& pattern, const std::string& source) {
  RE2::Options opt;
  opt.set_log_errors(false);
  opt.set_max_mem(64 << 20);  // big alternations still compile; a runaway one is an error, not a crash
  auto re = std::make_unique<RE2>(pattern, opt);
  if (!re->ok())
    throw ParseError(fmt::format(
        "bad regular expression /{}/ for '{}': {} (RE2 syntax: Perl-like classes \\d \\s \\S \\w, groups (...), "
        "(?:...); no backreferences like \\1 and no lookaround like (?=...))",
        pattern, source, re->error()));
  return re;
}

int line_of(const std::string& text, std::ptrdiff_t pos) {
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + pos, '\n'));
}

/// The text a match gives: capture group 1 if the pattern has one, else the whole match.
struct Match {
  std::string_view whole, value;
};

/// The first match at or after `from`; false if none.
bool find(const RE2& re, const std::string& text, std::size_t from, Match& m) {
  re2::StringPiece groups[2];
  const int ngroups = re.NumberOfCapturingGroups() > 0 ? 2 : 1;
  if (!re.Match(text, from, text.size(), RE2::UNANCHORED, groups, ngroups)) return false;
  m.whole = std::string_view(groups[0].data(), groups[0].size());
  m.value = ngroups == 2 ? std::string_view(groups[1].data() ? groups[1].data() : "", groups[1].size()) : m.whole;
  return true;
}

double match_number(const Match& m, const std::string& text, const std::string& pattern, const std::string& source) {
  std::string s(m.value);
  double v = 0;
  if (!parse_number(s, v)) {
    if (s.size() > 200) s = s.substr(0, 200) + "...";
    throw ParseError(fmt::format("'{}' line {}: /{}/ matched '{}', which is not a number", source,
                                 line_of(text, m.whole.data() - text.data()), pattern, s));
  }
  return v;
}

}  // namespace

std::string read_text_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ParseError(fmt::format("output file '{}' is missing or unreadable: {}", path, std::strerror(errno)));
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

double regex_number(const std::string& text, const std::string& pattern, const std::string& source) {
  const auto re = compile(pattern, source);
  Match m;
  if (!find(*re, text, 0, m)) throw ParseError(fmt::format("'{}': no match for /{}/", source, pattern));
  return match_number(m, text, pattern, source);
}

Eigen::VectorXd regex_numbers(const std::string& text, const std::string& pattern, const std::string& source) {
  const auto re = compile(pattern, source);
  std::vector<double> vals;
  Match m;
  for (std::size_t at = 0; at <= text.size() && find(*re, text, at, m);) {
    vals.push_back(match_number(m, text, pattern, source));
    const std::size_t end = static_cast<std::size_t>(m.whole.data() - text.data()) + m.whole.size();
    at = m.whole.empty() ? end + 1 : end;  // an empty match moves on by one character
  }
  return Eigen::Map<Eigen::VectorXd>(vals.data(), static_cast<Eigen::Index>(vals.size()));
}

Eigen::VectorXd csv_column(const std::string& text, const std::string& column, const std::string& source) {
  csv::ReadOptions ro;
  ro.comment = '#';
  const std::vector<csv::Record> recs = csv::read(text, source, ro);
  if (recs.empty()) throw ParseError(fmt::format("'{}': empty CSV file (no header line)", source));
  std::vector<std::string> header;
  for (const std::string& h : recs.front().fields) header.push_back(csv::trim(h));
  const auto it = std::find(header.begin(), header.end(), column);
  if (it == header.end()) {
    std::string names;
    for (const auto& h : header) names += (names.empty() ? "" : ", ") + h;
    throw ParseError(fmt::format("'{}' line {}: no column '{}' in the header (columns: {})", source,
                                 recs.front().line, column, names));
  }
  const std::size_t col = static_cast<std::size_t>(it - header.begin());
  std::vector<double> vals;
  for (std::size_t r = 1; r < recs.size(); ++r) {
    const csv::Record& rec = recs[r];
    if (rec.fields.size() != header.size())
      throw ParseError(fmt::format("'{}' line {}: {} fields, the header has {}", source, rec.line, rec.fields.size(),
                                   header.size()));
    double v = 0;
    if (!parse_number(rec.fields[col], v))
      throw ParseError(fmt::format("'{}' line {} column '{}': '{}' is not a number", source, rec.line, column,
                                   csv::trim(rec.fields[col])));
    vals.push_back(v);
  }
  return Eigen::Map<Eigen::VectorXd>(vals.data(), static_cast<Eigen::Index>(vals.size()));
}

std::vector<std::string> split_words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> out;
  std::string w;
  while (in >> w) out.push_back(w);
  return out;
}

std::string squeeze_blanks(const std::string& line) {
  std::string s;
  for (const char c : line)
    if (!std::isspace(static_cast<unsigned char>(c))) s += c;
  return s;
}

}  // namespace smi::eval
