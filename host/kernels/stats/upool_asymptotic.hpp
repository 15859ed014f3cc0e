// SPDX-License-Identifier: MIT
#pragma once
// u-pooling for many u-values without minutes of Monte Carlo. Under H0, sqrt(n)·U tends to
// A = ∫_0^1 |B(t)| dt, the L1 norm of a Brownian bridge (G_n(u) − u is an empirical process:
// sqrt(n)(G_n − id) → B), and it is at its limit already at moderate n (sqrt(n)·U_crit at 95 %
// is 0.5816, 0.5815, 0.5817, 0.5815 at n = 33, 64, 128, 256 by Monte Carlo). The table holds,
// per probability p, a(p) = the Monte Carlo quantile of sqrt(n)·U averaged over n = 48 ... 768
// (3.1·10^6 sets; bench/bench_upool_fit.cpp fit), so U_crit(n, p) = a(p)/sqrt(n) (the form keeps
// a b(p)/sqrt(n) term, 0 today: fitted, it was within the Monte Carlo noise). Checks: the mean
// of A from the table, ∫ a(p) dp, is sqrt(pi/32) (exact: E|B(t)| = sqrt(2t(1-t)/pi)) within
// 0.11 %; against an independent Monte Carlo of 10^5 sets (bench_upool_fit check,
// bench/results/upool_asymptotic.md) U_crit is within 0.35 % at confidence 0.5 ... 0.95 and
// 0.7 % at 0.99 for n = 100, 300, 1000, 3000 (the check's own sampling error is ~0.2-0.6 %).
// Beyond the table (p < 0.001 or > 0.999) the upper tail is continued by the Gaussian tail of A,
// P(A > x) ∝ exp(−6x²) (the largest variance of a linear functional of B is 1/12).
#include <vector>

namespace smi::stats {

/// Largest n for which upool_threshold / upool_pvalue run the Monte Carlo (a few seconds at
/// 10^6 sets); above it they use this fitted form.
inline constexpr int kUpoolMonteCarloMaxN = 50;

/// The probabilities of the table.
const std::vector<double>& upool_asymptotic_probabilities();
/// U_crit(n, confidence) from the fitted form.
double upool_asymptotic_threshold(int n, double confidence);
/// P_H0(U >= u) from the fitted form.
double upool_asymptotic_pvalue(int n, double u);

}  // namespace smi::stats
