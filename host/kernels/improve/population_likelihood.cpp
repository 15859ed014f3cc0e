// SPDX-License-Identifier: MIT
#include "kernels/improve/population_likelihood.hpp"

#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "platform/core/errors.hpp"
#include "platform/core/thread_pool.hpp"

namespace smi::improve {

namespace {

constexpr double kLog2Pi = 1.8378770664093453;

/// Sample covariance of the rows of Y.
Eigen::MatrixXd covariance(const Eigen::MatrixXd& Y) {
  const Eigen::MatrixXd D = Y.rowwise() - Y.colwise().mean();
  return D.transpose() * D / static_cast<double>(std::max<Eigen::Index>(1, Y.rows() - 1));
}

}  // namespace

PopulationLikelihood::PopulationLikelihood(std::vector<InputSpec> inputs, Eigen::Index params, Eigen::MatrixXd data, Eigen::MatrixXd noise_cov,
                                           Model model, PopulationOptions o)
    : inputs_(std::move(inputs)), params_(params), data_(std::move(data)), noise_(std::move(noise_cov)), model_(std::move(model)), o_(o) {
  if (inputs_.empty()) throw InvalidArgument("no inputs: describe at least one model input");
  if (data_.rows() < 1 || data_.cols() < 1) throw InvalidArgument("no data: give at least one specimen's responses");
  if (!data_.allFinite()) throw InvalidArgument("the data hold a value that is not finite (NaN or inf)");
  if (noise_.rows() != data_.cols() || noise_.cols() != data_.cols())
    throw DimensionMismatch(fmt::format("the noise covariance is {}x{} for {} responses", noise_.rows(), noise_.cols(), data_.cols()));
  if (!noise_.allFinite() || Eigen::LLT<Eigen::MatrixXd>(noise_).info() != Eigen::Success)
    throw InvalidArgument("the noise covariance must be symmetric positive definite (every response's noise sd > 0)");
  if (o_.n < 2) throw InvalidArgument(fmt::format("n (propagated samples per theta) must be at least 2, got {}", o_.n));
  if (!(o_.bandwidth >= 0.0) || !std::isfinite(o_.bandwidth)) throw InvalidArgument(fmt::format("bandwidth must be a factor >= 0, got {}", o_.bandwidth));
  for (const InputSpec& in : inputs_)
    if (in.mean_param >= params_ || in.std_param >= params_)
      throw InvalidArgument(fmt::format("input '{}' refers to a parameter beyond the {} calibrated ones", in.name, params_));
  if (!model_) throw InvalidArgument("no model");
  z_ = crn_matrix(o_.n, static_cast<Eigen::Index>(inputs_.size()), o_.seed, o_.crn);
}

Eigen::MatrixXd PopulationLikelihood::inputs_at(const Eigen::VectorXd& theta) const {
  if (theta.size() != params_) throw DimensionMismatch(fmt::format("theta has {} values for {} parameters", theta.size(), params_));
  Eigen::MatrixXd X(o_.n, static_cast<Eigen::Index>(inputs_.size()));
  for (std::size_t j = 0; j < inputs_.size(); ++j) {
    const InputSpec& in = inputs_[j];
    const double mean = in.mean_param >= 0 ? theta[in.mean_param] : in.mean;
    const double sd = in.std_param >= 0 ? theta[in.std_param] : in.std;
    X.col(static_cast<Eigen::Index>(j)) =
        map_standard_normal(in.family, mean, sd, z_.col(static_cast<Eigen::Index>(j)), fmt::format("input '{}'", in.name), in.shape);
  }
  return X;
}

std::pair<double, double> PopulationLikelihood::estimate(const Eigen::MatrixXd& Y) const {
  const Eigen::Index N = Y.rows(), R = Y.cols();
  const double rr = static_cast<double>(R);
  const double h = o_.bandwidth * std::pow(4.0 / ((rr + 2.0) * static_cast<double>(N)), 1.0 / (rr + 4.0));
  const Eigen::MatrixXd C = noise_ + h * h * covariance(Y);
  const Eigen::LLT<Eigen::MatrixXd> llt(C);
  const Eigen::MatrixXd L = llt.matrixL();
  const double log_norm = -L.diagonal().array().log().sum() - 0.5 * rr * kLog2Pi;
  const Eigen::Index n = data_.rows();
  Eigen::MatrixXd logK(N, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    Eigen::MatrixXd D = (-(Y.rowwise() - data_.row(i))).transpose();  // R×N: y_i − f(x_j)
    L.triangularView<Eigen::Lower>().solveInPlace(D);
    logK.col(i) = (-0.5 * D.colwise().squaredNorm().array() + log_norm).matrix().transpose();
  }
  double loglik = 0.0;
  Eigen::VectorXd g = Eigen::VectorXd::Zero(N);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double m = logK.col(i).maxCoeff();
    const double log_p = m + std::log((logK.col(i).array() - m).exp().sum() / static_cast<double>(N));
    loglik += log_p;
    g.array() += (logK.col(i).array() - log_p).exp();  // K_ij / p̂_i
  }
  const double var_g = (g.array() - g.mean()).square().sum() / static_cast<double>(N - 1);
  return {loglik, std::sqrt(var_g / static_cast<double>(N))};
}

PopulationEstimate PopulationLikelihood::evaluate(const Eigen::MatrixXd& Theta) const {
  if (Theta.cols() != params_) throw DimensionMismatch(fmt::format("theta has {} columns for {} parameters", Theta.cols(), params_));
  PopulationEstimate e{Eigen::VectorXd(Theta.rows()), Eigen::VectorXd(Theta.rows())};
  const Eigen::Index N = o_.n, k = static_cast<Eigen::Index>(inputs_.size());
  const Eigen::Index per_call = std::max<Eigen::Index>(1, o_.chunk_rows / N);
  for (Eigen::Index t0 = 0; t0 < Theta.rows(); t0 += per_call) {
    const Eigen::Index m = std::min(per_call, Theta.rows() - t0);
    Eigen::MatrixXd X(m * N, k);
    pool::parallel_for(static_cast<long>(m), o_.threads, [&](long t) {
      X.middleRows(t * N, N) = inputs_at(Theta.row(t0 + t).transpose());
    });
    const Eigen::MatrixXd Y = model_(X);
    calls_->fetch_add(1);
    rows_->fetch_add(static_cast<long>(X.rows()));
    if (Y.rows() != X.rows() || Y.cols() != data_.cols())
      throw DimensionMismatch(fmt::format("the model returned {}x{} outputs for {} input rows and {} responses", Y.rows(), Y.cols(), X.rows(),
                                          data_.cols()));
    pool::parallel_for(static_cast<long>(m), o_.threads, [&](long t) {
      const auto block = Y.middleRows(t * N, N);
      if (!block.allFinite()) {
        std::string at;
        for (Eigen::Index c = 0; c < Theta.cols(); ++c) at += fmt::format("{}{:.6g}", c ? ", " : "", Theta(t0 + t, c));
        throw InvalidArgument(fmt::format("the model returned a value that is not finite for the inputs at theta = ({})", at));
      }
      const auto [ll, err] = estimate(block);
      e.loglik[t0 + t] = ll;
      e.error[t0 + t] = err;
    });
  }
  return e;
}

}  // namespace smi::improve
