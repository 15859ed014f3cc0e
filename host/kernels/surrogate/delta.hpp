// SPDX-License-Identifier: MIT
#pragma once
// Borgonovo's moment-independent index delta_i = 1/2 E_{X_i} integral |f_Y - f_{Y|X_i}| dy
// (Borgonovo 2007) estimated from one given sample (Plischke, Borgonovo & Smith 2013, the
// estimator behind SALib's delta): the sample is split into M equal-count classes of X_i, and
// delta_i = 1/2 sum_m (n_m / n) integral |f_Y - f_m| with Gaussian KDEs (normal-reference
// bandwidths) on one common grid. It is the class-conditional counterpart of the eq.-3 PDF area
// and costs no runs beyond the sample it is given.
#include <Eigen/Core>
#include <cstdint>

namespace smi::surrogate::delta {

struct Options {
  Eigen::Index classes = 0;  // M; 0 = SALib's rule min(ceil(n^(2 / (7 + tanh((1500 - n) / 500)))), 48)
  Eigen::Index grid = 2001;
  std::uint64_t seed = 1;    // for the noise floor's permutation
};

struct Result {
  Eigen::VectorXd delta;  // one per column of X (0 for a constant column)
  /// delta of a column independent of y (a seeded permutation of the row order): what the
  /// estimator returns for an input without influence at this n and M; indices near it are noise.
  double floor = 0;
  Eigen::Index classes = 0;
};

/// SALib's class-count rule for n points.
Eigen::Index default_classes(Eigen::Index n);

/// X: n x k sample, y: n outputs at its rows.
Result estimate(const Eigen::MatrixXd& X, const Eigen::VectorXd& y, const Options& opt = {});

}  // namespace smi::surrogate::delta
