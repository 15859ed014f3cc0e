// SPDX-License-Identifier: MIT
#pragma once
// One option schema per bound function: a static table of entries {key, member,
// type, range, doc line} from which come
//   * the typed reads of an options table into the function's option struct,
//   * the unknown-key check with its "did you mean" suggestion,
//   * the "options:" lines of the function's reference text (its *_doc.cpp fills ${options}),
// so the code, its defaults and its reference cannot drift. A default is never written here:
// it is whatever the option struct holds before the read (its default member initialiser), and
// the reference shows the default-constructed struct's value.
//
// Declaring a schema (beside the binding, in <area>/<name>_options.cpp):
//   const Schema<smi::stats::KdeOptions>& kde_schema() {
//     static const Schema<smi::stats::KdeOptions> s("smi.kde", {
//         choice("method", &KdeOptions::method, {{"auto", KdeMethod::Auto}, ...}, "how to evaluate"),
//         number("tol", &KdeOptions::binned_tol, open(0, 0.1), "the binned path's error bound"),
//         integer("threads", &KdeOptions::threads, between(1, 64), "worker threads"),
//     });
//     return s;
//   }
// and reading it: `KdeOptions k = kde_schema().read(L, 2);`. A member may be nested: pass an
// accessor `[](auto& s) -> auto& { return s.optimizer.xtol_rel; }` instead of a member pointer.
// Keys a binding reads by hand (a nested table, a required bound, a callback) are listed with
// by_hand(key, default text, doc) so the unknown-key check and the reference know them.
#include <lua.hpp>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <functional>
#include <initializer_list>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace smi::lua {

/// The interval a numeric option must lie in (both ends infinite: any number).
struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false, hi_open = false;
  bool contains(double v) const;
  /// Every number, NaN and the infinities included (a seed, a free coordinate).
  bool any() const { return std::isinf(lo) && std::isinf(hi) && lo < 0 && hi > 0 && !lo_open && !hi_open; }
  /// As an error message says it: "in (0, 0.1)", "in 1..64" (integers), ">= 1", "> 0", "finite".
  std::string text(bool integer) const;
};
inline Range any_value() { return {}; }
inline Range at_least(double lo) { return {lo, std::numeric_limits<double>::infinity(), false, false}; }
inline Range above(double lo) { return {lo, std::numeric_limits<double>::infinity(), true, false}; }
inline Range between(double lo, double hi) { return {lo, hi, false, false}; }
inline Range open(double lo, double hi) { return {lo, hi, true, true}; }
/// Any finite number (not NaN, not ±inf).
inline Range finite() { return {-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(), true, true}; }
/// A finite number above lo (a standard deviation: > 0 and not inf).
inline Range finite_above(double lo) { return {lo, std::numeric_limits<double>::infinity(), true, true}; }
/// A finite number at or above lo.
inline Range finite_at_least(double lo) { return {lo, std::numeric_limits<double>::infinity(), false, true}; }

/// One key of an options table. read is empty for a key the binding reads by hand.
template <class S>
struct Option {
  const char* key;
  const char* doc;  ///< the reference's meaning; '\n' starts a continuation line
  std::function<void(lua_State* L, int value, S& into)> read;  ///< value: stack index, not nil; throws
  std::function<std::string(const S&)> show;                   ///< the value as the reference shows it
  std::string default_text;  ///< shown instead of show(S{}) when not empty ("smi.seed", "(required)")
};

/// The type-independent part of a schema: its function, keys and doc lines (for the reference,
/// the unknown-key check and the tests that every schema's empty read equals its struct's default).
class SchemaBase {
 public:
  SchemaBase(const char* fname, std::vector<std::string> keys);
  virtual ~SchemaBase() = default;
  const char* name() const { return fname_; }
  const std::vector<std::string>& keys() const { return keys_; }
  /// The "options:" lines of the reference text ("  key = default  -- meaning").
  virtual std::string doc() const = 0;
  /// Keys whose value read from an empty table differs from the default-constructed struct's
  /// (none when the schema holds no second default).
  virtual std::vector<std::string> default_mismatches(lua_State* L) const = 0;
  /// Raises "<fname>: unknown option '<key>' (did you mean '<closest>'?)" (or the known list)
  /// for a string key of the table at idx that is not one of keys(); `as` (when not null) names
  /// the table instead of fname (an element of a list: "prior[2]").
  void check_keys(lua_State* L, int idx, const char* as = nullptr) const;

