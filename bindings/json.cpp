// smi.json: JSON for results files.
//   smi.json.encode(value [, {indent = 2}]) -> string     smi.json.decode(text) -> value
//   smi.json.write(path, value [, {indent = 2}])          smi.json.read(path) -> value
//   smi.json.null                                         JSON null (kept in arrays and objects)
// Encoding: numbers are written so they read back exactly (shortest round trip; integers as
// integers), smi.vec -> array, smi.mat -> array of rows, tables with keys 1..n -> array (an empty
// table -> []), other tables -> object with sorted keys. NaN, infinities, functions and cycles
// are errors naming where in the value they are. Decoding errors give line and column.
// read/write go through the sandbox policy.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fcntl.h>
#include <fmt/format.h>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "bindings/modules.hpp"
#include "luax/luax.hpp"
#include "luax/policy.hpp"

namespace smi::bind {
namespace {

const char kNullKey = 0;  // registry key of the null sentinel
constexpr int kMaxDepth = 200;

void push_null(lua_State* L) { lua_rawgetp(L, LUA_REGISTRYINDEX, &kNullKey); }

bool is_null(lua_State* L, int idx) {
  idx = lua_absindex(L, idx);
  push_null(L);
  const bool r = lua_rawequal(L, idx, -1);
  lua_pop(L, 1);
  return r;
}

std::string number_text(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

// ---- encoding

class Encoder {
 public:
  Encoder(lua_State* L, int indent) : L_(L), indent_(indent) {}
  std::string out;

  void value(int idx, const std::string& where, int depth) {
    idx = lua_absindex(L_, idx);
    if (depth > kMaxDepth) throw Error(fmt::format("value at {} is nested deeper than {} levels", where, kMaxDepth));
    switch (lua_type(L_, idx)) {
      case LUA_TNIL: out += "null"; return;
      case LUA_TBOOLEAN: out += lua_toboolean(L_, idx) ? "true" : "false"; return;
      case LUA_TNUMBER:
        if (lua_isinteger(L_, idx))
          out += std::to_string(lua_tointeger(L_, idx));
        else
          number(lua_tonumber(L_, idx), where);
        return;
      case LUA_TSTRING: {
        std::size_t len = 0;
        const char* s = lua_tolstring(L_, idx, &len);
        string(s, len);
        return;
      }
      case LUA_TTABLE:
        if (is_null(L_, idx)) {
          out += "null";
          return;
        }
        table(idx, where, depth);
        return;
      case LUA_TUSERDATA:
        if (const Eigen::VectorXd* v = lua::test_vec(L_, idx)) {
          vec(*v, where, depth);
          return;
        }
        if (const Eigen::MatrixXd* m = lua::test_mat(L_, idx)) {
          out += '[';
          for (Eigen::Index i = 0; i < m->rows(); ++i) {
            if (i) out += ',';
            newline(depth + 1);
            vec(m->row(i).transpose(), fmt::format("{}[{}]", where, i + 1), depth + 1);
          }
          newline(depth);
          out += ']';
          return;
        }
        [[fallthrough]];
      default:
        throw Error(fmt::format("value at {} is a {}, which JSON cannot hold", where, luaL_typename(L_, idx)));
    }
  }

 private:
  void newline(int depth) {
    if (indent_ <= 0) return;
    out += '\n';
    out.append(static_cast<std::size_t>(depth * indent_), ' ');
  }

  void number(double v, const std::string& where) {
    if (!std::isfinite(v))
      throw Error(fmt::format("value at {} is {}; JSON has no NaN or infinity (replace it, e.g. by nil)", where,
                              number_text(v)));
    out += number_text(v);
  }

  void vec(const Eigen::VectorXd& v, const std::string& where, int depth) {
    out += '[';
    for (Eigen::Index i = 0; i < v.size(); ++i) {
      if (i) out += indent_ > 0 ? ", " : ",";
      number(v[i], fmt::format("{}[{}]", where, i + 1));
    }
    (void)depth;
    out += ']';
  }

  void string(const char* s, std::size_t len) {
    out += '"';
    for (std::size_t i = 0; i < len; ++i) {
      const unsigned char c = static_cast<unsigned char>(s[i]);
      switch (c) {
        case '"': out += "\\\""; break;
        case '\\': out += "\\\\"; break;
        case '\n': out += "\\n"; break;
        case '\r': out += "\\r"; break;
        case '\t': out += "\\t"; break;
        case '\b': out += "\\b"; break;
        case '\f': out += "\\f"; break;
        default:
          if (c < 0x20) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\u%04x", c);
            out += buf;
          } else {
            out += static_cast<char>(c);
          }
      }
    }
    out += '"';
  }

  /// A key of an object: its JSON text and how to push the original Lua key again.
  struct Key {
    std::string text;
    bool is_string;
    lua_Number num;
    bool operator<(const Key& o) const { return text < o.text; }
  };

  void push_key(const Key& k) {
    if (k.is_string)
      lua_pushlstring(L_, k.text.data(), k.text.size());
    else if (std::floor(k.num) == k.num && std::fabs(k.num) < 9.0e15)
      lua_pushinteger(L_, static_cast<lua_Integer>(k.num));
    else
      lua_pushnumber(L_, k.num);
  }

  void table(int idx, const std::string& where, int depth) {
    // Each level keeps a key and a value on the Lua stack: make room (without it a table nested
    // a few hundred levels wrote past the stack before the depth check could refuse it).
    if (!lua_checkstack(L_, 4)) throw Error(fmt::format("value at {} is nested too deeply for the Lua stack", where));
    const void* id = lua_topointer(L_, idx);
    if (std::find(open_.begin(), open_.end(), id) != open_.end())
      throw Error(fmt::format("value at {} contains itself (a cycle)", where));
    open_.push_back(id);
    // An array when the keys are exactly 1..n.
    const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L_, idx));
    std::vector<Key> keys;
    bool array = true;
    lua_pushnil(L_);
    while (lua_next(L_, idx)) {
      lua_pop(L_, 1);  // stack: [..., key]
      if (lua_isinteger(L_, -1) && lua_tointeger(L_, -1) >= 1 && lua_tointeger(L_, -1) <= n) {
        keys.push_back({std::to_string(lua_tointeger(L_, -1)), false, static_cast<lua_Number>(lua_tointeger(L_, -1))});
        continue;
      }
      array = false;
      if (lua_type(L_, -1) == LUA_TSTRING) {
        keys.push_back({lua_tostring(L_, -1), true, 0});
      } else if (lua_type(L_, -1) == LUA_TNUMBER) {
        const lua_Number v = lua_tonumber(L_, -1);
        keys.push_back({lua_isinteger(L_, -1) ? std::to_string(lua_tointeger(L_, -1)) : number_text(v), false, v});
      } else {
        throw Error(fmt::format("value at {} has a {} key; JSON object keys are strings", where,
                                luaL_typename(L_, -1)));
      }
    }
    if (array) {
      out += '[';
      for (lua_Integer i = 1; i <= n; ++i) {
        if (i > 1) out += ',';
        newline(depth + 1);
        lua_rawgeti(L_, idx, i);
        value(-1, fmt::format("{}[{}]", where, i), depth + 1);
        lua_pop(L_, 1);
      }
      if (n > 0) newline(depth);
      out += ']';
    } else {
      std::sort(keys.begin(), keys.end());
      out += '{';
      for (std::size_t k = 0; k < keys.size(); ++k) {
        if (k) out += ',';
        newline(depth + 1);
        string(keys[k].text.data(), keys[k].text.size());
        out += indent_ > 0 ? ": " : ":";
        push_key(keys[k]);
        lua_rawget(L_, idx);
        value(-1, where + "." + keys[k].text, depth + 1);
        lua_pop(L_, 1);
      }
      if (!keys.empty()) newline(depth);
      out += '}';
    }
    open_.pop_back();
  }

