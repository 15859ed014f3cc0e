// SPDX-License-Identifier: MIT
#pragma once
// The concentrated likelihood of DACE (spec §4, steps 1-6) and its analytic gradient, shared
// by the searches and the final assembly. Internal to the Kriging kernel.
#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "kernels/surrogate/kriging.hpp"

namespace smi::surrogate::kriging::detail {

/// Normalised data plus the per-pair distances D (pairs i > j, column by column).
struct Problem {
  Eigen::MatrixXd S, F;
  Eigen::VectorXd Y;
  Corr corr = Corr::gauss;
  Eigen::MatrixXd D;  // P x n, P = m(m-1)/2
  double mu = 0.0;    // (10 + m) eps
  Problem(Eigen::MatrixXd S, Eigen::VectorXd Y, Trend t, Corr c);
  Eigen::Index m() const { return S.rows(); }
};

struct Factors {
  bool ok = false;  // false: R not positive definite (psi = +inf)
  Eigen::MatrixXd C, Ft, Q, G;
  Eigen::VectorXd beta, gamma, s;  // s: per-pair sum theta_j D_j
  double sigma2 = 0, psi = 0, log_psi = 0;
};

/// Steps 1-6 at (theta, nugget). Throws for an ill-conditioned trend ("F too ill conditioned").
Factors factorize(const Problem& pb, const Eigen::VectorXd& theta, double nugget);
/// Gradient of ln psi with respect to ln theta (and ln nugget when with_nugget).
Eigen::VectorXd log_psi_gradient(const Problem& pb, const Factors& f, const Eigen::VectorXd& theta, double nugget,
                                 bool with_nugget);

}  // namespace smi::surrogate::kriging::detail

namespace smi::surrogate::kriging {
/// Fills md's factors at (theta, nugget) from the problem (md already holds the scalings).
Model assemble(const detail::Problem& pb, const Eigen::VectorXd& theta, double nugget, Model md);
}  // namespace smi::surrogate::kriging
