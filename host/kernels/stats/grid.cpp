// SPDX-License-Identifier: MIT
#include "kernels/stats/grid.hpp"

#include <cmath>
#include <fmt/format.h>

#include "platform/core/errors.hpp"

namespace smi::stats {

Eigen::VectorXd Grid::nodes() const {
  Eigen::VectorXd x(n);
  for (Eigen::Index i = 0; i < n; ++i) x[i] = node(i);
  return x;
}

double Grid::trapezoid(ConstVec y) const {
  if (y.size() != n) throw DimensionMismatch(fmt::format("grid has {} nodes, values have {}", n, y.size()));
  return step() * (y.sum() - 0.5 * (y[0] + y[n - 1]));
}

void Grid::validate() const {
  if (!std::isfinite(lo) || !std::isfinite(hi)) throw InvalidArgument(fmt::format("grid bounds must be finite, got [{}, {}]", lo, hi));
  if (!(lo < hi)) throw InvalidArgument(fmt::format("grid lower ({}) must be < upper ({})", lo, hi));
  if (n < 2) throw InvalidArgument(fmt::format("grid needs at least 2 nodes, got {}", n));
}

Grid Grid::covering(double data_lo, double data_hi, double h_max, Eigen::Index n) {
  Grid g{data_lo - 6.0 * h_max, data_hi + 6.0 * h_max, n};
  g.validate();
  return g;
}

Grid Grid::covering(ConstVec data, double h_max, Eigen::Index n) {
  require_size(data, 1, "data");
  require_finite(data, "data");
  return covering(data.minCoeff(), data.maxCoeff(), h_max, n);
}

}  // namespace smi::stats
