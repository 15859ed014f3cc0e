// SPDX-License-Identifier: MIT
// Ridge polynomial with closed-form leave-one-out selection (see poly_ridge.hpp).
#include "kernels/surrogate/poly_ridge.hpp"

#include <Eigen/SVD>
#include <cmath>
#include <limits>
#include <vector>

#include "platform/core/errors.hpp"

namespace smi::surrogate::polyfit {
namespace {

// Standardised basis without intercept: z_j, and z_j^2 - 1 for the quadratic basis.
Eigen::MatrixXd basis_matrix(const Eigen::MatrixXd& X, const Eigen::VectorXd& mu, const Eigen::VectorXd& sd, Basis b) {
  std::vector<Eigen::Index> cols;
  for (Eigen::Index j = 0; j < X.cols(); ++j)
    if (sd(j) > 0) cols.push_back(j);
  const Eigen::Index k = static_cast<Eigen::Index>(cols.size());
  Eigen::MatrixXd F(X.rows(), b == Basis::quadratic ? 2 * k : k);
  for (Eigen::Index c = 0; c < k; ++c) {
    const Eigen::Index j = cols[static_cast<std::size_t>(c)];
    F.col(c) = (X.col(j).array() - mu(j)) / sd(j);
    if (b == Basis::quadratic) F.col(k + c) = F.col(c).array().square() - 1.0;
  }
  return F;
}

}  // namespace

Basis parse_basis(const std::string& name) {
  if (name == "linear") return Basis::linear;
  if (name == "quadratic") return Basis::quadratic;
  throw InvalidArgument("basis must be \"linear\" or \"quadratic\", got '" + name + "'");
}

const char* basis_name(Basis b) { return b == Basis::linear ? "linear" : "quadratic"; }

Eigen::VectorXd Fit::predict(const Eigen::MatrixXd& X) const {
  if (X.cols() != mu.size())
    throw DimensionMismatch("surrogate has " + std::to_string(mu.size()) + " inputs, got " + std::to_string(X.cols()));
  const Eigen::MatrixXd F = basis_matrix(X, mu, sd, basis);
  return ((F.rowwise() - fmean.transpose()) * beta).array() + intercept;
}

Fit fit(const Eigen::MatrixXd& X, const Eigen::VectorXd& y, Basis basis, double lambda) {
  const Eigen::Index m = X.rows();
  if (m < 3) throw InvalidArgument("a surrogate needs at least 3 runs, got " + std::to_string(m));
  if (y.size() != m) throw DimensionMismatch("runs and outputs differ in length");
  if (!y.allFinite()) throw InvalidArgument("an output of the surrogate's design runs is not finite");
  Fit f;
  f.basis = basis;
  f.mu = X.colwise().mean().transpose();
  f.sd.resize(X.cols());
  for (Eigen::Index j = 0; j < X.cols(); ++j) {
    const double s = std::sqrt((X.col(j).array() - f.mu(j)).square().sum() / static_cast<double>(m - 1));
    f.sd(j) = s > 1e-300 * (1.0 + std::abs(f.mu(j))) ? s : 0.0;
  }
  const Eigen::MatrixXd F = basis_matrix(X, f.mu, f.sd, basis);
  const Eigen::Index p = F.cols();
  f.terms = p;
  f.fmean = F.colwise().mean().transpose();
  const double ymean = y.mean();
  const Eigen::VectorXd yc = y.array() - ymean;
  const double sst = yc.squaredNorm();
  f.intercept = ymean;
  if (p == 0 || sst == 0) {
    f.beta = Eigen::VectorXd::Zero(p);
    f.q2 = f.r2 = sst == 0 ? 1.0 : 0.0;
    f.press = sst == 0 ? 0.0 : sst * static_cast<double>(m * m) / static_cast<double>((m - 1) * (m - 1));
    return f;
  }
  const Eigen::MatrixXd Fc = F.rowwise() - f.fmean.transpose();
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(Fc, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd& s = svd.singularValues();
  const Eigen::MatrixXd& U = svd.matrixU();
  const Eigen::VectorXd uy = U.transpose() * yc;
  const Eigen::MatrixXd U2 = U.array().square();
  const double smax2 = s(0) * s(0);
  const Eigen::Index rank = (s.array() > s(0) * 1e-12).count();

  std::vector<double> lambdas;
  if (lambda >= 0) {
    lambdas.push_back(lambda);
  } else {
    if (rank == p && p < m - 1) lambdas.push_back(0.0);
    for (int t = -20; t <= 2; ++t) lambdas.push_back(smax2 * std::pow(10.0, 0.5 * t));
  }
  double best = std::numeric_limits<double>::infinity();
  for (double lam : lambdas) {
    Eigen::VectorXd shrink(s.size());  // s^2 / (s^2 + lambda), 0 beyond the rank
    for (Eigen::Index i = 0; i < s.size(); ++i)
      shrink(i) = i < rank ? s(i) * s(i) / (s(i) * s(i) + lam) : 0.0;
    const Eigen::VectorXd fitted = U * shrink.cwiseProduct(uy);
    const Eigen::VectorXd h = (U2 * shrink).array() + 1.0 / static_cast<double>(m);
    double press = 0;
    bool ok = true;
    for (Eigen::Index i = 0; i < m; ++i) {
      const double d = 1.0 - h(i);
      if (d < 1e-10) {
        ok = false;
        break;
      }
      const double e = (yc(i) - fitted(i)) / d;
      press += e * e;
    }
    if (ok && press < best) {
      best = press;
      f.lambda = lam;
      f.r2 = 1.0 - (yc - fitted).squaredNorm() / sst;
    }
  }
  if (!std::isfinite(best))
    throw InvalidArgument("the surrogate's leave-one-out error is undefined: every run is a leverage point (" +
                          std::to_string(m) + " runs for " + std::to_string(p + 1) +
                          " basis terms); add runs or use basis = \"linear\"");
  f.press = best;
  f.q2 = 1.0 - best / sst;
  Eigen::VectorXd coef(s.size());
  for (Eigen::Index i = 0; i < s.size(); ++i) coef(i) = i < rank ? s(i) / (s(i) * s(i) + f.lambda) : 0.0;
  f.beta = svd.matrixV() * coef.cwiseProduct(uy);
  return f;
}

}  // namespace smi::surrogate::polyfit
