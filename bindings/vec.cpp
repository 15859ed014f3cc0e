// SPDX-License-Identifier: MIT
// smi.vec: a 1-D float64 array owned by Lua, 1-based, with whole-vector arithmetic and
// reductions done in C++ (one Lua call per vector, never per element).
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <new>
#include <unistd.h>

#include "bindings/modules.hpp"
#include "luax/luax.hpp"
#include "luax/memory.hpp"
#include "platform/core/descriptive.hpp"

namespace smi::bind {
namespace {

using lua::check_box;
using lua::protect;
using lua::push_vec;
using Vec = Eigen::VectorXd;

Vec& self(lua_State* L) { return check_box<Vec>(L, 1, lua::kVecType); }

/// 1-based index with negative values counting from the end (as string.sub does).
Eigen::Index resolve(lua_Integer i, Eigen::Index n) { return i < 0 ? n + static_cast<Eigen::Index>(i) + 1 : i; }

// ---- constructors

/// The length argument at `idx` of `fname`, checked: a whole number >= 0 whose vector fits in
/// this machine's memory. smi.vec(1e12) used to die on an uncaught std::bad_alloc whose Lua
/// error object was the number itself ("1000000000000.0"); now the message says what happened
/// and what was probably meant.
Eigen::Index checked_length(lua_State* L, int idx, const char* fname) {
  const double x = luaL_checknumber(L, idx);
  const std::string shown = fmt::format("{}", x);  // 1e+12, not 1000000000000.0
  std::string msg;
  if (!(x >= 0) || std::floor(x) != x)
    msg = fmt::format("{}({}): a length must be a whole number >= 0; to make a vector holding the number {}, write "
                      "smi.vec{{{}}}", fname, shown, shown, shown);
  const double mem = static_cast<double>(::sysconf(_SC_PHYS_PAGES)) * static_cast<double>(::sysconf(_SC_PAGESIZE));
  if (msg.empty() && mem > 0 && 8.0 * x > mem)  // literal: bytes per double
    msg = fmt::format("{}({}): a vector of {:.0f} numbers needs {:.3g} GB of memory, more than this machine has "
                      "({:.3g} GB); to make a vector holding the number {}, write smi.vec{{{}}}",
                      fname, shown, x, 8e-9 * x, mem / 1e9, shown, shown);  // literal: bytes per double, bytes per GB
  if (!msg.empty()) luaL_error(L, "%s", msg.c_str());
  return static_cast<Eigen::Index>(x);
}

/// A vector of n copies of `value`; a failed allocation is a Lua error naming the size.
int push_filled(lua_State* L, Eigen::Index n, double value, const char* fname) {
  lua::check_alloc(L, static_cast<double>(n), sizeof(double), fname);  // --max-memory, before allocating
  return lua::protect(L, fname, [&] {
    try {
      push_vec(L, Vec::Constant(n, value));
    } catch (const std::bad_alloc&) {
      throw Error(fmt::format("not enough memory for a vector of {} numbers ({:.3g} GB)", n, 8e-9 * static_cast<double>(n)));  // literal: bytes per double
    }
    return 1;
  });
}

/// smi.vec(x): x a table of numbers, a vec or a one-column mat (copied), or a length (zeros).
int vec_new(lua_State* L) {
  // stack: [smi.vec table, x]
  if (lua_type(L, 2) == LUA_TNUMBER) return push_filled(L, checked_length(L, 2, "smi.vec"), 0.0, "smi.vec");
  push_vec(L, lua::to_vector(L, 2, "smi.vec"));
  return 1;
}

int vec_zeros(lua_State* L) { return push_filled(L, checked_length(L, 1, "smi.vec.zeros"), 0.0, "smi.vec.zeros"); }

int vec_ones(lua_State* L) { return push_filled(L, checked_length(L, 1, "smi.vec.ones"), 1.0, "smi.vec.ones"); }

/// smi.vec.linspace(a, b, n): n equally spaced values from a to b inclusive.
int vec_linspace(lua_State* L) {
  const double a = luaL_checknumber(L, 1), b = luaL_checknumber(L, 2);
  const lua_Integer n = luaL_checkinteger(L, 3);
  luaL_argcheck(L, n >= 2, 3, "need at least 2 points");
  lua::check_alloc(L, static_cast<double>(n), sizeof(double), "smi.vec.linspace(a, b, n)");
  push_vec(L, Vec::LinSpaced(static_cast<Eigen::Index>(n), a, b));
  return 1;
}

/// smi.vec.range(a, b [, step]): a, a+step, ... up to b (inclusive when it lands on it).
int vec_range(lua_State* L) {
  const double a = luaL_checknumber(L, 1), b = luaL_checknumber(L, 2), step = luaL_optnumber(L, 3, 1.0);
  luaL_argcheck(L, step != 0 && std::isfinite(step), 3, "step must be finite and non-zero");
  const double count = std::floor((b - a) / step + 1e-9) + 1;  // literal: rounding slack of a range count
  if (!std::isfinite(a) || !std::isfinite(b)) return luaL_error(L, "smi.vec.range: a and b must be finite");
  // Checked before the vec exists (pushing it would count it only once allocated), inside
  // protect: an allocation failure is a message, not a C++ exception crossing Lua.
  return lua::protect(L, "smi.vec.range", [&] {
    lua::require_room(L, std::max(0.0, count), sizeof(double), "the range");
    const auto n = static_cast<Eigen::Index>(std::max(0.0, count));
    Vec v(n);
    for (Eigen::Index i = 0; i < n; ++i) v[i] = a + step * static_cast<double>(i);
    push_vec(L, std::move(v));
    return 1;
  });
}

// ---- reductions

int vec_size(lua_State* L) {
  lua_pushinteger(L, self(L).size());
  return 1;
}

template <double (*F)(ConstVec)>
int reduce(lua_State* L, const char* name) {
  const Vec& v = self(L);
  double r = 0;
  const int n = protect(L, name, [&] {
    r = F(v);
    return 1;
  });
  lua_pushnumber(L, r);
  return n;
}

double sum_of(ConstVec v) { return v.sum(); }
double min_of(ConstVec v) {
  require_size(v, 1, "vec");
  return v.minCoeff();
}
double max_of(ConstVec v) {
  require_size(v, 1, "vec");
  return v.maxCoeff();
}
double median_of(ConstVec v) { return quantile(v, 0.5); }

int vec_sum(lua_State* L) { return reduce<sum_of>(L, "vec:sum"); }
int vec_mean(lua_State* L) { return reduce<smi::mean>(L, "vec:mean"); }
int vec_std(lua_State* L) { return reduce<smi::stddev>(L, "vec:std"); }
int vec_var(lua_State* L) { return reduce<smi::variance>(L, "vec:var"); }
int vec_min(lua_State* L) { return reduce<min_of>(L, "vec:min"); }
int vec_max(lua_State* L) { return reduce<max_of>(L, "vec:max"); }
int vec_median(lua_State* L) { return reduce<median_of>(L, "vec:median"); }

/// v:quantile(p): type-7 quantile; p a number or a vec/table of probabilities.
int vec_quantile(lua_State* L) {
  const Vec& v = self(L);
  return lua::push_mapped(L, 2, "vec:quantile", [&](const Vec& p) {
    const Vec s = smi::sorted(v);
    Vec out(p.size());
    for (Eigen::Index i = 0; i < p.size(); ++i) out[i] = quantile_sorted(s, p[i]);
    return out;
  });
}

int vec_argmin(lua_State* L) {
  const Vec& v = self(L);
  if (v.size() == 0) return luaL_error(L, "vec:argmin: empty vector");
  Eigen::Index i;
  v.minCoeff(&i);
  lua_pushinteger(L, i + 1);
  return 1;
}

int vec_argmax(lua_State* L) {
  const Vec& v = self(L);
  if (v.size() == 0) return luaL_error(L, "vec:argmax: empty vector");
  Eigen::Index i;
  v.maxCoeff(&i);
  lua_pushinteger(L, i + 1);
  return 1;
}

int vec_dot(lua_State* L) {
  const Vec& a = self(L);
  const Vec b = lua::to_vector(L, 2, "other");
  if (a.size() != b.size()) return luaL_error(L, "vec:dot: sizes differ (%d and %d)", (int)a.size(), (int)b.size());
  lua_pushnumber(L, a.dot(b));
  return 1;
}

int vec_norm(lua_State* L) {
  lua_pushnumber(L, self(L).norm());
  return 1;
}

// ---- transforms (each returns a new vec)

int vec_sort(lua_State* L) {
  const Vec& v = self(L);
  Vec s = smi::sorted(v);
  if (lua_toboolean(L, 2)) s.reverseInPlace();  // v:sort(true): descending
  push_vec(L, std::move(s));
  return 1;
}

int vec_copy(lua_State* L) {
  push_vec(L, self(L));
  return 1;
}

int vec_cumsum(lua_State* L) {
  const Vec& v = self(L);
  Vec c(v.size());
  double acc = 0;
  for (Eigen::Index i = 0; i < v.size(); ++i) c[i] = (acc += v[i]);
  push_vec(L, std::move(c));
  return 1;
}

/// v:sub(i [, j]): elements i..j (1-based, inclusive, negatives from the end), a copy.
int vec_sub(lua_State* L) {
  const Vec& v = self(L);
  const Eigen::Index n = v.size();
  Eigen::Index i = resolve(luaL_checkinteger(L, 2), n), j = resolve(luaL_optinteger(L, 3, -1), n);
  i = std::max<Eigen::Index>(i, 1);
  j = std::min<Eigen::Index>(j, n);
  push_vec(L, i > j ? Vec() : Vec(v.segment(i - 1, j - i + 1)));
  return 1;
}

template <class F>
int elementwise(lua_State* L, F f) {
  const Vec& v = self(L);
  push_vec(L, v.unaryExpr(f));
  return 1;
}
int vec_abs(lua_State* L) { return elementwise(L, [](double x) { return std::abs(x); }); }
int vec_sqrt(lua_State* L) { return elementwise(L, [](double x) { return std::sqrt(x); }); }
int vec_exp(lua_State* L) { return elementwise(L, [](double x) { return std::exp(x); }); }
int vec_log(lua_State* L) { return elementwise(L, [](double x) { return std::log(x); }); }

/// v:map(f): f called once per element (a convenience for small vectors; prefer whole-vector
/// operations for large ones).
int vec_map(lua_State* L) {
  const Vec& v = self(L);
  luaL_checktype(L, 2, LUA_TFUNCTION);
  Vec out(v.size());
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    lua_pushvalue(L, 2);
    lua_pushnumber(L, v[i]);
    lua_call(L, 1, 1);
    int isnum = 0;
    out[i] = lua_tonumberx(L, -1, &isnum);
    if (!isnum) return luaL_error(L, "vec:map: function returned %s for element %d", luaL_typename(L, -1), (int)i + 1);
    lua_pop(L, 1);
  }
  push_vec(L, std::move(out));
  return 1;
}

int vec_totable(lua_State* L) {
  const Vec& v = self(L);
  lua_createtable(L, static_cast<int>(v.size()), 0);
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    lua_pushnumber(L, v[i]);
    lua_rawseti(L, -2, i + 1);
  }
  return 1;
}

