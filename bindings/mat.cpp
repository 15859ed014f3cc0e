// SPDX-License-Identifier: MIT
// smi.mat: a 2-D float64 array (rows are points, columns are variables), 1-based.
#include <cmath>
#include <fmt/format.h>

#include "bindings/modules.hpp"
#include "luax/luax.hpp"
#include "luax/memory.hpp"
#include "platform/core/descriptive.hpp"
#include "platform/core/linalg.hpp"

namespace smi::bind {
namespace {

using lua::check_box;
using lua::push_mat;
using lua::push_vec;
using Mat = Eigen::MatrixXd;
using Vec = Eigen::VectorXd;

Mat& self(lua_State* L) { return check_box<Mat>(L, 1, lua::kMatType); }

Eigen::Index check_row(lua_State* L, const Mat& m, int arg) {
  const lua_Integer i = luaL_checkinteger(L, arg);
  if (i < 1 || i > m.rows()) luaL_error(L, "smi.mat row %d out of range 1..%d", (int)i, (int)m.rows());
  return static_cast<Eigen::Index>(i - 1);
}

Eigen::Index check_col(lua_State* L, const Mat& m, int arg) {
  const lua_Integer j = luaL_checkinteger(L, arg);
  if (j < 1 || j > m.cols()) luaL_error(L, "smi.mat column %d out of range 1..%d", (int)j, (int)m.cols());
  return static_cast<Eigen::Index>(j - 1);
}

/// smi.mat(rows_table | vec | mat) copies; smi.mat(r, c) gives zeros.
int mat_new(lua_State* L) {
  // stack: [smi.mat table, ...]
  if (lua_type(L, 2) == LUA_TNUMBER) {
    const lua_Integer r = luaL_checkinteger(L, 2), c = luaL_checkinteger(L, 3);
    luaL_argcheck(L, r >= 0 && c >= 0, 2, "sizes must be >= 0");
    lua::check_alloc(L, static_cast<double>(r) * static_cast<double>(c), sizeof(double), "smi.mat(rows, cols)");
    push_mat(L, Mat::Zero(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)));
    return 1;
  }
  push_mat(L, lua::to_matrix(L, 2, "smi.mat"));
  return 1;
}

int mat_zeros(lua_State* L) {
  const lua_Integer r = luaL_checkinteger(L, 1), c = luaL_checkinteger(L, 2);
  luaL_argcheck(L, r >= 0 && c >= 0, 1, "sizes must be >= 0");
  lua::check_alloc(L, static_cast<double>(r) * static_cast<double>(c), sizeof(double), "smi.mat.zeros(rows, cols)");
  push_mat(L, Mat::Zero(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)));
  return 1;
}

int mat_identity(lua_State* L) {
  const lua_Integer n = luaL_checkinteger(L, 1);
  luaL_argcheck(L, n >= 0, 1, "size must be >= 0");
  lua::check_alloc(L, static_cast<double>(n) * static_cast<double>(n), sizeof(double), "smi.mat.identity(n)");
  push_mat(L, Mat::Identity(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n)));
  return 1;
}

/// Joins the blocks of the table at index 1 side by side (columns) or stacked (rows); each block
/// is a vec, a table of numbers or a mat. `name` is the Lua function, for messages.
int join_blocks(lua_State* L, bool side_by_side, const char* name) {
  luaL_checktype(L, 1, LUA_TTABLE);
  const lua_Integer n = luaL_len(L, 1);
  Mat out;
  for (lua_Integer k = 1; k <= n; ++k) {
    lua_rawgeti(L, 1, k);
    Mat block = lua::to_matrix(L, -1, "block");
    lua_pop(L, 1);
    if (k == 1) {
      out = std::move(block);
      continue;
    }
    const Eigen::Index have = side_by_side ? out.rows() : out.cols();
    const Eigen::Index got = side_by_side ? block.rows() : block.cols();
    if (got != have)
      return luaL_error(L, "%s: block %d has %d %s, block 1 has %d", name, (int)k, (int)got,
                        side_by_side ? "rows" : "columns", (int)have);
    Mat joined(side_by_side ? out.rows() : out.rows() + block.rows(),
               side_by_side ? out.cols() + block.cols() : out.cols());
    // Eigen's comma initializer places `block` right of `out` when the row has room for it,
    // below it otherwise: the same line serves both joins.
    joined << out, block;
    out = std::move(joined);
  }
  push_mat(L, std::move(out));
  return 1;
}

