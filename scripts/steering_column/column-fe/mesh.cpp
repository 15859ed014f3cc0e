// SPDX-License-Identifier: MIT
#include "mesh.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace cfe {

const Axes& axes() {
  static const Axes ax = [] {
    const double c = std::cos(22.0 * std::numbers::pi / 180.0), s = std::sin(22.0 * std::numbers::pi / 180.0);
    return Axes{Vec3(c, 0, s), Vec3(0, 1, 0), Vec3(-s, 0, c)};
  }();
  return ax;
}

Vec3 point(double s, double y, double z) { return s * axes().a + y * axes().l + z * axes().v; }

std::vector<double> stations(const std::vector<double>& keys, int r) {
  std::vector<double> out{keys.front()};
  for (std::size_t k = 1; k < keys.size(); ++k) {
    const double s0 = keys[k - 1], s1 = keys[k];
    const int n = r * static_cast<int>(std::ceil((s1 - s0) / 80.0));
    // Interior points from the interval ends, so key stations are exact.
    for (int i = 1; i < n; ++i) out.push_back(s0 + (s1 - s0) * i / n);
    out.push_back(s1);
  }
  return out;
}

Vec3 hub_centre() { return point(kHubStation); }

Vec3 radial(double phi_deg) {
  const double p = phi_deg * std::numbers::pi / 180.0;
  return std::cos(p) * axes().l + std::sin(p) * axes().v;
}

static int find_station(const std::vector<double>& st, const std::vector<int>& ids, double s, const char* what) {
  for (std::size_t i = 0; i < st.size(); ++i)
    if (std::abs(st[i] - s) < 1e-9) return ids[i];
  throw std::logic_error(std::string("smi-column-fe: no ") + what + " node at s = " + std::to_string(s));
}
int Mesh::jacket_at(double s) const { return find_station(jacket_s, jacket, s, "jacket"); }
int Mesh::shaft_at(double s) const { return find_station(shaft_s, shaft, s, "shaft"); }

Mesh build_mesh(int r, Airbag airbag) {
  if (r < 1 || r > 8) throw std::invalid_argument("smi-column-fe: mesh_refinement must be 1..8, got " + std::to_string(r));
  Mesh m;
  auto add = [&](const Vec3& x, bool wheel) {
    m.nodes.push_back({x, wheel});
    return static_cast<int>(m.nodes.size()) - 1;
  };
  m.jacket_s = stations({0, 20, 150, 210, 270, 300, 330, 480, 520, 570}, r);
  for (double s : m.jacket_s) m.jacket.push_back(add(point(s), false));
  m.shaft_s = stations({150, 210, 270, 300, 330, 480, 520, 570, 710}, r);
  for (double s : m.shaft_s) m.shaft.push_back(add(point(s), false));

  const Vec3 H = hub_centre(), C = H + kRimOffset * axes().a;
  m.hub = add(H, true);
  const int nrim = 20 * r;
  for (int q = 0; q < nrim; ++q) m.rim.push_back(add(C + kRimRadius * radial(360.0 * q / nrim), true));

  for (double phi : kSpokeAngles) {
    const Vec3 root = H + kSpokeRoot * radial(phi);
    const int rim_node = m.rim[static_cast<std::size_t>(std::lround(phi / 360.0 * nrim))];
    std::vector<int> arm{m.hub}, spoke;
    for (int i = 1; i < r; ++i) arm.push_back(add(H + (root - H) * (double(i) / r), true));
    const int root_id = add(root, true);
    arm.push_back(root_id);
    spoke.push_back(root_id);
    const Vec3 tip = m.nodes[rim_node].x;
    for (int i = 1; i < r; ++i) spoke.push_back(add(root + (tip - root) * (double(i) / r), true));
    spoke.push_back(rim_node);
    m.arms.push_back(arm);
    m.spokes.push_back(spoke);
  }
  if (airbag == Airbag::spring) m.airbag = add(H - 10.0 * axes().a - 20.0 * axes().v, true);
  return m;
}

}  // namespace cfe
