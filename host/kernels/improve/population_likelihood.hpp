// SPDX-License-Identifier: MIT
#pragma once
// The likelihood of the population parameters θ (docs/spec/algorithms.md §9.1): the unknown
// inputs vary from specimen to specimen with distributions whose means and stds θ holds; each
// specimen i gives a vector y_i of all its measured responses (jointly: they share the inputs).
//
//   L(θ) = Π_i p(y_i | θ),   p(y_i | θ) = ∫ N(y_i; f(x), Σ_ε) p(x | θ) dx
//
// estimated from N propagated samples x_j = T_θ(z_j), the z_j common random numbers fixed for
// every θ (crn_mapping.hpp), so the estimate is a smooth function of θ:
//
//   p̂(y_i | θ) = (1/N) Σ_j N(y_i; f(x_j), Σ_ε + H),   H = h² S_f,  h = b (4 / ((R + 2) N))^(1/(R+4))
//
// S_f the sample covariance of the N predicted response vectors at θ, R the number of responses,
// b the bandwidth factor (1: the multivariate normal-reference rule; 0: no smoothing, the
// estimate is then unbiased for p(y_i | θ), and H only tames its variance when Σ_ε is small
// against the responses' spread). The bias is O(h²) = O(N^(−2/(R+4))).
//
// Monte Carlo error of log L̂ (delta method over the shared samples): with g_j = Σ_i K_ij / p̂_i,
// var(log L̂) ≈ var_j(g_j) / N.
//
// Batches: evaluate(Θ) maps the rows of Θ to N-row input blocks, stacks them (up to chunk_rows
// rows), calls the model once per stack, and sums the kernels over the pool, one θ per task.
#include <Eigen/Core>
#include <atomic>
#include <memory>
#include <vector>

#include "kernels/improve/crn_mapping.hpp"
#include "kernels/improve/statistical_objective.hpp"

namespace smi::improve {

struct PopulationOptions {
  Eigen::Index n = 2000;           ///< propagated samples per θ
  std::uint64_t seed = 0;          ///< of the common random numbers
  CrnKind crn = CrnKind::random;
  double bandwidth = 1.0;          ///< factor b on the normal-reference bandwidth (0: none)
  int threads = kDefaultThreads;   ///< kernel sums over θ in parallel (the same numbers on any count)
  Eigen::Index chunk_rows = Eigen::Index{1} << 20;  ///< model rows per call at most (at least one θ)
};

/// log L̂ per θ row and its Monte Carlo standard error.
struct PopulationEstimate {
  Eigen::VectorXd loglik;
  Eigen::VectorXd error;
};

class PopulationLikelihood {
 public:
  /// inputs: as the statistical calibration's (mean_param/std_param index θ's columns); data:
  /// specimens × responses; noise_cov: R×R, symmetric positive definite; model: X (N×k) -> Y (N×R).
  /// Throws InvalidArgument (no specimens, non-finite data, a noise matrix that is not SPD, an
  /// index outside θ) before any model run.
  PopulationLikelihood(std::vector<InputSpec> inputs, Eigen::Index params, Eigen::MatrixXd data, Eigen::MatrixXd noise_cov, Model model,
                       PopulationOptions o);

  PopulationEstimate evaluate(const Eigen::MatrixXd& Theta) const;
  Eigen::VectorXd operator()(const Eigen::MatrixXd& Theta) const { return evaluate(Theta).loglik; }

  /// The N×k inputs at θ (the CRN mapped by θ's means and stds).
  Eigen::MatrixXd inputs_at(const Eigen::VectorXd& theta) const;
  /// Model calls and model rows (N per θ) so far.
  long model_calls() const { return calls_->load(); }
  long model_rows() const { return rows_->load(); }
  const Eigen::MatrixXd& crn() const { return z_; }

 private:
  /// log p̂ and its error for one θ from its N×R predictions.
  std::pair<double, double> estimate(const Eigen::MatrixXd& Y) const;

  std::vector<InputSpec> inputs_;
  Eigen::Index params_;
  Eigen::MatrixXd data_;
  Eigen::MatrixXd noise_;
  Model model_;
  PopulationOptions o_;
  Eigen::MatrixXd z_;
  std::shared_ptr<std::atomic<long>> calls_ = std::make_shared<std::atomic<long>>(0);
  std::shared_ptr<std::atomic<long>> rows_ = std::make_shared<std::atomic<long>>(0);
};

}  // namespace smi::improve