// ---- metamethods

/// Field access: integer keys read elements; anything else is a missing field.
int vec_get(lua_State* L) {
  // stack: [self, key]
  if (!lua_isinteger(L, 2)) return 0;
  const Vec& v = self(L);
  const lua_Integer i = lua_tointeger(L, 2);
  if (i < 1 || i > v.size())
    return luaL_error(L, "smi.vec index %d out of range 1..%d", (int)i, (int)v.size());
  lua_pushnumber(L, v[i - 1]);
  return 1;
}

int vec_newindex(lua_State* L) {
  Vec& v = self(L);
  if (!lua_isinteger(L, 2)) return luaL_error(L, "smi.vec: only integer indices can be assigned");
  const lua_Integer i = lua_tointeger(L, 2);
  if (i < 1 || i > v.size())
    return luaL_error(L, "smi.vec index %d out of range 1..%d (a vec has a fixed length)", (int)i, (int)v.size());
  v[i - 1] = luaL_checknumber(L, 3);
  return 0;
}

int vec_len(lua_State* L) {
  lua_pushinteger(L, self(L).size());
  return 1;
}

std::string format_number(double x) { return fmt::format("{:.6g}", x); }

int vec_tostring(lua_State* L) {
  const Vec& v = self(L);
  const Eigen::Index n = v.size();
  std::string s = fmt::format("vec({})[", n);
  const bool summary = n > 12;  // literal: how many elements print in full
  for (Eigen::Index i = 0; i < n; ++i) {
    if (summary && i == 5) {
      s += ", ...";
      i = n - 5;
    }
    s += (i == 0 ? "" : ", ") + format_number(v[i]);
  }
  s += "]";
  if (summary)
    s += fmt::format(" mean={} std={} min={} max={}", format_number(v.mean()), format_number(smi::stddev(v)),
                     format_number(v.minCoeff()), format_number(v.maxCoeff()));
  lua_pushlstring(L, s.data(), s.size());
  return 1;
}