  lua_State* L_;
  int indent_;
  std::vector<const void*> open_;
};

std::string encode(lua_State* L, int idx, int indent) {
  Encoder e(L, indent);
  e.value(idx, "$", 0);
  return e.out;
}

// ---- decoding

class Decoder {
 public:
  Decoder(lua_State* L, const std::string& text, std::string source)
      : L_(L), s_(text), source_(std::move(source)) {}

  void document() {
    skip_ws();
    value(0);
    skip_ws();
    if (pos_ < s_.size()) fail("unexpected text after the JSON value");
  }

 private:
  [[noreturn]] void fail(const std::string& what) {
    long line = 1, col = 1;
    for (std::size_t i = 0; i < pos_ && i < s_.size(); ++i) {
      if (s_[i] == '\n') {
        ++line;
        col = 1;
      } else {
        ++col;
      }
    }
    std::string near = pos_ < s_.size() ? fmt::format(" near '{}'", s_.substr(pos_, 12)) : " at the end of the text";
    throw Error(fmt::format("{}:{}:{}: {}{}", source_, line, col, what, near));
  }

  void skip_ws() {
    while (pos_ < s_.size() && (s_[pos_] == ' ' || s_[pos_] == '\t' || s_[pos_] == '\n' || s_[pos_] == '\r')) ++pos_;
  }

