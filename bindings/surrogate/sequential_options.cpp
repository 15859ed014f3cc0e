// SPDX-License-Identifier: MIT
// The option schema of smi.kriging.sequential (sequential_options.hpp). Defaults: the kernel's.
#include "bindings/surrogate/sequential_options.hpp"

#include <limits>

#include "kernels/surrogate/correlation.hpp"
#include "kernels/surrogate/regression.hpp"

namespace smi::bind::surrogate {

using namespace smi::lua;
namespace kr = smi::surrogate::kriging;

const Schema<SequentialArgs>& sequential_schema() {
  using S = SequentialArgs;
  static const Schema<S> s("smi.kriging.sequential", std::vector<Option<S>>{
      by_hand<S>("model", "(required)", "an smi.model, a function of the sample matrix, or a model object"),
      by_hand<S>("design", "(required)", "the initial points (mat, columns = the model's inputs)"),
      by_hand<S>("candidates", "(required)", "the points it may add (mat, same columns)"),
      by_hand<S>("weights", "1", "a vec, one per candidate (> 0; 0: never chosen)"),
      integer<S>("batch", [](auto& s) -> auto& { return s.so.batch; }, at_least(1), "points per model call"),
      integer<S>("max", [](auto& s) -> auto& { return s.so.max_points; }, at_least(1), "the design never grows past this"),
      number<S>("q2", [](auto& s) -> auto& { return s.so.q2_target; }, Range{-std::numeric_limits<double>::infinity(), 1.0, false, false}, "leave-one-out Q2 every output must reach"),
      by_hand<S>("rmse", "{}", "{output = target}: leave-one-out RMSE in the output's units"),
      parsed<S>("trend", [](auto& s) -> auto& { return s.so.fit.trend; }, kr::parse_trend, kr::trend_name, "the Krigings' trend"),
      parsed<S>("corr", [](auto& s) -> auto& { return s.so.fit.corr; }, kr::parse_corr, kr::corr_name, "the Krigings' correlation family"),
      integer<S>("seed", [](auto& s) -> auto& { return s.so.fit.seed; }, any_value(), "the Krigings' multistart seed", "smi.seed"),
      by_hand<S>("inputs", "(the model's)", "input names the Krigings carry"),
  });
  return s;
}

}  // namespace smi::bind::surrogate
