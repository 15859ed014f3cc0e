// SPDX-License-Identifier: MIT
// Conversions between Lua values and Eigen vectors/matrices. The Lua face of smi.vec and
// smi.mat (constructors, methods, arithmetic) is in bindings/vec.cpp and bindings/mat.cpp.
#include <cmath>

#include "luax/luax.hpp"

namespace smi::lua {

Eigen::VectorXd& push_vec(lua_State* L, Eigen::VectorXd v) { return push_box(L, kVecType, std::move(v)); }

Eigen::MatrixXd& push_mat(lua_State* L, Eigen::MatrixXd m) { return push_box(L, kMatType, std::move(m)); }

Eigen::VectorXd* test_vec(lua_State* L, int idx) { return test_box<Eigen::VectorXd>(L, idx, kVecType); }

Eigen::MatrixXd* test_mat(lua_State* L, int idx) { return test_box<Eigen::MatrixXd>(L, idx, kMatType); }

Eigen::VectorXd to_vector(lua_State* L, int idx, const char* what) {
  idx = lua_absindex(L, idx);
  if (auto* v = test_vec(L, idx)) return *v;
  if (auto* m = test_mat(L, idx)) {
    if (m->cols() == 1) return m->col(0);
    if (m->rows() == 1) return m->row(0).transpose();
    luaL_error(L, "%s must be a vector, got a %dx%d smi.mat", what, static_cast<int>(m->rows()),
               static_cast<int>(m->cols()));
  }
  if (!lua_istable(L, idx))
    luaL_error(L, "%s must be a smi.vec or a table of numbers, got %s", what, luaL_typename(L, idx));
  const lua_Integer n = luaL_len(L, idx);
  Eigen::VectorXd out(static_cast<Eigen::Index>(n));
  for (lua_Integer i = 1; i <= n; ++i) {
    int isnum = 0;
    lua_rawgeti(L, idx, i);
    out[static_cast<Eigen::Index>(i - 1)] = lua_tonumberx(L, -1, &isnum);
    if (!isnum || lua_type(L, -1) != LUA_TNUMBER)
      luaL_error(L, "%s[%d] must be a number, got %s", what, static_cast<int>(i), luaL_typename(L, -1));
    lua_pop(L, 1);
  }
  return out;
}

Eigen::MatrixXd to_matrix(lua_State* L, int idx, const char* what) {
  idx = lua_absindex(L, idx);
  if (auto* m = test_mat(L, idx)) return *m;
  if (auto* v = test_vec(L, idx)) return *v;  // one column
  if (!lua_istable(L, idx))
    luaL_error(L, "%s must be a smi.mat or a table of rows, got %s", what, luaL_typename(L, idx));
  const lua_Integer rows = luaL_len(L, idx);
  if (rows == 0) return Eigen::MatrixXd(0, 0);
  Eigen::MatrixXd out;
  char rowname[128];
  for (lua_Integer i = 1; i <= rows; ++i) {
    lua_rawgeti(L, idx, i);
    std::snprintf(rowname, sizeof rowname, "%s[%d]", what, static_cast<int>(i));
    if (lua_type(L, -1) == LUA_TNUMBER) {  // a flat table of numbers: one column
      lua_pop(L, 1);
      return to_vector(L, idx, what);
    }
    Eigen::VectorXd row = to_vector(L, -1, rowname);
    lua_pop(L, 1);
    if (i == 1) out.resize(static_cast<Eigen::Index>(rows), row.size());
    if (row.size() != out.cols())
      luaL_error(L, "%s has %d values but row 1 has %d; every row needs the same length", rowname,
                 static_cast<int>(row.size()), static_cast<int>(out.cols()));
    out.row(static_cast<Eigen::Index>(i - 1)) = row.transpose();
  }
  return out;
}

}  // namespace smi::lua
