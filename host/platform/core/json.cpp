// SPDX-License-Identifier: MIT
#include "platform/core/json.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fmt/format.h>

#include "platform/core/errors.hpp"
#include "platform/core/number_text.hpp"

namespace smi::json {

namespace {
const std::string kEmptyString;

/// The two-character escapes of RFC 8259 (besides \/ and \u), both ways.
constexpr std::pair<char, char> kEscapes[] = {{'"', '"'},  {'\\', '\\'}, {'\n', 'n'}, {'\r', 'r'},
                                              {'\t', 't'}, {'\b', 'b'},   {'\f', 'f'}};
char escape_letter(char c) {
  for (const auto& [raw, letter] : kEscapes)
    if (raw == c) return letter;
  return 0;
}
char escaped_char(char letter) {
  if (letter == '/') return '/';
  for (const auto& [raw, l] : kEscapes)
    if (l == letter) return raw;
  return 0;
}
const Array kEmptyArray;
const Object kEmptyObject;
}  // namespace

double Value::number() const {
  if (const auto* i = std::get_if<std::int64_t>(&v)) return static_cast<double>(*i);
  if (const auto* d = std::get_if<double>(&v)) return *d;
  return std::nan("");
}
const std::string& Value::string() const {
  const auto* s = std::get_if<std::string>(&v);
  return s ? *s : kEmptyString;
}
const Array& Value::array() const {
  const auto* a = std::get_if<Array>(&v);
  return a ? *a : kEmptyArray;
}
const Object& Value::object() const {
  const auto* o = std::get_if<Object>(&v);
  return o ? *o : kEmptyObject;
}
const Value* Value::find(std::string_view key) const {
  const Value* found = nullptr;
  for (const auto& [k, val] : object())
    if (k == key) found = &val;
  return found;
}

// ---- writing

namespace {

class Writer {
 public:
  explicit Writer(const WriteOptions& o) : o_(o) {}
  std::string out;

  void value(const Value& v, const std::string& path, int depth) {
    if (depth > kMaxDepth) throw Error(fmt::format("value at {} is nested deeper than {} levels", path, kMaxDepth));
    std::visit(
        [&](const auto& x) {
          using T = std::decay_t<decltype(x)>;
          if constexpr (std::is_same_v<T, std::nullptr_t>) out += "null";
          else if constexpr (std::is_same_v<T, bool>) out += x ? "true" : "false";
          else if constexpr (std::is_same_v<T, std::int64_t>) out += std::to_string(x);
          else if constexpr (std::is_same_v<T, double>) number(x, path);
          else if constexpr (std::is_same_v<T, std::string>) string(x);
          else if constexpr (std::is_same_v<T, Array>) array(x, path, depth);
          else object(x, path, depth);
        },
        v.v);
  }

 private:
  void newline(int depth) {
    if (o_.indent <= 0) return;
    out += '\n';
    out.append(static_cast<std::size_t>(depth * o_.indent), ' ');
  }

  void number(double v, const std::string& path) {
    if (std::isfinite(v)) {
      out += number_text(v);
    } else if (o_.non_finite == NonFinite::Encode) {
      out += std::isnan(v) ? "null" : (v > 0 ? "1e999" : "-1e999");
    } else {
      throw Error(fmt::format("value at {} is {}; JSON has no NaN or infinity (replace it, e.g. by nil)", path,
                              std::isnan(v) ? "nan" : (v > 0 ? "inf" : "-inf")));
    }
  }

  void string(const std::string& s) {
    out += '"';
    for (const char ch : s) {
      const unsigned char c = static_cast<unsigned char>(ch);
      if (const char e = escape_letter(ch)) {
        out += '\\';
        out += e;
      } else if (c < 0x20) {
        out += fmt::format("\\u{:04x}", c);
      } else {
        out += ch;
      }
    }
    out += '"';
  }

  static bool scalar(const Value& v) { return !v.is_array() && !v.is_object(); }

  void array(const Array& a, const std::string& path, int depth) {
    // Indented: a row of scalars (a vector) stays on one line, anything else one element a line.
    const bool flat = std::all_of(a.begin(), a.end(), scalar);
    out += '[';
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (i) out += (flat && o_.indent > 0) ? ", " : ",";
      if (!flat) newline(depth + 1);
      value(a[i], fmt::format("{}[{}]", path, i + 1), depth + 1);
    }
    if (!flat && !a.empty()) newline(depth);
    out += ']';
  }