  bool literal(const char* word) {
    const std::size_t n = std::strlen(word);
    if (s_.compare(pos_, n, word) != 0) return false;
    pos_ += n;
    return true;
  }

  /// Pushes the value at pos_.
  void value(int depth) {
    if (depth > kMaxDepth) fail(fmt::format("nested deeper than {} levels", kMaxDepth));
    luaL_checkstack(L_, 4, "smi.json.decode");
    if (pos_ >= s_.size()) fail("expected a value");
    const char c = s_[pos_];
    if (c == '{') return object(depth);
    if (c == '[') return array(depth);
    if (c == '"') return string();
    if (c == '-' || (c >= '0' && c <= '9')) return number();
    if (literal("true")) return lua_pushboolean(L_, 1);
    if (literal("false")) return lua_pushboolean(L_, 0);
    if (literal("null")) return push_null(L_);
    fail("expected a value (object, array, string, number, true, false or null)");
  }

  void object(int depth) {
    ++pos_;
    lua_newtable(L_);
    skip_ws();
    if (pos_ < s_.size() && s_[pos_] == '}') {
      ++pos_;
      return;
    }
    for (;;) {
      skip_ws();
      if (pos_ >= s_.size() || s_[pos_] != '"') fail("expected a string key in the object");
      string();
      skip_ws();
      if (pos_ >= s_.size() || s_[pos_] != ':') fail("expected ':' after the object key");
      ++pos_;
      skip_ws();
      value(depth + 1);
      lua_rawset(L_, -3);
      skip_ws();
      if (pos_ < s_.size() && s_[pos_] == ',') {
        ++pos_;
        continue;
      }
      if (pos_ < s_.size() && s_[pos_] == '}') {
        ++pos_;
        return;
      }
      fail("expected ',' or '}' in the object");
    }
  }

  void array(int depth) {
    ++pos_;
    lua_newtable(L_);
    skip_ws();
    if (pos_ < s_.size() && s_[pos_] == ']') {
      ++pos_;
      return;
    }
    for (lua_Integer i = 1;; ++i) {
      skip_ws();
      value(depth + 1);
      lua_rawseti(L_, -2, i);
      skip_ws();
      if (pos_ < s_.size() && s_[pos_] == ',') {
        ++pos_;
        continue;
      }
      if (pos_ < s_.size() && s_[pos_] == ']') {
        ++pos_;
        return;
      }
      fail("expected ',' or ']' in the array");
    }
  }

  unsigned hex4() {
    if (pos_ + 4 > s_.size()) fail("\\u needs 4 hex digits");
    unsigned v = 0;
    for (int k = 0; k < 4; ++k) {
      const char c = s_[pos_++];
      v <<= 4;
      if (c >= '0' && c <= '9') v |= static_cast<unsigned>(c - '0');
      else if (c >= 'a' && c <= 'f') v |= static_cast<unsigned>(c - 'a' + 10);
      else if (c >= 'A' && c <= 'F') v |= static_cast<unsigned>(c - 'A' + 10);
      else fail("\\u needs 4 hex digits");
    }
    return v;
  }

  static void utf8(std::string& out, unsigned cp) {
    if (cp < 0x80) {
      out += static_cast<char>(cp);
    } else if (cp < 0x800) {
      out += static_cast<char>(0xC0 | (cp >> 6));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    } else if (cp < 0x10000) {
      out += static_cast<char>(0xE0 | (cp >> 12));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    } else {
      out += static_cast<char>(0xF0 | (cp >> 18));
      out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    }
  }

  void string() {
    ++pos_;  // opening quote
    std::string out;
    for (;;) {
      if (pos_ >= s_.size()) fail("unterminated string");
      const char c = s_[pos_++];
      if (c == '"') break;
      if (static_cast<unsigned char>(c) < 0x20) {
        --pos_;
        fail("control character in a string (escape it)");
      }
      if (c != '\\') {
        out += c;
        continue;
      }
      if (pos_ >= s_.size()) fail("unterminated string");
      const char e = s_[pos_++];
      switch (e) {
        case '"': out += '"'; break;
        case '\\': out += '\\'; break;
        case '/': out += '/'; break;
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'n': out += '\n'; break;
        case 'r': out += '\r'; break;
        case 't': out += '\t'; break;
        case 'u': {
          unsigned cp = hex4();
          if (cp >= 0xD800 && cp < 0xDC00 && s_.compare(pos_, 2, "\\u") == 0) {
            pos_ += 2;
            const unsigned lo = hex4();
            if (lo < 0xDC00 || lo > 0xDFFF) fail("bad surrogate pair");
            cp = 0x10000 + ((cp - 0xD800) << 10) + (lo - 0xDC00);
          }
          utf8(out, cp);
          break;
        }
        default:
          pos_ -= 2;
          fail("unknown escape in a string");
      }
    }
    lua_pushlstring(L_, out.data(), out.size());
  }

