// SPDX-License-Identifier: MIT
#pragma once
// Descriptive statistics over Eigen vectors, with the conventions pinned in
// docs/spec/algorithms.md §0: sd divides by n-1; quantiles are type 7 (linear interpolation).
#include <Eigen/Core>
#include <string_view>

namespace smi {

using ConstVec = Eigen::Ref<const Eigen::VectorXd>;

double mean(ConstVec x);
/// Sample variance, divisor n-1 (throws for n < 2).
double variance(ConstVec x);
double stddev(ConstVec x);
/// Type-7 quantile (R's default, numpy's 'linear'); p in [0, 1].
double quantile(ConstVec x, double p);
/// Type-7 quantile of data already sorted ascending.
double quantile_sorted(ConstVec sorted, double p);
Eigen::VectorXd sorted(ConstVec x);
/// Median absolute deviation from the median (unscaled).
double mad(ConstVec x);

/// Throws InvalidArgument naming `what` and the 1-based index of the first NaN or infinity.
void require_finite(ConstVec x, std::string_view what);
/// Throws InvalidArgument unless x has at least `n` elements.
void require_size(ConstVec x, Eigen::Index n, std::string_view what);

}  // namespace smi