/// smi.mat.hcat{a, b, ...}: columns side by side.
int mat_hcat(lua_State* L) { return join_blocks(L, true, "smi.mat.hcat"); }
/// smi.mat.vcat{a, b, ...}: rows stacked.
int mat_vcat(lua_State* L) { return join_blocks(L, false, "smi.mat.vcat"); }

int mat_rows(lua_State* L) {
  lua_pushinteger(L, self(L).rows());
  return 1;
}
int mat_cols(lua_State* L) {
  lua_pushinteger(L, self(L).cols());
  return 1;
}
int mat_shape(lua_State* L) {
  const Mat& m = self(L);
  lua_pushinteger(L, m.rows());
  lua_pushinteger(L, m.cols());
  return 2;
}
int mat_getij(lua_State* L) {
  const Mat& m = self(L);
  const auto i = check_row(L, m, 2);
  const auto j = check_col(L, m, 3);
  lua_pushnumber(L, m(i, j));
  return 1;
}
int mat_setij(lua_State* L) {
  Mat& m = self(L);
  const auto i = check_row(L, m, 2);
  const auto j = check_col(L, m, 3);
  m(i, j) = luaL_checknumber(L, 4);
  return 0;
}
int mat_row(lua_State* L) {
  const Mat& m = self(L);
  push_vec(L, m.row(check_row(L, m, 2)).transpose());
  return 1;
}
int mat_col(lua_State* L) {
  const Mat& m = self(L);
  push_vec(L, m.col(check_col(L, m, 2)));
  return 1;
}
/// m:set_col(j, v) and m:set_row(i, v): replace in place.
int mat_set_col(lua_State* L) {
  Mat& m = self(L);
  const auto j = check_col(L, m, 2);
  const Vec v = lua::to_vector(L, 3, "column");
  if (v.size() != m.rows()) return luaL_error(L, "mat:set_col: %d values for %d rows", (int)v.size(), (int)m.rows());
  m.col(j) = v;
  return 0;
}
int mat_set_row(lua_State* L) {
  Mat& m = self(L);
  const auto i = check_row(L, m, 2);
  const Vec v = lua::to_vector(L, 3, "row");
  if (v.size() != m.cols()) return luaL_error(L, "mat:set_row: %d values for %d columns", (int)v.size(), (int)m.cols());
  m.row(i) = v.transpose();
  return 0;
}
/// m:sub(i1, i2 [, j1, j2]): a block copy (rows i1..i2, columns j1..j2, inclusive).
int mat_sub(lua_State* L) {
  const Mat& m = self(L);
  const auto i1 = check_row(L, m, 2), i2 = check_row(L, m, 3);
  const Eigen::Index j1 = lua_isnoneornil(L, 4) ? 0 : check_col(L, m, 4);
  const Eigen::Index j2 = lua_isnoneornil(L, 5) ? m.cols() - 1 : check_col(L, m, 5);
  if (i2 < i1 || j2 < j1) return luaL_error(L, "mat:sub: empty range");
  push_mat(L, m.block(i1, j1, i2 - i1 + 1, j2 - j1 + 1));
  return 1;
}
int mat_t(lua_State* L) {
  push_mat(L, self(L).transpose());
  return 1;
}
int mat_copy(lua_State* L) {
  push_mat(L, self(L));
  return 1;
}
int mat_sum(lua_State* L) {
  lua_pushnumber(L, self(L).sum());
  return 1;
}
int mat_colmeans(lua_State* L) {
  push_vec(L, self(L).colwise().mean().transpose());
  return 1;
}
int mat_colstds(lua_State* L) {
  const Mat& m = self(L);
  return lua::protect(L, "mat:colstds", [&] {
    Vec s(m.cols());
    for (Eigen::Index j = 0; j < m.cols(); ++j) s[j] = smi::stddev(m.col(j));
    push_vec(L, std::move(s));
    return 1;
  });
}
/// m:dot(x): matrix product with a mat or a vec.
int mat_dot(lua_State* L) {
  const Mat& m = self(L);
  if (const Vec* v = lua::test_vec(L, 2)) {
    if (v->size() != m.cols()) return luaL_error(L, "mat:dot: %dx%d times vec(%d)", (int)m.rows(), (int)m.cols(), (int)v->size());
    push_vec(L, m * *v);
    return 1;
  }
  const Mat b = lua::to_matrix(L, 2, "other");
  if (b.rows() != m.cols())
    return luaL_error(L, "mat:dot: %dx%d times %dx%d", (int)m.rows(), (int)m.cols(), (int)b.rows(), (int)b.cols());
  push_mat(L, m * b);
  return 1;
}
// Linear algebra (platform/core/linalg.hpp): arguments are read from Lua first (Lua errors),
// the kernel runs under protect (its errors become "mat:solve: A (2x2) is singular: ...").

