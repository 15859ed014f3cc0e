// SPDX-License-Identifier: MIT
// smi.metric: area, pr, intersection, loglik, upool, upool_threshold, upool_pvalue, and the
// verdict object.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fmt/format.h>
#include <functional>
#include <memory>
#include <mutex>

#include "bindings/stats/args.hpp"
#include "bindings/stats/dist_box.hpp"
#include "bindings/stats/metric_options.hpp"
#include "bindings/stats/open_parts.hpp"
#include "kernels/stats/kde.hpp"
#include "kernels/stats/metrics.hpp"
#include "kernels/stats/upool.hpp"
#include "luax/luax.hpp"
#include "luax/run_context.hpp"
#include "luax/policy.hpp"
#include "platform/eval/progress_line.hpp"

namespace smi::bind::stats {
namespace {

constexpr const char* kVerdictType = "smi.verdict";

/// A distribution argument, or a sample (vec/table) turned into its normal-reference KDE.
smi::stats::DistributionPtr dist_or_kde(lua_State* L, int idx, const char* fname, const char* what) {
  if (auto d = test_distribution(L, idx)) return d;
  const Eigen::VectorXd x = data_arg(L, idx, fname, 2);
  smi::stats::DistributionPtr out;
  lua::protect(L, fname, [&] {
    out = smi::stats::make_kde(x, std::string("silverman"));
    return 0;
  });
  (void)what;
  return out;
}

/// Optional grid {lower =, upper =, nodes =} or nodes = n (a grid over both bulks) in the options
/// table at idx of smi.metric.pr (pr) or smi.metric.intersection: nullopt when neither is given.
std::optional<smi::stats::Grid> grid_option(lua_State* L, int idx, const char* fname, bool pr) {
  const OverlapArgs o = overlap_schema(pr).read(L, idx);
  if (!lua_istable(L, idx)) return std::nullopt;
  if (lua_getfield(L, idx, "grid") != LUA_TNIL) {
    if (!lua_istable(L, -1)) luaL_error(L, "%s: option 'grid' must be a table {lower =, upper =, nodes =}, got %s", fname, luaL_typename(L, -1));
    const GridArgs g = grid_schema(pr).read(L, -1);
    lua_pop(L, 1);
    // a Lua error, not required()'s exception: this runs outside protect()
    for (const auto& [key, v] : {std::pair<const char*, double>{"lower", g.lower}, {"upper", g.upper}})
      if (std::isnan(v)) luaL_error(L, "%s: missing field '%s' (a number): add grid = {%s = ...} to the options", fname, key, key);
    return smi::stats::Grid{g.lower, g.upper, g.nodes};
  }
  lua_pop(L, 1);
  const bool nodes_given = lua_getfield(L, idx, "nodes") != LUA_TNIL;
  lua_pop(L, 1);
  if (nodes_given) return smi::stats::Grid{0, 0, o.nodes};  // range filled later
  return std::nullopt;
}

smi::stats::Grid resolve_grid(const std::optional<smi::stats::Grid>& g, const smi::stats::Distribution& a, const smi::stats::Distribution& b) {
  if (g && g->hi > g->lo) {
    g->validate();
    return *g;
  }
  return smi::stats::comparison_grid(a, b, g ? g->n : kDefaultGridNodes);
}

/// PR (l1 = true) or intersection of a and b: exact between the pdf crossings without grid
/// options; on the grid when one is given (with a warning through the run's sink, and the exact integral
/// over the grid's range, when the grid does not resolve a pdf).
double overlap(lua_State* L, const char* fname, bool l1) {
  const auto a = dist_or_kde(L, 1, fname, "a");
  const auto b = dist_or_kde(L, 2, fname, "b");
  const auto g = grid_option(L, 3, fname, l1);
  double v = 0.0;
  lua::protect(L, fname, [&] {
    if (!g) {
      const smi::stats::PdfOverlap o = smi::stats::pdf_overlap(*a, *b);
      v = l1 ? o.l1 : o.intersection;
      return 0;
    }
    const smi::stats::GridComparison c = smi::stats::compare_on_grid(*a, *b, resolve_grid(g, *a, *b));
    for (const auto& w : c.warnings) lua::warn(L, fname, w);  // printed unless --quiet, and in smi.warnings()
    v = l1 ? c.pr : c.intersection;
    return 0;
  });
  return v;
}

/// smi.metric.pr(a, b [, {grid = {lower=, upper=, nodes=}} | {nodes = n}]) -> PR in [0, 2]
int m_pr(lua_State* L) {
  lua_pushnumber(L, overlap(L, "smi.metric.pr", true));
  return 1;
}

/// smi.metric.intersection(a, b [, grid options]) -> ∫ min(f_a, f_b) in [0, 1]
int m_intersection(lua_State* L) {
  lua_pushnumber(L, overlap(L, "smi.metric.intersection", false));
  return 1;
}

/// smi.metric.area(a, b): a, b each a sample (vec/table) or a distribution.
int m_area(lua_State* L) {
  const auto da = test_distribution(L, 1), db = test_distribution(L, 2);
  Eigen::VectorXd xa, xb;
  if (!da) xa = data_arg(L, 1, "smi.metric.area");
  if (!db) xb = data_arg(L, 2, "smi.metric.area");
  return lua::protect(L, "smi.metric.area", [&] {
    double v;
    if (!da && !db) v = smi::stats::area_metric_samples(xa, xb);
    else if (!da) v = smi::stats::area_metric(xa, *db);
    else if (!db) v = smi::stats::area_metric(xb, *da);
    else v = smi::stats::area_metric(*da, *db);
    lua_pushnumber(L, v);
    return 1;
  });
}

/// smi.metric.loglik(data, dist [, {floor = 1e-300}]) -> log L, number of floored densities
int m_loglik(lua_State* L) {
  const Eigen::VectorXd x = data_arg(L, 1, "smi.metric.loglik");
  const auto d = to_distribution(L, 2, "smi.metric.loglik: argument 2");
  const LoglikArgs o = loglik_schema().read(L, 3);
  return lua::protect(L, "smi.metric.loglik", [&] {
    int floored = 0;
    lua_pushnumber(L, smi::stats::loglik(x, *d, o.floor, &floored));
    lua_pushinteger(L, floored);
    return 2;
  });
}

/// The H0 Monte Carlo's progress line on a terminal (it takes seconds for n near 50 at 10^6 sets):
/// "u-pooling H0 Monte Carlo, n = 9: 1,000,000 sets, 45 %, ETA 1.2 s", at most 10 times a
/// second, from whichever worker finished a chunk; silent with --quiet or when stderr is not a
/// terminal.
std::function<void(double)> mc_progress(lua_State* L, int n, std::int64_t replications) {
  if (!lua::run_context(L).progress.live) return {};
  struct Line {
    std::mutex mu;
    std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now(), last{};
  };
  auto line = std::make_shared<Line>();
  return [line, n, replications, prefix = lua::run_context(L).progress.prefix()](double done) {
    std::lock_guard<std::mutex> lock(line->mu);
    const auto now = std::chrono::steady_clock::now();
    if (done < 1.0 && now - line->last < std::chrono::milliseconds(100)) return;  // literal: progress line refresh (ms) and percent
    line->last = now;
    const double elapsed = std::chrono::duration<double>(now - line->start).count();
    smi::eval::show_progress(stderr, prefix +
                             fmt::format("u-pooling H0 Monte Carlo, n = {}: {} sets, {:.0f} %, ETA {}", n, replications,
                                         100.0 * done, smi::eval::format_duration(elapsed * (1.0 - done) / done)),  // literal: percent
                             done >= 1.0);
  };
}

/// The MC settings as read by a schema, with the progress line for n u-values.
smi::stats::UpoolMcSettings mc_settings(lua_State* L, smi::stats::UpoolMcSettings s, lua_Integer n) {
  s.progress = mc_progress(L, static_cast<int>(n), s.replications);
  return s;
}

double check_confidence_arg(lua_State* L, int idx, const char* fname) {
  if (lua_isnoneornil(L, idx)) return smi::stats::kDefaultUpoolConfidence;
  const double c = luaL_checknumber(L, idx);
  if (!(c > 0.0 && c < 1.0)) luaL_error(L, "%s: confidence must be in (0, 1), e.g. 0.95; got %f", fname, c);
  return c;
}

/// smi.metric.upool_threshold(n, confidence [, {replications =, seed =}]) -> U_crit
int m_threshold(lua_State* L) {
  const lua_Integer n = luaL_checkinteger(L, 1);
  if (n < 1) return luaL_error(L, "smi.metric.upool_threshold: n must be >= 1 (the number of u-values), got %d", static_cast<int>(n));
  const double c = check_confidence_arg(L, 2, "smi.metric.upool_threshold");
  const smi::stats::UpoolMcSettings o = upool_mc_schema(true).read(L, 3);
  return lua::protect(L, "smi.metric.upool_threshold", [&] {
    lua_pushnumber(L, smi::stats::upool_threshold(static_cast<int>(n), c, mc_settings(L, o, n)));
    return 1;
  });
}

/// smi.metric.upool_pvalue(n, U [, {replications =, seed =}]) -> P_H0(U' >= U)
int m_pvalue(lua_State* L) {
  const lua_Integer n = luaL_checkinteger(L, 1);
  const double u = luaL_checknumber(L, 2);
  const smi::stats::UpoolMcSettings o = upool_mc_schema(false).read(L, 3);
  return lua::protect(L, "smi.metric.upool_pvalue", [&] {
    lua_pushnumber(L, smi::stats::upool_pvalue(static_cast<int>(n), u, mc_settings(L, o, n)));
    return 1;
  });
}

/// smi.metric.upool_statistic(u) -> U
int m_statistic(lua_State* L) {
  const Eigen::VectorXd u = data_arg(L, 1, "smi.metric.upool_statistic");
  return lua::protect(L, "smi.metric.upool_statistic", [&] {
    lua_pushnumber(L, smi::stats::upool_statistic(u));
    return 1;
  });
}

void push_verdict(lua_State* L, const smi::stats::UpoolVerdict& v) {
  lua_createtable(L, 0, 8);
  lua::set_number(L, "metric", v.metric);
  lua::set_number(L, "threshold", v.threshold);
  lua::set_number(L, "p", v.p);
  lua::set_boolean(L, "pass", v.pass);
  lua::set_number(L, "confidence", v.confidence);
  lua::set_integer(L, "n", v.n);
  lua::set_vec(L, "u", v.u);
  lua::set_string(L, "text", v.describe());
  luaL_setmetatable(L, kVerdictType);
}

/// Reads a verdict table back (for __tostring and curve).
smi::stats::UpoolVerdict read_verdict(lua_State* L, int idx) {
  luaL_checktype(L, idx, LUA_TTABLE);
  smi::stats::UpoolVerdict v;
  lua_getfield(L, idx, "metric"), v.metric = lua_tonumber(L, -1), lua_pop(L, 1);
  lua_getfield(L, idx, "threshold"), v.threshold = lua_tonumber(L, -1), lua_pop(L, 1);
  lua_getfield(L, idx, "p"), v.p = lua_tonumber(L, -1), lua_pop(L, 1);
  lua_getfield(L, idx, "pass"), v.pass = lua_toboolean(L, -1), lua_pop(L, 1);
  lua_getfield(L, idx, "confidence"), v.confidence = lua_tonumber(L, -1), lua_pop(L, 1);
  lua_getfield(L, idx, "n"), v.n = static_cast<int>(lua_tointeger(L, -1)), lua_pop(L, 1);
  lua_getfield(L, idx, "u");
  v.u = lua::to_vector(L, lua_gettop(L), "verdict.u");
  lua_pop(L, 1);
  return v;
}

int verdict_tostring(lua_State* L) {
  const smi::stats::UpoolVerdict v = read_verdict(L, 1);
  const std::string s = v.describe();
  lua_pushlstring(L, s.data(), s.size());
  return 1;
}

/// v:curve() -> {x =, y = (ECDF of u as steps), diagonal = {x = {0,1}, y = {0,1}}, threshold =}
int verdict_curve(lua_State* L) {
  const smi::stats::UpoolVerdict v = read_verdict(L, 1);
  Eigen::VectorXd x, y;
  smi::stats::upool_curve(v, x, y);
  lua_createtable(L, 0, 4);
  lua::set_vec(L, "x", x);
  lua::set_vec(L, "y", y);
  lua_createtable(L, 0, 2);
  lua::set_vec(L, "x", Eigen::Vector2d(0, 1));
  lua::set_vec(L, "y", Eigen::Vector2d(0, 1));
  lua_setfield(L, -2, "diagonal");
  lua::set_number(L, "metric", v.metric);
  lua::set_number(L, "threshold", v.threshold);
  return 1;
}

/// Collects data groups and their predicted distributions from the upool options table.
void read_groups(lua_State* L, int t, std::vector<Eigen::VectorXd>& data, std::vector<smi::stats::DistributionPtr>& pred) {
  lua_getfield(L, t, "predicted");
  lua_getfield(L, t, "data");
  const int ip = lua_absindex(L, -2), id = lua_absindex(L, -1);
  if (lua_isnil(L, id)) luaL_error(L, "smi.metric.upool: missing field 'data' (observations)");
  if (lua_isnil(L, ip)) luaL_error(L, "smi.metric.upool: missing field 'predicted' (a distribution, or one per group)");
  if (auto d = test_distribution(L, ip)) {  // one group under one prediction
    data.push_back(data_arg(L, id, "smi.metric.upool"));
    pred.push_back(d);
  } else {
    luaL_checktype(L, ip, LUA_TTABLE);
    const lua_Integer np = static_cast<lua_Integer>(lua_rawlen(L, ip));
    const bool flat = lua::test_vec(L, id) || (lua_istable(L, id) && lua_rawgeti(L, id, 1) == LUA_TNUMBER);
    if (lua_istable(L, id) && !lua::test_vec(L, id)) lua_pop(L, 1);
    if (flat) {  // datum i against predicted[i] (one site per datum)
      const Eigen::VectorXd x = data_arg(L, id, "smi.metric.upool");
      if (x.size() != np)
        luaL_error(L, "smi.metric.upool: data has %d values but predicted has %d distributions: give one per datum, or group the data",
                   static_cast<int>(x.size()), static_cast<int>(np));
      for (lua_Integer i = 1; i <= np; ++i) {
        lua_rawgeti(L, ip, i);
        data.push_back(Eigen::VectorXd::Constant(1, x[i - 1]));
        pred.push_back(to_distribution(L, -1, fmt::format("predicted[{}]", i).c_str()));
        lua_pop(L, 1);
      }
    } else {
      luaL_checktype(L, id, LUA_TTABLE);
      const lua_Integer nd = static_cast<lua_Integer>(lua_rawlen(L, id));
      if (nd != np)
        luaL_error(L, "smi.metric.upool: data has %d groups but predicted has %d: give one predicted distribution per group",
                   static_cast<int>(nd), static_cast<int>(np));
      for (lua_Integer i = 1; i <= nd; ++i) {
        lua_rawgeti(L, id, i);
        data.push_back(data_arg(L, lua_gettop(L), fmt::format("smi.metric.upool: data[{}]", i).c_str()));
        lua_pop(L, 1);
        lua_rawgeti(L, ip, i);
        pred.push_back(to_distribution(L, -1, fmt::format("predicted[{}]", i).c_str()));
        lua_pop(L, 1);
      }
    }
  }
  lua_pop(L, 2);
}

/// smi.metric.upool{data =, predicted =, confidence = 0.95, replications =, seed =} -> verdict
int m_upool(lua_State* L) {
  luaL_checktype(L, 1, LUA_TTABLE);
  const UpoolArgs o = upool_schema().read(L, 1);
  lua_getfield(L, 1, "confidence");
  const double c = check_confidence_arg(L, lua_gettop(L), "smi.metric.upool");
  lua_pop(L, 1);
  std::vector<Eigen::VectorXd> data;
  std::vector<smi::stats::DistributionPtr> pred;
  read_groups(L, 1, data, pred);
  return lua::protect(L, "smi.metric.upool", [&] {
    lua_Integer n = 0;  // u-values pooled over every group
    for (const auto& d : data) n += d.size();
    push_verdict(L, smi::stats::upool(data, pred, c, mc_settings(L, o, n)));
    return 1;
  });
}

}  // namespace

void open_metric(lua_State* L) {
  const luaL_Reg methods[] = {{"curve", verdict_curve}, {nullptr, nullptr}};
  const luaL_Reg meta[] = {{"__tostring", verdict_tostring}, {nullptr, nullptr}};
  lua::register_table_type(L, kVerdictType, methods, meta);
  const luaL_Reg fns[] = {{"pr", m_pr},
                          {"intersection", m_intersection},
                          {"area", m_area},
                          {"loglik", m_loglik},
                          {"upool", m_upool},
                          {"upool_threshold", m_threshold},
                          {"upool_pvalue", m_pvalue},
                          {"upool_statistic", m_statistic},
                          {nullptr, nullptr}};
  lua_newtable(L);
  lua::set_funcs(L, fns);
  lua_setfield(L, -2, "metric");
}

}  // namespace smi::bind::stats
