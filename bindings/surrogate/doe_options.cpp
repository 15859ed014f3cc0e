// SPDX-License-Identifier: MIT
// The option schemas of the designs of experiments (doe_options.hpp). Defaults: the structs'.
#include "bindings/surrogate/doe_options.hpp"

#include <vector>

namespace smi::bind::surrogate {

using namespace smi::lua;

const Schema<LhsArgs>& lhs_schema() {
  using S = LhsArgs;
  static const Schema<S> s("smi.doe.lhs", std::vector<Option<S>>{
      integer<S>("seed", &S::seed, any_value(), "the design's seed", "smi.seed"),
      string<S>("criterion", &S::criterion, {},  // the kernel names a bad one
                 "\"maximin\", \"phip\" or \"none\" (a random LHS)"),
      number<S>("p", &S::p, between(smi::surrogate::doe::kMinPhiP, smi::surrogate::doe::kMaxPhiP), "the exponent of phi_p"),
      integer<S>("iterations", &S::iterations, at_least(0), "ESE outer iterations; 0 = automatic by size"),
      boolean<S>("centered", &S::centered, "points at the cell centres instead of uniform in the cell"),
  });
  return s;
}

const Schema<smi::surrogate::doe::SobolOptions>& sobol_schema() {
  using S = smi::surrogate::doe::SobolOptions;
  static const Schema<S> s("smi.doe.sobol", std::vector<Option<S>>{
      integer<S>("skip", &S::skip, at_least(0), "points of the sequence skipped first"),
  });
  return s;
}

}  // namespace smi::bind::surrogate
