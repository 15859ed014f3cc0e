// SPDX-License-Identifier: MIT
#pragma once
// DACE's `boxmin` (Lophaven et al. 2002, dacefit.m): a coarse pattern search on theta inside
// [lo, up], reproduced step for step (spec §4) so that theta and the evaluation count match
// the toolbox the paper used. Not a good optimiser; kept for parity.
#include <Eigen/Core>
#include <functional>

namespace smi::surrogate::kriging {

struct BoxminResult {
  Eigen::VectorXd theta;
  double f = 0;
  int evaluations = 0;
};

/// f(theta) returns psi, or +inf where the correlation matrix is not positive definite.
BoxminResult boxmin(const Eigen::VectorXd& theta0, const Eigen::VectorXd& lo, const Eigen::VectorXd& up,
                    const std::function<double(const Eigen::VectorXd&)>& f);

}  // namespace smi::surrogate::kriging