 protected:
  /// Lines "  key = default  -- doc" aligned in one column (doc.lua's option-line format).
  static std::string format_lines(const std::vector<std::pair<std::string, std::string>>& heads,
                                  const std::vector<const char*>& docs);
  /// Raises the Lua error "<fname or as>: <what>" (called after the C++ frames that threw are left).
  [[noreturn]] void raise(lua_State* L, const char* what, const char* as = nullptr) const;

 private:
  const char* fname_;
  std::vector<std::string> keys_;
};

/// Every schema built so far in this process (a schema registers itself when first built;
/// binding_docs() builds them all).
std::vector<const SchemaBase*> schemas();

template <class S>
class Schema : public SchemaBase {
 public:
  Schema(const char* fname, std::vector<Option<S>> options) : SchemaBase(fname, keys_of(options)), options_(std::move(options)) {}

  /// Reads the options table at idx (nil or none: nothing) into `into`, whose current values are
  /// the defaults. Raises a Lua error naming the function and the key on an unknown key, a wrong
  /// type or a value out of range (nothing C++ is alive when it does). `as` (when not null) names
  /// the table in the messages instead of the function (an element of a list: "prior[2]").
  void read(lua_State* L, int idx, S& into, const char* as = nullptr) const {
    if (lua_isnoneornil(L, idx)) return;
    if (!lua_istable(L, idx)) raise_type(L, idx, as);
    idx = lua_absindex(L, idx);
    check_keys(L, idx, as);
    char msg[1024];
    msg[0] = '\0';
    try {
      for (const auto& o : options_) {
        if (!o.read) continue;
        if (lua_getfield(L, idx, o.key) != LUA_TNIL) o.read(L, lua_gettop(L), into);
        lua_pop(L, 1);
      }
      return;
    } catch (const std::exception& e) {
      copy_message(msg, sizeof msg, e.what());
    }
    raise(L, msg, as);
  }
  S read(lua_State* L, int idx, const char* as = nullptr) const {
    S s{};
    read(L, idx, s, as);
    return s;
  }

  std::string doc() const override { return doc(keys()); }
  /// The lines of some keys only, in the schema's order (a reference entry that says "options
  /// as <another function>, plus:" lists its own keys only).
  std::string doc(const std::vector<std::string>& only) const {
    const S def{};
    std::vector<std::pair<std::string, std::string>> heads;
    std::vector<const char*> docs;
    for (const auto& o : options_) {
      bool listed = false;
      for (const auto& k : only) listed = listed || k == o.key;
      if (!listed) continue;
      heads.emplace_back(o.key, o.default_text.empty() ? o.show(def) : o.default_text);
      docs.push_back(o.doc);
    }
    return format_lines(heads, docs);
  }

  std::vector<std::string> default_mismatches(lua_State* L) const override {
    const S def{};
    lua_newtable(L);
    const S got = read(L, -1);
    lua_pop(L, 1);
    std::vector<std::string> out;
    for (const auto& o : options_)
      if (o.show && o.show(got) != o.show(def)) out.emplace_back(o.key);
    return out;
  }

 private:
  static std::vector<std::string> keys_of(const std::vector<Option<S>>& options) {
    std::vector<std::string> k;
    for (const auto& o : options) k.emplace_back(o.key);
    return k;
  }
  [[noreturn]] void raise_type(lua_State* L, int idx, const char* as) const;
  static void copy_message(char* buf, std::size_t size, const char* what);
  std::vector<Option<S>> options_;
};

// ---------------------------------------------------------------------------------------------
// Entry builders. `acc` is a member pointer (&S::x) or an accessor [](auto& s) -> auto& {...}.

namespace schema_detail {
/// The value at idx as a number/integer/string/boolean; throws InvalidArgument
/// "option '<key>' must be <expected>, got <type>" otherwise.
double to_number(lua_State* L, int idx, const char* key);
long long to_integer(lua_State* L, int idx, const char* key);
std::string to_string(lua_State* L, int idx, const char* key);
bool to_boolean(lua_State* L, int idx, const char* key);
/// Throws "<key> must be <range>, got <v>" when v is outside r.
void check_range(const Range& r, double v, const char* key, bool integer);
/// Throws "<key> must be "a", "b" or "c", got "x"".
[[noreturn]] void bad_choice(const char* key, const std::vector<std::string>& names, const std::string& got);
std::string show_number(double v);
std::string show_string(const std::string& v);
}  // namespace schema_detail

