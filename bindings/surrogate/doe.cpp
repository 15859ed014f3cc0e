// SPDX-License-Identifier: MIT
// smi.doe: designs of experiments.
//   smi.doe.lhs(n, space [, {seed, criterion = "maximin"|"phip"|"none", p, iterations, centered}])
//   smi.doe.sobol(n, space [, {skip}])
//   smi.doe.full_factorial({levels_1, levels_2, ...})  or  full_factorial(k, space)
// `space` is a dimension count (unit cube) or a table with one entry per input: {lo, hi}
// (scaled to the bounds) or an smi.dist (pushed through its quantile function).
// All return an smi.mat, rows = points.
#include <cmath>
#include <cstdio>
#include <variant>

#include "bindings/stats/dist_box.hpp"
#include "bindings/surrogate/doe_options.hpp"
#include "bindings/surrogate/open_parts.hpp"
#include "kernels/surrogate/doe.hpp"
#include "luax/luax.hpp"
#include "luax/run_context.hpp"
#include "luax/memory.hpp"
#include "luax/policy.hpp"

namespace smi::bind::surrogate {
namespace {

struct Dim {
  double lo = 0, hi = 1;
  smi::stats::DistributionPtr dist;
};

std::vector<Dim> read_space(lua_State* L, int idx, const char* fname) {
  std::vector<Dim> space;
  if (lua_isinteger(L, idx)) {
    const lua_Integer d = lua_tointeger(L, idx);
    if (d < 1 || d > 10000) luaL_error(L, "%s: dimension must be in 1..10000, got %d", fname, static_cast<int>(d));  // literal: the largest dimension
    space.resize(static_cast<std::size_t>(d));
    return space;
  }
  if (!lua_istable(L, idx))
    luaL_error(L, "%s: space must be a dimension count or a table of {lo, hi} pairs / smi.dist, got %s", fname,
               luaL_typename(L, idx));
  const lua_Integer len = static_cast<lua_Integer>(lua_rawlen(L, idx));
  if (len < 1) luaL_error(L, "%s: space is empty (one {lo, hi} or smi.dist per input)", fname);
  for (lua_Integer i = 1; i <= len; ++i) {
    lua_rawgeti(L, idx, i);
    Dim d;
    if (smi::stats::DistributionPtr p = test_distribution(L, -1)) {
      d.dist = p;
    } else if (lua_istable(L, -1) && lua_rawlen(L, -1) == 2) {
      lua_rawgeti(L, -1, 1);
      lua_rawgeti(L, -2, 2);
      if (!lua_isnumber(L, -2) || !lua_isnumber(L, -1))
        luaL_error(L, "%s: space[%d] must be {lo, hi} with numbers", fname, static_cast<int>(i));
      d.lo = lua_tonumber(L, -2), d.hi = lua_tonumber(L, -1);
      lua_pop(L, 2);
      if (!(std::isfinite(d.lo) && std::isfinite(d.hi) && d.lo < d.hi)) {
        char msg[160];  // lua_pushfstring has no %g
        std::snprintf(msg, sizeof msg, "space[%d] = {%g, %g} needs finite lo < hi", static_cast<int>(i), d.lo, d.hi);
        luaL_error(L, "%s: %s", fname, msg);
      }
    } else {
      luaL_error(L, "%s: space[%d] must be {lo, hi} or an smi.dist, got %s", fname, static_cast<int>(i),
                 luaL_typename(L, -1));
    }
    lua_pop(L, 1);
    space.push_back(d);
  }
  return space;
}

Eigen::MatrixXd map_space(const Eigen::MatrixXd& U, const std::vector<Dim>& space) {
  Eigen::MatrixXd X(U.rows(), U.cols());
  for (std::size_t k = 0; k < space.size(); ++k) {
    const auto c = static_cast<Eigen::Index>(k);
    if (space[k].dist)
      X.col(c) = space[k].dist->quantile(U.col(c));
    else
      X.col(c) = space[k].lo + (space[k].hi - space[k].lo) * U.col(c).array();
  }
  return X;
}

Eigen::Index check_n(lua_State* L, int arg, const char* fname) {
  if (!lua_isinteger(L, arg)) luaL_error(L, "%s: n must be an integer number of points", fname);
  const lua_Integer n = lua_tointeger(L, arg);
  if (n < 1 || n > (lua_Integer(1) << 28)) luaL_error(L, "%s: n must be in 1..2^28, got %d", fname, static_cast<int>(n));  // literal: the largest n
  return static_cast<Eigen::Index>(n);
}

int doe_lhs(lua_State* L) {
  const Eigen::Index n = check_n(L, 1, "smi.doe.lhs");
  const std::vector<Dim> space = read_space(L, 2, "smi.doe.lhs");
  LhsArgs lo;
  lo.seed = lua::run_context(L).seed;
  lhs_schema().read(L, 3, lo);
  const std::uint64_t seed = lo.seed;
  return lua::protect(L, "smi.doe.lhs", [&] {
    // The design, its copies while optimised, and the n x n distances the criterion keeps.
    const double nd = static_cast<double>(n) * static_cast<double>(space.size());
    lua::require_room(L, 3 * nd + (lo.criterion == "none" ? 0.0 : static_cast<double>(n) * static_cast<double>(n)),
                      sizeof(double), "the design");
    lua::push_mat(L, map_space(smi::surrogate::doe::lhs(n, static_cast<Eigen::Index>(space.size()), seed, lo, lua::cancel_token(L)), space));
    return 1;
  });
}

int doe_sobol(lua_State* L) {
  const Eigen::Index n = check_n(L, 1, "smi.doe.sobol");
  const std::vector<Dim> space = read_space(L, 2, "smi.doe.sobol");
  const Eigen::Index skip = sobol_schema().read(L, 3).skip;
  return lua::protect(L, "smi.doe.sobol", [&] {
    lua::require_room(L, 2.0 * static_cast<double>(n) * static_cast<double>(space.size()), sizeof(double), "the design");
    lua::push_mat(L, map_space(smi::surrogate::doe::sobol(n, static_cast<Eigen::Index>(space.size()), skip), space));
    return 1;
  });
}

int doe_full_factorial(lua_State* L) {
  std::vector<Eigen::VectorXd> levels;
  std::vector<Dim> space;
  lua_Integer k = 0;
  if (lua_isinteger(L, 1)) {  // k evenly spaced levels per input of `space`
    k = lua_tointeger(L, 1);
    if (k < 2) luaL_error(L, "smi.doe.full_factorial: need at least 2 levels, got %d", static_cast<int>(k));
    space = read_space(L, 2, "smi.doe.full_factorial");
  } else {
    luaL_checktype(L, 1, LUA_TTABLE);
    const lua_Integer len = static_cast<lua_Integer>(lua_rawlen(L, 1));
    char what[64];
    for (lua_Integer i = 1; i <= len; ++i) {
      lua_rawgeti(L, 1, i);
      std::snprintf(what, sizeof what, "levels[%d]", static_cast<int>(i));
      levels.push_back(lua::to_vector(L, -1, what));
      lua_pop(L, 1);
    }
  }
  return lua::protect(L, "smi.doe.full_factorial", [&] {
    // rows = the product of the level counts (k^d with a space): checked before any of it exists.
    double rows = 1;
    for (const auto& l : levels) rows *= static_cast<double>(l.size());
    for (std::size_t i = 0; i < space.size(); ++i) rows *= static_cast<double>(k);
    lua::require_room(L, rows * static_cast<double>(levels.size() + space.size()), sizeof(double), "the design");
    for (const Dim& d : space) {
      Eigen::VectorXd u = Eigen::VectorXd::LinSpaced(k, 0.0, 1.0);
      if (d.dist)  // cell midpoints: quantiles at 0 and 1 may be infinite
        u = (Eigen::VectorXd::LinSpaced(k, 0.0, static_cast<double>(k - 1)).array() + 0.5) / static_cast<double>(k);
      levels.push_back(d.dist ? d.dist->quantile(u) : Eigen::VectorXd(d.lo + (d.hi - d.lo) * u.array()));
    }
    lua::push_mat(L, smi::surrogate::doe::full_factorial(levels));
    return 1;
  });
}

const luaL_Reg kFuncs[] = {
    {"lhs", doe_lhs}, {"sobol", doe_sobol}, {"full_factorial", doe_full_factorial}, {nullptr, nullptr}};

}  // namespace

void open_doe(lua_State* L) {
  lua_newtable(L);
  lua::set_funcs(L, kFuncs);
  lua_pushinteger(L, smi::surrogate::doe::sobol_max_dim());
  lua_setfield(L, -2, "sobol_max_dim");
  lua_setfield(L, -2, "doe");
}

}  // namespace smi::bind::surrogate
