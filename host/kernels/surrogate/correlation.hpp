// SPDX-License-Identifier: MIT
#pragma once
// Stationary correlation families in DACE's parametrisation (spec §4), on normalised inputs:
//   gauss     r = exp(-sum theta_j d_j^2)
//   exp       r = exp(-sum theta_j |d_j|)
//   matern32  r = (1 + sqrt3 h) exp(-sqrt3 h),            h^2 = sum theta_j d_j^2
//   matern52  r = (1 + sqrt5 h + 5h^2/3) exp(-sqrt5 h),    h^2 = sum theta_j d_j^2
// so for the Matern kernels theta_j = 1/l_j^2 with l_j the usual length scale.
// Every family is r = g(s) with s = sum theta_j D_j and D_j = d_j^2 (|d_j| for exp); the
// derivative dr/dtheta_j = g'(s) D_j drives the analytic likelihood gradient.
#include <Eigen/Core>
#include <string>

namespace smi::surrogate::kriging {

enum class Corr { gauss, exp, matern32, matern52 };

Corr parse_corr(const std::string& name);
const char* corr_name(Corr c);

/// D_j(a, b): the per-dimension "distance" the family sums (squared, or absolute for exp).
inline bool uses_abs(Corr c) { return c == Corr::exp; }

/// g(s) elementwise, in place.
void corr_from_s(Corr c, Eigen::Ref<Eigen::ArrayXd> s);
/// g'(s) elementwise given s (result written to out).
void corr_slope(Corr c, const Eigen::ArrayXd& s, Eigen::ArrayXd& out);

/// Cross correlations r(x_i - s_k) for rows of X (B x n) against rows of S (m x n): B x m.
/// Uses a GEMM for the squared families.
Eigen::MatrixXd cross_correlation(Corr c, const Eigen::VectorXd& theta, const Eigen::MatrixXd& X,
                                  const Eigen::MatrixXd& S);

}  // namespace smi::surrogate::kriging
