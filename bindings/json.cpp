// SPDX-License-Identifier: MIT
// smi.json: the Lua face of the one JSON codec (core/json.hpp: text, numbers, the non-finite rule).
//   smi.json.encode(value [, opts]) -> string [, skipped]  smi.json.decode(text [, {null = v}]) -> value
//   smi.json.write(path, value [, opts])                   smi.json.read(path [, {null = v}]) -> value
//   smi.json.null                                          JSON null (kept in arrays and objects)
// opts: indent (spaces, 0..16), nonfinite ("refuse": NaN/inf are errors naming their path;
// "encode": inf as 1e999, NaN as null), skip (leave out what JSON cannot hold and return their
// paths as a second result), root (the value's name in error paths, "$").
// Here only the Lua side: smi.vec -> array, smi.mat -> array of rows, tables with keys 1..n ->
// array (an empty table -> []), other tables -> object (sorted by the codec); functions and
// cycles are errors naming where in the value they are. read/write go through the sandbox policy.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fcntl.h>
#include <fmt/format.h>
#include <string>
#include <vector>

#include "bindings/csv_json_options.hpp"
#include "bindings/modules.hpp"
#include "luax/luax.hpp"
#include "luax/policy.hpp"
#include "platform/core/json.hpp"
#include "platform/core/number_text.hpp"

