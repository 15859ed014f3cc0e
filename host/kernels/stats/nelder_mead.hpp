// SPDX-License-Identifier: MIT
#pragma once
// A small Nelder–Mead minimiser for the maximum-likelihood fits of shape families (2–3
// parameters, smooth objectives); restarts once from the best point to avoid early collapse.
#include <Eigen/Core>
#include <functional>

namespace smi::stats::detail {

/// Minimises f from x0 with initial steps `step` (per coordinate); returns the minimiser.
/// f may return +inf for infeasible points.
Eigen::VectorXd nelder_mead(const std::function<double(const Eigen::VectorXd&)>& f, Eigen::VectorXd x0,
                            const Eigen::VectorXd& step, double ftol = 1e-13, int max_iter = 5000);

}  // namespace smi::stats::detail
