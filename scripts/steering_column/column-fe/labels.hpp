// SPDX-License-Identifier: MIT
#pragma once
// Mode labels by wheel-set participation (spec §8).
#include <array>
#include <Eigen/Core>
#include <string>

#include "eigen_solve.hpp"
#include "model.hpp"

namespace cfe {

/// Participation directions in the order of the results columns.
enum class Direction { axial, lateral, vertical, torsion, wheel_pitch, wheel_yaw };
const char* direction_name(Direction d);  // "AXIAL", ... as printed

struct Labels {
  Eigen::MatrixXd p;                 // modes x 6, p_kj in [0, 1]
  std::vector<Direction> direction;  // per mode, argmax_j p_kj
  std::array<int, 4> paper{-1, -1, -1, -1};  // 0-based mode index of paper modes 1..4, -1 if absent
};

/// The six rigid wheel motions psi_j (translations along a, l, v; rotations about a, l, v through H).
Eigen::MatrixXd wheel_motions(const Mesh& mesh);
Labels label_modes(const System& sys, const Modes& modes);

/// The direction that defines paper mode 1..4.
Direction paper_direction(int paper_mode);

}  // namespace cfe
