// SPDX-License-Identifier: MIT
#pragma once
// Σ_{i<j} g(|x_i − x_j|) for the cross-validation and plug-in bandwidth rules. Exact (all
// distances stored) up to kExactPairs points; beyond, linear binning on 2048 bins and sums over
// bin-distance counts (relative error O((range/2048)²/h²), below the rules' own noise).
#include <Eigen/Core>
#include <vector>

#include "platform/core/descriptive.hpp"

namespace smi::stats::detail {

class PairSums {
 public:
  static constexpr Eigen::Index kExactPairs = 2000;
  explicit PairSums(ConstVec x);
  template <class G>
  double sum(G&& g) const {
    double s = 0.0;
    if (binned_) {
      for (std::size_t m = 0; m < w_.size(); ++m) s += w_[m] * g(static_cast<double>(m) * delta_);
    } else {
      for (double d : d_) s += g(d);
    }
    return s;
  }

 private:
  bool binned_ = false;
  double delta_ = 0.0;
  std::vector<double> d_;  // exact: all pair distances
  std::vector<double> w_;  // binned: pair weight at distance m·delta
};

}  // namespace smi::stats::detail
