// SPDX-License-Identifier: MIT
// The option schema of smi.screen (screen_options.hpp). Defaults: the kernel's structs'.
#include "bindings/surrogate/screen_options.hpp"

#include <limits>
#include <vector>

#include "kernels/surrogate/poly_ridge.hpp"

namespace smi::bind::surrogate {

using namespace smi::lua;

// long: one table of 17 entries, one per option in the reference's order (data, no logic)
const Schema<ScreenArgs>& screen_schema() {
  using S = ScreenArgs;
  namespace pf = smi::surrogate::polyfit;
  static const Schema<S> s("smi.screen", std::vector<Option<S>>{
      by_hand<S>("model", "(required)", "as smi.propagate"),
      by_hand<S>("inputs", "(required)", "as smi.propagate"),
      integer<S>("n", [](auto& s) -> auto& { return s.full.n; }, at_least(smi::surrogate::screen::kMinScreenN), "Monte Carlo size"),
      integer<S>("seed", [](auto& s) -> auto& { return s.full.seed; }, any_value(), "the sample's seed", "smi.seed"),
      string<S>("fix", [](auto& s) -> auto& { return s.full.fix; }, {}, "the value an input is fixed at: \"mean\" or \"median\""),
      boolean<S>("sobol", [](auto& s) -> auto& { return s.full.sobol; }, "also compute Sobol S1 and ST"),
      integer<S>("bootstrap", [](auto& s) -> auto& { return s.full.bootstrap; }, at_least(0), "resamples for the Sobol intervals (0 = none)"),
      number<S>("level", [](auto& s) -> auto& { return s.full.level; }, open(0.0, 1.0), "the intervals' level"),
      integer<S>("grid", [](auto& s) -> auto& { return s.full.grid; }, at_least(2), "grid nodes of the PDF areas"),
      Option<S>{"output", "with several outputs: the one to rank (default: all, by name)",
                [](lua_State* L, int v, S& s) { s.output = schema_detail::to_string(L, v, "output"); },
                [](const S&) { return std::string("nil"); }, {}},
      by_hand<S>("order", "nil", "as smi.propagate"),
      string<S>("method", &S::method, {},  // validated by the binding, with its own message
                "\"full\" (eq. 3 on the model) or \"surrogate\": a ridge-regularised quadratic\n"
                "(or linear) fit from `runs` model runs, checked by leave-one-out Q2, then\n"
                "eq. 3 on the surrogate at no model cost"),
      integer<S>("runs", [](auto& s) -> auto& { return s.surrogate.runs; }, at_least(smi::surrogate::screen::kMinSurrogateRuns), "surrogate: model runs of its Latin hypercube"),
      parsed<S>("basis", [](auto& s) -> auto& { return s.surrogate.basis; }, pf::parse_basis, pf::basis_name,
                "surrogate: \"quadratic\" (main effects and squares) or \"linear\""),
      number<S>("q2_min", [](auto& s) -> auto& { return s.surrogate.q2_min; }, Range{-std::numeric_limits<double>::infinity(), 1.0, false, false},
                "surrogate: a leave-one-out Q2 below this warns (add runs or use \"full\")"),
      boolean<S>("delta", [](auto& s) -> auto& { return s.surrogate.delta; }, "surrogate: also Borgonovo's given-data delta from the same runs"),
      integer<S>("classes", [](auto& s) -> auto& { return s.surrogate.delta_classes; }, at_least(2),
                 "surrogate: delta's conditioning classes (0: SALib's rule by run count)"),
  });
  return s;
}

}  // namespace smi::bind::surrogate
