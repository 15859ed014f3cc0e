// SPDX-License-Identifier: MIT
#include "kernels/stats/fast_normal.hpp"

#include <vector>

#include "platform/core/normal.hpp"

namespace smi::stats::detail {

const double* phi_table() {
  // Built once (thread-safe static init) from the full-precision Φ and φ of core/normal.hpp.
  static const std::vector<double> tab = [] {
    std::vector<double> t(2 * kPhiTableSize);
    for (int k = 0; k < kPhiTableSize; ++k) {
      const double x = kPhiTableLo + k / kPhiTableInvStep;
      t[2 * k] = normal_cdf(x);
      t[2 * k + 1] = normal_pdf(x);
    }
    return t;
  }();
  return tab.data();
}

}  // namespace smi::stats::detail
