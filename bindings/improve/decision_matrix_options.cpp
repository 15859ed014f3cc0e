// SPDX-License-Identifier: MIT
// The option schema of smi.refine.decision_matrix (decision_matrix_options.hpp).
#include "bindings/improve/decision_matrix_options.hpp"

#include <vector>

namespace smi::bind::improve {

using namespace smi::lua;
using smi::improve::DecisionOptions;

const Schema<DecisionOptions>& decision_matrix_schema() {
  using S = DecisionOptions;
  static const Schema<S> schema("smi.refine.decision_matrix", std::vector<Option<S>>{
      by_hand<S>("candidates", "(required)", "a list of names, or of tables with name = ... (passed to magnitudes)"),
      by_hand<S>("criteria", "(required)",
                 "{{name =, weight =, magnitude = function(candidate, j) | {values} |\n"
                 "{name = value}}, ...}"),
      number<S>("tie_tol", &S::tie_tol, at_least(0), "overall ratings closer than this are ties"),
  });
  return schema;
}

}  // namespace smi::bind::improve
