// SPDX-License-Identifier: MIT
// smi.dist: the common Lua object of every distribution and density estimate.
#include "bindings/stats/dist_box.hpp"

#include <cmath>

#include "kernels/stats/ecdf.hpp"
#include "kernels/stats/kde.hpp"
#include "luax/luax.hpp"
#include "luax/memory.hpp"

namespace smi::bind {
namespace {

using Ptr = smi::stats::DistributionPtr;

const smi::stats::Distribution& dist_self(lua_State* L) { return *lua::check_box<Ptr>(L, 1, kDistType); }

/// d:pdf(x), d:cdf(x), d:quantile(p): x a number (-> number) or a vec/table (-> vec).
int dist_pdf(lua_State* L) {
  const smi::stats::Distribution& d = dist_self(L);
  return lua::push_mapped(L, 2, "dist:pdf", [&](const Eigen::VectorXd& x) { return d.pdf(x); });
}
int dist_cdf(lua_State* L) {
  const smi::stats::Distribution& d = dist_self(L);
  return lua::push_mapped(L, 2, "dist:cdf", [&](const Eigen::VectorXd& x) { return d.cdf(x); });
}
int dist_quantile(lua_State* L) {
  const smi::stats::Distribution& d = dist_self(L);
  return lua::push_mapped(L, 2, "dist:quantile", [&](const Eigen::VectorXd& p) {
    for (Eigen::Index i = 0; i < p.size(); ++i)
      if (!(p[i] > 0.0 && p[i] < 1.0) && !(p[i] == 0.0 || p[i] == 1.0))
        throw InvalidArgument("probability must be in [0, 1], got " + std::to_string(p[i]));
    return d.quantile(p);
  });
}
/// d:logpdf(x), d:logcdf(x), d:sf(x): in log space / as complements, so tails keep their
/// relative precision (d:sf(x) is not 1 − d:cdf(x) rounded).
template <double (smi::stats::Distribution::*F)(double) const>
int dist_scalar_map(lua_State* L, const char* fname) {
  const smi::stats::Distribution& d = dist_self(L);
  return lua::push_mapped(L, 2, fname, [&](const Eigen::VectorXd& x) {
    Eigen::VectorXd y(x.size());
    for (Eigen::Index i = 0; i < x.size(); ++i) y[i] = (d.*F)(x[i]);
    return y;
  });
}
int dist_logpdf(lua_State* L) { return dist_scalar_map<&smi::stats::Distribution::logpdf>(L, "dist:logpdf"); }
int dist_logcdf(lua_State* L) { return dist_scalar_map<&smi::stats::Distribution::logcdf>(L, "dist:logcdf"); }
int dist_sf(lua_State* L) { return dist_scalar_map<&smi::stats::Distribution::sf>(L, "dist:sf"); }
/// d:isf(q): x with sf(x) = q, q in [0, 1] (the upper-tail quantile without rounding 1 − q).
int dist_isf(lua_State* L) {
  const smi::stats::Distribution& d = dist_self(L);
  return lua::push_mapped(L, 2, "dist:isf", [&](const Eigen::VectorXd& q) {
    Eigen::VectorXd y(q.size());
    for (Eigen::Index i = 0; i < q.size(); ++i) {
      if (!(q[i] >= 0.0 && q[i] <= 1.0))
        throw InvalidArgument("upper-tail probability must be in [0, 1], got " + std::to_string(q[i]));
      y[i] = d.isf(q[i]);
    }
    return y;
  });
}
/// d:sample(n, seed_or_rng): n draws; the generator is explicit (an integer seed or an smi.rng).
int dist_sample(lua_State* L) {
  const smi::stats::Distribution& d = dist_self(L);
  const lua_Integer n = luaL_checkinteger(L, 2);
  luaL_argcheck(L, n >= 0, 2, "count must be >= 0");
  Rng* rng = lua::test_box<Rng>(L, 3, "smi.rng");
  Rng local(0);
  if (!rng) {
    if (!lua_isinteger(L, 3)) return luaL_error(L, "dist:sample: argument 3 must be an integer seed or an smi.rng");
    local = Rng(static_cast<std::uint64_t>(lua_tointeger(L, 3)));
    rng = &local;
  }
  return lua::protect(L, "dist:sample", [&] {
    lua::require_room(L, static_cast<double>(n), sizeof(double), "the sample");  // before drawing, not after
    lua::push_vec(L, d.sample(*rng, static_cast<Eigen::Index>(n)));
    return 1;
  });
}
int dist_mean(lua_State* L) {
  lua_pushnumber(L, dist_self(L).mean());
  return 1;
}
int dist_std(lua_State* L) {
  lua_pushnumber(L, dist_self(L).stddev());
  return 1;
}
int dist_support(lua_State* L) {
  const auto s = dist_self(L).support();
  lua_pushnumber(L, s.first);
  lua_pushnumber(L, s.second);
  return 2;
}
/// d:curve([n = 401]) -> {x =, pdf =, cdf =}: plot series over the bulk of the distribution
/// (a KDE: data range ± 4h; otherwise the 1e-4 and 1 − 1e-4 quantiles, or finite support ends).
/// An ECDF gives its steps {x =, cdf =} instead.
int dist_curve(lua_State* L) {
  const smi::stats::Distribution& d = dist_self(L);
  const lua_Integer n = luaL_optinteger(L, 2, kDefaultCurvePoints);
  luaL_argcheck(L, n >= 2 && n <= 10000000, 2, "number of points must be in 2..1e7");  // literal: the most points
  return lua::protect(L, "dist:curve", [&] {
    if (const auto* e = dynamic_cast<const smi::stats::Ecdf*>(&d)) {
      Eigen::VectorXd x, y;
      e->steps(x, y);
      lua_createtable(L, 0, 2);
      lua::set_vec(L, "x", x);
      lua::set_vec(L, "cdf", y);
      return 1;
    }
    double lo, hi;
    if (const auto* k = dynamic_cast<const smi::stats::Kde*>(&d)) {
      lo = k->data()[0] - 4 * k->bandwidth();
      hi = k->data()[k->data().size() - 1] + 4 * k->bandwidth();
    } else {
      const auto s = d.support();
      lo = std::isfinite(s.first) ? s.first : d.quantile(1e-4);  // literal: the plotted quantile range
      hi = std::isfinite(s.second) ? s.second : d.quantile(1 - 1e-4);  // literal: the plotted quantile range
    }
    const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(static_cast<Eigen::Index>(n), lo, hi);
    lua_createtable(L, 0, 3);
    lua::set_vec(L, "x", x);
    lua::set_vec(L, "pdf", d.pdf(x));
    lua::set_vec(L, "cdf", d.cdf(x));
    return 1;
  });
}
int dist_tostring(lua_State* L) {
  const std::string s = dist_self(L).describe();
  lua_pushlstring(L, s.data(), s.size());
  return 1;
}
/// d.family, and the numeric fields of the subtype (Distribution::field).
int dist_field(lua_State* L) {
  if (lua_type(L, 2) != LUA_TSTRING) return 0;
  const std::string key = lua_tostring(L, 2);
  if (key == "family") {
    lua_pushstring(L, dist_self(L).family().c_str());
    return 1;
  }
  if (const auto v = dist_self(L).field(key)) {
    lua_pushnumber(L, *v);
    return 1;
  }
  return 0;
}

const luaL_Reg kDistMethods[] = {{"pdf", dist_pdf},   {"cdf", dist_cdf}, {"quantile", dist_quantile},
                             {"sample", dist_sample}, {"mean", dist_mean}, {"std", dist_std},
                             {"support", dist_support}, {"curve", dist_curve}, {"logpdf", dist_logpdf},
                             {"logcdf", dist_logcdf}, {"sf", dist_sf},   {"isf", dist_isf},
                             {nullptr, nullptr}};
const luaL_Reg kDistMeta[] = {{"__tostring", dist_tostring}, {nullptr, nullptr}};

}  // namespace

void push_distribution(lua_State* L, smi::stats::DistributionPtr d) { lua::push_box<Ptr>(L, kDistType, std::move(d)); }

smi::stats::DistributionPtr test_distribution(lua_State* L, int idx) {
  Ptr* p = lua::test_box<Ptr>(L, idx, kDistType);
  return p ? *p : nullptr;
}

smi::stats::DistributionPtr to_distribution(lua_State* L, int idx, const char* what) {
  if (Ptr* p = lua::test_box<Ptr>(L, idx, kDistType)) return *p;
  luaL_error(L, "%s must be a distribution (smi.dist), got %s", what, luaL_typename(L, idx));
  return nullptr;
}

void register_distribution_type(lua_State* L) { lua::register_type<Ptr>(L, kDistType, kDistMethods, kDistMeta, dist_field); }

}  // namespace smi::bind
