// SPDX-License-Identifier: MIT
// Reference texts of smi.metric.* and the u-pooling verdict (metric_lua.cpp). The option lists
// come from the schemas (metric_options.cpp), whose defaults are the kernels' structs'.
#include "bindings/doc.hpp"
#include "bindings/stats/metric_options.hpp"
#include "kernels/stats/grid.hpp"
#include "kernels/stats/metrics.hpp"
#include "kernels/stats/upool.hpp"

namespace smi::bind {
namespace {

const char* const kMetricText = R"DOC(
@ module smi.metric
Validity and calibration metrics: probability residual, intersection area, area metric,
log-likelihood, and the u-pooling verdict with its Monte Carlo threshold.

@ smi.metric.pr(a, b [, opts]) -> number
The probability residual PR = integral of |f_a - f_b| (paper eq. 9), in [0, 2]. a and b are each a
dist or a sample (a vec/table, turned into its KDE).
options:
${pr_options}
returns: a number
errors: an argument neither a dist nor numbers (named); an unknown option
example:
  local x = smi.vec{30.12, 30.45, 29.88, 30.61, 30.02, 29.75, 30.33, 30.90, 30.20}
  print(smi.metric.pr(x, smi.dist.normal{mean = 30.25, std = 0.36}))

@ smi.metric.intersection(a, b [, opts]) -> number
The intersection area: the integral of min(f_a, f_b), in [0, 1] (1 for equal densities).
options:
${intersection_options}
returns: a number
errors: as smi.metric.pr
example:
  print(smi.metric.intersection(smi.dist.normal{mean = 0, std = 1}, smi.dist.normal{mean = 0.5, std = 1}))

@ smi.metric.area(a, b) -> number
The area metric: the integral of |F_a - F_b| between two CDFs (a sample's ECDF, or a dist), in the
variable's units.
returns: a number
errors: an argument neither a dist nor numbers
example:
  print(smi.metric.area(smi.vec{1, 2, 3}, smi.dist.normal{mean = 2, std = 1}))

@ smi.metric.loglik(data, dist [, opts]) -> logL, floored
The log-likelihood of data under dist; densities below floor are floored (and counted), so a
datum outside a KDE's reach gives a finite, very low value instead of -inf.
options:
${loglik_options}
returns: the sum of log densities, and the number of floored data
errors: data not numbers; dist not a distribution
example:
  print(smi.metric.loglik(smi.vec{0, 1}, smi.dist.normal{mean = 0, std = 1}))

@ smi.metric.upool{data =, predicted =} -> verdict
The u-pooling validity check (paper section 5): u_i = F_i(y_i) pooled over every prediction, their
area metric U against the uniform CDF, and the threshold U_crit(n, confidence) of U under H0: from
seeded Monte Carlo (cached per n) for n <= 50, from a fitted table of sqrt(n) U quantiles above
(n = 1: exact). data and predicted are one sample and one dist, a list of
groups and one dist per group, or one datum per dist.
options:
${upool_options}
returns: a verdict table {metric =, threshold =, p =, pass =, confidence =, n =, u = vec, text =};
  tostring(v) is its sentence, v:curve() its plot series
errors: data and predicted of different counts (both named); a missing field; confidence outside (0, 1)
example:
  local x = smi.vec{30.12, 30.45, 29.88, 30.61, 30.02, 29.75, 30.33, 30.90, 30.20}
  local v = smi.metric.upool{data = {x}, predicted = {smi.dist.normal{mean = 30.25, std = 0.36}}}
  print(v.pass, v)

@ smi.verdict:curve() -> {x =, y =, diagonal =, metric =, threshold =}
The plot series of a u-pooling verdict: the ECDF of the u-values as steps, and the diagonal.
returns: a table of vecs and numbers
errors: none
example:
  local v = smi.metric.upool{data = {smi.vec{0.1, -0.4, 0.3}}, predicted = {smi.dist.normal{mean = 0, std = 1}}}
  print(v:curve().x)

@ smi.metric.upool_threshold(n, confidence [, opts]) -> U_crit
The (confidence) quantile of U under H0 for n u-values. For n <= 50 from seeded Monte Carlo
(cached per n); for n > 50 from a fitted table of the quantiles of sqrt(n) U (replications and
seed then do not apply); n = 1 exact.
options:
${threshold_options}
returns: a number
errors: n < 1; confidence outside (0, 1); replications < 1000
example:
  print(smi.metric.upool_threshold(9, 0.95, {replications = 20000}))

@ smi.metric.upool_pvalue(n, U [, opts]) -> p
P(U' >= U) under H0 for n u-values.
options:
${pvalue_options}
returns: a number in [0, 1]
errors: n < 1; U not a number
example:
  print(smi.metric.upool_pvalue(9, 0.2, {replications = 20000}))

@ smi.metric.upool_statistic(u) -> U
U = integral over [0, 1] of |G_n(u) - u| for u-values in [0, 1], exact on every ECDF step.
returns: a number
errors: a u-value outside [0, 1]
example:
  print(smi.metric.upool_statistic(smi.vec{0.1, 0.5, 0.9}))
)DOC";

}  // namespace

DocText doc_stats_metric() {
  return {"bindings/stats/metric_doc.cpp",
          fill(kMetricText, {{"pr_options", stats::overlap_schema(true).doc()},
                       {"intersection_options", stats::overlap_schema(false).doc()},
                       {"loglik_options", stats::loglik_schema().doc()},
                       {"upool_options", stats::upool_schema().doc()},
                       {"threshold_options", stats::upool_mc_schema(true).doc()},
                       {"pvalue_options", stats::upool_mc_schema(false).doc()}})};
}

}  // namespace smi::bind