  void number() {
    const std::size_t start = pos_;
    if (s_[pos_] == '-') ++pos_;
    auto digits = [&] {
      const std::size_t d = pos_;
      while (pos_ < s_.size() && s_[pos_] >= '0' && s_[pos_] <= '9') ++pos_;
      return pos_ - d;
    };
    if (digits() == 0) fail("expected digits in a number");
    bool integral = true;
    if (pos_ < s_.size() && s_[pos_] == '.') {
      ++pos_;
      integral = false;
      if (digits() == 0) fail("expected digits after '.'");
    }
    if (pos_ < s_.size() && (s_[pos_] == 'e' || s_[pos_] == 'E')) {
      ++pos_;
      integral = false;
      if (pos_ < s_.size() && (s_[pos_] == '+' || s_[pos_] == '-')) ++pos_;
      if (digits() == 0) fail("expected digits in the exponent");
    }
    const char* b = s_.data() + start;
    const char* e = s_.data() + pos_;
    if (integral) {
      long long v = 0;
      const auto r = std::from_chars(b, e, v);
      if (r.ec == std::errc() && r.ptr == e) return lua_pushinteger(L_, static_cast<lua_Integer>(v));
    }
    lua_pushnumber(L_, std::strtod(std::string(b, e).c_str(), nullptr));  // out of range: +-inf
  }

  lua_State* L_;
  const std::string& s_;
  std::string source_;
  std::size_t pos_ = 0;
};

int indent_option(lua_State* L, int idx, const char* fname, int def) {
  lua::Options o(L, idx, fname);
  o.check_known({"indent"});
  const lua_Integer n = o.integer("indent", def);
  luaL_argcheck(L, n >= 0 && n <= 16, idx, "indent must be 0..16");
  return static_cast<int>(n);
}

int json_encode(lua_State* L) {
  luaL_checkany(L, 1);
  const int indent = indent_option(L, 2, "smi.json.encode", 0);
  return lua::protect(L, "smi.json.encode", [&] {
    const std::string s = encode(L, 1, indent);
    lua_pushlstring(L, s.data(), s.size());
    return 1;
  });
}

int json_decode(lua_State* L) {
  std::size_t len = 0;
  const char* s = luaL_checklstring(L, 1, &len);
  const std::string text(s, len);
  return lua::protect(L, "smi.json.decode", [&] {
    Decoder(L, text, "json").document();
    return 1;
  });
}

int json_write(lua_State* L) {
  const char* path = luaL_checkstring(L, 1);
  luaL_checkany(L, 2);
  const int indent = indent_option(L, 3, "smi.json.write", 2);
  return lua::protect(L, "smi.json.write", [&] {
    std::string s = encode(L, 2, indent);
    s += '\n';
    const CheckedFile f = lua::policy(L).open_write(path, O_WRONLY | O_CREAT | O_TRUNC);
    if (!pathwalk::write_all(f.fd.get(), s))
      throw Error(fmt::format("writing '{}' failed: {}", path, std::strerror(errno)));
    return 0;
  });
}

int json_read(lua_State* L) {
  const char* path = luaL_checkstring(L, 1);
  return lua::protect(L, "smi.json.read", [&] {
    const CheckedFile f = lua::policy(L).open_read(path);
    const std::string text = read_checked(f, path);
    Decoder(L, text, path).document();
    return 1;
  });
}

constexpr const char* kNullType = "smi.json.null";

int null_tostring(lua_State* L) {
  lua_pushliteral(L, "null");
  return 1;
}

const luaL_Reg kFunctions[] = {{"encode", json_encode}, {"decode", json_decode}, {"read", json_read},
                               {"write", json_write},   {nullptr, nullptr}};

}  // namespace

void open_json(lua_State* L) {
  lua_newtable(L);  // stack: [smi, json]
  luaL_setfuncs(L, kFunctions, 0);
  // null: an empty table with a named metatable, unique per state
  const luaL_Reg null_meta[] = {{"__tostring", null_tostring}, {nullptr, nullptr}};
  lua::register_table_type(L, kNullType, nullptr, null_meta);
  lua_newtable(L);
  luaL_setmetatable(L, kNullType);
  lua_pushvalue(L, -1);
  lua_rawsetp(L, LUA_REGISTRYINDEX, &kNullKey);
  lua_setfield(L, -2, "null");
  lua_setfield(L, -2, "json");
}

}  // namespace smi::bind
