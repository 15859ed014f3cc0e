// SPDX-License-Identifier: MIT
#include "assembly.hpp"

#include <vector>

namespace cfe {

Assembler::Assembler(int ndof) : K_(Eigen::MatrixXd::Zero(ndof, ndof)), M_(Eigen::MatrixXd::Zero(ndof, ndof)) {}

template <class Mat>
void Assembler::scatter(Eigen::MatrixXd& G, const Mat& k, std::initializer_list<int> nodes) {
  const std::vector<int> n(nodes);
  for (std::size_t p = 0; p < n.size(); ++p) {
    if (n[p] == kClamped) continue;
    for (std::size_t q = 0; q < n.size(); ++q) {
      if (n[q] == kClamped) continue;
      G.block<6, 6>(6 * n[p], 6 * n[q]) += k.template block<6, 6>(6 * p, 6 * q);
    }
  }
}

void Assembler::beam(int i, const Vec3& xi, int j, const Vec3& xj, const Vec3& ref, const Section& s) {
  const double L = (xj - xi).norm();
  const Mat3 lam = beam_frame(xi, xj, ref);
  Mat12 T = Mat12::Zero();
  for (int b = 0; b < 4; ++b) T.block<3, 3>(3 * b, 3 * b) = lam;
  const Mat12 k = T.transpose() * beam_stiffness_local(s, L) * T;
  const Mat12 m = T.transpose() * beam_mass_local(s, L) * T;
  scatter(K_, k, {i, j});
  scatter(M_, m, {i, j});
}

void Assembler::spring(int i, const Vec3& ri, int j, const Vec3& rj, const Vec3& e, double k) {
  Eigen::Matrix<double, 12, 1> b;
  b << e, ri.cross(e), -e, -rj.cross(e);
  const Mat12 kk = k * b * b.transpose();
  scatter(K_, kk, {i, j});
}

void Assembler::ground_spring(int i, const Vec3& ri, const Vec3& e, double k) {
  Eigen::Matrix<double, 6, 1> b;
  b << e, ri.cross(e);
  const Eigen::Matrix<double, 6, 6> kk = k * b * b.transpose();
  scatter(K_, kk, {i});
}

void Assembler::rotational_spring(int i, int j, const Vec3& e, double k) {
  Eigen::Matrix<double, 12, 1> b;
  b << Vec3::Zero(), e, Vec3::Zero(), -e;
  const Mat12 kk = k * b * b.transpose();
  scatter(K_, kk, {i, j});
}

void Assembler::rigid_mass(int node, const Vec3& r, double m, const Eigen::Matrix3d& Ic) {
  Eigen::Matrix<double, 6, 6> T = Eigen::Matrix<double, 6, 6>::Identity();
  T.block<3, 3>(0, 3) = -cross_matrix(r);
  Eigen::Matrix<double, 6, 6> D = Eigen::Matrix<double, 6, 6>::Zero();
  D.block<3, 3>(0, 0) = m * Eigen::Matrix3d::Identity();
  D.block<3, 3>(3, 3) = Ic;
  const Eigen::Matrix<double, 6, 6> mm = T.transpose() * D * T;
  scatter(M_, mm, {node});
}

}  // namespace cfe
