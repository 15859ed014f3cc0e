// SPDX-License-Identifier: MIT
// The option schemas of the metrics (metric_options.hpp). Defaults: the kernels' structs.
#include "bindings/stats/metric_options.hpp"

#include <vector>

#include "luax/doc_text.hpp"

namespace smi::bind::stats {

using namespace smi::lua;
using smi::stats::UpoolMcSettings;

namespace {

/// replications and seed, shared by the u-pooling functions; `sets` words replications' doc.
template <class S>
std::vector<Option<S>> mc_options(const char* sets) {
  return {integer<S>("replications", &UpoolMcSettings::replications, at_least(smi::stats::kMinUpoolReplications), sets),
          integer<S>("seed", &UpoolMcSettings::seed, any_value(), "the Monte Carlo seed")};
}

}  // namespace

const Schema<LoglikArgs>& loglik_schema() {
  static const Schema<LoglikArgs> s("smi.metric.loglik", std::vector<Option<LoglikArgs>>{
                                                              number<LoglikArgs>("floor", &LoglikArgs::floor, finite_above(0), "the smallest density used")});
  return s;
}

const Schema<GridArgs>& grid_schema(bool pr) {
  using S = GridArgs;
  auto make = [](const char* fname) {
    return Schema<S>(fname, std::vector<Option<S>>{
        number<S>("lower", &S::lower, finite(), "the grid's lower end", "(required)"),
        number<S>("upper", &S::upper, finite(), "the grid's upper end", "(required)"),
        integer<S>("nodes", &S::nodes, at_least(2), "the number of grid nodes")});
  };
  // named after the function and the table, as its messages say: "smi.metric.pr grid: ..."
  static const Schema<S> p = make("smi.metric.pr grid");
  static const Schema<S> i = make("smi.metric.intersection grid");
  return pr ? p : i;
}

const Schema<OverlapArgs>& overlap_schema(bool pr) {
  using S = OverlapArgs;
  (void)grid_schema(pr);  // built with it: every schema the reference lists is checked by the tests
  auto make = [](const char* fname, const char* grid_doc, const char* nodes_doc) {
    return Schema<S>(fname, std::vector<Option<S>>{by_hand<S>("grid", "nil", grid_doc),
                                                   integer<S>("nodes", &S::nodes, at_least(2), nodes_doc)});
  };
  static const Schema<S> p = make("smi.metric.pr", "{lower =, upper =, nodes =}: the integration grid (default: both bulks)",
                                  "the number of grid nodes when grid is not given");
  static const Schema<S> i = make("smi.metric.intersection", "{lower =, upper =, nodes =}, as smi.metric.pr", "as smi.metric.pr");
  return pr ? p : i;
}

const Schema<UpoolArgs>& upool_schema() {
  static const Schema<UpoolArgs> s("smi.metric.upool", [] {
    std::vector<Option<UpoolArgs>> o{
        by_hand<UpoolArgs>("data", "(required)", "a vec/table, or a list of them (groups)"),
        by_hand<UpoolArgs>("predicted", "(required)", "a dist, or a list of dists (one per group or per datum)"),
        by_hand<UpoolArgs>("confidence", num(smi::stats::kDefaultUpoolConfidence), "the confidence of the threshold, in (0, 1)")};
    for (auto& e : mc_options<UpoolArgs>("Monte Carlo sets of n uniforms for the threshold")) o.push_back(std::move(e));
    return o;
  }());
  return s;
}

const Schema<UpoolMcSettings>& upool_mc_schema(bool threshold) {
  static const Schema<UpoolMcSettings> t("smi.metric.upool_threshold", mc_options<UpoolMcSettings>("Monte Carlo sets"));
  static const Schema<UpoolMcSettings> p("smi.metric.upool_pvalue", mc_options<UpoolMcSettings>("Monte Carlo sets"));
  return threshold ? t : p;
}

}  // namespace smi::bind::stats
