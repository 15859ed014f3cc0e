// SPDX-License-Identifier: MIT
// Reference texts of smi.kde, smi.kde_bd, smi.kde_ebd, smi.ecdf, smi.bandwidth (kde_lua.cpp).
// The option lists come from the functions' schemas (kde_options.cpp), defaults from their structs.
#include "bindings/doc.hpp"
#include "bindings/stats/kde_options.hpp"

namespace smi::bind {
namespace {

const char* const kText = R"DOC(
@ smi.kde(data [, opts]) -> dist
Gaussian kernel density estimate of data, with the bandwidth rule named by its formula or a fixed
bandwidth; large evaluations use a binned path with a stated error bound.
options:
${kde}
returns: a dist (smi.dist:* methods) with k.bandwidth and k.family = "kde"
errors: a rule needs at least 2 data ("pass a fixed bandwidth"); an unknown rule or option (the
  closest name is suggested); a non-finite datum
example:
  local k = smi.kde(smi.vec{30.12, 30.45, 29.88, 30.61, 30.02}, {bandwidth = "scott"})
  print(k.bandwidth, k:pdf(30.2))

@ smi.kde_bd(data, opts) -> dist, info
KDE with known bounded data (spec 1.2): points are added inside [lower, upper] until the
intersection area of successive KDEs reaches critical_area.
options:
${kde_bd}
returns: the KDE (with d.lower, d.upper, d.added, d.converged) and info = {lower =, upper =,
  added =, converged =, bandwidth =, added_points = vec, ia_history = vec, outside =}
errors: no opts or no bounds; lower >= upper; fewer than 2 data. Data outside the bounds are
  counted (info.outside) and warned about
example:
  local d, info = smi.kde_bd(smi.vec{0.2, 0.5, 0.7}, {lower = 0, upper = 1, seed = 1})
  print(d.added, info.converged)

@ smi.kde_ebd(data [, opts]) -> dist, info
KDE with estimated bounded data (spec 1.2): bounds from the data (min/max estimators with
c = alpha^(-1/n), or the unbiased ones), then the loop of smi.kde_bd.
options:
${kde_ebd}
returns: as smi.kde_bd
errors: fewer than 2 data; alpha outside (0, 1); an unknown option
example:
  local x = smi.vec{30.12, 30.45, 29.88, 30.61, 30.02, 29.75, 30.33, 30.90, 30.20}
  local e = smi.kde_ebd(x, {alpha = 0.1, seed = 1})
  print(("[%.3f, %.3f], %d added"):format(e.lower, e.upper, e.added))

@ smi.ecdf(data) -> dist
The empirical distribution: steps of 1/n at the sorted data; e:curve() gives the plot steps.
returns: a dist (family "ecdf")
errors: empty data; a non-finite datum
example:
  print(smi.ecdf(smi.vec{1, 2, 3}):cdf(2.5))

@ smi.bandwidth(data [, rule]) -> h
The bandwidth a rule gives for data, without building the KDE.
rule: silverman (default), 1.06, robust, scott, mad, lscv, sj.
returns: a number
errors: fewer than 2 data; an unknown rule (the known ones are listed)
example:
  print(smi.bandwidth(smi.vec{1, 2, 4, 7}, "sj"))
)DOC";

}  // namespace

DocText doc_stats_kde() {
  return {"bindings/stats/kde_doc.cpp",
          fill(kText, {{"kde", stats::kde_schema().doc()}, {"kde_bd", stats::kde_bd_schema().doc()}, {"kde_ebd", stats::kde_ebd_schema().doc()}})};
}

}  // namespace smi::bind
