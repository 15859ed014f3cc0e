// SPDX-License-Identifier: MIT
#pragma once
// Geometry and mesh (spec §1, §3): axes, stations, and the nodes of jacket, shaft and wheel.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "inputs.hpp"

namespace cfe {

using Vec3 = Eigen::Vector3d;

/// The column axes of §1: a rises 22 degrees above the horizontal, l to the driver's right,
/// v = a x l.
struct Axes {
  Vec3 a, l, v;
};
const Axes& axes();
/// P(s, y, z) = s a + y l + z v.
Vec3 point(double s, double y = 0.0, double z = 0.0);

/// Stations for consecutive keys, each interval cut into r * ceil(length / 80) equal parts.
std::vector<double> stations(const std::vector<double>& keys, int r);

struct Node {
  Vec3 x;
  bool wheel = false;  // member of the wheel set of §8
};

/// The mesh of §3. Each node has 6 DOF; node n owns DOF 6n .. 6n+5 (u_x u_y u_z th_x th_y th_z).
struct Mesh {
  std::vector<Node> nodes;
  std::vector<double> jacket_s, shaft_s;  // stations of the jacket / shaft nodes
  std::vector<int> jacket, shaft;         // node ids, same order as the stations
  int hub = -1;                           // H
  std::vector<int> rim;                   // 20 r rim nodes, rim[q] at phi_q = 360 q / (20 r)
  std::vector<std::vector<int>> arms;     // per spoke (0, 180, 270 deg): H ... spoke root
  std::vector<std::vector<int>> spokes;   // per spoke: root ... rim node
  int airbag = -1;                        // AB (variant spring only)

  int dof() const { return 6 * static_cast<int>(nodes.size()); }
  int jacket_at(double s) const;  // node id of the jacket node at station s (throws if none)
  int shaft_at(double s) const;
};

/// Angles of the three spokes (degrees, from +l towards +v).
inline constexpr double kSpokeAngles[3] = {0.0, 180.0, 270.0};

/// Geometry constants of §3 / §6, in mm.
inline constexpr double kHubStation = 730.0, kRimOffset = 45.0, kRimRadius = 190.0, kSpokeRoot = 35.0;

Vec3 hub_centre();            // H
Vec3 radial(double phi_deg);  // r^ = cos(phi) l + sin(phi) v

Mesh build_mesh(int r, Airbag airbag);

}  // namespace cfe
