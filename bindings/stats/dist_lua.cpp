// smi.dist.<family>{...} constructors and smi.dist.fit(data, {families}).
#include <fmt/format.h>

#include "bindings/stats/args.hpp"
#include "bindings/stats/dist_box.hpp"
#include "bindings/stats/open_parts.hpp"
#include "kernels/stats/families.hpp"
#include "kernels/stats/fit.hpp"
#include "luax/luax.hpp"

namespace smi::bind::stats {
namespace {

using lua::Options;

template <class Make>
int construct(lua_State* L, const char* fname, std::initializer_list<const char*> known, Make&& make) {
  Options o(L, 1, fname);
  if (!o.present()) return luaL_error(L, "%s: pass an options table, e.g. %s{...}", fname, fname);
  o.check_known(known);
  return lua::protect(L, fname, [&] {
    push_distribution(L, make(o));
    return 1;
  });
}

int d_normal(lua_State* L) {
  return construct(L, "smi.dist.normal", {"mean", "std"}, [](const Options& o) {
    return std::make_shared<smi::stats::Normal>(required_number(o, "mean", "smi.dist.normal"), required_number(o, "std", "smi.dist.normal"));
  });
}
int d_lognormal(lua_State* L) {
  return construct(L, "smi.dist.lognormal", {"mean", "std", "mu_log", "sigma_log"}, [](const Options& o) {
    if (o.has("mu_log") || o.has("sigma_log"))
      return std::make_shared<smi::stats::LogNormal>(smi::stats::LogNormal::from_log_params(required_number(o, "mu_log", "smi.dist.lognormal"),
                                                                    required_number(o, "sigma_log", "smi.dist.lognormal")));
    return std::make_shared<smi::stats::LogNormal>(smi::stats::LogNormal::from_moments(required_number(o, "mean", "smi.dist.lognormal"),
                                                               required_number(o, "std", "smi.dist.lognormal")));
  });
}
int d_uniform(lua_State* L) {
  return construct(L, "smi.dist.uniform", {"lower", "upper", "mean", "std"}, [](const Options& o) {
    if (o.has("mean") || o.has("std"))
      return std::make_shared<smi::stats::Uniform>(smi::stats::Uniform::from_moments(required_number(o, "mean", "smi.dist.uniform"),
                                                             required_number(o, "std", "smi.dist.uniform")));
    return std::make_shared<smi::stats::Uniform>(required_number(o, "lower", "smi.dist.uniform"), required_number(o, "upper", "smi.dist.uniform"));
  });
}
int d_truncnormal(lua_State* L) {
  return construct(L, "smi.dist.truncnormal", {"mean", "std", "lower", "upper"}, [](const Options& o) {
    const double inf = std::numeric_limits<double>::infinity();
    return std::make_shared<smi::stats::TruncNormal>(required_number(o, "mean", "smi.dist.truncnormal"),
                                         required_number(o, "std", "smi.dist.truncnormal"), o.number("lower", -inf),
                                         o.number("upper", inf));
  });
}
int d_weibull(lua_State* L) {
  return construct(L, "smi.dist.weibull", {"shape", "scale", "loc"}, [](const Options& o) {
    return std::make_shared<smi::stats::Weibull>(required_number(o, "shape", "smi.dist.weibull"), required_number(o, "scale", "smi.dist.weibull"),
                                     o.number("loc", 0.0));
  });
}
int d_gumbel(lua_State* L) {
  return construct(L, "smi.dist.gumbel", {"loc", "scale"}, [](const Options& o) {
    return std::make_shared<smi::stats::Gumbel>(required_number(o, "loc", "smi.dist.gumbel"), required_number(o, "scale", "smi.dist.gumbel"));
  });
}
int d_gamma(lua_State* L) {
  return construct(L, "smi.dist.gamma", {"shape", "scale", "rate", "loc"}, [](const Options& o) {
    const double k = required_number(o, "shape", "smi.dist.gamma");
    const double scale = o.has("rate") ? 1.0 / required_number(o, "rate", "smi.dist.gamma") : required_number(o, "scale", "smi.dist.gamma");
    return std::make_shared<smi::stats::Gamma>(k, scale, o.number("loc", 0.0));
  });
}
int d_beta(lua_State* L) {
  return construct(L, "smi.dist.beta", {"alpha", "beta", "lower", "upper"}, [](const Options& o) {
    return std::make_shared<smi::stats::Beta>(required_number(o, "alpha", "smi.dist.beta"), required_number(o, "beta", "smi.dist.beta"),
                                  o.number("lower", 0.0), o.number("upper", 1.0));
  });
}
int d_triangular(lua_State* L) {
  return construct(L, "smi.dist.triangular", {"lower", "mode", "upper"}, [](const Options& o) {
    return std::make_shared<smi::stats::Triangular>(required_number(o, "lower", "smi.dist.triangular"),
                                        required_number(o, "mode", "smi.dist.triangular"),
                                        required_number(o, "upper", "smi.dist.triangular"));
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
