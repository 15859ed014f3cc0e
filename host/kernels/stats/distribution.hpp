// SPDX-License-Identifier: MIT
#pragma once
// The interface every 1-D probability model implements: parametric families, KDEs, empirical
// distributions. Vectorised evaluation is the rule (one virtual call per vector, not per
// sample); the scalar forms exist for the families' own implementations.
#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "platform/core/rng.hpp"

namespace smi::stats {

class Distribution {
 public:
  virtual ~Distribution() = default;

  /// "normal(mean=30.25, std=0.36)": for printing and results files.
  virtual std::string describe() const = 0;
  /// The family name: "normal", "lognormal", "kde", ...
  virtual std::string family() const = 0;

  virtual double pdf(double x) const = 0;
  virtual double cdf(double x) const = 0;
  /// Inverse CDF for p in (0, 1).
  virtual double quantile(double p) const = 0;
  /// log pdf(x); the families compute it in log space (finite where pdf underflows).
  virtual double logpdf(double x) const;
  /// log cdf(x); the families keep precision where cdf(x) is tiny.
  virtual double logcdf(double x) const;
  /// Survival function 1 − cdf(x); the families compute it as a complement, not a difference,
  /// so that it keeps its relative precision in the upper tail.
  virtual double sf(double x) const;
  /// Inverse survival function: x with sf(x) = q, q in [0, 1] (quantile(1 − q) without
  /// the rounding of 1 − q).
  virtual double isf(double q) const;
  virtual double mean() const = 0;
  virtual double stddev() const = 0;
  /// Where the density is positive (may be infinite).
  virtual std::pair<double, double> support() const = 0;

  virtual Eigen::VectorXd pdf(const Eigen::VectorXd& x) const;
  virtual Eigen::VectorXd cdf(const Eigen::VectorXd& x) const;
  virtual Eigen::VectorXd quantile(const Eigen::VectorXd& p) const;
  /// n draws; the default inverts the CDF of uniforms from `rng`.
  virtual Eigen::VectorXd sample(Rng& rng, Eigen::Index n) const;

  /// Named numeric fields a subtype exposes to Lua as d.<name> (a KDE's "bandwidth",
  /// a family's "mean"...); empty for unknown names.
  virtual std::optional<double> field(std::string_view /*name*/) const { return std::nullopt; }
};

using DistributionPtr = std::shared_ptr<const Distribution>;

}  // namespace smi::stats