/// A:solve(b): b a vec or a table of numbers gives a vec; b a mat (n x k) gives a mat.
int mat_solve(lua_State* L) {
  const Mat& a = self(L);
  const bool vector_rhs = lua::test_vec(L, 2) || (lua_istable(L, 2) && !lua::test_mat(L, 2) &&
                                                  (lua_rawgeti(L, 2, 1), lua_type(L, -1) == LUA_TNUMBER));
  lua_settop(L, 2);
  const Mat b = vector_rhs ? Mat(lua::to_vector(L, 2, "b")) : lua::to_matrix(L, 2, "b");
  return lua::protect(L, "mat:solve", [&] {
    Mat x = smi::linalg::solve(a, b);
    if (vector_rhs) push_vec(L, x.col(0));
    else push_mat(L, std::move(x));
    return 1;
  });
}
int mat_inverse(lua_State* L) {
  const Mat& a = self(L);
  return lua::protect(L, "mat:inverse", [&] {
    push_mat(L, smi::linalg::inverse(a));
    return 1;
  });
}
int mat_det(lua_State* L) {
  const Mat& a = self(L);
  return lua::protect(L, "mat:det", [&] {
    lua_pushnumber(L, smi::linalg::det(a));
    return 1;
  });
}
int mat_chol(lua_State* L) {
  const Mat& a = self(L);
  return lua::protect(L, "mat:chol", [&] {
    push_mat(L, smi::linalg::chol(a));
    return 1;
  });
}
/// smi.mat.eigh(K [, M]) -> values (vec, ascending), vectors (mat, by column).
int mat_eigh(lua_State* L) {
  const Mat k = lua::to_matrix(L, 1, "K");
  const Mat m = lua_isnoneornil(L, 2) ? Mat() : lua::to_matrix(L, 2, "M");
  return lua::protect(L, "smi.mat.eigh", [&] {
    smi::linalg::Eigh e = smi::linalg::eigh(k, m);
    push_vec(L, std::move(e.values));
    push_mat(L, std::move(e.vectors));
    return 2;
  });
}

int mat_totable(lua_State* L) {
  const Mat& m = self(L);
  lua_createtable(L, static_cast<int>(m.rows()), 0);
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    lua_createtable(L, static_cast<int>(m.cols()), 0);
    for (Eigen::Index j = 0; j < m.cols(); ++j) {
      lua_pushnumber(L, m(i, j));
      lua_rawseti(L, -2, j + 1);
    }
    lua_rawseti(L, -2, i + 1);
  }
  return 1;
}

/// m[i]: row i as a new vec.
int mat_get(lua_State* L) {
  if (!lua_isinteger(L, 2)) return 0;
  const Mat& m = self(L);
  push_vec(L, m.row(check_row(L, m, 2)).transpose());
  return 1;
}
int mat_len(lua_State* L) {
  lua_pushinteger(L, self(L).rows());
  return 1;
}

