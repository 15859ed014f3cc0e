// SPDX-License-Identifier: MIT
#pragma once
// Profile intervals. For each parameter the objective is minimised over the
// others with that parameter held at a value, walking out from the optimum on each side until
// the profile rises by `delta` (then the crossing is bisected) or the bound is reached. For a
// negative log-likelihood, delta = ½ χ²₁(level) gives the likelihood-ratio interval at `level`.
// A side that reaches its bound within delta is open there; a parameter open on both sides is
// not determined by the data.
#include <Eigen/Core>
#include <vector>

#include "kernels/improve/bounded_optimizer.hpp"

namespace smi::improve {

struct ProfileOptions {
  double delta = 1.3527717;  ///< objective increase bounding the interval (½ χ²₁(0.90))
  int bisections = 8;        ///< refinement of each crossing
  int max_steps = 12;        ///< profile points per side before the crossing
  OptimizerOptions optimizer;  ///< for the inner minimisations (multistart forced to 1)
};

/// ½ χ²₁ quantile at `level`: the delta of a likelihood-ratio interval.
double likelihood_ratio_delta(double level);
/// The same with a small-sample calibration for `observations` data and `parameters` fitted
/// ones (n > k): delta = n/2 · ln(1 + F₁,ₙ₋ₖ(level)/(n − k)), F₁,ₘ = t²ₘ((1 + level)/2). For a
/// normal linear model with p coefficients and an error sd (k = p + 1) the profile likelihood
/// ratio of a coefficient is n ln(1 + t²/(n − p)), so the interval is exact up to using n − k for
/// n − p (slightly conservative); on the line of bench/run_coverage.sh (n = 25, k = 3) the exact
/// coverage of the error sd's interval is 86.9 % with ½ χ²₁ and 89.6 % with this delta
/// (bench/coverage_exact.py). It tends to ½ χ²₁ as n grows.
double likelihood_ratio_delta(double level, int observations, int parameters);

struct ProfileInterval {
  double lower = 0.0, upper = 0.0;
  bool lower_open = false, upper_open = false;  ///< reached the bound still within delta
  bool determined = true;                       ///< false when open on both sides
  Eigen::VectorXd nodes, values;                ///< the profile, ascending in the parameter
};

struct ProfileResult {
  std::vector<ProfileInterval> intervals;  ///< one per parameter
  int evaluations = 0;
  std::vector<std::string> warnings;
};

/// `value` is the objective at `optimum`. `gradient` (optional) is passed to the inner SLSQP.
ProfileResult profile_intervals(const std::vector<Parameter>& params, const Objective& f, const Eigen::VectorXd& optimum, double value,
                                const ProfileOptions& opt, const ObjectiveGradient& gradient = {});

}  // namespace smi::improve
