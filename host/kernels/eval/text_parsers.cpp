#include "eval/text_parsers.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fmt/format.h>
#include <fstream>
#include <regex>
#include <sstream>

namespace smi::eval {
namespace {

std::regex compile(const std::string& pattern, const std::string& source) {
  try {
    return std::regex(pattern, std::regex::ECMAScript);
  } catch (const std::regex_error& e) {
    throw ParseError(fmt::format("bad regular expression /{}/ for '{}': {}", pattern, source, e.what()));
  }
}

int line_of(const std::string& text, std::ptrdiff_t pos) {
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + pos, '\n'));
}

double match_number(const std::smatch& m, const std::string& text, const std::string& pattern,
                    const std::string& source) {
  const std::string s = m.size() > 1 ? m[1].str() : m[0].str();
  double v = 0;
  if (!parse_number(s, v))
    throw ParseError(fmt::format("'{}' line {}: /{}/ matched '{}', which is not a number", source,
                                 line_of(text, m.position(0)), pattern, s));
  return v;
}

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    std::string f = line.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    const auto b = f.find_first_not_of(" \t\r\"");
    const auto e = f.find_last_not_of(" \t\r\"");
    out.push_back(b == std::string::npos ? "" : f.substr(b, e - b + 1));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

}  // namespace

bool parse_number(const std::string& text, double& out) {
  const char* s = text.c_str();
  while (*s == ' ' || *s == '\t') ++s;
  if (!*s) return false;
  char* end = nullptr;
  errno = 0;
  out = std::strtod(s, &end);
  if (end == s) return false;
  while (*end == ' ' || *end == '\t' || *end == '\r') ++end;
  return *end == '\0';
}

std::string read_text_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ParseError(fmt::format("output file '{}' is missing or unreadable: {}", path, std::strerror(errno)));
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

double regex_number(const std::string& text, const std::string& pattern, const std::string& source) {
  const std::regex re = compile(pattern, source);
  std::smatch m;
  if (!std::regex_search(text, m, re))
    throw ParseError(fmt::format("'{}': no match for /{}/", source, pattern));
  return match_number(m, text, pattern, source);
}

Eigen::VectorXd regex_numbers(const std::string& text, const std::string& pattern, const std::string& source) {
  const std::regex re = compile(pattern, source);
  std::vector<double> vals;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), re); it != std::sregex_iterator(); ++it)
    vals.push_back(match_number(*it, text, pattern, source));
  return Eigen::Map<Eigen::VectorXd>(vals.data(), static_cast<Eigen::Index>(vals.size()));
}

Eigen::VectorXd csv_column(const std::string& text, const std::string& column, const std::string& source) {
  std::istringstream in(text);
  std::string line;
  int lineno = 0;
  std::vector<std::string> header;
  std::size_t col = 0;
  std::vector<double> vals;
  while (std::getline(in, line)) {
    ++lineno;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos || line[line.find_first_not_of(" \t")] == '#') continue;
    const auto fields = split_csv(line);
    if (header.empty()) {
      header = fields;
      const auto it = std::find(header.begin(), header.end(), column);
      if (it == header.end()) {
        std::string names;
        for (const auto& h : header) names += (names.empty() ? "" : ", ") + h;
        throw ParseError(fmt::format("'{}' line {}: no column '{}' in the header (columns: {})", source, lineno,
                                     column, names));
      }
      col = static_cast<std::size_t>(it - header.begin());
      continue;
    }
    if (fields.size() != header.size())
      throw ParseError(fmt::format("'{}' line {}: {} fields, the header has {}", source, lineno, fields.size(),
                                   header.size()));
    double v = 0;
    if (!parse_number(fields[col], v))
      throw ParseError(fmt::format("'{}' line {} column '{}': '{}' is not a number", source, lineno, column,
                                   fields[col]));
    vals.push_back(v);
  }
  if (header.empty()) throw ParseError(fmt::format("'{}': empty CSV file (no header line)", source));
  return Eigen::Map<Eigen::VectorXd>(vals.data(), static_cast<Eigen::Index>(vals.size()));
}

}  // namespace smi::eval