template <class S, class Acc>
Option<S> number(const char* key, Acc acc, Range r, const char* doc, std::string default_text = {}) {
  return {key, doc,
          [=](lua_State* L, int v, S& s) {
            const double x = schema_detail::to_number(L, v, key);
            schema_detail::check_range(r, x, key, false);
            std::invoke(acc, s) = x;
          },
          [=](const S& s) { return schema_detail::show_number(static_cast<double>(std::invoke(acc, s))); }, std::move(default_text)};
}

template <class S, class Acc>
Option<S> integer(const char* key, Acc acc, Range r, const char* doc, std::string default_text = {}) {
  return {key, doc,
          [=](lua_State* L, int v, S& s) {
            const long long x = schema_detail::to_integer(L, v, key);
            schema_detail::check_range(r, static_cast<double>(x), key, true);
            using M = std::remove_reference_t<decltype(std::invoke(acc, s))>;
            std::invoke(acc, s) = static_cast<M>(x);
          },
          [=](const S& s) { return std::to_string(static_cast<long long>(std::invoke(acc, s))); }, std::move(default_text)};
}

/// A string member; `allowed` empty: any string.
template <class S, class Acc>
Option<S> string(const char* key, Acc acc, std::vector<std::string> allowed, const char* doc, std::string default_text = {}) {
  return {key, doc,
          [=](lua_State* L, int v, S& s) {
            std::string x = schema_detail::to_string(L, v, key);
            if (!allowed.empty()) {
              bool ok = false;
              for (const auto& a : allowed) ok = ok || a == x;
              if (!ok) schema_detail::bad_choice(key, allowed, x);
            }
            std::invoke(acc, s) = std::move(x);
          },
          [=](const S& s) { return schema_detail::show_string(std::invoke(acc, s)); }, std::move(default_text)};
}

/// The names of an enum's values, as a choice() lists them.
template <class E>
using Names = std::vector<std::pair<std::string, E>>;

/// An enum member read from its name.
template <class S, class Acc, class E>
Option<S> choice(const char* key, Acc acc, std::vector<std::pair<std::string, E>> names, const char* doc) {
  return {key, doc,
          [=](lua_State* L, int v, S& s) {
            const std::string x = schema_detail::to_string(L, v, key);
            for (const auto& [n, e] : names)
              if (n == x) {
                std::invoke(acc, s) = e;
                return;
              }
            std::vector<std::string> all;
            for (const auto& ne : names) all.push_back(ne.first);
            schema_detail::bad_choice(key, all, x);
          },
          [=](const S& s) {
            for (const auto& [n, e] : names)
              if (std::invoke(acc, s) == e) return schema_detail::show_string(n);
            return std::string("?");
          },
          {}};
}

/// A member read from a string by `parse` (which throws its own message for a bad name) and
/// shown by `name` (the kernel's own pair, e.g. improve::parse_method / method_name).
template <class S, class Acc, class Parse, class Show>
Option<S> parsed(const char* key, Acc acc, Parse parse, Show name, const char* doc) {
  return {key, doc, [=](lua_State* L, int v, S& s) { std::invoke(acc, s) = parse(schema_detail::to_string(L, v, key)); },
          [=](const S& s) { return schema_detail::show_string(name(std::invoke(acc, s))); }, {}};
}

template <class S, class Acc>
Option<S> boolean(const char* key, Acc acc, const char* doc) {
  return {key, doc, [=](lua_State* L, int v, S& s) { std::invoke(acc, s) = schema_detail::to_boolean(L, v, key); },
          [=](const S& s) { return std::string(std::invoke(acc, s) ? "true" : "false"); }, {}};
}

/// A key the binding reads itself (a nested table, a callback, a required value): known to the
/// unknown-key check and listed in the reference with `default_text`.
template <class S>
Option<S> by_hand(const char* key, std::string default_text, const char* doc) {
  return {key, doc, {}, {}, std::move(default_text)};
}

// ---------------------------------------------------------------------------------------------

template <class S>
void Schema<S>::raise_type(lua_State* L, int idx, const char* as) const {
  luaL_error(L, "%s: options must be a table, got %s", as ? as : name(), luaL_typename(L, idx));
  std::abort();  // not reached
}

template <class S>
void Schema<S>::copy_message(char* buf, std::size_t size, const char* what) {
  std::size_t i = 0;
  for (; what[i] && i + 1 < size; ++i) buf[i] = what[i];
  buf[i] = '\0';
}

}  // namespace smi::lua
