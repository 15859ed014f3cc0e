// SPDX-License-Identifier: MIT
#include "labels.hpp"

namespace cfe {

const char* direction_name(Direction d) {
  static const char* names[] = {"AXIAL", "LATERAL", "VERTICAL", "TORSION", "WHEEL_PITCH", "WHEEL_YAW"};
  return names[static_cast<int>(d)];
}

Direction paper_direction(int paper_mode) {
  static const Direction d[4] = {Direction::vertical, Direction::lateral, Direction::torsion, Direction::wheel_pitch};
  return d[paper_mode - 1];
}

Eigen::MatrixXd wheel_motions(const Mesh& mesh) {
  const Axes& ax = axes();
  const Vec3 e[3] = {ax.a, ax.l, ax.v};
  const Vec3 XH = mesh.nodes[mesh.hub].x;
  Eigen::MatrixXd psi = Eigen::MatrixXd::Zero(mesh.dof(), 6);
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n) {
    if (!mesh.nodes[n].wheel) continue;
    const Eigen::Index r = 6 * static_cast<Eigen::Index>(n);
    for (int j = 0; j < 3; ++j) {
      psi.block<3, 1>(r, j) = e[j];
      psi.block<3, 1>(r, 3 + j) = e[j].cross(mesh.nodes[n].x - XH);
      psi.block<3, 1>(r + 3, 3 + j) = e[j];
    }
  }
  return psi;
}

Labels label_modes(const System& sys, const Modes& modes) {
  const Eigen::MatrixXd psi = wheel_motions(sys.mesh);
  const Eigen::MatrixXd Mpsi = sys.M * psi;
  const Eigen::MatrixXd cross = modes.phi.transpose() * Mpsi;  // modes x 6: phi_k' M psi_j
  const Eigen::VectorXd psi_norm = (psi.transpose() * Mpsi).diagonal();
  const Eigen::Index nm = modes.phi.cols();
  Labels out;
  out.p.resize(nm, 6);
  for (Eigen::Index k = 0; k < nm; ++k) {
    const double phi_norm = modes.phi.col(k).dot(sys.M * modes.phi.col(k));
    for (int j = 0; j < 6; ++j) out.p(k, j) = cross(k, j) * cross(k, j) / (psi_norm(j) * phi_norm);
    Eigen::Index best;
    out.p.row(k).maxCoeff(&best);
    out.direction.push_back(static_cast<Direction>(best));
  }
  for (int pm = 1; pm <= 4; ++pm)
    for (Eigen::Index k = 0; k < nm; ++k)
      if (out.direction[k] == paper_direction(pm)) {
        out.paper[pm - 1] = static_cast<int>(k);
        break;
      }
  return out;
}

}  // namespace cfe
