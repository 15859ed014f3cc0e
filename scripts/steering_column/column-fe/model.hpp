// SPDX-License-Identifier: MIT
#pragma once
// The steering-column model of spec §5-§6: parts, sections, supports and the airbag variants,
// assembled into K and M.
#include <Eigen/Core>

#include "inputs.hpp"
#include "mesh.hpp"

namespace cfe {

struct ModelOptions {
  /// false drops the bushes, the two brackets and the tilt lock: the free-free check of §11
  /// (exactly six rigid-body modes).
  bool supports = true;
};

struct System {
  Mesh mesh;
  Eigen::MatrixXd K, M;  // over all (free) DOF, 6 per node
};

/// Throws std::invalid_argument for inputs outside their domain (a library caller may skip the
/// deck parser).
System build_system(const Inputs& in, const ModelOptions& opt = {});

}  // namespace cfe
