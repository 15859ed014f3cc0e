// SPDX-License-Identifier: MIT
#include "kernels/improve/pr_tolerance.hpp"

#include <fmt/format.h>

#include <cmath>
#include <vector>

#include "kernels/improve/bootstrap.hpp"
#include "platform/core/descriptive.hpp"
#include "platform/core/errors.hpp"

namespace smi::improve {

bool can_measure_pr_tolerance(const StatisticalObjective& obj) {
  if (obj.options().metric != MetricKind::pr) return false;
  for (const ResponseSpec& r : obj.responses())
    if (r.data.size() < 2) return false;
  return true;
}

PrTolerance measure_pr_tolerance(const StatisticalObjective& obj, const Eigen::VectorXd& theta, int resamples,
                                 std::uint64_t seed, int threads) {
  if (!can_measure_pr_tolerance(obj))
    throw InvalidArgument("the PR tolerance is measured on the data points: every response needs two or more (metric \"pr\")");
  if (resamples < 2) throw InvalidArgument(fmt::format("the PR tolerance needs at least 2 resamples, got {}", resamples));
  std::vector<Eigen::VectorXd> data;
  for (const ResponseSpec& r : obj.responses()) data.push_back(r.data);
  PrTolerance out;
  out.paired = same_sizes(data);
  std::vector<std::vector<Eigen::VectorXd>> sets;
  sets.reserve(static_cast<std::size_t>(resamples));
  for (int b = 0; b < resamples; ++b) sets.push_back(resample_data(data, out.paired, seed, fmt::format("tolerance/{}", b)));
  const std::vector<double> sums = obj.pr_sums_against(theta, sets, threads);
  std::vector<double> ok;
  for (const double v : sums)
    if (!std::isnan(v)) ok.push_back(v);  // NaN: a degenerate resample (all its points equal)
  out.resamples = static_cast<int>(ok.size());
  out.failed = resamples - out.resamples;
  if (out.resamples < 2)
    throw InvalidArgument(fmt::format("the PR tolerance: only {} of {} resamples of the data gave a KDE (are the points all equal?)",
                                      out.resamples, resamples));
  const Eigen::Map<const Eigen::VectorXd> v(ok.data(), static_cast<Eigen::Index>(ok.size()));
  out.value = stddev(v);
  out.mean = v.mean();
  return out;
}

}  // namespace smi::improve
