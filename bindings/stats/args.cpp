// SPDX-License-Identifier: MIT
#include "bindings/stats/args.hpp"

#include <fmt/format.h>

#include <cmath>

#include "platform/core/descriptive.hpp"

namespace smi::bind::stats {

double required(double v, const char* key, const char* fname) {
  if (std::isnan(v)) throw InvalidArgument(fmt::format("missing field '{}' (a number): add {} = ... to the options of {}", key, key, fname));
  return v;
}

Eigen::VectorXd data_arg(lua_State* L, int idx, const char* fname, Eigen::Index min_size) {
  if (lua_isnoneornil(L, idx)) luaL_error(L, "%s: data (argument %d) is missing: pass a vec or a table of numbers", fname, idx);
  if (!lua::test_vec(L, idx) && !lua_istable(L, idx))
    luaL_error(L, "%s: argument %d must be data (a vec or a table of numbers) or a distribution, got %s", fname, idx,
               luaL_typename(L, idx));
  Eigen::VectorXd x = lua::to_vector(L, idx, "data");
  lua::protect(L, fname, [&] {
    if (x.size() == 0) throw InvalidArgument("data is empty: pass at least " + std::to_string(min_size) + " number(s)");
    if (x.size() < min_size)
      throw InvalidArgument(fmt::format("data has {} point(s), need at least {}", x.size(), min_size));
    require_finite(x, "data");
    return 0;
  });
  return x;
}

void push_curve(lua_State* L, const Eigen::VectorXd& x, const Eigen::VectorXd* pdf, const Eigen::VectorXd* cdf) {
  lua_createtable(L, 0, 3);
  lua::set_vec(L, "x", x);
  if (pdf) lua::set_vec(L, "pdf", *pdf);
  if (cdf) lua::set_vec(L, "cdf", *cdf);
}

}  // namespace smi::bind::stats
