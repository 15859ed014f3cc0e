#include "kernels/improve/bootstrap.hpp"

#include <fmt/format.h>

#include <cmath>

#include "platform/core/descriptive.hpp"
#include "platform/core/errors.hpp"
#include "platform/core/rng.hpp"

namespace smi::improve {

BootstrapResult bootstrap_calibration(const std::vector<Parameter>& params, const Eigen::VectorXd& optimum,
                                      const std::vector<Eigen::VectorXd>& data, const ObjectiveFactory& make_objective,
                                      const BootstrapOptions& opt) {
  ReplicateFactory make = [&make_objective](const std::vector<Eigen::VectorXd>& d) { return Replicate{make_objective(d), {}, {}, {}}; };
  return bootstrap_calibration(params, optimum, data, make, opt);
}

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
  res.paired = true;
  for (const auto& d : data) {
    if (d.size() < 2) throw InvalidArgument(fmt::format("bootstrap needs at least 2 data per response, got {}", d.size()));
    res.paired = res.paired && d.size() == data[0].size();
  }
  std::vector<Parameter> starts = params;
  OptimizerOptions oo = opt.optimizer;
  oo.observer = {};
  if (opt.warm_start) {
    for (Eigen::Index i = 0; i < k; ++i) starts[static_cast<std::size_t>(i)].start = optimum[i];
    oo.multistart = 1;
  }

  Rng rng(opt.seed, hash_label("bootstrap"));
  std::vector<Eigen::VectorXd> rows;
  for (int b = 0; b < opt.replicates; ++b) {
    std::vector<Eigen::VectorXd> sample(data.size());
    Eigen::VectorXi shared(data[0].size());
    if (res.paired)
      for (Eigen::Index i = 0; i < shared.size(); ++i) shared[i] = static_cast<int>(rng.integer(0, shared.size() - 1));
    for (std::size_t r = 0; r < data.size(); ++r) {
      const Eigen::Index n = data[r].size();
      sample[r].resize(n);
      for (Eigen::Index i = 0; i < n; ++i) sample[r][i] = data[r][res.paired ? shared[i] : rng.integer(0, n - 1)];
    }
    try {
      const Replicate rep = make_replicate(sample);
      OptimizerOptions ro = oo;
      ro.gradient = rep.gradient;
      ro.prepare_start = rep.prepare_start;
      ro.seed = oo.seed + static_cast<std::uint64_t>(b) + 1;  // its own multistart points
      const OptimizationResult o = minimize(starts, rep.f, ro);
      res.evaluations += o.evaluations;
      rows.push_back(o.theta);
    } catch (const Error& e) {
      // A resample can be degenerate (all points equal: no KDE); count it and go on.
      ++res.failed;
      if (res.failed <= 3) res.warnings.push_back(fmt::format("bootstrap replicate {} failed: {}", b + 1, e.what()));
    }
    if (opt.progress) opt.progress(b + 1, opt.replicates, res.evaluations);
  }
  if (rows.size() < 2) throw Error(fmt::format("bootstrap: only {} of {} replicates succeeded", rows.size(), opt.replicates));
  if (res.failed > 0) res.warnings.push_back(fmt::format("{} of {} bootstrap replicates failed and were left out", res.failed, opt.replicates));
  res.thetas.resize(static_cast<Eigen::Index>(rows.size()), k);
  for (std::size_t b = 0; b < rows.size(); ++b) res.thetas.row(static_cast<Eigen::Index>(b)) = rows[b].transpose();
  res.lower.resize(k);
  res.upper.resize(k);
  res.stddev.resize(k);
  const double a = 0.5 * (1.0 - opt.level);
  for (Eigen::Index i = 0; i < k; ++i) {
    const Eigen::VectorXd c = res.thetas.col(i);
    res.lower[i] = quantile(c, a);
    res.upper[i] = quantile(c, 1.0 - a);
    res.stddev[i] = stddev(c);
  }
  return res;
}

}  // namespace smi::improve
