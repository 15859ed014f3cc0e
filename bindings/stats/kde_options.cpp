// SPDX-License-Identifier: MIT
// The option schemas of the KDE functions (kde_options.hpp). Defaults: the structs'.
#include "bindings/stats/kde_options.hpp"

#include <vector>

#include "platform/core/defaults.hpp"

namespace smi::bind::stats {

using namespace smi::lua;
using smi::stats::BoundedKdeOptions;
using smi::stats::KdeMethod;

namespace {

/// The bounded-KDE loop's options, shared by kde_bd and kde_ebd (`as` prefixes kde_ebd's docs).
template <class S>
std::vector<Option<S>> loop_options(bool as_bd) {
  auto d = [&](const char* own) { return as_bd ? own : "as smi.kde_bd"; };
  return {
      number<S>("critical_area", &BoundedKdeOptions::critical_area, Range{0.0, 1.0, true, false}, d("stop when IA(previous, new) >= this")),
      integer<S>("step", &BoundedKdeOptions::step, at_least(1), d("points added per iteration")),
      integer<S>("max_added", &BoundedKdeOptions::max_added, at_least(-1), d("the most points added; -1 means 10 n")),
      string<S>("compare", &BoundedKdeOptions::compare, {}, d("\"previous\" (the last KDE) or \"data\" (the KDE of the data only)")),
      string<S>("bandwidth", &BoundedKdeOptions::bandwidth, {}, d("the rule applied to the pooled points every iteration")),
      boolean<S>("deterministic", &BoundedKdeOptions::deterministic,
                 d("place points at l + (u - l)(j - 1/2)/m instead of drawing them")),
      integer<S>("seed", &BoundedKdeOptions::seed, any_value(), d("the draws' seed"), "smi.seed"),
      integer<S>("grid_nodes", &BoundedKdeOptions::grid_nodes, at_least(static_cast<double>(smi::kMinGridNodes)), d("quadrature nodes of the intersection area")),
  };
}

}  // namespace

const Schema<KdeArgs>& kde_schema() {
  static const Schema<KdeArgs> s(
      "smi.kde",
      {by_hand<KdeArgs>("bandwidth", "\"silverman\"", "a number, or a rule: silverman, 1.06, robust, scott, mad, lscv, sj"),
       choice<KdeArgs>("method", &KdeArgs::method, Names<KdeMethod>{{"auto", KdeMethod::Auto}, {"exact", KdeMethod::Exact}, {"binned", KdeMethod::Binned}},
              "\"exact\" sums, \"binned\" (linear binning, then exact Gaussian weights\n"
              "over the bins; no FFT), or \"auto\" (binned for large data x points)"),
       number<KdeArgs>("tol", &KdeArgs::binned_tol, open(0, 0.1), "the binned path's error bound relative to the kernel peak, in (0, 0.1)"),  // literal: the range of tol
       integer<KdeArgs>("threads", &KdeArgs::threads, between(1, 64), "worker threads for large evaluations (results identical for any count)")});  // literal: the range of threads
  return s;
}

const Schema<KdeBdArgs>& kde_bd_schema() {
  static const Schema<KdeBdArgs> s("smi.kde_bd", [] {
    std::vector<Option<KdeBdArgs>> o{number<KdeBdArgs>("lower", &KdeBdArgs::lower, finite(), "the lower bound", "(required)"),
                                     number<KdeBdArgs>("upper", &KdeBdArgs::upper, finite(), "the upper bound", "(required)")};
    for (auto& e : loop_options<KdeBdArgs>(true)) o.push_back(std::move(e));
    return o;
  }());
  return s;
}

const Schema<KdeEbdArgs>& kde_ebd_schema() {
  static const Schema<KdeEbdArgs> s("smi.kde_ebd", [] {
    std::vector<Option<KdeEbdArgs>> o{
        number<KdeEbdArgs>("alpha", &smi::stats::EbdBoundsOptions::alpha, open(0.0, 1.0), "the bounds' significance level"),
        boolean<KdeEbdArgs>("unbiased", &smi::stats::EbdBoundsOptions::unbiased, "use the unbiased bound estimators")};
    for (auto& e : loop_options<KdeEbdArgs>(false)) o.push_back(std::move(e));
    return o;
  }());
  return s;
}

}  // namespace smi::bind::stats
