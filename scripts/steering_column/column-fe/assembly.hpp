// SPDX-License-Identifier: MIT
#pragma once
// Global assembly of K and M (spec §4) over the free DOF. Every node is free (the clamped points
// of §3 are not nodes), so a node index n maps to DOF 6n..6n+5; kClamped stands for a clamped end.
#include <Eigen/Core>

#include "elements.hpp"

namespace cfe {

inline constexpr int kClamped = -1;

class Assembler {
 public:
  explicit Assembler(int ndof);

  /// Beam from node i (or kClamped) at xi to node j at xj with reference vector ref.
  void beam(int i, const Vec3& xi, int j, const Vec3& xj, const Vec3& ref, const Section& s);
  /// Spring k along unit e between the point at offset ri from node i and offset rj from node j.
  void spring(int i, const Vec3& ri, int j, const Vec3& rj, const Vec3& e, double k);
  /// Spring k along unit e from the point at offset ri from node i to ground.
  void ground_spring(int i, const Vec3& ri, const Vec3& e, double k);
  /// Rotational spring k about unit e between nodes i and j.
  void rotational_spring(int i, int j, const Vec3& e, double k);
  /// Rigid mass m, inertia Ic about its CG, CG at node + r.
  void rigid_mass(int node, const Vec3& r, double m, const Eigen::Matrix3d& Ic);

  const Eigen::MatrixXd& K() const { return K_; }
  const Eigen::MatrixXd& M() const { return M_; }
  Eigen::MatrixXd& K() { return K_; }
  Eigen::MatrixXd& M() { return M_; }

 private:
  // Add k (sized 6*nodes.size()) over the DOF blocks of `nodes` (kClamped blocks are dropped).
  template <class Mat>
  void scatter(Eigen::MatrixXd& G, const Mat& k, std::initializer_list<int> nodes);
  Eigen::MatrixXd K_, M_;
};

}  // namespace cfe
