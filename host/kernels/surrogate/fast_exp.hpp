// SPDX-License-Identifier: MIT
#pragma once
// exp(-x) for x >= 0 over whole arrays, the inner cost of every correlation matrix. Eigen's
// exp is built for SSE2 here (no -march), and Kriging prediction is mostly exponentials, so we
// use a branch-free Cody-Waite reduction + degree-13 Taylor polynomial (relative error below
// 1e-15) that GCC vectorizes, compiled twice (AVX2 and baseline) and picked at load time.
namespace smi::surrogate::kriging {

/// x[i] <- exp(-x[i]) for i < n; inputs below 0 are taken as 0, above 708 give ~1e-308.
void exp_neg_inplace(double* x, long n);

}  // namespace smi::surrogate::kriging
