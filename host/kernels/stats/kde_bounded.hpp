// SPDX-License-Identifier: MIT
#pragma once
// KDE with bounded data (spec §1.2; Kang, Noh, Lim 2018): artificial points drawn uniformly in
// [l, u] are appended until adding more no longer changes the KDE's shape (intersection area
// >= critical_area). KDE-bd takes known bounds; KDE-ebd estimates them from the data.
#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "kernels/stats/kde.hpp"

namespace smi::stats {

/// Every rule of the stopping loop (defaults are the spec's Decision).
struct BoundedKdeOptions {
  double critical_area = 0.95;   ///< stop when IA(f_prev, f_new) >= this
  int step = 1;                  ///< points added per iteration
  int max_added = -1;            ///< m_max; -1 means 10·n
  std::string compare = "previous";  ///< "previous" (f_prev) or "data" (KDE of the data only)
  std::string bandwidth = "silverman";  ///< rule applied to the pooled data every iteration
  bool deterministic = false;    ///< place m points at l + (u − l)(j − ½)/m instead of drawing
  std::uint64_t seed = 0;
  Eigen::Index grid_nodes = kDefaultGridNodes;
};

/// KDE-ebd's bound estimation (§1.2): the significance level and which estimators.
struct EbdBoundsOptions {
  double alpha = 0.1;     ///< c = alpha^(-1/n)
  bool unbiased = false;  ///< the unbiased bound estimators instead of min/max
};

/// §1.2 bounds: min/max estimators (unbiased = false) or the unbiased ones; c = α^{-1/n}.
std::pair<double, double> ebd_bounds(ConstVec x, double alpha, bool unbiased = false);

struct BoundedKdeResult {
  std::shared_ptr<Kde> kde;  ///< the final KDE of T = [X, added]
  double lower = 0.0, upper = 0.0;
  int added = 0;
  bool converged = false;
  Eigen::VectorXd added_points;
  std::vector<double> ia_history;
};

/// KDE-bd: bounds given (lower < upper). Data outside the bounds are counted in `outside`.
BoundedKdeResult kde_bounded(const Eigen::VectorXd& x, double lower, double upper, const BoundedKdeOptions& o,
                             int* outside = nullptr);
/// KDE-ebd: bounds from ebd_bounds(x, alpha, unbiased).
BoundedKdeResult kde_ebd(const Eigen::VectorXd& x, double alpha, bool unbiased, const BoundedKdeOptions& o);

}  // namespace smi::stats
