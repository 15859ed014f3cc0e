// SPDX-License-Identifier: MIT
#include "kernels/improve/bootstrap.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>
#include <optional>

#include "platform/core/descriptive.hpp"
#include "platform/core/errors.hpp"
#include "platform/core/normal.hpp"
#include "platform/core/rng.hpp"
#include "platform/core/thread_pool.hpp"

namespace smi::improve {

BootstrapResult bootstrap_calibration(const std::vector<Parameter>& params, const Eigen::VectorXd& optimum,
                                      const std::vector<Eigen::VectorXd>& data, const ObjectiveFactory& make_objective,
                                      const BootstrapOptions& opt) {
  ReplicateFactory make = [&make_objective](const std::vector<Eigen::VectorXd>& d) { return Replicate{make_objective(d), {}, {}, {}}; };
  return bootstrap_calibration(params, optimum, data, make, opt);
}

std::vector<Eigen::VectorXd> resample_data(const std::vector<Eigen::VectorXd>& data, bool paired, std::uint64_t seed,
                                          const std::string& label) {
  Rng rng = Rng::derive(seed, label);
  std::vector<Eigen::VectorXd> sample(data.size());
  Eigen::VectorXi shared(data[0].size());
  if (paired)
    for (Eigen::Index i = 0; i < shared.size(); ++i) shared[i] = static_cast<int>(rng.integer(0, shared.size() - 1));
  for (std::size_t r = 0; r < data.size(); ++r) {
    const Eigen::Index n = data[r].size();
    sample[r].resize(n);
    for (Eigen::Index i = 0; i < n; ++i) sample[r][i] = data[r][paired ? shared[i] : rng.integer(0, n - 1)];
  }
  return sample;
}

bool same_sizes(const std::vector<Eigen::VectorXd>& data) {
  for (const auto& d : data)
    if (d.size() != data.front().size()) return false;
  return true;
}

namespace {

/// Percentile bounds, their Monte Carlo errors and the replicates they need (see the header).
void summarise(BootstrapResult& res, double level) {
  const Eigen::Index k = res.thetas.cols();
  const double b = static_cast<double>(res.thetas.rows());
  const double a = 0.5 * (1.0 - level);
  // The a-quantile of B replicates is about the (B a)-th order statistic, whose rank has a
  // binomial spread of sqrt(B a (1 − a)): the quantiles one such spread either side span about
  // two standard errors of the endpoint (distribution-free; no density estimate).
  const double d = std::sqrt(a * (1.0 - a) / b);
  auto mc_error = [d](const Eigen::VectorXd& c, double p) {
    return 0.5 * (quantile(c, std::min(1.0, p + d)) - quantile(c, std::max(0.0, p - d)));
  };
  res.lower.resize(k);
  res.upper.resize(k);
  res.stddev.resize(k);
  res.lower_mc_error.resize(k);
  res.upper_mc_error.resize(k);
  double worst = 0.0;  // the largest endpoint error as a fraction of its half-width
  for (Eigen::Index i = 0; i < k; ++i) {
    const Eigen::VectorXd c = res.thetas.col(i);
    res.lower[i] = quantile(c, a);
    res.upper[i] = quantile(c, 1.0 - a);
    res.stddev[i] = stddev(c);
    res.lower_mc_error[i] = mc_error(c, a);
    res.upper_mc_error[i] = mc_error(c, 1.0 - a);
    const double half = 0.5 * (res.upper[i] - res.lower[i]);
    if (half > 0.0) worst = std::max(worst, std::max(res.lower_mc_error[i], res.upper_mc_error[i]) / half);
  }
  // The error falls as 1/sqrt(B): B (worst / 0.1)² replicates bring it to a tenth of the half-width.
  const double by_error = b * (worst / 0.1) * (worst / 0.1);
  const double by_tail = 5.0 / a;  // at least 5 replicates beyond each endpoint
  res.replicates_needed = static_cast<int>(std::ceil(std::max({b, by_error, by_tail}) - 1e-9));
  if (res.replicates_needed > res.thetas.rows())
    res.warnings.push_back(fmt::format(
        "the {:g} % bootstrap interval rests on {} replicates: its endpoints have a Monte Carlo error of up to {:.0f} % of its "
        "half-width; about {} replicates bring that under 10 % (bootstrap = {{replicates = {}}})",
        100.0 * level, res.thetas.rows(), 100.0 * worst, res.replicates_needed, res.replicates_needed));
}

}  // namespace

BootstrapResult bootstrap_calibration(const std::vector<Parameter>& params, const Eigen::VectorXd& optimum,
                                      const std::vector<Eigen::VectorXd>& data, const ReplicateFactory& make_replicate,
                                      const BootstrapOptions& opt) {
  validate_parameters(params);
  const Eigen::Index k = static_cast<Eigen::Index>(params.size());
  if (optimum.size() != k) throw DimensionMismatch(fmt::format("optimum has {} values for {} parameters", optimum.size(), k));
  if (opt.replicates < 2) throw InvalidArgument(fmt::format("bootstrap needs at least 2 replicates, got {}", opt.replicates));
  if (!(opt.level > 0.0 && opt.level < 1.0)) throw InvalidArgument(fmt::format("bootstrap level must be in (0, 1), got {}", opt.level));
  if (data.empty()) throw InvalidArgument("bootstrap needs experimental data (the objective form has none to resample)");
  BootstrapResult res;
  for (const auto& d : data)
    if (d.size() < 2) throw InvalidArgument(fmt::format("bootstrap needs at least 2 data per response, got {}", d.size()));
  res.paired = same_sizes(data);
  // Every replicate starts at the optimum (its first start), then its own multistart points.
  std::vector<Parameter> starts = params;
  for (Eigen::Index i = 0; i < k; ++i) starts[static_cast<std::size_t>(i)].start = optimum[i];
  OptimizerOptions oo = opt.optimizer;
  oo.observer = {};
  if (opt.warm_start) oo.multistart = 1;

  const std::size_t nrep = static_cast<std::size_t>(opt.replicates);
  std::vector<std::optional<Eigen::VectorXd>> rows(nrep);
  std::vector<std::string> failures(nrep);
  std::atomic<long> evaluations{0};
  std::mutex progress_mutex;
  int done = 0;
  pool::parallel_for(opt.replicates, opt.threads, [&](long b) {
    const auto i = static_cast<std::size_t>(b);
    try {
      const Replicate rep = make_replicate(resample_data(data, res.paired, opt.seed, fmt::format("bootstrap/{}", b)));
      OptimizerOptions ro = oo;
      ro.gradient = rep.gradient;
      ro.prepare_start = rep.prepare_start;
      ro.start_threads = 1;                                   // the replicates are the parallel work
      ro.xtol_rel = std::max(ro.xtol_rel, opt.xtol_rel);
      ro.seed = oo.seed + static_cast<std::uint64_t>(b) + 1;  // its own multistart points
      const OptimizationResult o = minimize(starts, rep.f, ro);
      evaluations += o.evaluations;
      rows[i] = o.theta;
    } catch (const Interrupted&) {
      throw;  // --timeout or Ctrl-C: the whole bootstrap stops
    } catch (const Error& e) {
      failures[i] = e.what();  // a resample can be degenerate (all points equal: no KDE); counted below
    }
    if (opt.progress) {
      const std::lock_guard<std::mutex> lock(progress_mutex);
      opt.progress(++done, opt.replicates, evaluations.load());
    }
  });
  res.evaluations = static_cast<int>(evaluations.load());
  std::vector<Eigen::VectorXd> ok;
  for (std::size_t b = 0; b < nrep; ++b) {
    if (rows[b]) {
      ok.push_back(*rows[b]);
    } else {
      res.failures.emplace_back(static_cast<int>(b) + 1, failures[b]);
      if (++res.failed <= 3) res.warnings.push_back(fmt::format("bootstrap replicate {} failed: {}", b + 1, failures[b]));
    }
  }
  if (ok.size() < 2)  // at least one of the two or more replicates failed: name the first
    throw Error(fmt::format("bootstrap: only {} of {} replicates succeeded (replicate {}: {})", ok.size(), opt.replicates,
                            res.failures.front().first, res.failures.front().second));
  if (res.failed > 0) res.warnings.push_back(fmt::format("{} of {} bootstrap replicates failed and were left out", res.failed, opt.replicates));
  res.thetas.resize(static_cast<Eigen::Index>(ok.size()), k);
  for (std::size_t b = 0; b < ok.size(); ++b) res.thetas.row(static_cast<Eigen::Index>(b)) = ok[b].transpose();
  summarise(res, opt.level);
  // The normal interval: the estimate ± z sd, inside the bounds. The percentiles can sit to one
  // side of the estimate when a replicate's objective differs from the estimate's (plain KDEs of
  // the resamples against a given KDE-ebd); the normal interval is centred on the estimate.
  const double z = normal_quantile(0.5 + 0.5 * opt.level);
  res.normal_lower.resize(k);
  res.normal_upper.resize(k);
  for (Eigen::Index i = 0; i < k; ++i) {
    const Parameter& q = params[static_cast<std::size_t>(i)];
    res.normal_lower[i] = std::max(q.lower, optimum[i] - z * res.stddev[i]);
    res.normal_upper[i] = std::min(q.upper, optimum[i] + z * res.stddev[i]);
  }
  return res;
}

}  // namespace smi::improve