int mat_tostring(lua_State* L) {
  const Mat& m = self(L);
  std::string s = fmt::format("mat({}x{})", m.rows(), m.cols());
  const Eigen::Index show_rows = std::min<Eigen::Index>(m.rows(), 6), show_cols = std::min<Eigen::Index>(m.cols(), 8);
  for (Eigen::Index i = 0; i < show_rows; ++i) {
    s += "\n  [";
    for (Eigen::Index j = 0; j < show_cols; ++j) s += (j ? ", " : "") + fmt::format("{:.6g}", m(i, j));
    if (show_cols < m.cols()) s += ", ...";
    s += "]";
  }
  if (show_rows < m.rows()) s += fmt::format("\n  ... {} more rows", m.rows() - show_rows);
  lua_pushlstring(L, s.data(), s.size());
  return 1;
}

template <class Op>
int arith(lua_State* L, const char* name, Op op) {
  const Mat* a = lua::test_mat(L, 1);
  const Mat* b = lua::test_mat(L, 2);
  if (a && b) {
    if (a->rows() != b->rows() || a->cols() != b->cols())
      return luaL_error(L, "smi.mat %s: shapes differ (%dx%d and %dx%d)", name, (int)a->rows(), (int)a->cols(),
                        (int)b->rows(), (int)b->cols());
    push_mat(L, a->binaryExpr(*b, op));
  } else if (a) {
    const double y = luaL_checknumber(L, 2);
    push_mat(L, a->unaryExpr([&](double x) { return op(x, y); }));
  } else if (b) {
    const double x = luaL_checknumber(L, 1);
    push_mat(L, b->unaryExpr([&](double y) { return op(x, y); }));
  } else {
    return luaL_error(L, "smi.mat %s: no mat operand", name);
  }
  return 1;
}
int mat_add(lua_State* L) { return arith(L, "+", [](double x, double y) { return x + y; }); }
int mat_subtract(lua_State* L) { return arith(L, "-", [](double x, double y) { return x - y; }); }
int mat_mul(lua_State* L) { return arith(L, "*", [](double x, double y) { return x * y; }); }
int mat_div(lua_State* L) { return arith(L, "/", [](double x, double y) { return x / y; }); }
int mat_unm(lua_State* L) {
  push_mat(L, -self(L));
  return 1;
}

const luaL_Reg kMethods[] = {{"rows", mat_rows},       {"cols", mat_cols},         {"shape", mat_shape},
                             {"get", mat_getij},       {"set", mat_setij},         {"row", mat_row},
                             {"col", mat_col},         {"set_col", mat_set_col},   {"set_row", mat_set_row},
                             {"sub", mat_sub},         {"t", mat_t},               {"copy", mat_copy},
                             {"sum", mat_sum},         {"colmeans", mat_colmeans}, {"colstds", mat_colstds},
                             {"dot", mat_dot},         {"totable", mat_totable},   {"solve", mat_solve},
                             {"inverse", mat_inverse}, {"det", mat_det},           {"chol", mat_chol},
                             {nullptr, nullptr}};

const luaL_Reg kMeta[] = {{"__len", mat_len}, {"__tostring", mat_tostring}, {"__add", mat_add},
                          {"__sub", mat_subtract}, {"__mul", mat_mul}, {"__div", mat_div},
                          {"__unm", mat_unm}, {nullptr, nullptr}};

const luaL_Reg kMatFunctions[] = {{"zeros", mat_zeros}, {"identity", mat_identity}, {"hcat", mat_hcat},
                               {"vcat", mat_vcat},   {"eigh", mat_eigh},         {nullptr, nullptr}};

}  // namespace

void open_mat(lua_State* L) {
  lua::register_type<Eigen::MatrixXd>(L, lua::kMatType, kMethods, kMeta, mat_get);
  lua_newtable(L);
  luaL_setfuncs(L, kMatFunctions, 0);
  lua_newtable(L);
  lua_pushcfunction(L, mat_new);
  lua_setfield(L, -2, "__call");
  lua_setmetatable(L, -2);
  lua_setfield(L, -2, "mat");
}

}  // namespace smi::bind
