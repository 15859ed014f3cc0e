// SPDX-License-Identifier: MIT
#include "platform/core/descriptive.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "platform/core/errors.hpp"

namespace smi {

double mean(ConstVec x) {
  require_size(x, 1, "data");
  return x.mean();
}

double variance(ConstVec x) {
  require_size(x, 2, "data");
  const double m = x.mean();
  return (x.array() - m).square().sum() / static_cast<double>(x.size() - 1);
}

double stddev(ConstVec x) { return std::sqrt(variance(x)); }

Eigen::VectorXd sorted(ConstVec x) {
  Eigen::VectorXd s = x;
  std::sort(s.data(), s.data() + s.size());
  return s;
}

double quantile_sorted(ConstVec s, double p) {
  require_size(s, 1, "data");
  if (!(p >= 0.0 && p <= 1.0)) throw InvalidArgument(fmt::format("probability must be in [0, 1], got {}", p));
  const double h = (static_cast<double>(s.size()) - 1.0) * p;
  const auto lo = static_cast<Eigen::Index>(std::floor(h));
  const Eigen::Index hi = std::min<Eigen::Index>(lo + 1, s.size() - 1);
  return s[lo] + (h - static_cast<double>(lo)) * (s[hi] - s[lo]);
}

double quantile(ConstVec x, double p) { return quantile_sorted(sorted(x), p); }

double mad(ConstVec x) {
  const double med = quantile(x, 0.5);
  Eigen::VectorXd dev = (x.array() - med).abs();
  return quantile(dev, 0.5);
}

void require_finite(ConstVec x, std::string_view what) {
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    if (!std::isfinite(x[i]))
      throw InvalidArgument(fmt::format("{}[{}] is {}; remove or replace non-finite values", what, i + 1,
                                        std::isnan(x[i]) ? "NaN" : (x[i] > 0 ? "inf" : "-inf")));
  }
}

void require_size(ConstVec x, Eigen::Index n, std::string_view what) {
  if (x.size() < n)
    throw InvalidArgument(fmt::format("{} needs at least {} value{}, got {}", what, n, n == 1 ? "" : "s", x.size()));
}

}  // namespace smi
