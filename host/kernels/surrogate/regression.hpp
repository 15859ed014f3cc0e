// SPDX-License-Identifier: MIT
#pragma once
// DACE's polynomial trends regpoly0/1/2 (spec §4): rows f(x) of the regression matrix F.
#include <Eigen/Core>
#include <string>

namespace smi::surrogate::kriging {

enum class Trend { constant, linear, quadratic };

Trend parse_trend(const std::string& name);
const char* trend_name(Trend t);
/// Number of basis functions p for n inputs.
Eigen::Index trend_size(Trend t, Eigen::Index n);
/// F (rows = points): [1], [1, x], or [1, x, x_k x_l for k <= l in DACE's order].
Eigen::MatrixXd trend_basis(Trend t, const Eigen::MatrixXd& X);

}  // namespace smi::surrogate::kriging