namespace smi::bind {
namespace {

const char kNullKey = 0;  // registry key of the null sentinel

void push_null(lua_State* L) { lua_rawgetp(L, LUA_REGISTRYINDEX, &kNullKey); }

bool is_null(lua_State* L, int idx) {
  idx = lua_absindex(L, idx);
  push_null(L);
  const bool r = lua_rawequal(L, idx, -1);
  lua_pop(L, 1);
  return r;
}


// ---- Lua -> json::Value (the codec itself is core/json.hpp)

bool identifier(const std::string& k) {
  if (k.empty() || !(std::isalpha(static_cast<unsigned char>(k[0])) || k[0] == '_')) return false;
  return std::all_of(k.begin(), k.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
}

/// The name of a Lua value's type for messages: its metatable's __name (smi.vec, FILE*) or type.
std::string type_name(lua_State* L, int idx) {
  std::string name = luaL_typename(L, idx);
  if (luaL_getmetafield(L, idx, "__name") != LUA_TNIL) {
    if (lua_type(L, -1) == LUA_TSTRING) name = lua_tostring(L, -1);
    lua_pop(L, 1);
  }
  return name;
}

class ToJson {
 public:
  ToJson(lua_State* L, bool skip) : L_(L), skip_(skip) {}
  std::vector<std::string> skipped;

  /// The JSON value of the Lua value at idx; false when it was skipped (opts.skip).
  bool convert(int idx, const std::string& where, int depth, json::Value& out) {
    idx = lua_absindex(L_, idx);
    if (depth > json::kMaxDepth)
      throw Error(fmt::format("value at {} is nested deeper than {} levels", where, json::kMaxDepth));
    switch (lua_type(L_, idx)) {
      case LUA_TNIL: out = nullptr; return true;
      case LUA_TBOOLEAN: out = lua_toboolean(L_, idx) != 0; return true;
      case LUA_TNUMBER:
        if (lua_isinteger(L_, idx)) out = static_cast<std::int64_t>(lua_tointeger(L_, idx));
        else out = static_cast<double>(lua_tonumber(L_, idx));
        return true;
      case LUA_TSTRING: {
        std::size_t len = 0;
        const char* s = lua_tolstring(L_, idx, &len);
        out = std::string(s, len);
        return true;
      }
      case LUA_TTABLE:
        if (is_null(L_, idx)) {
          out = nullptr;
          return true;
        }
        table(idx, where, depth, out);
        return true;
      case LUA_TUSERDATA:
        if (const Eigen::VectorXd* v = lua::test_vec(L_, idx)) {
          out = vec(*v);
          return true;
        }
        if (const Eigen::MatrixXd* m = lua::test_mat(L_, idx)) {
          json::Array rows;
          for (Eigen::Index i = 0; i < m->rows(); ++i) rows.emplace_back(vec(m->row(i).transpose()));
          out = std::move(rows);
          return true;
        }
        [[fallthrough]];
      default:
        if (skip_) {
          skipped.push_back(fmt::format("{} ({})", where, type_name(L_, idx)));
          return false;
        }
        throw Error(fmt::format("value at {} is a {}, which JSON cannot hold (convert it to numbers or a table, "
                                "or leave it out)",
                                where, type_name(L_, idx)));
    }
  }

 private:
  static json::Value vec(const Eigen::VectorXd& v) {
    json::Array a;
    a.reserve(static_cast<std::size_t>(v.size()));
    for (Eigen::Index i = 0; i < v.size(); ++i) a.emplace_back(v[i]);
    return a;
  }

  /// A key of an object: its JSON text and how to push the original Lua key again.
  struct Key {
    std::string text;
    bool is_string;
    lua_Number num;
  };

  void push_key(const Key& k) {
    if (k.is_string)
      lua_pushlstring(L_, k.text.data(), k.text.size());
    else if (std::floor(k.num) == k.num && std::fabs(k.num) < 9.0e15)  // literal: integers exact in a double (below 2^53)
      lua_pushinteger(L_, static_cast<lua_Integer>(k.num));
    else
      lua_pushnumber(L_, k.num);
  }

  void table(int idx, const std::string& where, int depth, json::Value& out) {
    // Each level keeps a key and a value on the Lua stack: make room (without it a table nested
    // a few hundred levels wrote past the stack before the depth check could refuse it).
    if (!lua_checkstack(L_, 4)) throw Error(fmt::format("value at {} is nested too deeply for the Lua stack", where));
    const void* id = lua_topointer(L_, idx);
    if (std::find(open_.begin(), open_.end(), id) != open_.end())
      throw Error(fmt::format("value at {} contains itself (a cycle)", where));
    open_.push_back(id);
    // An array when the keys are exactly 1..n (an empty table too).
    const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L_, idx));
    std::vector<Key> keys;
    std::string bad_key;
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
      } else if (bad_key.empty() || std::strcmp(luaL_typename(L_, -1), bad_key.c_str()) < 0) {
        bad_key = luaL_typename(L_, -1);  // the error names the same type every run, whatever the traversal order
      }
    }
    if (!bad_key.empty())
      throw Error(fmt::format("value at {} has a key of type {}; JSON object keys are strings", where, bad_key));
    if (array) {
      json::Array a;
      a.reserve(static_cast<std::size_t>(n));
      for (lua_Integer i = 1; i <= n; ++i) {
        lua_rawgeti(L_, idx, i);
        a.emplace_back();
        if (!convert(-1, fmt::format("{}[{}]", where, i), depth + 1, a.back())) a.back() = nullptr;
        lua_pop(L_, 1);
      }
      out = std::move(a);
    } else {
      // Values converted in key order (the writer's), not the table's traversal order, which
      // changes from process to process: the list `skip` fills and the error naming the first
      // value JSON cannot hold are then the same every run.
      std::stable_sort(keys.begin(), keys.end(), [](const Key& a, const Key& b) {
        return a.text != b.text ? a.text < b.text : a.is_string < b.is_string;
      });
      json::Object o;
      for (const Key& k : keys) {
        push_key(k);
        lua_rawget(L_, idx);
        json::Value v;
        const std::string sub = identifier(k.text) ? where + "." + k.text : fmt::format("{}[\"{}\"]", where, k.text);
        if (convert(-1, sub, depth + 1, v)) o.emplace_back(k.text, std::move(v));
        lua_pop(L_, 1);
      }
      out = std::move(o);
    }
    open_.pop_back();
  }

  lua_State* L_;
  bool skip_;
  std::vector<const void*> open_;
};

// ---- json::Value -> Lua

