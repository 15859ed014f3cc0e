#pragma once
// Bootstrap confidence intervals on calibrated parameters (beyond the paper).
// Each replicate resamples the experimental data with replacement (seeded), rebuilds the
// objective on the resampled data and re-runs the whole calibration: its own starts (the given
// start and the seeded multistart points), not a warm start at the optimum, which would only
// measure the local spread and miss the other optima of a flat or multimodal problem. warm_start keeps the
// old, cheaper replicate. Percentile intervals summarise the spread. When every response has the same number
// of data they are
// resampled as paired rows (one specimen gives all its responses), otherwise independently.
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "kernels/improve/bounded_optimizer.hpp"

namespace smi::improve {

struct BootstrapOptions {
  int replicates = 100;
  std::uint64_t seed = 0;
  double level = 0.95;          ///< two-sided percentile interval
  OptimizerOptions optimizer;   ///< the replicates' calibration (its starts, multistart, budget)
  bool warm_start = false;      ///< start each replicate at the optimum, one start only
  /// Called after each replicate with (replicates done, replicates, evaluations so far).
  std::function<void(int, int, long)> progress;
};

struct BootstrapResult {
  Eigen::MatrixXd thetas;   ///< replicates × parameters (only successful replicates)
  Eigen::VectorXd lower;    ///< percentile bounds, one per parameter
  Eigen::VectorXd upper;
  Eigen::VectorXd stddev;   ///< bootstrap standard error
  int evaluations = 0;
  int failed = 0;           ///< replicates whose optimisation threw (their messages in warnings)
  bool paired = false;
  std::vector<std::string> warnings;
};

/// Builds the objective for one set of data (one vector per response).
using ObjectiveFactory = std::function<Objective(const std::vector<Eigen::VectorXd>& data)>;

/// A replicate's problem: its objective and, optionally, its gradient and start preparation
/// (set into the replicate's OptimizerOptions). `keep` holds whatever they refer to.
struct Replicate {
  Objective f;
  ObjectiveGradient gradient;
  std::function<PreparedStart(const Eigen::VectorXd&)> prepare_start;
  std::shared_ptr<const void> keep;
};
using ReplicateFactory = std::function<Replicate(const std::vector<Eigen::VectorXd>& data)>;

BootstrapResult bootstrap_calibration(const std::vector<Parameter>& params, const Eigen::VectorXd& optimum,
                                      const std::vector<Eigen::VectorXd>& data, const ReplicateFactory& make,
                                      const BootstrapOptions& opt);
BootstrapResult bootstrap_calibration(const std::vector<Parameter>& params, const Eigen::VectorXd& optimum,
                                      const std::vector<Eigen::VectorXd>& data, const ObjectiveFactory& make_objective,
                                      const BootstrapOptions& opt);

}  // namespace smi::improve
