// SPDX-License-Identifier: MIT
#pragma once
// The Kriging mean's correlation sum for the Gaussian family, fused: for each point x,
//   sum_k gamma_k exp(-sum_j (xw_j - sw_kj)^2),   xw = x sqrt(theta), sw = s sqrt(theta),
// computed in registers (no m-wide row of correlations goes through memory) from the direct
// differences (no |x|^2 + |s|^2 - 2 x.s cancellation). AVX2 + FMA, chosen at run time.
#include <Eigen/Core>

namespace smi::surrogate::kriging::detail {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// True when this CPU runs the fused kernel (AVX2 and FMA).
bool fused_gauss_available();
/// out[i] = sum_k gamma[k] exp(-|Xw.row(i) - Sw.row(k)|^2). Every row's value depends on
/// that row only (not on how the rows are blocked). Requires fused_gauss_available().
void fused_gauss_sum(const Eigen::MatrixXd& Xw, const RowMatrix& Sw, const Eigen::VectorXd& gamma, double* out);

}  // namespace smi::surrogate::kriging::detail
