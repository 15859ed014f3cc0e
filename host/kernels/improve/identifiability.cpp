// SPDX-License-Identifier: MIT
#include "kernels/improve/identifiability.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "platform/core/errors.hpp"

namespace smi::improve {

IdentifiabilityResult identifiability(const std::vector<Parameter>& params, const Objective& f, const Eigen::VectorXd& optimum,
                                      const IdentifiabilityOptions& opt) {
  validate_parameters(params);
  const Eigen::Index k = static_cast<Eigen::Index>(params.size());
  if (optimum.size() != k) throw DimensionMismatch(fmt::format("optimum has {} values for {} parameters", optimum.size(), k));
  if (opt.points < 3) throw InvalidArgument(fmt::format("identifiability sweep needs >= 3 points, got {}", opt.points));
  IdentifiabilityResult r;
  r.profiles.resize(k, opt.points);
  r.nodes.resize(k, opt.points);
  r.span.resize(k);
  for (Eigen::Index i = 0; i < k; ++i) {
    const Parameter& p = params[static_cast<std::size_t>(i)];
    for (int j = 0; j < opt.points; ++j) {
      Eigen::VectorXd t = optimum;
      t[i] = p.lower + (p.upper - p.lower) * j / (opt.points - 1);
      r.nodes(i, j) = t[i];
      r.profiles(i, j) = f(t).value;
      ++r.evaluations;
    }
    r.span[i] = r.profiles.row(i).maxCoeff() - r.profiles.row(i).minCoeff();
  }
  const double biggest = r.span.maxCoeff();
  for (Eigen::Index i = 0; i < k; ++i) {
    const bool weak = r.span[i] <= opt.abs_tol || r.span[i] <= opt.rel_tol * biggest;
    r.weak.push_back(weak);
    if (weak)
      r.warnings.push_back(fmt::format("parameter '{}' looks unidentifiable: the objective changes by only {:.3g} over its whole range "
                                       "[{}, {}] (largest change of any parameter {:.3g}); the data do not determine it",
                                       params[static_cast<std::size_t>(i)].name, r.span[i], params[static_cast<std::size_t>(i)].lower,
                                       params[static_cast<std::size_t>(i)].upper, biggest));
  }
  return r;
}

}  // namespace smi::improve
