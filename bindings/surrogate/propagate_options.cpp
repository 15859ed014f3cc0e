// SPDX-License-Identifier: MIT
// The option schema of smi.propagate (propagate_options.hpp).
#include "bindings/surrogate/propagate_options.hpp"

#include <vector>

namespace smi::bind::surrogate {

using namespace smi::lua;

const Schema<PropagateArgs>& propagate_schema() {
  using S = PropagateArgs;
  static const Schema<S> s("smi.propagate", std::vector<Option<S>>{
      by_hand<S>("model", "(required)",
                 "an smi.kriging, a table of them by output name, a function(X) returning\n"
                 "{name = vec}, or an smi.model.* model"),
      by_hand<S>("inputs", "(required)", "{name = dist | number, ...} or {{name, dist | number}, ...} (ordered)"),
      integer<S>("n", &S::n, between(1, static_cast<double>(smi::surrogate::propagate::kMaxSampleSize)), "sample size"),
      integer<S>("seed", &S::seed, any_value(), "the sample's seed", "smi.seed"),
      by_hand<S>("order", "nil", "the input order for a function model (names)"),
  });
  return s;
}

}  // namespace smi::bind::surrogate
