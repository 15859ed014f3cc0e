// SPDX-License-Identifier: MIT
// Common-random-number samples for propagation, screening and calibration.
#include "kernels/surrogate/propagate.hpp"

#include <algorithm>
#include <cmath>

#include "platform/core/errors.hpp"
#include "platform/core/rng.hpp"
#include "platform/core/thread_pool.hpp"

namespace smi::surrogate::propagate {

Eigen::VectorXd crn_uniforms(const std::string& name, Eigen::Index n, std::uint64_t seed, const std::string& stream) {
  Rng rng = Rng::derive(seed, stream + "/" + name);
  return rng.uniform(n);
}

Eigen::MatrixXd crn_sample(const std::vector<Input>& inputs, Eigen::Index n, std::uint64_t seed,
                           const std::string& stream, int threads) {
  if (n < 1) throw InvalidArgument("sample size n must be at least 1, got " + std::to_string(n));
  if (inputs.empty()) throw InvalidArgument("no inputs to sample");
  const auto k = static_cast<long>(inputs.size());
  for (const Input& in : inputs)
    if (!in.dist && !std::isfinite(in.value))
      throw InvalidArgument("input '" + in.name + "' is a constant that is not finite");
  // Each column's uniforms come from its own stream (one task per column); the quantiles, the
  // costly part, are then split into chunks so that both workers stay busy whatever k is.
  // Every element is computed by exactly one task: the sample does not depend on `threads`.
  Eigen::MatrixXd X(n, k);
  pool::parallel_for(k, threads, [&](long c) {
    const Input& in = inputs[static_cast<std::size_t>(c)];
    if (in.dist)
      X.col(c) = crn_uniforms(in.name, n, seed, stream);
    else
      X.col(c).setConstant(in.value);
  });
  constexpr Eigen::Index kChunk = 1 << 15;
  const Eigen::Index per = (n + kChunk - 1) / kChunk;
  pool::parallel_for(k * per, threads, [&](long t) {
    const long c = t / per;
    const stats::DistributionPtr& dist = inputs[static_cast<std::size_t>(c)].dist;
    if (!dist) return;
    const Eigen::Index r0 = (t % per) * kChunk, nr = std::min(kChunk, n - r0);
    X.col(c).segment(r0, nr) = dist->quantile(Eigen::VectorXd(X.col(c).segment(r0, nr)));
  });
  for (long c = 0; c < k; ++c) {
    const Input& in = inputs[static_cast<std::size_t>(c)];
    if (in.dist && !X.col(c).allFinite())
      throw InvalidArgument("input '" + in.name + "' (" + in.dist->describe() + ") gave non-finite quantiles");
  }
  return X;
}

}  // namespace smi::surrogate::propagate
