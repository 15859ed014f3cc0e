#pragma once
// Profile intervals (issue 11 item 4). For each parameter the objective is minimised over the
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
