// SPDX-License-Identifier: MIT
#pragma once
// Element matrices (spec §4): Euler-Bernoulli beam stiffness and consistent mass
// (Przemieniecki 1968), cross-sections, spring vectors and the rigid-mass transform.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace cfe {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Mat12 = Eigen::Matrix<double, 12, 12>;

/// Section data of a beam: axial, bending about local y (x-z plane), bending about local z
/// (x-y plane), torsional rigidities; mass and polar mass moment per unit length.
struct Section {
  double EA = 0, EIy = 0, EIz = 0, GJ = 0, m = 0, j = 0;
};
/// Rigidities and masses add for parts that share the same axis (composite rim of §5).
Section operator+(const Section& p, const Section& q);

struct Material {
  double E, nu, rho;
  double G() const { return E / (2.0 * (1.0 + nu)); }
};

/// Circular tube, outer diameter D, wall t (t = D/2 is solid).
Section tube(double D, double t, const Material& mat);
/// Tube given by inner diameter Di and wall t (the rim cover, §5).
Section tube_inner(double Di, double t, const Material& mat);
/// Thin-walled box b (local y) x h (local z), wall t; J by Bredt.
Section box(double b, double h, double t, const Material& mat);
/// Plate-bending strip of width b, thickness t: bends in x-z only, stiffness ~ E t^3.
Section plate_strip(double b, double t, const Material& mat);

Mat12 beam_stiffness_local(const Section& s, double L);
Mat12 beam_mass_local(const Section& s, double L);
/// Rows = local x, y, z in global components; y = part of `ref` normal to x.
Mat3 beam_frame(const Vec3& xi, const Vec3& xj, const Vec3& ref);

/// Cross-product matrix [r]x, so that [r]x w = r x w.
Mat3 cross_matrix(const Vec3& r);

}  // namespace cfe
