// SPDX-License-Identifier: MIT
#pragma once
// Φ(z) for bulk evaluation (KDE CDFs): a table of Φ and φ at nodes 1/64 apart on [−9, 9] and a
// 6-term Taylor expansion about the nearest node (|d| <= 1/128): Φ(x0 + d) = Φ(x0) +
// φ(x0) Σ_{m=1..6} (−1)^{m−1} He_{m−1}(x0) d^m / m!. Truncation error < 1e-17; the absolute
// error is that of the table entries (1e-16). Outside [−9, 9] it returns 0 or 1 (Φ(−9) = 1e-19).
namespace smi::stats::detail {

inline constexpr double kPhiTableLo = -9.0;
inline constexpr double kPhiTableInvStep = 64.0;
inline constexpr int kPhiTableSize = 18 * 64 + 1;

/// Φ and φ at the nodes (interleaved: [2k] = Φ, [2k+1] = φ).
const double* phi_table();

inline double fast_normal_cdf(double z, const double* tab) {
  if (z <= -9.0) return 0.0;
  if (z >= 9.0) return 1.0;
  const double s = (z - kPhiTableLo) * kPhiTableInvStep;
  const int k = static_cast<int>(s + 0.5);
  const double x = kPhiTableLo + k / kPhiTableInvStep;
  const double d = z - x;
  const double x2 = x * x;
  const double c2 = -0.5 * x;
  const double c3 = (x2 - 1.0) * (1.0 / 6.0);
  const double c4 = -x * (x2 - 3.0) * (1.0 / 24.0);
  const double c5 = (x2 * x2 - 6.0 * x2 + 3.0) * (1.0 / 120.0);
  const double c6 = -x * (x2 * x2 - 10.0 * x2 + 15.0) * (1.0 / 720.0);
  const double poly = d * (1.0 + d * (c2 + d * (c3 + d * (c4 + d * (c5 + d * c6)))));
  return tab[2 * k] + tab[2 * k + 1] * poly;
}

}  // namespace smi::stats::detail
