#pragma once
// Bootstrap confidence intervals on calibrated parameters (beyond the paper; issue 6 item 6).
// Each replicate resamples the experimental data with replacement (seeded), rebuilds the
// objective on the resampled data and re-runs the calibration from the optimum; percentile
// intervals summarise the spread. When every response has the same number of data they are
// resampled as paired rows (one specimen gives all its responses), otherwise independently.
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "improve/bounded_optimizer.hpp"

namespace smi::improve {

struct BootstrapOptions {
  int replicates = 100;
  std::uint64_t seed = 0;
  double level = 0.95;          ///< two-sided percentile interval
  OptimizerOptions optimizer;   ///< multistart is forced to 1; the start is the optimum
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

BootstrapResult bootstrap_calibration(const std::vector<Parameter>& params, const Eigen::VectorXd& optimum,
                                      const std::vector<Eigen::VectorXd>& data, const ObjectiveFactory& make_objective,
                                      const BootstrapOptions& opt);

}  // namespace smi::improve
