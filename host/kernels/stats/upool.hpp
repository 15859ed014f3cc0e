// SPDX-License-Identifier: MIT
#pragma once
// u-pooling validation (spec §5; Ferson et al. 2008, Liu et al. 2011): u_i = F_pre,i(y_i),
// U = ∫_0^1 |G_n(u) − u| du against the uniform CDF, its H0 distribution by seeded Monte Carlo
// (cached per n, replications and seed), the threshold U_crit(n, confidence) and the p-value.
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "platform/core/cancel.hpp"
#include "kernels/stats/distribution.hpp"
#include "platform/core/defaults.hpp"
#include "platform/core/descriptive.hpp"

namespace smi::stats {

/// Exact U for the u-values (any order; values outside [0,1] are an error). Uses the
/// antiderivative (u − c)|u − c|/2 of |u − c| on each ECDF step, so ties need no special case.
double upool_statistic(ConstVec u);

/// Settings of the H0 Monte-Carlo (part of a result's reproducible state).
/// The fewest Monte Carlo replications of the u-pooling threshold.
inline constexpr int kMinUpoolReplications = 1000;

struct UpoolMcSettings {
  std::int64_t replications = 1'000'000;
  std::uint64_t seed = 20200101;
  int threads = kDefaultThreads;  ///< results are identical for any thread count (fixed chunking)
  /// Called with the fraction of sets simulated after each chunk, from the worker threads (so it
  /// must be thread-safe), only while a sample is being made (a cached one calls nothing). Not
  /// part of the cached state: it changes no number.
  std::function<void(double done)> progress;
  /// The run's cancel token, polled between chunks (nullptr: the process's). Changes no number.
  const cancel::Token* stop = nullptr;
};

/// The H0 sample of U for n u-values, in generation order (computed once per (n, replications,
/// seed), then cached for the process; thread-safe).
std::shared_ptr<const std::vector<double>> upool_null_sample(int n, const UpoolMcSettings& s = {});
/// The threshold's confidence unless told.
inline constexpr double kDefaultUpoolConfidence = 0.95;

/// U_crit(n, confidence): the confidence-quantile of U under H0 (type-7 on the MC sample).
/// confidence in (0, 1), n >= 1; n = 1 uses the exact closed form ¼ + (confidence/2)²; n above
/// kUpoolMonteCarloMaxN (50) the fitted large-n form of stats/upool_asymptotic.hpp (the MC
/// settings then do not apply).
double upool_threshold(int n, double confidence, const UpoolMcSettings& s = {});
/// p = P_H0(U >= u_obs) from the MC sample (n = 1: exact; n > 50: the fitted large-n form).
double upool_pvalue(int n, double u_obs, const UpoolMcSettings& s = {});
/// E U under H0, exact: ∫_0^1 E|B/n − t| dt with B ~ Bin(n, t) (Gauss–Legendre per piece).
double upool_null_mean(int n);

/// A validation verdict (prints as "u-pooling: U = ... <= threshold ... (p = ...): valid").
struct UpoolVerdict {
  double metric = 0.0;     ///< U
  double threshold = 0.0;  ///< U_crit(n, confidence)
  double p = 0.0;          ///< P_H0(U >= metric)
  bool pass = false;       ///< metric <= threshold
  double confidence = 0.95;
  int n = 0;
  Eigen::VectorXd u;  ///< the u-values in input order
  std::string describe() const;
};

/// u-values of data groups, each against its own predicted distribution (group j's data under
/// predicted[j]), pooled and tested. Throws for empty input or mismatched sizes.
UpoolVerdict upool(const std::vector<Eigen::VectorXd>& data, const std::vector<DistributionPtr>& predicted,
                   double confidence = 0.95, const UpoolMcSettings& s = {});
/// The verdict for u-values already computed.
UpoolVerdict upool_from_u(Eigen::VectorXd u, double confidence = 0.95, const UpoolMcSettings& s = {});

/// Plot series for a verdict: the ECDF of u as a step curve (x, y), the diagonal is y = x.
void upool_curve(const UpoolVerdict& v, Eigen::VectorXd& x, Eigen::VectorXd& y);

}  // namespace smi::stats
