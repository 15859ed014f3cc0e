// SPDX-License-Identifier: MIT
#pragma once
#include <limits>
// Parametric 1-D families. Constructors validate their parameters and throw InvalidArgument
// naming the parameter and the fix. Parameters follow the paper's tables where it gives them
// (normal, lognormal and uniform by the variable's own mean and std).
#include <memory>
#include <string>
#include <vector>

#include "kernels/stats/distribution.hpp"

namespace smi::stats {

/// +∞: the open end of a support, the log-density outside it (-kInf).
inline constexpr double kInf = std::numeric_limits<double>::infinity();

/// Shared by the families: quantile and isf by bracketed Newton/bisection (used unless a family
/// has a closed form) on cdf below the median and on sf above it, so both tails keep their
/// relative precision; parameter list for describe() and field().
class Parametric : public Distribution {
 public:
  double quantile(double p) const override;
  double isf(double q) const override;
  using Distribution::cdf;
  using Distribution::pdf;
  using Distribution::quantile;
  std::string describe() const override;
  std::optional<double> field(std::string_view name) const override;
  /// (name, value) of the defining parameters, e.g. {("mean", 30.25), ("std", 0.36)}.
  virtual std::vector<std::pair<std::string, double>> params() const = 0;

 protected:
  /// x with cdf(x) = t (upper = false) or sf(x) = t (upper = true), t in (0, 1).
  double invert(double t, bool upper) const;
};

class Normal : public Parametric {
 public:
  Normal(double mean, double sd);
  std::string family() const override { return "normal"; }
  double pdf(double x) const override;
  double cdf(double x) const override;
  double logpdf(double x) const override;
  double logcdf(double x) const override;
  double sf(double x) const override;
  double isf(double q) const override;
  double quantile(double p) const override;
  double mean() const override { return m_; }
  double stddev() const override { return s_; }
  std::pair<double, double> support() const override;
  Eigen::VectorXd pdf(const Eigen::VectorXd& x) const override;
  std::vector<std::pair<std::string, double>> params() const override { return {{"mean", m_}, {"std", s_}}; }

 private:
  double m_, s_;
};

/// Lognormal given the mean and std of the variable itself (§7): σ_ln² = ln(1 + s²/μ²),
/// μ_ln = ln μ − σ_ln²/2.
class LogNormal : public Parametric {
 public:
  static LogNormal from_moments(double mean, double sd);
  static LogNormal from_log_params(double mu_log, double sigma_log);
  std::string family() const override { return "lognormal"; }
  double pdf(double x) const override;
  double cdf(double x) const override;
  double logpdf(double x) const override;
  double logcdf(double x) const override;
  double sf(double x) const override;
  double isf(double q) const override;
  double quantile(double p) const override;
  double mean() const override;
  double stddev() const override;
  std::pair<double, double> support() const override;
  std::vector<std::pair<std::string, double>> params() const override;

 private:
  LogNormal(double mu_log, double sigma_log) : mu_(mu_log), sig_(sigma_log) {}
  double mu_, sig_;
};

class Uniform : public Parametric {
 public:
  Uniform(double lower, double upper);
  /// a = μ − √3 s, b = μ + √3 s.
  static Uniform from_moments(double mean, double sd);
  std::string family() const override { return "uniform"; }
  double pdf(double x) const override;
  double cdf(double x) const override;
  double logpdf(double x) const override;
  double sf(double x) const override;
  double isf(double q) const override;
  double quantile(double p) const override;
  double mean() const override { return 0.5 * (a_ + b_); }
  double stddev() const override;
  std::pair<double, double> support() const override { return {a_, b_}; }
  std::vector<std::pair<std::string, double>> params() const override { return {{"lower", a_}, {"upper", b_}}; }

