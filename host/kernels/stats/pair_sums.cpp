// SPDX-License-Identifier: MIT
#include "kernels/stats/pair_sums.hpp"

#include <cmath>

namespace smi::stats::detail {

PairSums::PairSums(ConstVec x) {
  const Eigen::Index n = x.size();
  if (n <= kExactPairs) {
    d_.reserve(static_cast<std::size_t>(n * (n - 1) / 2));
    for (Eigen::Index i = 0; i < n; ++i)
      for (Eigen::Index j = i + 1; j < n; ++j) d_.push_back(std::abs(x[i] - x[j]));
    return;
  }
  binned_ = true;
  const int nb = 2048;
  const double lo = x.minCoeff(), hi = x.maxCoeff();
  delta_ = (hi - lo) / (nb - 1);
  std::vector<double> c(nb + 1, 0.0);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double s = (x[i] - lo) / delta_;
    const auto k = static_cast<int>(s);
    const double f = s - k;
    c[k] += 1.0 - f;
    c[k + 1] += f;
  }
  // w[m] = Σ_k c_k c_{k+m} for m >= 1; at m = 0 the self pairs (Σ c_k² − n)/2 remain.
  w_.assign(nb + 1, 0.0);
  for (int m = 1; m <= nb; ++m)
    for (int k = 0; k + m <= nb; ++k) w_[m] += c[k] * c[k + m];
  double sq = 0.0;
  for (double v : c) sq += v * v;
  w_[0] = std::max(0.0, 0.5 * (sq - static_cast<double>(n)));
}

}  // namespace smi::stats::detail