/// Binary arithmetic: vec op vec (same length), vec op number, number op vec.
template <class Op>
int arith(lua_State* L, const char* name, Op op) {
  const Vec* a = lua::test_vec(L, 1);
  const Vec* b = lua::test_vec(L, 2);
  if (a && b) {
    if (a->size() != b->size())
      return luaL_error(L, "smi.vec %s: lengths differ (%d and %d)", name, (int)a->size(), (int)b->size());
    push_vec(L, a->binaryExpr(*b, op));
  } else if (a) {
    const double y = luaL_checknumber(L, 2);
    push_vec(L, a->unaryExpr([&](double x) { return op(x, y); }));
  } else if (b) {
    const double x = luaL_checknumber(L, 1);
    push_vec(L, b->unaryExpr([&](double y) { return op(x, y); }));
  } else {
    return luaL_error(L, "smi.vec %s: no vec operand", name);
  }
  return 1;
}
int vec_add(lua_State* L) { return arith(L, "+", [](double x, double y) { return x + y; }); }
int vec_subtract(lua_State* L) { return arith(L, "-", [](double x, double y) { return x - y; }); }
int vec_mul(lua_State* L) { return arith(L, "*", [](double x, double y) { return x * y; }); }
int vec_div(lua_State* L) { return arith(L, "/", [](double x, double y) { return x / y; }); }
int vec_pow(lua_State* L) { return arith(L, "^", [](double x, double y) { return std::pow(x, y); }); }
int vec_unm(lua_State* L) {
  push_vec(L, -self(L));
  return 1;
}
int vec_eq(lua_State* L) {
  const Vec* a = lua::test_vec(L, 1);
  const Vec* b = lua::test_vec(L, 2);
  lua_pushboolean(L, a && b && a->size() == b->size() && *a == *b);
  return 1;
}

