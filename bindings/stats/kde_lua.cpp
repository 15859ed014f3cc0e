// smi.kde(data, opts), smi.kde_bd(data, opts), smi.kde_ebd(data, opts), smi.ecdf(data).
#include <fmt/format.h>

#include "bindings/stats/args.hpp"
#include "bindings/stats/dist_box.hpp"
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

using lua::Options;

smi::stats::KdeOptions kde_options(const Options& o) {
  smi::stats::KdeOptions k;
  const std::string m = o.string("method", "auto");
  if (m == "auto") k.method = smi::stats::KdeMethod::Auto;
  else if (m == "exact") k.method = smi::stats::KdeMethod::Exact;
  else if (m == "binned") k.method = smi::stats::KdeMethod::Binned;
  else throw InvalidArgument(fmt::format("method must be \"auto\", \"exact\" or \"binned\", got \"{}\"", m));
  k.binned_tol = o.number("tol", k.binned_tol);
  if (!(k.binned_tol > 0.0 && k.binned_tol < 0.1)) throw InvalidArgument(fmt::format("tol must be in (0, 0.1), got {}", k.binned_tol));
  k.threads = static_cast<int>(o.integer("threads", k.threads));
  if (k.threads < 1 || k.threads > 64) throw InvalidArgument(fmt::format("threads must be in 1..64, got {}", k.threads));
  return k;
}

/// smi.kde(data [, {bandwidth = h | "rule", method = "auto"|"exact"|"binned", tol =, threads =}])
int kde_new(lua_State* L) {
  const Eigen::VectorXd x = data_arg(L, 1, "smi.kde");
  Options o(L, 2, "smi.kde");
  o.check_known({"bandwidth", "method", "tol", "threads"});
  const int bt = o.push("bandwidth");
  std::string rule = "silverman";
  double h = 0.0;
  if (bt == LUA_TNUMBER) h = lua_tonumber(L, -1);
  else if (bt == LUA_TSTRING) rule = lua_tostring(L, -1);
  else if (bt != LUA_TNIL) return luaL_error(L, "smi.kde: bandwidth must be a number or a rule name such as \"silverman\", got %s", lua_typename(L, bt));
  lua_pop(L, 1);
  return lua::protect(L, "smi.kde", [&] {
    const smi::stats::KdeOptions ko = kde_options(o);
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

smi::stats::BoundedKdeOptions bounded_options(lua_State* L, const Options& o) {
  smi::stats::BoundedKdeOptions b;
  b.critical_area = o.number("critical_area", b.critical_area);
  b.step = static_cast<int>(o.integer("step", b.step));
  b.max_added = static_cast<int>(o.integer("max_added", b.max_added));
  b.compare = o.string("compare", b.compare);
  b.bandwidth = o.string("bandwidth", b.bandwidth);
  b.deterministic = o.boolean("deterministic", b.deterministic);
  b.seed = static_cast<std::uint64_t>(o.integer("seed", static_cast<lua_Integer>(lua::run_context(L).seed)));
  b.grid_nodes = static_cast<Eigen::Index>(o.integer("grid_nodes", b.grid_nodes));
  return b;
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
  Options o(L, 2, "smi.kde_bd");
  if (!o.present()) return luaL_error(L, "smi.kde_bd: pass the bounds, e.g. smi.kde_bd(data, {lower = 0, upper = 1})");
  return lua::protect(L, "smi.kde_bd", [&] {
    o.check_known({"lower", "upper", "critical_area", "step", "max_added", "compare", "bandwidth", "deterministic", "seed", "grid_nodes"});
    const double lo = required_number(o, "lower", "smi.kde_bd"), hi = required_number(o, "upper", "smi.kde_bd");
    if (!(lo < hi)) throw InvalidArgument(fmt::format("lower ({}) must be < upper ({}): swap them", lo, hi));
    int outside = 0;
    const auto r = smi::stats::kde_bounded(x, lo, hi, bounded_options(L, o), &outside);
    if (outside > 0) {
      char w[160];
      std::snprintf(w, sizeof w, "%d data point(s) lie outside [%g, %g]", outside, lo, hi);
      lua::warn(L, "smi.kde_bd", w);  // the run's warning channel: result and terminal, never behind --quiet
    }
    return push_bounded(L, r, outside);
  });
}

/// smi.kde_ebd(data [, {alpha = 0.1, unbiased = false, <loop options>}])
int kde_ebd_new(lua_State* L) {
  const Eigen::VectorXd x = data_arg(L, 1, "smi.kde_ebd", 2);
  Options o(L, 2, "smi.kde_ebd");
  return lua::protect(L, "smi.kde_ebd", [&] {
    o.check_known({"alpha", "unbiased", "critical_area", "step", "max_added", "compare", "bandwidth", "deterministic", "seed", "grid_nodes"});
    const auto r = smi::stats::kde_ebd(x, o.number("alpha", 0.1), o.boolean("unbiased", false), bounded_options(L, o));
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
