// SPDX-License-Identifier: MIT
#pragma once
// Identifiability check (beyond the paper): a parameter is flagged when the
// objective barely changes as that parameter sweeps its whole range with the others held at the
// optimum. Such a parameter is not determined by the data; its calibrated value means little.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "kernels/improve/bounded_optimizer.hpp"

namespace smi::improve {

struct IdentifiabilityOptions {
  int points = 11;          ///< sweep nodes per parameter (bounds included)
  double abs_tol = 0.0;     ///< flagged when the objective's span over the sweep is below abs_tol...
  double rel_tol = 0.01;    ///< ...or below rel_tol times the largest span of any parameter
  /// abs_tol under the PR metric when not given: PR is unit-free (range [0, 2] per response), so
  /// a change below this over a whole range is noise.
  double pr_abs_tol = 1e-3;
};

struct IdentifiabilityResult {
  Eigen::MatrixXd profiles;  ///< parameters × points: the objective along each sweep
  Eigen::MatrixXd nodes;     ///< parameters × points: the swept values
  Eigen::VectorXd span;      ///< max − min of each profile
  std::vector<bool> weak;    ///< flagged parameters
  int evaluations = 0;
  std::vector<std::string> warnings;
};

IdentifiabilityResult identifiability(const std::vector<Parameter>& params, const Objective& f, const Eigen::VectorXd& optimum,
                                      const IdentifiabilityOptions& opt = {});

}  // namespace smi::improve
