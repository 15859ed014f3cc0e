// SPDX-License-Identifier: MIT
#pragma once
// Uncertainty propagation with common random numbers (spec §7): every input's column of the
// sample is its distribution's quantile of a fixed uniform column drawn from the stream
// derive(seed, "<stream>/<input name>"), so the same seed gives the same standard sample and
// an input's column does not move when other inputs are added, removed or re-parametrised.
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "kernels/stats/distribution.hpp"

namespace smi::surrogate::propagate {

/// smi.propagate's sample size unless told.
inline constexpr Eigen::Index kDefaultSampleSize = 10000;
/// The largest sample smi.propagate draws (2^28 rows: 2 GB a column of doubles).
inline constexpr Eigen::Index kMaxSampleSize = Eigen::Index{1} << 28;

/// A named input: a distribution, or a constant when dist is null.
struct Input {
  std::string name;
  stats::DistributionPtr dist;
  double value = 0.0;
};

/// The n x k sample (columns in the order of `inputs`). `threads` workers share the quantile
/// evaluations (the sample does not depend on the count).
Eigen::MatrixXd crn_sample(const std::vector<Input>& inputs, Eigen::Index n, std::uint64_t seed,
                           const std::string& stream = "base", int threads = 2);
/// The fixed uniforms behind crn_sample's column for `name` (in (0, 1)).
Eigen::VectorXd crn_uniforms(const std::string& name, Eigen::Index n, std::uint64_t seed, const std::string& stream);

/// A model on whole matrices: rows are points; returns one column per output.
using MatrixModel = std::function<Eigen::MatrixXd(const Eigen::MatrixXd&)>;

}  // namespace smi::surrogate::propagate