  void object(const Object& o, const std::string& path, int depth) {
    std::vector<const std::pair<std::string, Value>*> members;
    for (const auto& m : o) members.push_back(&m);
    std::stable_sort(members.begin(), members.end(), [](auto* a, auto* b) { return a->first < b->first; });
    out += '{';
    for (std::size_t k = 0; k < members.size(); ++k) {
      if (k) out += ',';
      newline(depth + 1);
      string(members[k]->first);
      out += o_.indent > 0 ? ": " : ":";
      value(members[k]->second, path + "." + members[k]->first, depth + 1);
    }
    if (!members.empty()) newline(depth);
    out += '}';
  }

  const WriteOptions& o_;
};

// ---- reading

class Reader {
 public:
  Reader(std::string_view text, const std::string& source) : s_(text), source_(source) {}

  Value document() {
    skip_ws();
    Value v = value(0);
    skip_ws();
    if (pos_ < s_.size()) fail("unexpected text after the JSON value");
    return v;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    long line = 1, col = 1;
    for (std::size_t i = 0; i < pos_ && i < s_.size(); ++i) {
      if (s_[i] == '\n') {
        ++line;
        col = 1;
      } else {
        ++col;
      }
    }
    const std::string near =
        pos_ < s_.size() ? fmt::format(" near '{}'", s_.substr(pos_, 12)) : " at the end of the text";
    throw Error(fmt::format("{}:{}:{}: {}{}", source_, line, col, what, near));
  }

  void skip_ws() {
    while (pos_ < s_.size() && (s_[pos_] == ' ' || s_[pos_] == '\t' || s_[pos_] == '\n' || s_[pos_] == '\r')) ++pos_;
  }

  bool literal(std::string_view word) {
    if (s_.substr(pos_, word.size()) != word) return false;
    pos_ += word.size();
    return true;
  }

  Value value(int depth) {
    if (depth > kMaxDepth) fail(fmt::format("nested deeper than {} levels", kMaxDepth));
    if (pos_ >= s_.size()) fail("expected a value");
    const char c = s_[pos_];
    if (c == '{') return object(depth);
    if (c == '[') return array(depth);
    if (c == '"') return string();
    if (c == '-' || (c >= '0' && c <= '9')) return number();
    if (literal("true")) return true;
    if (literal("false")) return false;
    if (literal("null")) return nullptr;
    fail("expected a value (object, array, string, number, true, false or null)");
  }

  /// Consumes c when it is next.
  bool eat(char c) {
    if (pos_ >= s_.size() || s_[pos_] != c) return false;
    ++pos_;
    return true;
  }

  /// The items of an object or array up to `close`, separated by commas (the opening bracket
  /// is at pos_).
  template <class Item>
  void sequence(char close, const char* what, Item&& item) {
    ++pos_;
    skip_ws();
    if (eat(close)) return;
    do {
      skip_ws();
      item();
      skip_ws();
    } while (eat(','));
    if (!eat(close)) fail(fmt::format("expected ',' or '{}' in the {}", close, what));
  }

  Value object(int depth) {
    Object o;
    sequence('}', "object", [&] {
      if (pos_ >= s_.size() || s_[pos_] != '"') fail("expected a string key in the object");
      std::string key = string();
      skip_ws();
      if (!eat(':')) fail("expected ':' after the object key");
      skip_ws();
      o.emplace_back(std::move(key), value(depth + 1));
    });
    return o;
  }

  Value array(int depth) {
    Array a;
    sequence(']', "array", [&] { a.push_back(value(depth + 1)); });
    return a;
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

  std::string string() {
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
      if (const char c2 = escaped_char(e)) {
        out += c2;
        continue;
      }
      switch (e) {
        case 'u': {
          unsigned cp = hex4();
          if (cp >= 0xD800 && cp < 0xDC00 && s_.substr(pos_, 2) == "\\u") {
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
    return out;
  }

  Value number() {
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
      std::int64_t v = 0;
      const auto r = std::from_chars(b, e, v);
      if (r.ec == std::errc() && r.ptr == e) return v;
    }
    return std::strtod(std::string(b, e).c_str(), nullptr);  // out of range: +-inf
  }

  std::string_view s_;
  const std::string& source_;
  std::size_t pos_ = 0;
};

}  // namespace

std::string write(const Value& v, const WriteOptions& opts) {
  Writer w(opts);
  w.value(v, opts.root, 0);
  return std::move(w.out);
}

Value read(std::string_view text, const std::string& source) { return Reader(text, source).document(); }

}  // namespace smi::json
