// SPDX-License-Identifier: MIT
#include "kernels/stats/ecdf.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "platform/core/descriptive.hpp"
#include "platform/core/errors.hpp"

namespace smi::stats {

Ecdf::Ecdf(Eigen::VectorXd data) : t_(std::move(data)) {
  require_size(t_, 1, "data");
  require_finite(t_, "data");
  std::sort(t_.data(), t_.data() + t_.size());
}

std::string Ecdf::describe() const { return fmt::format("ecdf(n={}, range=[{:.6g}, {:.6g}])", t_.size(), t_[0], t_[t_.size() - 1]); }

double Ecdf::pdf(double) const {
  throw InvalidArgument("an empirical CDF has no density; use smi.kde(data) for a density");
}

double Ecdf::cdf(double x) const {
  const auto k = std::upper_bound(t_.data(), t_.data() + t_.size(), x) - t_.data();
  return static_cast<double>(k) / static_cast<double>(t_.size());
}

Eigen::VectorXd Ecdf::cdf(const Eigen::VectorXd& x) const {
  Eigen::VectorXd y(x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) y[i] = cdf(x[i]);
  return y;
}

double Ecdf::quantile(double p) const {
  if (p <= 0.0) return t_[0];
  const auto n = static_cast<double>(t_.size());
  const auto k = static_cast<Eigen::Index>(std::ceil(p * n - 1e-12));
  return t_[std::clamp<Eigen::Index>(k - 1, 0, t_.size() - 1)];
}

double Ecdf::mean() const { return t_.mean(); }
double Ecdf::stddev() const { return t_.size() < 2 ? 0.0 : smi::stddev(t_); }

Eigen::VectorXd Ecdf::sample(Rng& rng, Eigen::Index n) const {
  Eigen::VectorXd y(n);
  for (Eigen::Index i = 0; i < n; ++i) y[i] = t_[static_cast<Eigen::Index>(rng.integer(0, t_.size() - 1))];
  return y;
}

std::optional<double> Ecdf::field(std::string_view name) const {
  if (name == "n") return static_cast<double>(t_.size());
  return std::nullopt;
}

void Ecdf::steps(Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  const Eigen::Index n = t_.size();
  x.resize(2 * n);
  y.resize(2 * n);
  for (Eigen::Index i = 0; i < n; ++i) {
    x[2 * i] = x[2 * i + 1] = t_[i];
    y[2 * i] = static_cast<double>(i) / static_cast<double>(n);
    y[2 * i + 1] = static_cast<double>(i + 1) / static_cast<double>(n);
  }
}

}  // namespace smi::stats
