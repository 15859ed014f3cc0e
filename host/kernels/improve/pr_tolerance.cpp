// SPDX-License-Identifier: MIT
#include "kernels/improve/pr_tolerance.hpp"

#include <fmt/format.h>

#include <optional>
#include <vector>

#include "kernels/improve/bootstrap.hpp"
#include "platform/core/descriptive.hpp"
#include "platform/core/errors.hpp"
#include "platform/core/thread_pool.hpp"

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
  (void)obj.predict(theta);  // the one model run, here: the resamples below reuse its outputs
  std::vector<std::optional<double>> sums(static_cast<std::size_t>(resamples));
  pool::parallel_for(resamples, threads, [&](long b) {
    try {
      StatisticalObjective o = obj.with_data(resample_data(data, out.paired, seed, fmt::format("tolerance/{}", b)));
      o.set_threads(threads > 1 ? 1 : obj.options().threads);
      sums[static_cast<std::size_t>(b)] = o(theta).value;
    } catch (const InvalidArgument&) {
      // a degenerate resample (all its points equal: no bandwidth), counted below
    }
  });
  std::vector<double> ok;
  for (const auto& s : sums)
    if (s) ok.push_back(*s);
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
