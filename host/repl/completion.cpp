// SPDX-License-Identifier: MIT
#include "repl/completion.hpp"

#include <algorithm>
#include <cctype>
#include <set>

namespace smi::repl {
namespace {

/// Pushes the table that lists the fields of the value at idx: the value itself for a table,
/// else its metatable's __index table (or the methods table upvalue of an __index closure).
/// Returns false (nothing pushed) if there is none.
bool push_field_table(lua_State* L, int idx, bool want_own) {
  idx = lua_absindex(L, idx);
  if (want_own && lua_istable(L, idx)) {
    lua_pushvalue(L, idx);
    return true;
  }
  if (!lua_getmetatable(L, idx)) return false;  // stack: [mt]
  lua_pushliteral(L, "__index");
  lua_rawget(L, -2);  // stack: [mt, index]
  lua_remove(L, -2);
  if (lua_istable(L, -1)) return true;
  if (lua_iscfunction(L, -1) && lua_getupvalue(L, -1, 1) && lua_istable(L, -1)) {
    lua_remove(L, -2);
    return true;
  }
  lua_settop(L, idx);
  return false;
}

/// Adds the identifier keys of the table at the top starting with `prefix`, then those of its
/// metatable's __index chain (a few levels). Stack: unchanged.
void collect(lua_State* L, const std::string& prefix, std::set<std::string>& out, int levels = 3) {
  const int t = lua_gettop(L);
  lua_pushnil(L);
  while (lua_next(L, t)) {
    lua_pop(L, 1);
    if (lua_type(L, -1) != LUA_TSTRING) continue;
    const std::string k = lua_tostring(L, -1);
    if (k.compare(0, prefix.size(), prefix) != 0) continue;
    if (k.empty() || !(std::isalpha(static_cast<unsigned char>(k[0])) || k[0] == '_')) continue;
    out.insert(k);
  }
  if (levels > 0 && push_field_table(L, t, false)) {
    collect(L, prefix, out, levels - 1);
    lua_pop(L, 1);
  }
}

}  // namespace

std::vector<std::string> complete(lua_State* L, const std::string& text) {
  const int top = lua_gettop(L);
  const std::size_t cut = text.find_last_of(".:");
  const std::string head = cut == std::string::npos ? "" : text.substr(0, cut + 1);
  const std::string prefix = cut == std::string::npos ? text : text.substr(cut + 1);
  lua_pushglobaltable(L);
  // Walk the path "a.b.c" (the part before the last separator) with raw lookups.
  std::size_t start = 0;
  bool ok = true;
  while (ok && cut != std::string::npos && start <= cut) {
    const std::size_t end = text.find_first_of(".:", start);
    const std::string seg = text.substr(start, end - start);
    if (seg.empty() || !push_field_table(L, -1, true)) {
      ok = false;
      break;
    }
    lua_pushlstring(L, seg.data(), seg.size());
    lua_rawget(L, -2);  // stack: [..., holder, fields, value]
    lua_remove(L, -2);
    if (lua_isnil(L, -1)) ok = false;
    start = end + 1;
  }
  std::vector<std::string> out;
  if (ok) {
    const bool methods_only = cut != std::string::npos && text[cut] == ':';
    if (push_field_table(L, -1, !methods_only)) {
      std::set<std::string> keys;
      collect(L, prefix, keys);
      for (const auto& k : keys) out.push_back(head + k);
    }
  }
  lua_settop(L, top);
  return out;
}

namespace {

/// require("smi.doc").names(prefix), or nothing when the doc module fails (completion must not).
std::vector<std::string> doc_names(lua_State* L, const std::string& prefix) {
  const int top = lua_gettop(L);
  std::vector<std::string> out;
  static constexpr char kCode[] = "local p = ... return require('smi.doc').names(p)";
  if (luaL_loadbufferx(L, kCode, sizeof kCode - 1, "=completion", "t") == LUA_OK) {
    lua_pushlstring(L, prefix.data(), prefix.size());
    if (lua_pcall(L, 1, 1, 0) == LUA_OK && lua_istable(L, -1)) {
      const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L, -1));
      for (lua_Integer i = 1; i <= n; ++i) {
        if (lua_rawgeti(L, -1, i) == LUA_TSTRING) out.emplace_back(lua_tostring(L, -1));
        lua_pop(L, 1);
      }
    }
  }
  lua_settop(L, top);
  return out;
}

bool ends_with_help_string(const std::string& before) {
  std::string b = before;
  while (!b.empty() && b.back() == ' ') b.pop_back();
  if (b.empty() || (b.back() != '"' && b.back() != '\'')) return false;
  b.pop_back();
  while (!b.empty() && (b.back() == ' ' || b.back() == '(')) b.pop_back();
  return b.size() >= 4 && b.compare(b.size() - 4, 4, "help") == 0 &&
         (b.size() == 4 || !(std::isalnum(static_cast<unsigned char>(b[b.size() - 5])) || b[b.size() - 5] == '_'));
}

}  // namespace

std::vector<std::string> complete_line(lua_State* L, const std::string& text, const std::string& before) {
  if (!text.empty() && text[0] == '?' && before.find_first_not_of(' ') == std::string::npos) {
    std::vector<std::string> out;
    for (auto& n : doc_names(L, text.substr(1))) out.push_back("?" + n);
    return out;
  }
  if (ends_with_help_string(before)) return doc_names(L, text);
  return complete(L, text);
}

}  // namespace smi::repl
