// SPDX-License-Identifier: MIT
#pragma once
// Derivatives of the CRN-mapped inputs x_i = Q(Φ(z_i); mean, std) with respect to the mean and
// std (the chain rule through each family's quantile function):
//   normal     x = m + s z                     dx/dm = 1, dx/ds = z
//   lognormal  x = exp(mu + sig z), sig² = ln(1 + s²/m²), mu = ln m − sig²/2
//              dx = x (dmu + z dsig)
//   uniform    x = m + √3 s (2Φ(z) − 1)        dx/dm = 1, dx/ds = √3 (2Φ(z) − 1)
//   constant   x = m                           dx/dm = 1, dx/ds = 0
// Any other family: central differences of map_standard_normal (no model run; the mapping is
// cheap and smooth), so a family added to crn_mapping works here before it has a closed form.
#include <Eigen/Core>

#include "kernels/improve/crn_mapping.hpp"

namespace smi::improve {

struct InputDerivatives {
  Eigen::VectorXd dmean, dstd;
};

InputDerivatives input_derivatives(InputFamily family, double mean, double std, const Eigen::Ref<const Eigen::VectorXd>& z);

/// The same by central differences of map_standard_normal (the reference the tests use, and the
/// fallback for families without a closed form).
InputDerivatives input_derivatives_numeric(InputFamily family, double mean, double std, const Eigen::Ref<const Eigen::VectorXd>& z);

}  // namespace smi::improve
