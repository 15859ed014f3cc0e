// SPDX-License-Identifier: MIT
// smi.kde(data, opts), smi.kde_bd(data, opts), smi.kde_ebd(data, opts), smi.ecdf(data).
#include <fmt/format.h>

#include "bindings/stats/args.hpp"
#include "bindings/stats/dist_box.hpp"
#include "bindings/stats/kde_options.hpp"
#include "bindings/stats/open_parts.hpp"
#include "kernels/stats/bandwidth.hpp"
#include "kernels/stats/ecdf.hpp"
#include "kernels/stats/kde.hpp"
#include "kernels/stats/kde_bounded.hpp"
#include "luax/luax.hpp"
#include "luax/run_context.hpp"
#include "luax/policy.hpp"

namespace smi::bind::stats {
namespace {

/// smi.kde(data [, {bandwidth = h | "rule", method = "auto"|"exact"|"binned", tol =, threads =}])
int kde_new(lua_State* L) {
  const Eigen::VectorXd x = data_arg(L, 1, "smi.kde");
  const KdeArgs ko = kde_schema().read(L, 2);
  const int bt = lua_istable(L, 2) ? lua_getfield(L, 2, "bandwidth") : (lua_pushnil(L), LUA_TNIL);
  std::string rule = "silverman";
  double h = 0.0;
  if (bt == LUA_TNUMBER) h = lua_tonumber(L, -1);
  else if (bt == LUA_TSTRING) rule = lua_tostring(L, -1);
  else if (bt != LUA_TNIL) return luaL_error(L, "smi.kde: bandwidth must be a number or a rule name such as \"silverman\", got %s", lua_typename(L, bt));
  lua_pop(L, 1);
  return lua::protect(L, "smi.kde", [&] {
    if (bt == LUA_TNUMBER) {
      push_distribution(L, smi::stats::make_kde(x, h, ko));
      return 1;
    }
    if (x.size() < 2)
      throw InvalidArgument(fmt::format("data has 1 point: the bandwidth rule '{}' needs at least 2; pass a fixed bandwidth, e.g. {{bandwidth = 0.1}}", rule));
    push_distribution(L, smi::stats::make_kde(x, rule, ko));
    return 1;
  });
}

/// Returns d (the KDE, with d.lower, d.upper, d.added) and an info table.
int push_bounded(lua_State* L, const smi::stats::BoundedKdeResult& r, int outside) {
  r.kde->set_field("lower", r.lower);
  r.kde->set_field("upper", r.upper);
  r.kde->set_field("added", r.added);
  r.kde->set_field("converged", r.converged ? 1.0 : 0.0);
  push_distribution(L, r.kde);
  lua_createtable(L, 0, 8);
  lua::set_number(L, "lower", r.lower);
  lua::set_number(L, "upper", r.upper);
  lua::set_integer(L, "added", r.added);
  lua::set_boolean(L, "converged", r.converged);
  lua::set_number(L, "bandwidth", r.kde->bandwidth());
  lua::set_vec(L, "added_points", r.added_points);
  lua::set_vec(L, "ia_history", Eigen::Map<const Eigen::VectorXd>(r.ia_history.data(), static_cast<Eigen::Index>(r.ia_history.size())));
  lua::set_integer(L, "outside", outside);
  return 2;
}

/// smi.kde_bd(data, {lower =, upper =, <loop options>})
int kde_bd(lua_State* L) {
  const Eigen::VectorXd x = data_arg(L, 1, "smi.kde_bd", 2);
  if (lua_isnoneornil(L, 2)) return luaL_error(L, "smi.kde_bd: pass the bounds, e.g. smi.kde_bd(data, {lower = 0, upper = 1})");
  KdeBdArgs b;
  b.seed = lua::run_context(L).seed;
  kde_bd_schema().read(L, 2, b);
  return lua::protect(L, "smi.kde_bd", [&] {
    const double lo = required(b.lower, "lower", "smi.kde_bd"), hi = required(b.upper, "upper", "smi.kde_bd");
    if (!(lo < hi)) throw InvalidArgument(fmt::format("lower ({}) must be < upper ({}): swap them", lo, hi));
    int outside = 0;
    const auto r = smi::stats::kde_bounded(x, lo, hi, b, &outside);
    if (outside > 0) {
      char w[160];
      std::snprintf(w, sizeof w, "%d data point(s) lie outside [%g, %g]", outside, lo, hi);
      lua::warn(L, "smi.kde_bd", w);  // the run's warning channel: result and terminal, never behind --quiet
    }
    return push_bounded(L, r, outside);
  });
}

/// smi.kde_ebd(data [, {alpha =, unbiased =, <loop options>}])
int kde_ebd_new(lua_State* L) {
  const Eigen::VectorXd x = data_arg(L, 1, "smi.kde_ebd", 2);
  KdeEbdArgs e;
  e.seed = lua::run_context(L).seed;
  kde_ebd_schema().read(L, 2, e);
  return lua::protect(L, "smi.kde_ebd", [&] {
    const auto r = smi::stats::kde_ebd(x, e.alpha, e.unbiased, e);
    return push_bounded(L, r, 0);
  });
}

/// smi.ecdf(data): the empirical distribution (steps i/n); e:steps() gives the plot series.
int ecdf_new(lua_State* L) {
  const Eigen::VectorXd x = data_arg(L, 1, "smi.ecdf");
  return lua::protect(L, "smi.ecdf", [&] {
    push_distribution(L, std::make_shared<smi::stats::Ecdf>(x));
    return 1;
  });
}

/// smi.bandwidth(data, rule) -> number
int bandwidth_fn(lua_State* L) {
  const Eigen::VectorXd x = data_arg(L, 1, "smi.bandwidth", 2);
  const std::string rule = luaL_optstring(L, 2, "silverman");
  return lua::protect(L, "smi.bandwidth", [&] {
    lua_pushnumber(L, smi::stats::bandwidth_by_name(x, rule));
    return 1;
  });
}

}  // namespace

void open_kde(lua_State* L) {
  const luaL_Reg fns[] = {{"kde", kde_new}, {"kde_bd", kde_bd}, {"kde_ebd", kde_ebd_new}, {"ecdf", ecdf_new},
                          {"bandwidth", bandwidth_fn}, {nullptr, nullptr}};
  lua::set_funcs(L, fns);
}

}  // namespace smi::bind::stats
