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
  return {integer<S>("replications", &UpoolMcSettings::replications, any_value(), sets),
          integer<S>("seed", &UpoolMcSettings::seed, any_value(), "the Monte Carlo seed")};
}

}  // namespace

const Schema<LoglikArgs>& loglik_schema() {
  static const Schema<LoglikArgs> s("smi.metric.loglik", std::vector<Option<LoglikArgs>>{
                                                              number<LoglikArgs>("floor", &LoglikArgs::floor, any_value(), "the smallest density used")});
  return s;
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