 private:
  double a_, b_;
};

/// Normal(mu, sigma) (parent parameters) truncated to [lower, upper] (either may be infinite).
class TruncNormal : public Parametric {
 public:
  TruncNormal(double mu, double sigma, double lower, double upper);
  std::string family() const override { return "truncnormal"; }
  double pdf(double x) const override;
  double cdf(double x) const override;
  double logpdf(double x) const override;
  double logcdf(double x) const override;
  double sf(double x) const override;
  double mean() const override;
  double stddev() const override;
  std::pair<double, double> support() const override { return {a_, b_}; }
  std::vector<std::pair<std::string, double>> params() const override;

 private:
  double mu_, sig_, a_, b_;
  double al_, be_;  ///< standardised bounds (a − μ)/σ, (b − μ)/σ
  double z_;         ///< Φ(β) − Φ(α), by normal_mass (precise in the tails)
};

/// Weibull: F(x) = 1 − exp(−((x − loc)/scale)^shape), x >= loc.
class Weibull : public Parametric {
 public:
  Weibull(double shape, double scale, double loc = 0.0);
  std::string family() const override { return "weibull"; }
  double pdf(double x) const override;
  double cdf(double x) const override;
  double logpdf(double x) const override;
  double logcdf(double x) const override;
  double sf(double x) const override;
  double isf(double q) const override;
  double quantile(double p) const override;
  double mean() const override;
  double stddev() const override;
  std::pair<double, double> support() const override;
  std::vector<std::pair<std::string, double>> params() const override;

 private:
  double k_, l_, loc_;
};

/// Gumbel for maxima: F(x) = exp(−exp(−(x − loc)/scale)).
class Gumbel : public Parametric {
 public:
  Gumbel(double loc, double scale);
  std::string family() const override { return "gumbel"; }
  double pdf(double x) const override;
  double cdf(double x) const override;
  double logpdf(double x) const override;
  double logcdf(double x) const override;
  double sf(double x) const override;
  double isf(double q) const override;
  double quantile(double p) const override;
  double mean() const override;
  double stddev() const override;
  std::pair<double, double> support() const override;
  std::vector<std::pair<std::string, double>> params() const override { return {{"loc", mu_}, {"scale", b_}}; }

 private:
  double mu_, b_;
};

/// Gamma(shape k, scale θ) shifted by loc.
class Gamma : public Parametric {
 public:
  Gamma(double shape, double scale, double loc = 0.0);
  std::string family() const override { return "gamma"; }
  double pdf(double x) const override;
  double cdf(double x) const override;
  double logpdf(double x) const override;
  double logcdf(double x) const override;
  double sf(double x) const override;
  double mean() const override { return loc_ + k_ * th_; }
  double stddev() const override;
  std::pair<double, double> support() const override;
  std::vector<std::pair<std::string, double>> params() const override;

 private:
  double k_, th_, loc_;
};

/// Beta(α, β) on [lower, upper].
class Beta : public Parametric {
 public:
  Beta(double alpha, double beta, double lower = 0.0, double upper = 1.0);
  std::string family() const override { return "beta"; }
  double pdf(double x) const override;
  double cdf(double x) const override;
  double logpdf(double x) const override;
  double logcdf(double x) const override;
  double sf(double x) const override;
  double mean() const override;
  double stddev() const override;
  std::pair<double, double> support() const override { return {lo_, hi_}; }
  std::vector<std::pair<std::string, double>> params() const override;

 private:
  double a_, b_, lo_, hi_;
};

class Triangular : public Parametric {
 public:
  Triangular(double lower, double mode, double upper);
  std::string family() const override { return "triangular"; }
  double pdf(double x) const override;
  double cdf(double x) const override;
  double logpdf(double x) const override;
  double logcdf(double x) const override;
  double sf(double x) const override;
  double isf(double q) const override;
  double quantile(double p) const override;
  double mean() const override { return (a_ + c_ + b_) / 3.0; }
  double stddev() const override;
  std::pair<double, double> support() const override { return {a_, b_}; }
  std::vector<std::pair<std::string, double>> params() const override;

 private:
  double a_, c_, b_;
};

}  // namespace smi::stats
