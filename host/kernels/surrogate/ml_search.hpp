// SPDX-License-Identifier: MIT
#pragma once
// Maximum-likelihood search for theta (and optionally the nugget): candidate starts on a
// space-filling design in log space, then L-BFGS (NLopt) on the analytic gradient of ln psi
// from the best few, in parallel.
#include <Eigen/Core>
#include <cstdint>

#include "platform/core/cancel.hpp"
#include "kernels/surrogate/likelihood.hpp"

namespace smi::surrogate::kriging::detail {

struct MlResult {
  Eigen::VectorXd theta;
  double nugget = 0, log_psi = 0;
  int evaluations = 0;
};

/// lower/upper: theta bounds (length n); nugget bounds used when estimate_nugget.
/// With `start` (theta, then ln nugget when estimated, as log-parameters' exponentials): a
/// single local search from it with at most `maxeval` evaluations (the polish on the full
/// data after a search on a subset). `stop`, the run's cancel token, is polled between starts
/// and after each local search.
MlResult ml_search(const Problem& pb, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, double nugget,
                   bool estimate_nugget, int starts, std::uint64_t seed, int threads,
                   const MlResult* start = nullptr, int maxeval = 0,
                   const cancel::Token& stop = cancel::process_token());

}  // namespace smi::surrogate::kriging::detail
