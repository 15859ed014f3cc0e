// SPDX-License-Identifier: MIT
#pragma once
// Warns when a calibrated input walks outside the region its surrogate was fitted on: a Kriging model
// extrapolates badly, so an optimum there is not to be trusted.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace smi::improve {

struct DesignRange {
  std::string input;
  double lower = 0.0;
  double upper = 0.0;
};

/// For each input with a design range: a warning when its calibrated mean lies outside the
/// range, and when more than `max_outside` of its calibrated sample (column of X) does.
/// `names` label the columns of X.
std::vector<std::string> design_bound_warnings(const std::vector<std::string>& names, const Eigen::MatrixXd& X,
                                               const std::vector<double>& means, const std::vector<DesignRange>& ranges,
                                               double max_outside = 0.05);

}  // namespace smi::improve
