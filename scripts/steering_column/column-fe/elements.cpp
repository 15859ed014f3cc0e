// SPDX-License-Identifier: MIT
#include "elements.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace cfe {

constexpr double pi = std::numbers::pi;

Section operator+(const Section& p, const Section& q) {
  return {p.EA + q.EA, p.EIy + q.EIy, p.EIz + q.EIz, p.GJ + q.GJ, p.m + q.m, p.j + q.j};
}

static Section annulus(double ro, double ri, const Material& mat) {
  const double A = pi * (ro * ro - ri * ri);
  const double I = pi * (std::pow(ro, 4) - std::pow(ri, 4)) / 4.0;
  const double J = 2.0 * I;
  return {mat.E * A, mat.E * I, mat.E * I, mat.G() * J, mat.rho * A, mat.rho * 2.0 * I};
}

Section tube(double D, double t, const Material& mat) { return annulus(D / 2.0, D / 2.0 - t, mat); }

Section tube_inner(double Di, double t, const Material& mat) { return annulus(Di / 2.0 + t, Di / 2.0, mat); }

Section box(double b, double h, double t, const Material& mat) {
  const double bi = b - 2 * t, hi = h - 2 * t;
  const double A = b * h - bi * hi;
  const double Iy = (b * h * h * h - bi * hi * hi * hi) / 12.0;
  const double Iz = (h * b * b * b - hi * bi * bi * bi) / 12.0;
  const double J = 2.0 * t * std::pow(b - t, 2) * std::pow(h - t, 2) / ((b - t) + (h - t));
  return {mat.E * A, mat.E * Iy, mat.E * Iz, mat.G() * J, mat.rho * A, mat.rho * (Iy + Iz)};
}

Section plate_strip(double b, double t, const Material& mat) {
  Section s;
  s.EIy = b * mat.E * t * t * t / (12.0 * (1.0 - mat.nu * mat.nu));
  s.m = mat.rho * b * t;
  return s;
}

// Indices below are 0-based: the spec's (1..12) minus one.
Mat12 beam_stiffness_local(const Section& s, double L) {
  Mat12 k = Mat12::Zero();
  const double a = s.EA / L, g = s.GJ / L;
  k(0, 0) = k(6, 6) = a;
  k(0, 6) = -a;
  k(3, 3) = k(9, 9) = g;
  k(3, 9) = -g;
  const double L2 = L * L, L3 = L2 * L;
  // x-y plane, DOF (2, 6, 8, 12)
  {
    const double c = s.EIz / L3;
    const int d[4] = {1, 5, 7, 11};
    const double u[4][4] = {{12, 6 * L, -12, 6 * L}, {0, 4 * L2, -6 * L, 2 * L2}, {0, 0, 12, -6 * L}, {0, 0, 0, 4 * L2}};
    for (int p = 0; p < 4; ++p)
      for (int q = p; q < 4; ++q) k(d[p], d[q]) = c * u[p][q];
  }
  // x-z plane, DOF (3, 5, 9, 11)
  {
    const double c = s.EIy / L3;
    const int d[4] = {2, 4, 8, 10};
    const double u[4][4] = {{12, -6 * L, -12, -6 * L}, {0, 4 * L2, 6 * L, 2 * L2}, {0, 0, 12, 6 * L}, {0, 0, 0, 4 * L2}};
    for (int p = 0; p < 4; ++p)
      for (int q = p; q < 4; ++q) k(d[p], d[q]) = c * u[p][q];
  }
  return k.selfadjointView<Eigen::Upper>();
}

Mat12 beam_mass_local(const Section& s, double L) {
  Mat12 m = Mat12::Zero();
  const double ma = s.m * L / 6.0, mt = s.j * L / 6.0;
  m(0, 0) = m(6, 6) = 2 * ma;
  m(0, 6) = ma;
  m(3, 3) = m(9, 9) = 2 * mt;
  m(3, 9) = mt;
  const double c = s.m * L / 420.0, L2 = L * L;
  {
    const int d[4] = {1, 5, 7, 11};
    const double u[4][4] = {{156, 22 * L, 54, -13 * L}, {0, 4 * L2, 13 * L, -3 * L2}, {0, 0, 156, -22 * L}, {0, 0, 0, 4 * L2}};
    for (int p = 0; p < 4; ++p)
      for (int q = p; q < 4; ++q) m(d[p], d[q]) = c * u[p][q];
  }
  {
    const int d[4] = {2, 4, 8, 10};
    const double u[4][4] = {{156, -22 * L, 54, 13 * L}, {0, 4 * L2, -13 * L, -3 * L2}, {0, 0, 156, 22 * L}, {0, 0, 0, 4 * L2}};
    for (int p = 0; p < 4; ++p)
      for (int q = p; q < 4; ++q) m(d[p], d[q]) = c * u[p][q];
  }
  return m.selfadjointView<Eigen::Upper>();
}

Mat3 beam_frame(const Vec3& xi, const Vec3& xj, const Vec3& ref) {
  const Vec3 x = (xj - xi).normalized();
  Vec3 y = ref - ref.dot(x) * x;
  // A reference vector along the element would leave y undefined; the model never does that.
  if (y.norm() < 1e-9 * ref.norm()) throw std::logic_error("smi-column-fe: beam reference vector parallel to the element");
  y.normalize();
  const Vec3 z = x.cross(y);
  Mat3 lam;
  lam.row(0) = x;
  lam.row(1) = y;
  lam.row(2) = z;
  return lam;
}

Mat3 cross_matrix(const Vec3& r) {
  Mat3 c;
  c << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
  return c;
}

}  // namespace cfe
