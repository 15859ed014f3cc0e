// SPDX-License-Identifier: MIT
#include "repl/printer.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <vector>

namespace smi::repl {
namespace {

bool is_identifier(const char* s) {
  static const char* const kKeywords[] = {"and", "break", "do", "else", "elseif", "end", "false", "for",
                                          "function", "goto", "if", "in", "local", "nil", "not", "or",
                                          "repeat", "return", "then", "true", "until", "while"};
  if (!(std::isalpha(static_cast<unsigned char>(*s)) || *s == '_')) return false;
  for (const char* p = s; *p; ++p)
    if (!(std::isalnum(static_cast<unsigned char>(*p)) || *p == '_')) return false;
  for (const char* k : kKeywords)
    if (std::strcmp(k, s) == 0) return false;
  return true;
}

std::string quote(const char* s, std::size_t len, std::size_t max) {
  std::string out = "\"";
  for (std::size_t i = 0; i < len; ++i) {
    if (out.size() > max) {
      out += "...";
      break;
    }
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c == '\n') {
      out += "\\n";
    } else if (c < 32 || c == 127) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\%d", c);
      out += buf;
    } else {
      out += static_cast<char>(c);
    }
  }
  return out + "\"";
}

class Printer {
 public:
  Printer(lua_State* L, const PrintLimits& lim) : L_(L), lim_(lim) {}

  std::string value(int idx, int depth, bool top) {
    idx = lua_absindex(L_, idx);
    switch (lua_type(L_, idx)) {
      case LUA_TSTRING: {
        std::size_t len = 0;
        const char* s = lua_tolstring(L_, idx, &len);
        return top ? std::string(s, len) : quote(s, len, 200);
      }
      case LUA_TTABLE:
        if (!luaL_getmetafield(L_, idx, "__tostring")) return table(idx, depth);
        lua_pop(L_, 1);
        return tostring(idx);
      default:
        return tostring(idx);
    }
  }

 private:
  std::string tostring(int idx) {
    std::size_t len = 0;
    const char* s = luaL_tolstring(L_, idx, &len);  // runs __tostring / __name
    std::string out(s, std::min(len, lim_.max_chars));
    if (len > lim_.max_chars) out += "...";
    lua_pop(L_, 1);
    return out;
  }

  std::string key(int idx) {
    if (lua_type(L_, idx) == LUA_TSTRING && is_identifier(lua_tostring(L_, idx))) return lua_tostring(L_, idx);
    std::string out = "[";
    out += value(idx, lim_.max_depth, false);
    out += ']';
    return out;
  }

  std::string table(int idx, int depth) {
    if (std::find(open_.begin(), open_.end(), lua_topointer(L_, idx)) != open_.end()) return "{<cycle>}";
    if (depth >= lim_.max_depth) return "{...}";
    open_.push_back(lua_topointer(L_, idx));
    std::vector<std::string> items;
    const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L_, idx));
    long long total = 0;
    for (lua_Integer i = 1; i <= n; ++i, ++total) {
      if (static_cast<int>(items.size()) >= lim_.max_entries) continue;
      lua_rawgeti(L_, idx, i);
      items.push_back(value(-1, depth + 1, false));
      lua_pop(L_, 1);
    }
    // Other keys, sorted by their rendering so the output is stable.
    std::vector<std::pair<std::string, std::string>> named;
    lua_pushnil(L_);
    while (lua_next(L_, idx)) {  // stack: [..., k, v]
      if (lua_isinteger(L_, -2)) {
        const lua_Integer k = lua_tointeger(L_, -2);
        if (k >= 1 && k <= n) {
          lua_pop(L_, 1);
          continue;
        }
      }
      ++total;
      if (static_cast<int>(named.size()) < 4 * lim_.max_entries) {
        std::string k = key(-2);
        named.emplace_back(k, value(-1, depth + 1, false));
      }
      lua_pop(L_, 1);
    }
    open_.pop_back();
    std::sort(named.begin(), named.end());
    for (const auto& [k, v] : named) {
      if (static_cast<int>(items.size()) >= lim_.max_entries) break;
      items.push_back(k + " = " + v);
    }
    if (total > static_cast<long long>(items.size()))
      items.push_back("... (" + std::to_string(total - static_cast<long long>(items.size())) + " more)");
    return join(items, depth);
  }

  std::string join(const std::vector<std::string>& items, int depth) {
    if (items.empty()) return "{}";
    std::size_t width = 2;
    bool multiline = false;
    for (const auto& s : items) {
      width += s.size() + 2;
      multiline = multiline || s.find('\n') != std::string::npos;
    }
    std::string out = "{";
    if (!multiline && width <= lim_.wrap) {
      for (std::size_t i = 0; i < items.size(); ++i) out += (i ? ", " : "") + items[i];
      return out + "}";
    }
    const std::string pad(2 * static_cast<std::size_t>(depth + 1), ' ');
    for (std::size_t i = 0; i < items.size(); ++i) {
      out += "\n" + pad + items[i] + (i + 1 < items.size() ? "," : "");
      if (out.size() > lim_.max_chars) {
        out += "\n" + pad + "...";
        break;
      }
    }
    return out + "\n" + std::string(2 * static_cast<std::size_t>(depth), ' ') + "}";
  }

  lua_State* L_;
  const PrintLimits& lim_;
  std::vector<const void*> open_;  // tables being printed (cycle detection)
};

}  // namespace

std::string describe(lua_State* L, int idx, const PrintLimits& lim) {
  Printer p(L, lim);
  std::string s = p.value(idx, 0, true);
  if (s.size() > lim.max_chars) s = s.substr(0, lim.max_chars) + "...";
  return s;
}

int print_values(lua_State* L) {
  const int n = lua_gettop(L);
  std::string line;
  for (int i = 1; i <= n; ++i) {
    if (i > 1) line += '\t';
    line += describe(L, i);
  }
  line += "\n";
  std::fwrite(line.data(), 1, line.size(), stdout);
  std::fflush(stdout);
  return 0;
}

}  // namespace smi::repl
