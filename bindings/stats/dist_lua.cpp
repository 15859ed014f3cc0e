// SPDX-License-Identifier: MIT
// smi.dist.<family>{...} constructors and smi.dist.fit(data, {families}).
#include <fmt/format.h>

#include <cmath>
#include <string>

#include "bindings/stats/args.hpp"
#include "bindings/stats/dist_box.hpp"
#include "bindings/stats/dist_options.hpp"
#include "bindings/stats/open_parts.hpp"
#include "kernels/stats/families.hpp"
#include "kernels/stats/fit.hpp"
#include "luax/luax.hpp"

namespace smi::bind::stats {
namespace {

/// Reads the family's options with its schema (dist_options.cpp) and pushes make(args) as a dist.
/// A parameter given as NaN is refused here: NaN stands for "not given" in the option structs.
template <class S, class Make>
int construct(lua_State* L, const char* fname, const lua::Schema<S>& schema, Make&& make) {
  if (lua_isnoneornil(L, 1)) return luaL_error(L, "%s: pass an options table, e.g. %s{...}", fname, fname);
  const S args = schema.read(L, 1);
  for (const std::string& k : schema.keys()) {
    const bool nan = lua_getfield(L, 1, k.c_str()) == LUA_TNUMBER && std::isnan(lua_tonumber(L, -1));
    lua_pop(L, 1);
    if (nan) return luaL_error(L, "%s: %s must be finite, got nan", fname, k.c_str());
  }
  return lua::protect(L, fname, [&] {
    push_distribution(L, make(args));
    return 1;
  });
}

/// Whether a parameter was given (the option structs hold NaN until it is).
bool given(double v) { return !std::isnan(v); }

int d_normal(lua_State* L) {
  const char* f = "smi.dist.normal";
  return construct(L, f, normal_schema(), [f](const NormalArgs& a) {
    return std::make_shared<smi::stats::Normal>(required(a.mean, "mean", f), required(a.std, "std", f));
  });
}
int d_lognormal(lua_State* L) {
  const char* f = "smi.dist.lognormal";
  return construct(L, f, lognormal_schema(), [f](const LognormalArgs& a) {
    if (given(a.mu_log) || given(a.sigma_log))
      return std::make_shared<smi::stats::LogNormal>(
          smi::stats::LogNormal::from_log_params(required(a.mu_log, "mu_log", f), required(a.sigma_log, "sigma_log", f)));
    return std::make_shared<smi::stats::LogNormal>(smi::stats::LogNormal::from_moments(required(a.mean, "mean", f), required(a.std, "std", f)));
  });
}
int d_uniform(lua_State* L) {
  const char* f = "smi.dist.uniform";
  return construct(L, f, uniform_schema(), [f](const UniformArgs& a) {
    if (given(a.mean) || given(a.std))
      return std::make_shared<smi::stats::Uniform>(smi::stats::Uniform::from_moments(required(a.mean, "mean", f), required(a.std, "std", f)));
    return std::make_shared<smi::stats::Uniform>(required(a.lower, "lower", f), required(a.upper, "upper", f));
  });
}
int d_truncnormal(lua_State* L) {
  const char* f = "smi.dist.truncnormal";
  return construct(L, f, truncnormal_schema(), [f](const TruncnormalArgs& a) {
    return std::make_shared<smi::stats::TruncNormal>(required(a.mean, "mean", f), required(a.std, "std", f), a.lower, a.upper);
  });
}
int d_weibull(lua_State* L) {
  const char* f = "smi.dist.weibull";
  return construct(L, f, weibull_schema(), [f](const WeibullArgs& a) {
    return std::make_shared<smi::stats::Weibull>(required(a.shape, "shape", f), required(a.scale, "scale", f), a.loc);
  });
}
int d_gumbel(lua_State* L) {
  const char* f = "smi.dist.gumbel";
  return construct(L, f, gumbel_schema(), [f](const GumbelArgs& a) {
    return std::make_shared<smi::stats::Gumbel>(required(a.loc, "loc", f), required(a.scale, "scale", f));
  });
}
int d_gamma(lua_State* L) {
  const char* f = "smi.dist.gamma";
  return construct(L, f, gamma_schema(), [f](const GammaArgs& a) {
    const double k = required(a.shape, "shape", f);
    const double scale = given(a.rate) ? 1.0 / a.rate : required(a.scale, "scale", f);
    return std::make_shared<smi::stats::Gamma>(k, scale, a.loc);
  });
}
int d_beta(lua_State* L) {
  const char* f = "smi.dist.beta";
  return construct(L, f, beta_schema(), [f](const BetaArgs& a) {
    return std::make_shared<smi::stats::Beta>(required(a.alpha, "alpha", f), required(a.beta, "beta", f), a.lower, a.upper);
  });
}
int d_triangular(lua_State* L) {
  const char* f = "smi.dist.triangular";
  return construct(L, f, triangular_schema(), [f](const TriangularArgs& a) {
    return std::make_shared<smi::stats::Triangular>(required(a.lower, "lower", f), required(a.mode, "mode", f), required(a.upper, "upper", f));
  });
}

/// smi.dist.fit(data [, {families}]) -> ranked list of {family, dist, loglik, aic, bic, ks, k};
/// the list also has .best (the first dist).
int d_fit(lua_State* L) {
  const Eigen::VectorXd x = data_arg(L, 1, "smi.dist.fit", 2);
  std::vector<std::string> fams = {"normal", "lognormal", "uniform", "weibull", "gumbel", "gamma"};
  if (!lua_isnoneornil(L, 2)) fams = lua::to_strings(L, 2, "families");
  return lua::protect(L, "smi.dist.fit", [&] {
    const auto res = smi::stats::fit(x, fams);
    lua_createtable(L, static_cast<int>(res.size()), 1);
    for (std::size_t i = 0; i < res.size(); ++i) {
      const auto& r = res[i];
      lua_createtable(L, 0, 8);
      lua::set_string(L, "family", r.family);
      push_distribution(L, r.dist);
      lua_setfield(L, -2, "dist");
      lua::set_number(L, "loglik", r.loglik);
      lua::set_number(L, "aic", r.aic);
      lua::set_number(L, "bic", r.bic);
      lua::set_number(L, "ks", r.ks);
      lua::set_integer(L, "k", r.k);
      lua::set_integer(L, "rank", static_cast<lua_Integer>(i + 1));
      lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
    }
    push_distribution(L, res.front().dist);
    lua_setfield(L, -2, "best");
    return 1;
  });
}

const luaL_Reg kDist[] = {{"normal", d_normal},     {"lognormal", d_lognormal}, {"uniform", d_uniform},
                          {"truncnormal", d_truncnormal}, {"weibull", d_weibull}, {"gumbel", d_gumbel},
                          {"gamma", d_gamma},       {"beta", d_beta},           {"triangular", d_triangular},
                          {"fit", d_fit},           {nullptr, nullptr}};

}  // namespace

void open_dist(lua_State* L) {
  lua_newtable(L);
  lua::set_funcs(L, kDist);
  lua_setfield(L, -2, "dist");
}

}  // namespace smi::bind::stats
