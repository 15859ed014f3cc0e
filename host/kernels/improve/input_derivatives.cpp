// SPDX-License-Identifier: MIT
#include "kernels/improve/input_derivatives.hpp"

#include <algorithm>
#include <cmath>

#include "platform/core/normal.hpp"

namespace smi::improve {

InputDerivatives input_derivatives_numeric(InputFamily family, double mean, double std, const Eigen::Ref<const Eigen::VectorXd>& z) {
  InputDerivatives d;
  const double hm = 1e-6 * std::max(std::abs(mean), std::max(std, 1e-3));
  const double hs = 1e-6 * std::max(std, 1e-3 * std::max(1.0, std::abs(mean)));
  d.dmean = (map_standard_normal(family, mean + hm, std, z, "input") - map_standard_normal(family, mean - hm, std, z, "input")) / (2 * hm);
  // One-sided at std = 0 (a std below 0 does not exist).
  const double lo = std::max(0.0, std - hs);
  d.dstd = (map_standard_normal(family, mean, std + hs, z, "input") - map_standard_normal(family, mean, lo, z, "input")) / (std + hs - lo);
  return d;
}

InputDerivatives input_derivatives(InputFamily family, double mean, double std, const Eigen::Ref<const Eigen::VectorXd>& z) {
  InputDerivatives d;
  const Eigen::Index n = z.size();
  switch (family) {
    case InputFamily::normal:
      d.dmean = Eigen::VectorXd::Ones(n);
      d.dstd = z;
      return d;
    case InputFamily::constant:
      d.dmean = Eigen::VectorXd::Ones(n);
      d.dstd = Eigen::VectorXd::Zero(n);
      return d;
    case InputFamily::uniform: {
      d.dmean = Eigen::VectorXd::Ones(n);
      d.dstd.resize(n);
      for (Eigen::Index i = 0; i < n; ++i) d.dstd[i] = std::sqrt(3.0) * (2.0 * normal_cdf(z[i]) - 1.0);
      return d;
    }
    case InputFamily::lognormal: {
      const LognormalParams p = lognormal_params(mean, std);
      const double r = std / mean, q = 1.0 + r * r;
      // sig² = ln(1 + s²/m²): d sig/ds = s / (m² q sig), d sig/dm = −(s/m) d sig/ds; as s -> 0
      // sig -> s/m and d sig/ds -> 1/m.
      const double dsig_ds = p.sigma_ln > 0.0 ? std / (mean * mean * q * p.sigma_ln) : 1.0 / mean;
      const double dsig_dm = -r * dsig_ds;
      const double dmu_dm = 1.0 / mean - p.sigma_ln * dsig_dm, dmu_ds = -p.sigma_ln * dsig_ds;
      const Eigen::ArrayXd x = (p.mu_ln + p.sigma_ln * z.array()).exp();
      d.dmean = (x * (dmu_dm + z.array() * dsig_dm)).matrix();
      d.dstd = (x * (dmu_ds + z.array() * dsig_ds)).matrix();
      return d;
    }
    default:
      break;
  }
  return input_derivatives_numeric(family, mean, std, z);
}

}  // namespace smi::improve
