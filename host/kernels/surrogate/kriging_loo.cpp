// SPDX-License-Identifier: MIT
// Closed-form leave-one-out for universal Kriging at fixed theta (Dubrule 1983): with
// Qt = R^-1 - R^-1 F (F^T R^-1 F)^-1 F^T R^-1 = C^-T (I - Q Q^T) C^-1, the residual of point i
// is gamma_i / Qt_ii and its variance sigma2 / Qt_ii (normalised units).
#include <cmath>

#include "kernels/surrogate/kriging.hpp"

namespace smi::surrogate::kriging {

LooResult loo(const Model& md) {
  const Eigen::Index m = md.size();
  Eigen::MatrixXd Cinv = Eigen::MatrixXd::Identity(m, m);
  md.C.triangularView<Eigen::Lower>().solveInPlace(Cinv);
  const Eigen::MatrixXd QtC = md.Q.transpose() * Cinv;
  const Eigen::ArrayXd qd = Cinv.colwise().squaredNorm().array() - QtC.colwise().squaredNorm().array();
  LooResult r;
  r.residuals = (md.sY * md.gamma.array() / qd).matrix();
  r.variance = (md.process_variance() / qd).matrix();
  const Eigen::VectorXd y = md.mY + md.sY * md.Y.array();
  const double ss = (y.array() - y.mean()).square().sum();
  r.rmse = std::sqrt(r.residuals.squaredNorm() / static_cast<double>(m));
  r.q2 = ss > 0 ? 1.0 - r.residuals.squaredNorm() / ss : 0.0;
  return r;
}

}  // namespace smi::surrogate::kriging
