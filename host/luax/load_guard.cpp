// SPDX-License-Identifier: MIT
#include "luax/load_guard.hpp"

#include <cctype>
#include <cstring>
#include <set>

namespace smi::lua {
namespace {

constexpr std::size_t kMaxSafeConstants = 255;  // MAXINDEXRK: constants past it are not RK operands

bool is_keyword(std::string_view w) {
  static const std::set<std::string_view> k = {"and",   "break", "do",     "else", "elseif", "end",   "false", "for",
                                               "function", "goto", "if",   "in",   "local",  "nil",   "not",   "or",
                                               "repeat", "return", "then", "true", "until",  "while"};
  return k.count(w) > 0;
}

/// Length of the "[==[" opener at text[i] (its level + 2), or 0 when there is none.
std::size_t long_bracket(std::string_view t, std::size_t i) {
  if (i >= t.size() || t[i] != '[') return 0;
  std::size_t j = i + 1;
  while (j < t.size() && t[j] == '=') ++j;
  return j < t.size() && t[j] == '[' ? j - i + 1 : 0;
}

/// Skips a long string or comment whose opener (length `open`) starts at i; returns the index
/// after its closer (or the end). Counts newlines into `line`.
std::size_t skip_long(std::string_view t, std::size_t i, std::size_t open, int& line) {
  std::string close(open, '=');  // "]==]": as long as the opener
  close.front() = ']';
  close.back() = ']';
  std::size_t j = i + open;
  const std::size_t end = t.find(close, j);
  const std::size_t stop = end == std::string_view::npos ? t.size() : end + close.size();
  for (std::size_t k = j; k < stop; ++k)
    if (t[k] == '\n') ++line;
  return stop;
}

/// A constant's text with its kind in front (a string "x" and a name x are two constants).
/// (Built by append, not "s" + std::string: GCC 12 warns falsely with -Wrestrict there.)
std::string tagged(char kind, std::string_view text) {
  std::string k(1, kind);
  k.append(text);
  return k;
}

}  // namespace

std::string lua544_refusal(std::string_view t) {
  std::set<std::string> names_and_strings;
  std::size_t numerals = 0;
  int line = 1, bitwise_line = 0;
  std::size_t i = 0;
  while (i < t.size()) {
    const char c = t[i];
    if (c == '\n') {
      ++line;
      ++i;
    } else if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
    } else if (c == '-' && i + 1 < t.size() && t[i + 1] == '-') {
      if (const std::size_t open = long_bracket(t, i + 2)) {
        i = skip_long(t, i + 2, open, line);
      } else {
        while (i < t.size() && t[i] != '\n') ++i;
      }
    } else if (const std::size_t open = long_bracket(t, i)) {
      const std::size_t end = skip_long(t, i, open, line);
      names_and_strings.insert(tagged('s', t.substr(i, end - i)));
      i = end;
    } else if (c == '"' || c == '\'') {
      std::size_t j = i + 1;
      while (j < t.size() && t[j] != c && t[j] != '\n') {
        if (t[j] == '\\' && j + 1 < t.size()) {
          if (t[j + 1] == '\n') ++line;
          ++j;
        }
        ++j;
      }
      names_and_strings.insert(tagged('s', t.substr(i + 1, j - i - 1)));
      i = j + 1;
    } else if (std::isdigit(static_cast<unsigned char>(c)) ||
               (c == '.' && i + 1 < t.size() && std::isdigit(static_cast<unsigned char>(t[i + 1])))) {
      ++numerals;
      std::size_t j = i;
      while (j < t.size() && (std::isalnum(static_cast<unsigned char>(t[j])) || t[j] == '.' || t[j] == '_' ||
                              ((t[j] == '+' || t[j] == '-') && j > i && std::strchr("eEpP", t[j - 1])))) {
        ++j;
      }
      i = j;
    } else if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
      std::size_t j = i;
      while (j < t.size() && (std::isalnum(static_cast<unsigned char>(t[j])) || t[j] == '_')) ++j;
      const std::string_view w = t.substr(i, j - i);
      if (!is_keyword(w)) names_and_strings.insert(tagged('n', w));
      i = j;
    } else if (c == '~' && i + 1 < t.size() && t[i + 1] == '=') {
      i += 2;
    } else if (c == '~' || c == '&' || c == '|' || ((c == '<' || c == '>') && i + 1 < t.size() && t[i + 1] == c)) {
      if (!bitwise_line) bitwise_line = line;
      i += (c == '<' || c == '>') ? 2 : 1;
    } else {
      ++i;
    }
  }
  const std::size_t constants = names_and_strings.size() + numerals + 3;  // + true, false, nil
  if (!bitwise_line || constants < kMaxSafeConstants) return "";
  std::string why = "line ";
  why += std::to_string(bitwise_line);
  return why +
         ": a bitwise operator in a chunk that may hold more than 255 constants. The Lua in use (5.4.4) can "
         "compile it into wrong arithmetic there (`1 ~ (2 or 3)` gives 0; a known bug, fixed upstream in Lua 5.4.5 "
         "by commit c764ca71), so smi-lua refuses the chunk rather than compute wrong numbers. Split it into "
         "smaller files or functions, or avoid bitwise operators in it";
}

int load_buffer(lua_State* L, const char* data, std::size_t size, const char* chunkname) {
  const std::string why = lua544_refusal(std::string_view(data, size));
  if (!why.empty()) {
    // As a syntax error reads: "<chunk>:<line>: <message>" (luaO_chunkid shortens the name).
    const char* name = chunkname ? chunkname : "?";
    const std::string shown = (*name == '@' || *name == '=') ? std::string(name + 1) : std::string("[string]");
    lua_pushfstring(L, "%s:%s", shown.c_str(), why.substr(5).c_str());
    return LUA_ERRSYNTAX;
  }
  return luaL_loadbufferx(L, data, size, chunkname, "t");
}

}  // namespace smi::lua
