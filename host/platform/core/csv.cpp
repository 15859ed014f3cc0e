// SPDX-License-Identifier: MIT
#include "platform/core/csv.hpp"

#include <algorithm>
#include <cstdlib>
#include <fmt/format.h>

#include "platform/core/errors.hpp"

namespace smi::csv {
namespace {

bool blank(char c) { return c == ' ' || c == '\t'; }

/// At the start of a record: true (and i past the line) when the line is a comment.
bool skip_comment(std::string_view text, std::size_t& i, char comment, long& line) {
  if (!comment) return false;
  std::size_t j = i;
  while (j < text.size() && blank(text[j])) ++j;
  if (j >= text.size() || text[j] != comment) return false;
  while (j < text.size() && text[j] != '\n') ++j;
  i = j < text.size() ? j + 1 : j;
  ++line;
  return true;
}

}  // namespace

std::vector<Record> read(std::string_view text, const std::string& source, const ReadOptions& opts) {
  // A UTF-8 byte-order mark (spreadsheets write one) is not part of the first field.
  constexpr std::string_view bom = "\xEF\xBB\xBF";
  if (text.substr(0, bom.size()) == bom) text.remove_prefix(bom.size());
  const char sep = opts.sep;
  std::vector<Record> out;
  long line = 1;
  std::size_t i = 0;
  const std::size_t n = text.size();
  while (i < n) {
    if (skip_comment(text, i, opts.comment, line)) continue;
    Record rec;
    rec.line = line;
    std::string field;
    bool any = false;
    for (;;) {
      if (i < n && text[i] == '"') {
        const long start_line = line;
        ++i;
        for (;;) {
          if (i >= n) throw Error(fmt::format("line {} of {}: a quoted field never ends (missing '\"')", start_line, source));
          if (text[i] == '"') {
            if (i + 1 < n && text[i + 1] == '"') {
              field += '"';
              i += 2;
              continue;
            }
            ++i;
            break;
          }
          if (text[i] == '\n') ++line;
          field += text[i++];
        }
        any = true;
      }
      while (i < n && text[i] != sep && text[i] != '\n' && text[i] != '\r') field += text[i++];
      any = any || !trim(field).empty();
      rec.fields.push_back(std::move(field));
      field.clear();
      if (i < n && text[i] == sep) {
        ++i;
        any = true;
        continue;
      }
      break;
    }
    if (i < n && text[i] == '\r') ++i;
    if (i < n && text[i] == '\n') ++i;
    ++line;
    if (any) out.push_back(std::move(rec));  // blank lines are skipped
  }
  return out;
}

bool decimal_comma(std::string_view cell) {
  const std::string t = trim(cell);
  std::size_t i = (!t.empty() && (t[0] == '-' || t[0] == '+')) ? 1 : 0;
  const std::size_t comma = t.find(',');
  if (comma == std::string::npos || comma == i || comma + 1 >= t.size() || t.find('.') != std::string::npos) return false;
  for (std::size_t k = i; k < t.size(); ++k)
    if (k != comma && (t[k] < '0' || t[k] > '9')) return false;
  return true;
}

namespace {
std::string sep_name(char c) { return c == '\t' ? "a tab" : fmt::format("'{}'", c); }
std::string sep_lua(char c) { return c == '\t' ? "'\\t'" : fmt::format("'{}'", c); }
}  // namespace

std::string sniff(std::string_view text, char sep) {
  constexpr std::string_view bom = "\xEF\xBB\xBF";
  if (text.substr(0, bom.size()) == bom) text.remove_prefix(bom.size());
  // the first few non-blank lines, as written
  std::vector<std::string_view> lines;
  for (std::size_t i = 0; i < text.size() && lines.size() < 6;) {
    std::size_t e = text.find('\n', i);
    if (e == std::string_view::npos) e = text.size();
    std::string_view l = text.substr(i, e - i);
    if (!l.empty() && l.back() == '\r') l.remove_suffix(1);
    if (!trim(l).empty()) lines.push_back(l);
    i = e + 1;
  }
  if (lines.empty()) return "";
  const auto count = [](std::string_view l, char c) { return static_cast<long>(std::count(l.begin(), l.end(), c)); };
  if (count(lines[0], sep) > 0) return "";  // the header splits on sep: it is the separator
  char found = 0;
  for (const char c : {';', '\t'})
    if (c != sep && count(lines[0], c) > 0) {
      found = c;
      break;
    }
  if (!found) return "";
  bool comma_decimals = false;
  for (std::size_t r = 1; r < lines.size() && !comma_decimals; ++r) {
    std::string_view l = lines[r];
    for (std::size_t b = 0; b <= l.size();) {
      std::size_t e = l.find(found, b);
      if (e == std::string_view::npos) e = l.size();
      comma_decimals = comma_decimals || decimal_comma(l.substr(b, e - b));
      b = e + 1;
    }
  }
  if (comma_decimals)
    return fmt::format("the file uses {} between fields and ',' as the decimal mark: pass sep = {}, decimal = ',' "
                       "or save as CSV with '.' decimals",
                       sep_name(found), sep_lua(found));
  return fmt::format("the file uses {} between fields: pass sep = {} or save as CSV", sep_name(found), sep_lua(found));
}

std::string trim(std::string_view s) {
  std::size_t b = 0, e = s.size();
  while (b < e && (blank(s[b]) || s[b] == '\r')) ++b;
  while (e > b && (blank(s[e - 1]) || s[e - 1] == '\r')) --e;
  return std::string(s.substr(b, e - b));
}

bool parse_number(std::string_view cell, double& out) {
  const std::string t = trim(cell);
  if (t.empty()) return false;
  char* end = nullptr;
  out = std::strtod(t.c_str(), &end);
  return end == t.c_str() + t.size();
}

std::string quote(std::string_view cell, char sep) {
  if (cell.find_first_of(std::string("\"\r\n") + sep) == std::string_view::npos) return std::string(cell);
  std::string out = "\"";
  for (const char c : cell) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

std::string write(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& columns,
                  char sep) {
  std::string out;
  for (std::size_t j = 0; j < header.size(); ++j) {
    if (j) out += sep;
    out += quote(header[j], sep);
  }
  out += '\n';
  const std::size_t rows = columns.empty() ? 0 : columns.front().size();
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t j = 0; j < columns.size(); ++j) {
      if (j) out += sep;
      out += quote(columns[j].at(r), sep);
    }
    out += '\n';
  }
  return out;
}

}  // namespace smi::csv
