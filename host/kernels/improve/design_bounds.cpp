// SPDX-License-Identifier: MIT
#include "kernels/improve/design_bounds.hpp"

#include <fmt/format.h>

#include <cmath>

#include "platform/core/errors.hpp"

namespace smi::improve {

std::vector<std::string> design_bound_warnings(const std::vector<std::string>& names, const Eigen::MatrixXd& X,
                                               const std::vector<double>& means, const std::vector<DesignRange>& ranges,
                                               double max_outside) {
  if (static_cast<Eigen::Index>(names.size()) != X.cols() || means.size() != names.size())
    throw DimensionMismatch(fmt::format("design bounds: {} names, {} means for {} sample columns", names.size(), means.size(), X.cols()));
  std::vector<std::string> out;
  for (const DesignRange& r : ranges) {
    if (!(r.lower < r.upper)) throw InvalidArgument(fmt::format("design range of '{}': need lower < upper, got [{}, {}]", r.input, r.lower, r.upper));
    std::size_t j = 0;
    while (j < names.size() && names[j] != r.input) ++j;
    if (j == names.size()) throw InvalidArgument(fmt::format("design range given for '{}', which is not an input", r.input));
    const Eigen::VectorXd x = X.col(static_cast<Eigen::Index>(j));
    if (means[j] < r.lower || means[j] > r.upper)
      out.push_back(fmt::format("input '{}': calibrated mean {:.6g} lies outside the surrogate's design range [{}, {}]: the optimum "
                                "rests on extrapolation (widen the design and refit)", r.input, means[j], r.lower, r.upper));
    const Eigen::Index outside = ((x.array() < r.lower) || (x.array() > r.upper)).count();
    const double frac = static_cast<double>(outside) / static_cast<double>(std::max<Eigen::Index>(1, x.size()));
    if (frac > max_outside)
      out.push_back(fmt::format("input '{}': {:.1f} % of its calibrated sample lies outside the surrogate's design range [{}, {}] "
                                "(more than {:.1f} %): the surrogate extrapolates there", r.input, 100.0 * frac, r.lower, r.upper,
                                100.0 * max_outside));
  }
  return out;
}

}  // namespace smi::improve
