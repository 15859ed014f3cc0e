// SPDX-License-Identifier: MIT
#pragma once
// The one JSON codec of the tree (RFC 8259), Lua-free: smi.json (bindings/json.cpp), the
// results/report writer (stdlib smi.report.json, over smi.json) and `smi-lua verify` all read
// and write through it.
//
// Numbers: integers that fit in 64 bits stay integers; other numbers are doubles written in the
// shortest text that reads back to the same bits.
//
// Non-finite numbers, one rule: JSON has no NaN or infinity, so by default the writer refuses
// them with an error naming the value's path ("$.steps.fit[3] is NaN ..."). A writer asked for
// NonFinite::Encode (results files: a NaN metric is a result, not a reason to lose the file)
// writes +inf as 1e999, -inf as -1e999 (valid JSON numbers that every IEEE reader, this one and
// Python's included, reads back as +-inf) and NaN as null (read back as NaN by a reader that asks
// for it: smi.json.decode(text, {null = 0/0}), what smi.report.json.decode does).
//
// Reading errors name the source, line and column ("results.json:3:7: expected ':' ...").
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace smi::json {

struct Value;
using Array = std::vector<Value>;
/// Members in the order read (a later duplicate key follows an earlier one); the writer sorts
/// keys, so the same data give the same text.
using Object = std::vector<std::pair<std::string, Value>>;

struct Value {
  std::variant<std::nullptr_t, bool, std::int64_t, double, std::string, Array, Object> v;

  Value() : v(nullptr) {}
  Value(std::nullptr_t) : v(nullptr) {}
  Value(bool b) : v(b) {}
  Value(int i) : v(std::int64_t{i}) {}
  Value(std::int64_t i) : v(i) {}
  Value(double d) : v(d) {}
  Value(const char* s) : v(std::string(s)) {}
  Value(std::string s) : v(std::move(s)) {}
  Value(Array a) : v(std::move(a)) {}
  Value(Object o) : v(std::move(o)) {}

  bool is_null() const { return std::holds_alternative<std::nullptr_t>(v); }
  bool is_number() const { return std::holds_alternative<std::int64_t>(v) || std::holds_alternative<double>(v); }
  bool is_string() const { return std::holds_alternative<std::string>(v); }
  bool is_array() const { return std::holds_alternative<Array>(v); }
  bool is_object() const { return std::holds_alternative<Object>(v); }
  /// The number as a double (an integer converted); NaN when not a number.
  double number() const;
  /// The string, or "" when not a string.
  const std::string& string() const;
  const Array& array() const;    // empty when not an array
  const Object& object() const;  // empty when not an object
  /// The member `key` of an object (the last one of that name), or nullptr.
  const Value* find(std::string_view key) const;
};

enum class NonFinite { Refuse, Encode };

struct WriteOptions {
  int indent = 0;                          // spaces per level; 0: one line
  NonFinite non_finite = NonFinite::Refuse;
  std::string root = "$";                  // the name of the whole value in error paths
};

/// JSON text of `v`. Throws smi::Error naming the path of a refused non-finite number (array
/// elements count from 1, as in Lua) or of a value nested deeper than kMaxDepth.
std::string write(const Value& v, const WriteOptions& opts = {});

/// The value of JSON text; `source` names it in errors ("file:line:column: what near '...'").
/// Numbers out of the double range read as +-inf (so 1e999 reads back as infinity).
Value read(std::string_view text, const std::string& source = "json");

/// The nesting the reader and writer accept (deeper input is refused, not a stack overflow).
constexpr int kMaxDepth = 200;

}  // namespace smi::json
