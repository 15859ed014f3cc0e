// SPDX-License-Identifier: MIT
#include "kernels/stats/upool_asymptotic.hpp"

#include <algorithm>
#include <cmath>

namespace smi::stats {
namespace {

struct Row {
  double p, a, b;  // sqrt(n)·U_crit(n, p) = a + b/sqrt(n)
};

// Made by `bench_upool_fit fit` (see the header); do not edit by hand.
constexpr Row kTable[] = {
#include "kernels/stats/upool_asymptotic_table.inc"
};
constexpr int kRows = static_cast<int>(sizeof kTable / sizeof kTable[0]);

double at(int i, double rn) { return kTable[i].a + kTable[i].b / rn; }

}  // namespace

const std::vector<double>& upool_asymptotic_probabilities() {
  static const std::vector<double> ps = {
      0.001, 0.002, 0.005, 0.01, 0.02, 0.03, 0.04, 0.05, 0.06, 0.07, 0.08, 0.09, 0.1,  0.11,  0.12,  0.13, 0.14,
      0.15,  0.16,  0.17,  0.18, 0.19, 0.2,  0.21, 0.22, 0.23, 0.24, 0.25, 0.26, 0.27, 0.28,  0.29,  0.3,  0.31,
      0.32,  0.33,  0.34,  0.35, 0.36, 0.37, 0.38, 0.39, 0.4,  0.41, 0.42, 0.43, 0.44, 0.45,  0.46,  0.47, 0.48,
      0.49,  0.5,   0.51,  0.52, 0.53, 0.54, 0.55, 0.56, 0.57, 0.58, 0.59, 0.6,  0.61, 0.62,  0.63,  0.64, 0.65,
      0.66,  0.67,  0.68,  0.69, 0.7,  0.71, 0.72, 0.73, 0.74, 0.75, 0.76, 0.77, 0.78, 0.79,  0.8,   0.81, 0.82,
      0.83,  0.84,  0.85,  0.86, 0.87, 0.88, 0.89, 0.9,  0.91, 0.92, 0.93, 0.94, 0.95, 0.96,  0.97,  0.98, 0.99,
      0.995, 0.998, 0.999};
  return ps;
}

double upool_asymptotic_threshold(int n, double confidence) {
  const double rn = std::sqrt(static_cast<double>(n));
  const double c = confidence;
  double x;
  if (c <= kTable[0].p) {
    x = at(0, rn) * c / kTable[0].p;  // the lower tail is never a threshold in practice
  } else if (c >= kTable[kRows - 1].p) {
    // P(A > x) = (1 − p_last)·exp(−6(x² − x_last²))
    const double xl = at(kRows - 1, rn);
    x = std::sqrt(xl * xl + std::log((1.0 - kTable[kRows - 1].p) / (1.0 - c)) / 6.0);
  } else {
    int i = 0;
    while (kTable[i + 1].p < c) ++i;
    const double w = (c - kTable[i].p) / (kTable[i + 1].p - kTable[i].p);
    x = (1.0 - w) * at(i, rn) + w * at(i + 1, rn);
  }
  return x / rn;
}

double upool_asymptotic_pvalue(int n, double u) {
  const double rn = std::sqrt(static_cast<double>(n));
  const double x = rn * u;
  if (x <= at(0, rn)) return std::clamp(1.0 - kTable[0].p * std::max(0.0, x) / at(0, rn), 0.0, 1.0);
  const double xl = at(kRows - 1, rn);
  if (x >= xl) return (1.0 - kTable[kRows - 1].p) * std::exp(-6.0 * (x * x - xl * xl));
  int i = 0;
  while (at(i + 1, rn) < x) ++i;
  const double w = (x - at(i, rn)) / (at(i + 1, rn) - at(i, rn));
  return 1.0 - ((1.0 - w) * kTable[i].p + w * kTable[i + 1].p);
}

}  // namespace smi::stats
