// SPDX-License-Identifier: MIT
#include "solve.hpp"

#include "eigen_solve.hpp"
#include "labels.hpp"
#include "model.hpp"

namespace cfe {

Results run_model(const Inputs& in) {
  const System sys = build_system(in);
  const Modes modes = solve_modes(sys.K, sys.M, 10);
  const Labels labels = label_modes(sys, modes);
  return make_results(in.airbag, sys.mesh.dof(), modes, labels, sys.M);
}

}  // namespace cfe
