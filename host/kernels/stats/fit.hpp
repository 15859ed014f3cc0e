// SPDX-License-Identifier: MIT
#pragma once
// Maximum-likelihood fits of the parametric families, ranked by AIC (then BIC), each with its
// Kolmogorov–Smirnov statistic, so an analyst can ask which family fits a set of measurements.
#include <string>
#include <vector>

#include "kernels/stats/distribution.hpp"
#include "platform/core/descriptive.hpp"

namespace smi::stats {

struct FitResult {
  std::string family;
  DistributionPtr dist;
  double loglik = 0.0;
  int k = 0;  ///< number of fitted parameters
  double aic = 0.0, bic = 0.0;
  double ks = 0.0;  ///< sup |F(x) − S_n(x)|
};

/// MLE of one family. Closed forms: normal (mean, biased std), lognormal (on logs), uniform
/// (min, max). Nelder–Mead on the log-likelihood otherwise: weibull and gamma with loc = 0,
/// gumbel; beta and triangular with bounds at min/max widened by range/n (fitted shape/mode);
/// truncnormal with bounds at min/max widened by range/n (fitted parent mean/std).
FitResult fit_family(ConstVec data, const std::string& family);
/// Fits every family and sorts by AIC ascending. Data: >= 2 finite points, not all equal.
std::vector<FitResult> fit(ConstVec data, const std::vector<std::string>& families);
/// The families fit() knows.
const std::vector<std::string>& fit_family_names();
/// KS statistic of data against d.
double ks_statistic(ConstVec data, const Distribution& d);

}  // namespace smi::stats