/// Pushes v; a JSON null becomes the value at null_idx (0: smi.json.null).
void push_value(lua_State* L, const json::Value& v, int null_idx) {
  luaL_checkstack(L, 4, "smi.json: nesting");
  std::visit(
      [&](const auto& x) {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, std::nullptr_t>) {
          if (null_idx) lua_pushvalue(L, null_idx);
          else push_null(L);
        } else if constexpr (std::is_same_v<T, bool>) {
          lua_pushboolean(L, x);
        } else if constexpr (std::is_same_v<T, std::int64_t>) {
          lua_pushinteger(L, static_cast<lua_Integer>(x));
        } else if constexpr (std::is_same_v<T, double>) {
          lua_pushnumber(L, x);
        } else if constexpr (std::is_same_v<T, std::string>) {
          lua_pushlstring(L, x.data(), x.size());
        } else if constexpr (std::is_same_v<T, json::Array>) {
          lua_createtable(L, static_cast<int>(x.size()), 0);
          for (std::size_t i = 0; i < x.size(); ++i) {
            push_value(L, x[i], null_idx);
            lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
          }
        } else {
          lua_createtable(L, 0, static_cast<int>(x.size()));
          for (const auto& [k, val] : x) {
            lua_pushlstring(L, k.data(), k.size());
            push_value(L, val, null_idx);
            lua_rawset(L, -3);
          }
        }
      },
      v.v);
}

// ---- options

using EncodeOptions = JsonEncodeArgs;

/// The stack index of the value that JSON null decodes to (opts.null), or 0 for smi.json.null.
int null_option(lua_State* L, int idx, const char* fname) {
  json_decode_schema(std::string_view(fname) == "smi.json.read").read(L, idx);  // the unknown-key check
  if (lua_isnoneornil(L, idx) || lua_getfield(L, idx, "null") == LUA_TNIL) {
    if (!lua_isnoneornil(L, idx)) lua_pop(L, 1);
    return 0;
  }
  return lua_gettop(L);  // the value stays on the stack for the decode
}

/// Encodes the value at idx; with skip, pushes nothing and fills `skipped`.
std::string encode(lua_State* L, int idx, const EncodeOptions& e, std::vector<std::string>* skipped = nullptr) {
  ToJson t(L, e.skip);
  json::Value v;
  if (!t.convert(idx, e.root, 0, v)) v = nullptr;
  if (skipped) *skipped = std::move(t.skipped);
  return json::write(v, e);
}

int json_encode(lua_State* L) {
  luaL_checkany(L, 1);
  const EncodeOptions e = json_encode_schema().read(L, 2);
  return lua::protect(L, "smi.json.encode", [&] {
    std::vector<std::string> skipped;
    const std::string s = encode(L, 1, e, &skipped);
    lua_pushlstring(L, s.data(), s.size());
    if (!e.skip) return 1;
    lua_createtable(L, static_cast<int>(skipped.size()), 0);
    for (std::size_t i = 0; i < skipped.size(); ++i) {
      lua_pushstring(L, skipped[i].c_str());
      lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
    }
    return 2;
  });
}

int json_decode(lua_State* L) {
  std::size_t len = 0;
  const char* s = luaL_checklstring(L, 1, &len);
  const int null_idx = null_option(L, 2, "smi.json.decode");
  return lua::protect(L, "smi.json.decode", [&] {
    push_value(L, json::read(std::string_view(s, len), "json"), null_idx);
    return 1;
  });
}

int json_write(lua_State* L) {
  const char* path = luaL_checkstring(L, 1);
  luaL_checkany(L, 2);
  const EncodeOptions e = json_write_schema().read(L, 3);
  return lua::protect(L, "smi.json.write", [&] {
    std::string s = encode(L, 2, e);
    s += '\n';
    const lua::CheckedFile f = lua::policy(L).open_write(path, O_WRONLY | O_CREAT | O_TRUNC);
    if (!pathwalk::write_all(f.fd.get(), s))
      throw Error(fmt::format("writing '{}' failed: {}", path, std::strerror(errno)));
    return 0;
  });
}

int json_read(lua_State* L) {
  const char* path = luaL_checkstring(L, 1);
  const int null_idx = null_option(L, 2, "smi.json.read");
  return lua::protect(L, "smi.json.read", [&] {
    const lua::CheckedFile f = lua::policy(L).open_read(path);
    const std::string text = lua::read_checked(f, path);
    push_value(L, json::read(text, path), null_idx);
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
