// SPDX-License-Identifier: MIT
#pragma once
// Prior densities of the Bayesian calibration (docs/spec/algorithms.md §9.2): one independent
// density per parameter, uniform on a range by default, or normal / lognormal, optionally
// truncated to a range. A prior enters the posterior as a density (its log is added to the
// log-likelihood), never as a weighted penalty.
#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

#include "kernels/stats/distribution.hpp"

namespace smi::improve {

enum class PriorKind { uniform, normal, lognormal };

/// One parameter's prior. uniform: on [lower, upper] (both finite). normal / lognormal: mean and
/// std of the parameter itself (a lognormal's, not its logarithm's), truncated to [lower, upper]
/// where those are finite (the density renormalised to the range, so it still integrates to 1).
struct Prior {
  std::string name;
  PriorKind kind = PriorKind::uniform;
  double mean = 0.0;
  double std = 1.0;
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
};

/// The priors of all parameters, checked and ready to evaluate and sample.
class PriorSet {
 public:
  /// Throws InvalidArgument naming the parameter: a uniform without a finite range, lower >= upper,
  /// std <= 0, a lognormal with mean <= 0, or a range that holds no prior mass.
  explicit PriorSet(std::vector<Prior> priors);

  Eigen::Index size() const { return static_cast<Eigen::Index>(priors_.size()); }
  const std::vector<Prior>& priors() const { return priors_; }
  std::vector<std::string> names() const;

  /// Σ log π_k(θ_k) per row of Theta (rows = points); −∞ outside a range or a support.
  Eigen::VectorXd log_density(const Eigen::MatrixXd& Theta) const;
  /// Maps uniforms U (rows = points, in (0, 1)) to prior draws by each prior's quantile.
  Eigen::MatrixXd from_uniforms(const Eigen::MatrixXd& U) const;

 private:
  struct Part {
    stats::DistributionPtr dist;  ///< the untruncated density
    double cdf_lower = 0.0;       ///< its cdf at the range's ends
    double cdf_upper = 1.0;
    double log_mass = 0.0;        ///< log of the mass within the range
  };
  std::vector<Prior> priors_;
  std::vector<Part> parts_;
};

std::string prior_kind_name(PriorKind k);

}  // namespace smi::improve
