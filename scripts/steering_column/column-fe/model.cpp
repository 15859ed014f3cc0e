// SPDX-License-Identifier: MIT
#include "model.hpp"

#include <cmath>
#include <stdexcept>

#include "assembly.hpp"

namespace cfe {

namespace {

Material material(const Inputs& in, const std::string& part) {
  return {in(part + "_E"), in(part + "_nu"), in(part + "_rho")};
}

void check_inputs(const Inputs& in) {
  for (const auto& s : input_specs()) {
    if (s.name == "airbag_stiffness" && in.airbag == Airbag::rigid) continue;
    const double x = in(s.name);
    const bool ok = std::isfinite(x) && x > 0 && (s.kind != InputKind::poisson || x < 0.5);
    if (!ok)
      throw std::invalid_argument("smi-column-fe: input " + s.name + " = " + std::to_string(x) +
                                  (s.kind == InputKind::poisson ? " is outside (0, 0.5)" : " must be finite and > 0"));
  }
}

void jacket_and_shaft(Assembler& as, const Mesh& m, const Inputs& in) {
  const Axes& ax = axes();
  const Material steel = material(in, "column_frame"), housing = material(in, "housing");
  const Section jacket_tube = tube(52, in("column_tube_thickness"), steel);
  const Section housing_tube = tube(80, in("housing_thickness"), housing);
  for (std::size_t e = 0; e + 1 < m.jacket.size(); ++e) {
    const double s0 = m.jacket_s[e], s1 = m.jacket_s[e + 1];
    const bool in_housing = s0 >= 150 && s1 <= 270;
    const int i = m.jacket[e], j = m.jacket[e + 1];
    as.beam(i, m.nodes[i].x, j, m.nodes[j].x, ax.v, in_housing ? housing_tube : jacket_tube);
  }
  const Section shaft_tube = tube(30, 4, steel), stub = tube(19, 9.5, steel);
  for (std::size_t e = 0; e + 1 < m.shaft.size(); ++e) {
    const int i = m.shaft[e], j = m.shaft[e + 1];
    as.beam(i, m.nodes[i].x, j, m.nodes[j].x, ax.v, m.shaft_s[e] < 570 ? shaft_tube : stub);
  }
}

void column_links(Assembler& as, const Mesh& m, const Inputs& in) {
  const Axes& ax = axes();
  const Vec3 o = Vec3::Zero();
  const double bearing_s[4] = {150, 270, 520, 570};
  for (int b = 0; b < 4; ++b) {
    const int sh = m.shaft_at(bearing_s[b]), ja = m.jacket_at(bearing_s[b]);
    const std::string p = "bearing" + std::to_string(b + 1);
    as.spring(sh, o, ja, o, ax.l, in(p + "_kl"));
    as.spring(sh, o, ja, o, ax.v, in(p + "_kv"));
  }
  as.spring(m.shaft_at(210), o, m.jacket_at(210), o, ax.a, 1.0e5);      // axial tie
  as.rotational_spring(m.shaft_at(480), m.jacket_at(480), ax.a, 3.0e7);  // steering lock engaged
}

void supports(Assembler& as, const Mesh& m, const Inputs& in) {
  const Axes& ax = axes();
  const struct { double s, y; } bush[4] = {{20, 45}, {20, -45}, {300, 60}, {300, -60}};
  for (int b = 0; b < 4; ++b) {
    const int n = m.jacket_at(bush[b].s);
    const Vec3 r = bush[b].y * ax.l;
    const std::string p = "bush" + std::to_string(b + 1);
    as.ground_spring(n, r, ax.a, in(p + "_ka"));
    as.ground_spring(n, r, ax.l, in(p + "_kl"));
    as.ground_spring(n, r, ax.v, in(p + "_kv"));
  }
  const Material steel = material(in, "column_frame");
  const int n300 = m.jacket_at(300);
  as.beam(kClamped, point(235), n300, m.nodes[n300].x, ax.l, plate_strip(70, in("ecu_bracket_thickness"), steel));
  as.beam(kClamped, point(300, 0, 70), n300, m.nodes[n300].x, ax.a, plate_strip(60, in("tilt_bracket_thickness"), steel));
  as.ground_spring(m.jacket_at(330), Vec3::Zero(), ax.v, in("tilt_lock_k"));
}

void column_masses(Assembler& as, const Mesh& m, const Inputs& in) {
  const Axes& ax = axes();
  const Eigen::Matrix3d I3 = Eigen::Matrix3d::Identity();
  as.rigid_mass(m.jacket_at(210), -75.0 * ax.v, 2.4e-3, 1.92 * I3);  // power pack
  const double ecu = 0.4e-3 + in("heatsink_rho") * 9000.0 * in("heatsink_thickness");
  as.rigid_mass(m.jacket_at(300), 60.0 * ax.v, ecu, ecu * 1250.0 * I3);  // ECU module
}

void wheel(Assembler& as, const Mesh& m, const Inputs& in) {
  const Axes& ax = axes();
  const Material hub = material(in, "hub"), frame = material(in, "wheel_frame"), cover = material(in, "wheel_cover");
  const int s710 = m.shaft.back();
  as.beam(s710, m.nodes[s710].x, m.hub, m.nodes[m.hub].x, ax.v, tube(36, 8, hub));  // hub boss
  // Rim: magnesium core plus PU cover on the same axis, rigidities and masses added.
  const Section rim = tube(22, 11, frame) + tube_inner(24, in("wheel_cover_thickness"), cover);
  const std::size_t n = m.rim.size();
  for (std::size_t q = 0; q < n; ++q) {
    const int i = m.rim[q], j = m.rim[(q + 1) % n];
    as.beam(i, m.nodes[i].x, j, m.nodes[j].x, ax.a, rim);
  }
  const Section arm = tube(30, 15, frame), spoke = box(36, 20, in("spoke_thickness"), frame);
  for (std::size_t k = 0; k < m.arms.size(); ++k) {
    const auto& ch = m.arms[k];
    for (std::size_t e = 0; e + 1 < ch.size(); ++e)
      as.beam(ch[e], m.nodes[ch[e]].x, ch[e + 1], m.nodes[ch[e + 1]].x, ax.a, arm);
    const Vec3 ref = ax.a.cross(radial(kSpokeAngles[k]));
    const auto& sp = m.spokes[k];
    for (std::size_t e = 0; e + 1 < sp.size(); ++e)
      as.beam(sp[e], m.nodes[sp[e]].x, sp[e + 1], m.nodes[sp[e + 1]].x, ref, spoke);
  }
}

void airbag(Assembler& as, const Mesh& m, const Inputs& in) {
  const Axes& ax = axes();
  const Eigen::Matrix3d Ic = 4.52 * ax.a * ax.a.transpose() + 2.45 * ax.l * ax.l.transpose() +
                             3.05 * ax.v * ax.v.transpose();
  const double mass = 1.2e-3;
  if (in.airbag == Airbag::rigid) {
    // Model A: lumped at H, rigidly tied to the hub at the wrong point.
    as.rigid_mass(m.hub, Vec3::Zero(), mass, Ic);
    return;
  }
  // Model B: the mass on its own node at the true CG, hung on nine springs.
  as.rigid_mass(m.airbag, Vec3::Zero(), mass, Ic);
  const Vec3 H = m.nodes[m.hub].x, AB = m.nodes[m.airbag].x;
  const Vec3 Q[3] = {H + 10 * ax.a + 55 * ax.l, H + 10 * ax.a - 55 * ax.l, H + 10 * ax.a - 60 * ax.v};
  const double k = in("airbag_stiffness") / 3.0;
  for (const Vec3& q : Q)
    for (const Vec3& e : {ax.a, ax.l, ax.v}) as.spring(m.airbag, q - AB, m.hub, q - H, e, k);
}

}  // namespace

System build_system(const Inputs& in, const ModelOptions& opt) {
  check_inputs(in);
  System sys;
  sys.mesh = build_mesh(in.refinement, in.airbag);
  Assembler as(sys.mesh.dof());
  jacket_and_shaft(as, sys.mesh, in);
  column_links(as, sys.mesh, in);
  if (opt.supports) supports(as, sys.mesh, in);
  column_masses(as, sys.mesh, in);
  wheel(as, sys.mesh, in);
  airbag(as, sys.mesh, in);
  sys.K = std::move(as.K());
  sys.M = std::move(as.M());
  return sys;
}

}  // namespace cfe
