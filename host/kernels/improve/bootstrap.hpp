// SPDX-License-Identifier: MIT
#pragma once
// Bootstrap confidence intervals on calibrated parameters (beyond the paper).
// Each replicate resamples the experimental data with replacement, rebuilds the objective on the
// resampled data and re-runs the calibration from its own starts: the optimum first (a warm start:
// a replicate's optimum is near the original one, so the first local run is short), then the
// seeded multistart points, so a flat or multimodal problem still shows its other optima; a
// warm start alone would only measure the local spread. warm_start keeps that one start only.
// Replicates run side by side on the thread pool (threads); each draws its resample from its own
// stream (Rng::derive(seed, "bootstrap/<b>")) and optimises from its own seed, so the numbers do
// not depend on the thread count. Every evaluation is one model call on the whole CRN batch.
// Percentile intervals summarise the spread, each endpoint with its Monte Carlo standard error
// (an order statistic's: the spread of the quantiles at a ± sqrt(a(1 − a)/B)), and the number
// of replicates that brings that error under a tenth of the interval's half-width: a percentile
// interval from few replicates rests on the one or two most extreme ones, and says so.
// When every response has the same number of data they are resampled as paired rows (one
// specimen gives all its responses), otherwise independently.
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "kernels/improve/bounded_optimizer.hpp"

namespace smi::improve {

/// The replicates' default relative tolerance (BootstrapOptions::xtol_rel).
inline constexpr double kBootstrapXtolRel = 1e-4;

struct BootstrapOptions {
  int replicates = 100;
  std::uint64_t seed = 0;
  double level = 0.95;          ///< two-sided percentile interval
  OptimizerOptions optimizer;   ///< the replicates' calibration (its starts, multistart, budget)
  bool warm_start = false;      ///< start each replicate at the optimum, one start only
  /// The replicates' relative tolerance on the scaled parameters (the calibration's when finer).
  /// A replicate's optimum matters to a fraction of the replicates' spread, which resampling a
  /// few specimens makes a percent of a range or more: 1e-4 leaves the standard errors the same
  /// to three digits and saves about 30 % of the evaluations (docs/benchmarks.md).
  double xtol_rel = kBootstrapXtolRel;
  /// Replicates optimised side by side (pool::run_tasks); the result does not depend on it. Above
  /// 1 the factory and the replicates' objectives are called from several threads at once and
  /// must be safe for that (C++ models, a Lua model behind its gate: yes; other Lua callbacks: no).
  int threads = 1;
  /// Called after each replicate with (replicates done, replicates, evaluations so far), one call
  /// at a time even when replicates run side by side.
  std::function<void(int, int, long)> progress;
};

struct BootstrapResult {
  Eigen::MatrixXd thetas;   ///< replicates × parameters (only successful replicates)
  Eigen::VectorXd lower;    ///< percentile bounds, one per parameter
  Eigen::VectorXd upper;
  Eigen::VectorXd stddev;   ///< bootstrap standard error
  /// The normal interval at the same level: optimum ± z sd (z the normal quantile of
  /// ½ + level/2), clipped to the parameter's bounds.
  Eigen::VectorXd normal_lower;
  Eigen::VectorXd normal_upper;
  Eigen::VectorXd lower_mc_error;  ///< Monte Carlo standard error of each lower endpoint
  Eigen::VectorXd upper_mc_error;  ///< and of each upper endpoint
  /// Replicates that would bring every endpoint's Monte Carlo error under a tenth of its
  /// interval's half-width (and leave at least 5 replicates beyond each endpoint).
  int replicates_needed = 0;
  int evaluations = 0;
  int failed = 0;           ///< replicates whose optimisation threw
  /// Each failed replicate (1-based) with its error, in replicate order.
  std::vector<std::pair<int, std::string>> failures;
  bool paired = false;
  std::vector<std::string> warnings;
};

/// One resample with replacement of the data (one vector per response), drawn from the stream
/// Rng::derive(seed, label): paired rows (one index per row for every response, which must then
/// have the same size) or each response on its own. The bootstrap's replicate b is label
/// "bootstrap/<b>", so replicates can be drawn in any order.
std::vector<Eigen::VectorXd> resample_data(const std::vector<Eigen::VectorXd>& data, bool paired, std::uint64_t seed,
                                          const std::string& label);
/// Every response has as many data as the first: their rows are specimens, resampled paired.
bool same_sizes(const std::vector<Eigen::VectorXd>& data);

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
