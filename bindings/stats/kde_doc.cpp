// Reference texts of smi.kde, smi.kde_bd, smi.kde_ebd, smi.ecdf, smi.bandwidth (kde_lua.cpp).
// Defaults are read from the kernels' option structs (stats/kde.hpp, stats/kde_bounded.hpp).
#include "bindings/doc.hpp"
#include "kernels/stats/kde.hpp"
#include "kernels/stats/kde_bounded.hpp"

namespace smi::bind {
namespace {

const char* const kText = R"DOC(
@ smi.kde(data [, opts]) -> dist
Gaussian kernel density estimate of data, with the bandwidth rule named by its formula or a fixed
bandwidth; large evaluations use a binned path with a stated error bound.
options:
  bandwidth = "silverman"  -- a number, or a rule: silverman, 1.06, robust, scott, mad, lscv, sj
  method = "auto"          -- "exact" sums, "binned" (linear binning, then exact Gaussian weights
                           -- over the bins; no FFT), or "auto" (binned for large data x points)
  tol = ${tol}             -- the binned path's error bound relative to the kernel peak, in (0, 0.1)
  threads = ${threads}     -- worker threads for large evaluations (results identical for any count)
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
  lower = (required)          -- the lower bound
  upper = (required)          -- the upper bound
  critical_area = ${critical_area}  -- stop when IA(previous, new) >= this
  step = ${step}              -- points added per iteration
  max_added = ${max_added}    -- the most points added; -1 means 10 n
  compare = "${compare}"      -- "previous" (the last KDE) or "data" (the KDE of the data only)
  bandwidth = "${bandwidth}"  -- the rule applied to the pooled points every iteration
  deterministic = false       -- place points at l + (u - l)(j - 1/2)/m instead of drawing them
  seed = smi.seed             -- the draws' seed
  grid_nodes = ${grid_nodes}  -- quadrature nodes of the intersection area
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
  alpha = 0.1                 -- the bounds' significance level
  unbiased = false            -- use the unbiased bound estimators
  critical_area = ${critical_area}  -- as smi.kde_bd
  step = ${step}              -- as smi.kde_bd
  max_added = ${max_added}    -- as smi.kde_bd
  compare = "${compare}"      -- as smi.kde_bd
  bandwidth = "${bandwidth}"  -- as smi.kde_bd
  deterministic = false       -- as smi.kde_bd
  seed = smi.seed             -- as smi.kde_bd
  grid_nodes = ${grid_nodes}  -- as smi.kde_bd
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
  const smi::stats::KdeOptions k;
  const smi::stats::BoundedKdeOptions b;
  return {"bindings/stats/kde_doc.cpp",
          fill(kText, {{"tol", num(k.binned_tol)},
                       {"threads", num(k.threads)},
                       {"critical_area", num(b.critical_area)},
                       {"step", num(b.step)},
                       {"max_added", num(b.max_added)},
                       {"compare", b.compare},
                       {"bandwidth", b.bandwidth},
                       {"grid_nodes", num(static_cast<double>(b.grid_nodes))}})};
}

}  // namespace smi::bind
