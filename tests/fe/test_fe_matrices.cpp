// SPDX-License-Identifier: MIT
// Structural properties of K and M (spec §11 "further checks") and element matrices against
// closed forms.
#include <catch2/catch.hpp>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <numbers>

#include "assembly.hpp"
#include "eigen_solve.hpp"
#include "fe_test_util.hpp"
#include "model.hpp"

using cfe::Airbag;

TEST_CASE("K and M are symmetric positive definite; total mass 8.905 kg", "[fe][matrices]") {
  for (Airbag a : {Airbag::rigid, Airbag::spring}) {
    const cfe::System s = cfe::build_system(cfe::nominal_inputs(a));
    CHECK(s.mesh.dof() == (a == Airbag::rigid ? 282 : 288));
    CHECK((s.K - s.K.transpose()).cwiseAbs().maxCoeff() <= 1e-12 * s.K.cwiseAbs().maxCoeff());
    CHECK((s.M - s.M.transpose()).cwiseAbs().maxCoeff() <= 1e-12 * s.M.cwiseAbs().maxCoeff());
    CHECK(Eigen::LLT<Eigen::MatrixXd>(s.K).info() == Eigen::Success);
    CHECK(Eigen::LLT<Eigen::MatrixXd>(s.M).info() == Eigen::Success);
    // Total mass as a weight generator reports it: the mass a unit rigid translation of the free
    // nodes moves, along global X and Z. (Along Y it is 8.9087 kg: the brackets' clamped ends
    // keep a different consistent-mass share in bending than in tension.)
    for (int d : {0, 2}) {
      Eigen::VectorXd u = Eigen::VectorXd::Zero(s.mesh.dof());
      for (std::size_t n = 0; n < s.mesh.nodes.size(); ++n) u(6 * static_cast<Eigen::Index>(n) + d) = 1.0;
      CHECK(u.dot(s.M * u) * 1000.0 == Approx(8.905).margin(0.0005));  // tonne -> kg
    }
  }
}

TEST_CASE("without bushes, brackets and tilt lock exactly six modes lie below 1 Hz", "[fe][matrices]") {
  for (Airbag a : {Airbag::rigid, Airbag::spring}) {
    const cfe::System s = cfe::build_system(cfe::nominal_inputs(a), {.supports = false});
    const cfe::Modes m = cfe::solve_modes(s.K, s.M, 10, /*allow_rigid=*/true);
    const Eigen::VectorXd f = m.frequency_hz();
    CHECK((f.array() < 1.0).count() == 6);
    CHECK(f(6) > 1.0);
    // The supported model is restrained; the free one is refused unless asked for.
    CHECK_THROWS_WITH(cfe::solve_modes(s.K, s.M, 10), Catch::Contains("unrestrained"));
  }
}

TEST_CASE("heatsink_E and heatsink_nu change nothing", "[fe][matrices]") {
  for (Airbag a : {Airbag::rigid, Airbag::spring}) {
    const cfe::Results base = cfe::run_model(cfe::nominal_inputs(a));
    cfe::Inputs in = cfe::nominal_inputs(a);
    in.set("heatsink_E", 50000);
    in.set("heatsink_nu", 0.2);
    const cfe::Results moved = cfe::run_model(in);
    for (std::size_t k = 0; k < 10; ++k) CHECK(moved.modes[k].eigenvalue == base.modes[k].eigenvalue);
    // ...while heatsink_rho does act (through the ECU mass), so the test can tell.
    in.set("heatsink_rho", 3.0e-9);
    CHECK(cfe::run_model(in).modes[0].eigenvalue != base.modes[0].eigenvalue);
  }
}

