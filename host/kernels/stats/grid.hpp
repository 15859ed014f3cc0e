// SPDX-License-Identifier: MIT
#pragma once
// The common integration grid of spec §0: uniform nodes on [lo, hi], trapezoid rule. Every
// integral of a PDF difference (PR, screening e_k, intersection area) is taken on one of these,
// and the grid is part of the reproducible state of a result.
#include <Eigen/Core>
#include <initializer_list>

#include "platform/core/defaults.hpp"
#include "platform/core/descriptive.hpp"

namespace smi::stats {

struct Grid {
  double lo = 0.0;
  double hi = 1.0;
  Eigen::Index n = kDefaultGridNodes;  ///< number of nodes (>= 2001 by §0; 4001 recommended)

  /// Node spacing (hi - lo) / (n - 1).
  double step() const { return (hi - lo) / static_cast<double>(n - 1); }
  /// Node i (0-based), lo + i*step, exactly hi at i = n-1.
  double node(Eigen::Index i) const { return i == n - 1 ? hi : lo + static_cast<double>(i) * step(); }
  /// All nodes.
  Eigen::VectorXd nodes() const;
  /// Trapezoid rule of values y given at the nodes (y.size() == n).
  double trapezoid(ConstVec y) const;

  /// Checks lo < hi, both finite, n >= 2; throws InvalidArgument naming the field otherwise.
  void validate() const;

  /// §0: [min(data) - 6*h_max, max(data) + 6*h_max] with n nodes, data being every sample that
  /// enters the comparison (pass the union) and h_max the largest bandwidth involved.
  static Grid covering(ConstVec data, double h_max, Eigen::Index n = kDefaultGridNodes);
  /// The same from a range already known: [lo - 6*h_max, hi + 6*h_max].
  static Grid covering(double data_lo, double data_hi, double h_max, Eigen::Index n = kDefaultGridNodes);
};

}  // namespace smi::stats
