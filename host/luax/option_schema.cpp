// SPDX-License-Identifier: MIT
// The type-independent half of the option schema (option_schema.hpp): the unknown-key check, the
// reference's option lines, the typed conversions and their messages, the registry of schemas.
#include "luax/option_schema.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <mutex>

#include "luax/doc_text.hpp"
#include "luax/luax.hpp"
#include "platform/core/errors.hpp"

namespace smi::lua {

namespace {
std::mutex g_schemas_mutex;
std::vector<const SchemaBase*>& registry() {
  static std::vector<const SchemaBase*> r;
  return r;
}
}  // namespace

bool Range::contains(double v) const {
  if (std::isnan(v)) return any();
  const bool lo_ok = lo_open ? v > lo : v >= lo;
  const bool hi_ok = hi_open ? v < hi : v <= hi;
  return lo_ok && hi_ok;
}

std::string Range::text(bool integer) const {
  const bool lo_inf = std::isinf(lo), hi_inf = std::isinf(hi);
  if (lo_inf && hi_inf) return "a finite number";
  if (lo_inf && !hi_inf) return fmt::format("{} {}", hi_open ? "<" : "<=", num(hi));
  if (hi_inf && !lo_inf) return fmt::format("{} {}", lo_open ? ">" : ">=", num(lo));
  if (integer && !lo_open && !hi_open) return fmt::format("in {}..{}", num(lo), num(hi));
  return fmt::format("in {}{}, {}{}", lo_open ? "(" : "[", num(lo), num(hi), hi_open ? ")" : "]");
}

SchemaBase::SchemaBase(const char* fname, std::vector<std::string> keys) : fname_(fname), keys_(std::move(keys)) {
  record_known_options(fname_, keys_);  // smi-lua doc --check compares them with the reference
  const std::lock_guard<std::mutex> lock(g_schemas_mutex);
  registry().push_back(this);
}

std::vector<const SchemaBase*> schemas() {
  const std::lock_guard<std::mutex> lock(g_schemas_mutex);
  return registry();
}

void SchemaBase::check_keys(lua_State* L, int idx, const char* as) const {
  {  // the message (C++ strings) in a scope of its own; the Lua error is raised after it
    const std::string msg = unknown_option_message(L, idx, as ? as : fname_, keys_);
    if (msg.empty()) return;
    luaL_where(L, 1);  // as luaL_error would
    lua_pushlstring(L, msg.data(), msg.size());
    lua_concat(L, 2);
  }
  lua_error(L);
}

void SchemaBase::raise(lua_State* L, const char* what, const char* as) const {
  luaL_error(L, "%s: %s", as ? as : fname_, what);
  std::abort();  // not reached: luaL_error does not return
}

std::string SchemaBase::format_lines(const std::vector<std::pair<std::string, std::string>>& heads,
                                     const std::vector<const char*>& docs) {
  std::size_t w = 0;
  for (const auto& [k, d] : heads) w = std::max(w, k.size() + d.size() + 5);
  w = std::min<std::size_t>(w, 36);
  std::string out;
  for (std::size_t i = 0; i < heads.size(); ++i) {
    std::string head = "  " + heads[i].first + " = " + heads[i].second;
    head.append(head.size() + 2 < w ? w - head.size() : 2, ' ');
    const std::string_view doc = docs[i];
    std::size_t at = 0;
    bool first = true;
    while (at <= doc.size()) {
      const std::size_t nl = doc.find('\n', at);
      const std::string_view part = doc.substr(at, nl == std::string_view::npos ? std::string_view::npos : nl - at);
      out += first ? head : std::string(w, ' ');
      out += "-- ";
      out += part;
      out += '\n';
      first = false;
      if (nl == std::string_view::npos) break;
      at = nl + 1;
    }
  }
  if (!out.empty()) out.pop_back();  // the text's own line break follows ${options}
  return out;
}

namespace schema_detail {

namespace {
[[noreturn]] void type_error(lua_State* L, int idx, const char* key, const char* expected) {
  throw InvalidArgument(fmt::format("option '{}' must be {}, got {}", key, expected, luaL_typename(L, idx)));
}
}  // namespace

double to_number(lua_State* L, int idx, const char* key) {
  if (lua_type(L, idx) != LUA_TNUMBER) type_error(L, idx, key, "a number");
  return lua_tonumber(L, idx);
}

long long to_integer(lua_State* L, int idx, const char* key) {
  int isint = 0;
  const lua_Integer v = lua_type(L, idx) == LUA_TNUMBER ? lua_tointegerx(L, idx, &isint) : 0;
  if (!isint) type_error(L, idx, key, "an integer");
  return static_cast<long long>(v);
}

std::string to_string(lua_State* L, int idx, const char* key) {
  if (lua_type(L, idx) != LUA_TSTRING) type_error(L, idx, key, "a string");
  return lua_tostring(L, idx);
}

bool to_boolean(lua_State* L, int idx, const char* key) {
  if (lua_type(L, idx) != LUA_TBOOLEAN) type_error(L, idx, key, "a boolean");
  return lua_toboolean(L, idx) != 0;
}

void check_range(const Range& r, double v, const char* key, bool integer) {
  if (r.contains(v)) return;
  throw InvalidArgument(fmt::format("{} must be {}, got {}", key, r.text(integer), integer ? fmt::format("{}", static_cast<long long>(v)) : num(v)));
}

void bad_choice(const char* key, const std::vector<std::string>& names, const std::string& got) {
  std::string list;
  for (std::size_t i = 0; i < names.size(); ++i)
    list += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + ("\"" + names[i] + "\"");
  throw InvalidArgument(fmt::format("{} must be {}, got \"{}\"", key, list, got));
}

std::string show_number(double v) { return num(v); }
std::string show_string(const std::string& v) { return "\"" + v + "\""; }

}  // namespace schema_detail

}  // namespace smi::lua