TEST_CASE("beam element: cantilever tip deflection P L^3 / (3 E I) in both planes, any orientation", "[fe][elements]") {
  // Cubic Hermite elements reproduce the Euler-Bernoulli cantilever exactly.
  const cfe::Material steel{205000, 0.29, 7.85e-9};
  const cfe::Section s = cfe::box(36, 20, 3, steel);
  const cfe::Vec3 xi(0, 0, 0), xj(300, 120, -80), ref(0, 0, 1);
  const double L = (xj - xi).norm();
  const cfe::Mat3 lam = cfe::beam_frame(xi, xj, ref);
  cfe::Assembler as(6);
  as.beam(cfe::kClamped, xi, 0, xj, ref, s);
  const Eigen::MatrixXd K = as.K();
  for (int axis = 1; axis <= 2; ++axis) {  // load along local y (bends with EIz), then local z (EIy)
    Eigen::VectorXd F = Eigen::VectorXd::Zero(6);
    F.head<3>() = 1000.0 * lam.row(axis).transpose();
    const Eigen::VectorXd u = K.ldlt().solve(F);
    const double EI = axis == 1 ? s.EIz : s.EIy;
    CHECK(u.head<3>().dot(lam.row(axis)) == Approx(1000.0 * L * L * L / (3 * EI)).epsilon(1e-10));
  }
  // Axial: P L / EA; torsion: T L / GJ.
  Eigen::VectorXd F = Eigen::VectorXd::Zero(6);
  F.head<3>() = 1000.0 * lam.row(0).transpose();
  CHECK(K.ldlt().solve(F).head<3>().dot(lam.row(0)) == Approx(1000.0 * L / s.EA).epsilon(1e-10));
  F.setZero();
  F.tail<3>() = 1.0e5 * lam.row(0).transpose();
  CHECK(K.ldlt().solve(F).tail<3>().dot(lam.row(0)) == Approx(1.0e5 * L / s.GJ).epsilon(1e-10));
}

TEST_CASE("sections: box torsion by Bredt, tube areas, plate strip ~ E t^3", "[fe][elements]") {
  const cfe::Material unit{1.0, 0.25, 1.0};
  // J = 2 t (b-t)^2 (h-t)^2 / ((b-t)+(h-t)) for b 36, h 20, t 3: 2*3*33^2*17^2/50.
  CHECK(cfe::box(36, 20, 3, unit).GJ == Approx(2.0 * 3 * 33 * 33 * 17 * 17 / 50.0 / 2.5));
  CHECK(cfe::tube(52, 2, unit).EA == Approx(std::numbers::pi * (26.0 * 26 - 24.0 * 24)));
  CHECK(cfe::tube(30, 15, unit).EIy == Approx(std::numbers::pi * std::pow(15.0, 4) / 4));
  const cfe::Section p1 = cfe::plate_strip(70, 3.2, unit), p2 = cfe::plate_strip(70, 6.4, unit);
  CHECK(p2.EIy / p1.EIy == Approx(8.0));
  CHECK(p1.EA == 0.0);
  CHECK(p1.EIz == 0.0);
  CHECK(p1.GJ == 0.0);
}

TEST_CASE("rigid mass: offset CG gives the parallel-axis inertia", "[fe][elements]") {
  cfe::Assembler as(6);
  const cfe::Vec3 r(0, 0, -75);
  as.rigid_mass(0, r, 2.4e-3, 1.92 * Eigen::Matrix3d::Identity());
  const Eigen::MatrixXd& M = as.M();
  CHECK(M(3, 3) == Approx(1.92 + 2.4e-3 * 75 * 75));  // about x through the node
  CHECK(M(5, 5) == Approx(1.92));                     // about z: the offset lies on the axis
  CHECK(M(0, 0) == Approx(2.4e-3));
  CHECK(M(0, 4) == Approx(-2.4e-3 * 75));  // u_x couples with theta_y: v = u + theta x r
}

TEST_CASE("fast subspace eigen-solution agrees with the dense reference solver", "[fe][eigen]") {
  for (const cfe::Inputs& in : {cfe::nominal_inputs(Airbag::rigid), cfe::nominal_inputs(Airbag::spring, 2),
                                fe_test::corner(Airbag::spring)}) {
    const cfe::System s = cfe::build_system(in);
    const cfe::Modes fast = cfe::solve_modes(s.K, s.M, 10), ref = cfe::solve_modes_dense(s.K, s.M, 10);
    for (int k = 0; k < 10; ++k) {
      CHECK(fast.lambda(k) == Approx(ref.lambda(k)).epsilon(1e-8));
      // Same mode shape up to sign: |phi_f' M phi_r| = 1 for mass-normalised vectors.
      CHECK(std::abs(fast.phi.col(k).dot(s.M * ref.phi.col(k))) == Approx(1.0).epsilon(1e-6));
      CHECK(fast.phi.col(k).dot(s.M * fast.phi.col(k)) == Approx(1.0).epsilon(1e-12));
    }
  }
}
