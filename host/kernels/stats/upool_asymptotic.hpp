#pragma once
// u-pooling for many u-values without minutes of Monte Carlo. Under H0, sqrt(n)·U tends to
// A = ∫_0^1 |B(t)| dt, the L1 norm of a Brownian bridge (G_n(u) − u is an empirical process:
// sqrt(n)(G_n − id) → B), and it is close to its limit already at moderate n (sqrt(n)·U_crit at
// 95 % is 0.5816 at n = 33 and 0.5815 at n = 256, Monte Carlo). The quantiles of sqrt(n)·U are
// held as a + b/sqrt(n) per probability p, a and b fitted by weighted least squares to Monte
// Carlo quantiles at n = 48, 96, 192, 384 (bench/bench_upool_fit.cpp fit, 1.5·10^6 sets in all);
// a(p) is then the quantile of A. Error against an independent Monte Carlo (bench_upool_fit
// check; bench/results/upool_asymptotic.md): within 0.5 % of U_crit at n = 100 ... 3000.
// Beyond the table (p < 0.001 or > 0.999) the upper tail is continued by the Gaussian tail of A,
// P(A > x) ∝ exp(−6x²) (the largest variance of a linear functional of B is 1/12).
#include <vector>

namespace smi {

/// Largest n for which upool_threshold / upool_pvalue run the Monte Carlo (a few seconds at
/// 10^6 sets); above it they use this fitted form.
inline constexpr int kUpoolMonteCarloMaxN = 50;

/// The probabilities of the table.
const std::vector<double>& upool_asymptotic_probabilities();
/// U_crit(n, confidence) from the fitted form.
double upool_asymptotic_threshold(int n, double confidence);
/// P_H0(U >= u) from the fitted form.
double upool_asymptotic_pvalue(int n, double u);

}  // namespace smi