const luaL_Reg kMethods[] = {
    {"size", vec_size},     {"sum", vec_sum},       {"mean", vec_mean},     {"std", vec_std},
    {"var", vec_var},       {"min", vec_min},       {"max", vec_max},       {"median", vec_median},
    {"quantile", vec_quantile}, {"argmin", vec_argmin}, {"argmax", vec_argmax}, {"dot", vec_dot},
    {"norm", vec_norm},     {"sort", vec_sort},     {"copy", vec_copy},     {"cumsum", vec_cumsum},
    {"sub", vec_sub},       {"slice", vec_sub},     {"abs", vec_abs},       {"sqrt", vec_sqrt},
    {"exp", vec_exp},       {"log", vec_log},       {"map", vec_map},       {"totable", vec_totable},
    {nullptr, nullptr}};

const luaL_Reg kMeta[] = {{"__newindex", vec_newindex}, {"__len", vec_len}, {"__tostring", vec_tostring},
                          {"__add", vec_add},           {"__sub", vec_subtract}, {"__mul", vec_mul},
                          {"__div", vec_div},           {"__pow", vec_pow}, {"__unm", vec_unm},
                          {"__eq", vec_eq},             {nullptr, nullptr}};

const luaL_Reg kFunctions[] = {{"zeros", vec_zeros}, {"ones", vec_ones}, {"linspace", vec_linspace},
                               {"range", vec_range}, {nullptr, nullptr}};

}  // namespace

void open_vec(lua_State* L) {
  lua::register_type<Eigen::VectorXd>(L, lua::kVecType, kMethods, kMeta, vec_get);
  // stack: [smi]
  lua_newtable(L);  // smi.vec: functions, and callable as a constructor
  luaL_setfuncs(L, kFunctions, 0);
  lua_newtable(L);
  lua_pushcfunction(L, vec_new);
  lua_setfield(L, -2, "__call");
  lua_setmetatable(L, -2);
  lua_setfield(L, -2, "vec");
}

}  // namespace smi::bind
