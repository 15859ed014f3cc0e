// SPDX-License-Identifier: MIT
#include "platform/eval/deck_template.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fmt/format.h>
#include <fstream>
#include <re2/re2.h>
#include <sstream>

namespace smi::eval {
namespace {

bool valid_name(const std::string& s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  for (char c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  return true;
}

// One printf conversion of a number, nothing else: the format goes to snprintf, so it is
// checked to be exactly this shape (a stray %s or %n would read memory that is not there).
const RE2& format_re() {
  static const RE2 re(R"(%[-+ 0#]{0,5}[0-9]{0,3}(\.[0-9]{0,3})?[eEfFgGd])");
  return re;
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t");
  return s.substr(b, e - b + 1);
}

/// snprintf into a string of the right size (a %999.3f of 1e300 is long).
template <class T>
void append_printf(std::string& out, const char* format, T value) {
  const int n = std::snprintf(nullptr, 0, format, value);
  if (n <= 0) return;
  const std::size_t at = out.size();
  out.resize(at + static_cast<std::size_t>(n) + 1);
  std::snprintf(out.data() + at, static_cast<std::size_t>(n) + 1, format, value);
  out.resize(at + static_cast<std::size_t>(n));
}

}  // namespace

DeckTemplate::DeckTemplate(std::string text, std::string source) : source_(std::move(source)) {
  int line = 1;
  std::size_t pos = 0;
  std::string lit;
  auto count_lines = [&](std::size_t from, std::size_t to) {
    for (std::size_t i = from; i < to; ++i)
      if (text[i] == '\n') ++line;
  };
  while (pos < text.size()) {
    const std::size_t open = text.find("{{", pos);
    if (open == std::string::npos) {
      lit += text.substr(pos);
      break;
    }
    lit += text.substr(pos, open - pos);
    count_lines(pos, open);
    const std::size_t close = text.find("}}", open + 2);
    const std::size_t eol = text.find('\n', open);
    if (close == std::string::npos || (eol != std::string::npos && eol < close))
      throw TemplateError(fmt::format("template '{}' line {}: '{{{{' without a closing '}}}}' on the same line",
                                      source_, line));
    const std::string inner = text.substr(open + 2, close - open - 2);
    const std::size_t colon = inner.find(':');
    const std::string name = trim(inner.substr(0, colon));
    const std::string format = colon == std::string::npos ? "" : trim(inner.substr(colon + 1));
    if (!valid_name(name))
      throw TemplateError(fmt::format(
          "template '{}' line {}: placeholder '{{{{{}}}}}' is not a name (letters, digits and _, "
          "not starting with a digit)", source_, line, inner));
    if (!format.empty() && !RE2::FullMatch(format, format_re()))
      throw TemplateError(fmt::format(
          "template '{}' line {}: placeholder '{}' has format '{}'; use one printf number conversion "
          "such as %.6E, %12.4f, %g or %d", source_, line, name, format));
    if (!lit.empty()) pieces_.push_back({true, std::move(lit), "", line});
    lit.clear();
    pieces_.push_back({false, name, format, line});
    pos = close + 2;
  }
  if (!lit.empty()) pieces_.push_back({true, std::move(lit), "", line});
}

DeckTemplate DeckTemplate::from_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw TemplateError(fmt::format("cannot read template '{}': {}", path, std::strerror(errno)));
  std::ostringstream ss;
  ss << in.rdbuf();
  return DeckTemplate(ss.str(), path);
}

std::string DeckTemplate::render(const DeckValues& values) const {
  std::string out;
  for (const Piece& p : pieces_) {
    if (p.literal) {
      out += p.text;
      continue;
    }
    const auto it = values.find(p.text);
    if (it == values.end()) {
      std::string known;
      for (const auto& [k, v] : values) known += (known.empty() ? "" : ", ") + k;
      throw TemplateError(fmt::format(
          "template '{}' line {}: placeholder {{{{{}}}}} has no value; it must be one of the model's "
          "inputs or constants ({})", source_, p.line, p.text, known.empty() ? "none" : known));
    }
    const DeckValue& v = it->second;
    if (!v.is_number) {
      if (!p.format.empty())
        throw TemplateError(fmt::format("template '{}' line {}: placeholder {{{{{}}}}} has number format '{}' "
                                        "but its value is the string '{}'", source_, p.line, p.text, p.format, v.text));
      if (v.text.find_first_of(std::string("\n\r\0", 3)) != std::string::npos)
        throw TemplateError(fmt::format("template '{}' line {}: value for {{{{{}}}}} holds a line break or NUL; "
                                        "deck values must be one line", source_, p.line, p.text));
      out += v.text;
      continue;
    }
    if (!std::isfinite(v.number))
      throw TemplateError(fmt::format("template '{}' line {}: value for {{{{{}}}}} is {}; decks take finite numbers",
                                      source_, p.line, p.text, v.number));
    if (p.format.empty()) {
      out += fmt::format("{}", v.number);  // shortest text that reads back as the same double
    } else if (p.format.back() == 'd') {
      if (v.number != std::floor(v.number) || std::fabs(v.number) > 9.0e15)
        throw TemplateError(fmt::format("template '{}' line {}: placeholder {{{{{}}}}} has format '{}' but its "
                                        "value {} is not an integer", source_, p.line, p.text, p.format, v.number));
      const std::string f = p.format.substr(0, p.format.size() - 1) + "lld";
      append_printf(out, f.c_str(), static_cast<long long>(v.number));
    } else {
      append_printf(out, p.format.c_str(), v.number);
    }
  }
  return out;
}

std::vector<std::string> DeckTemplate::names() const {
  std::vector<std::string> out;
  for (const Piece& p : pieces_)
    if (!p.literal && std::find(out.begin(), out.end(), p.text) == out.end()) out.push_back(p.text);
  return out;
}

bool DeckTemplate::uses(const std::string& name) const {
  for (const Piece& p : pieces_)
    if (!p.literal && p.text == name) return true;
  return false;
}

}  // namespace smi::eval
