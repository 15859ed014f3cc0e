// SPDX-License-Identifier: MIT
// Weibull, Gumbel, gamma and beta (the shape families).
#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "kernels/stats/families.hpp"
#include "kernels/stats/special.hpp"
#include "platform/core/errors.hpp"

namespace smi::stats {
namespace {
constexpr double kEulerGamma = 0.57721566490153286061;

void positive(double v, const char* name, const char* family) {
  if (!(v > 0.0) || !std::isfinite(v))
    throw InvalidArgument(fmt::format("{}: {} must be a positive finite number, got {}", family, name, v));
}
void finite(double v, const char* name, const char* family) {
  if (!std::isfinite(v)) throw InvalidArgument(fmt::format("{}: {} must be finite, got {}", family, name, v));
}
}  // namespace

// ---- Weibull ------------------------------------------------------------------------------

Weibull::Weibull(double shape, double scale, double loc) : k_(shape), l_(scale), loc_(loc) {
  positive(shape, "shape", "weibull");
  positive(scale, "scale", "weibull");
  finite(loc, "loc", "weibull");
}
double Weibull::pdf(double x) const {
  const double z = (x - loc_) / l_;
  if (z < 0) return 0.0;
  if (z == 0) return k_ < 1 ? kInf : k_ == 1 ? 1.0 / l_ : 0.0;
  return k_ / l_ * std::pow(z, k_ - 1.0) * std::exp(-std::pow(z, k_));
}
double Weibull::cdf(double x) const {
  const double z = (x - loc_) / l_;
  return z <= 0 ? 0.0 : -std::expm1(-std::pow(z, k_));
}
double Weibull::quantile(double p) const { return loc_ + l_ * std::pow(-std::log1p(-p), 1.0 / k_); }
double Weibull::isf(double q) const { return loc_ + l_ * std::pow(-std::log(q), 1.0 / k_); }
double Weibull::sf(double x) const {
  const double z = (x - loc_) / l_;
  return z <= 0 ? 1.0 : std::exp(-std::pow(z, k_));
}
double Weibull::logcdf(double x) const {
  const double z = (x - loc_) / l_;
  if (z <= 0) return -kInf;
  // t = z^k in log space: far in the lower tail z^k underflows while log cdf = log t − t/2 + …
  // is an ordinary number (k·log z).
  const double log_t = k_ * std::log(z);
  if (log_t < -30.0) return log_t - 0.5 * std::exp(log_t);
  const double t = std::exp(log_t);
  return t > M_LN2 ? std::log1p(-std::exp(-t)) : std::log(-std::expm1(-t));
}
double Weibull::logpdf(double x) const {
  const double z = (x - loc_) / l_;
  if (z < 0) return -kInf;
  if (z == 0) return std::log(pdf(x));
  return std::log(k_ / l_) + (k_ - 1.0) * std::log(z) - std::pow(z, k_);
}
double Weibull::mean() const { return loc_ + l_ * std::tgamma(1.0 + 1.0 / k_); }
double Weibull::stddev() const {
  const double g1 = std::tgamma(1.0 + 1.0 / k_), g2 = std::tgamma(1.0 + 2.0 / k_);
  return l_ * std::sqrt(std::max(0.0, g2 - g1 * g1));
}
std::pair<double, double> Weibull::support() const { return {loc_, kInf}; }
std::vector<std::pair<std::string, double>> Weibull::params() const { return {{"shape", k_}, {"scale", l_}, {"loc", loc_}}; }

// ---- Gumbel -------------------------------------------------------------------------------

Gumbel::Gumbel(double loc, double scale) : mu_(loc), b_(scale) {
  finite(loc, "loc", "gumbel");
  positive(scale, "scale", "gumbel");
}
double Gumbel::pdf(double x) const {
  const double z = (x - mu_) / b_;
  return std::exp(-z - std::exp(-z)) / b_;
}
double Gumbel::cdf(double x) const { return std::exp(-std::exp(-(x - mu_) / b_)); }
double Gumbel::quantile(double p) const { return mu_ - b_ * std::log(-std::log(p)); }
double Gumbel::isf(double q) const { return mu_ - b_ * std::log(-std::log1p(-q)); }
double Gumbel::sf(double x) const { return -std::expm1(-std::exp(-(x - mu_) / b_)); }
double Gumbel::logcdf(double x) const { return -std::exp(-(x - mu_) / b_); }
double Gumbel::logpdf(double x) const {
  const double z = (x - mu_) / b_;
  return -z - std::exp(-z) - std::log(b_);
}
double Gumbel::mean() const { return mu_ + b_ * kEulerGamma; }
double Gumbel::stddev() const { return M_PI * b_ / std::sqrt(6.0); }
std::pair<double, double> Gumbel::support() const { return {-kInf, kInf}; }

// ---- Gamma --------------------------------------------------------------------------------

Gamma::Gamma(double shape, double scale, double loc) : k_(shape), th_(scale), loc_(loc) {
  positive(shape, "shape", "gamma");
  positive(scale, "scale", "gamma");
  finite(loc, "loc", "gamma");
}
double Gamma::pdf(double x) const {
  const double z = (x - loc_) / th_;
  if (z < 0) return 0.0;
  if (z == 0) return k_ < 1 ? kInf : k_ == 1 ? 1.0 / th_ : 0.0;
  return std::exp((k_ - 1.0) * std::log(z) - z - std::lgamma(k_)) / th_;
}
double Gamma::cdf(double x) const { return gamma_pq(k_, (x - loc_) / th_).p; }
double Gamma::sf(double x) const { return gamma_pq(k_, (x - loc_) / th_).q; }
double Gamma::logcdf(double x) const { return gamma_pq(k_, (x - loc_) / th_).log_p; }
double Gamma::logpdf(double x) const {
  const double z = (x - loc_) / th_;
  if (z < 0) return -kInf;
  if (z == 0) return std::log(pdf(x));
  return (k_ - 1.0) * std::log(z) - z - std::lgamma(k_) - std::log(th_);
}
double Gamma::stddev() const { return std::sqrt(k_) * th_; }
std::pair<double, double> Gamma::support() const { return {loc_, kInf}; }
std::vector<std::pair<std::string, double>> Gamma::params() const { return {{"shape", k_}, {"scale", th_}, {"loc", loc_}}; }

// ---- Beta ---------------------------------------------------------------------------------

Beta::Beta(double alpha, double beta, double lower, double upper) : a_(alpha), b_(beta), lo_(lower), hi_(upper) {
  positive(alpha, "alpha", "beta");
  positive(beta, "beta", "beta");
  finite(lower, "lower", "beta");
  finite(upper, "upper", "beta");
  if (!(lower < upper))
    throw InvalidArgument(fmt::format("beta: lower ({}) must be < upper ({}); swap them or widen the interval", lower, upper));
}
double Beta::pdf(double x) const {
  const double w = hi_ - lo_, y = (x - lo_) / w;
  if (y < 0 || y > 1) return 0.0;
  if ((y == 0 && a_ < 1) || (y == 1 && b_ < 1)) return kInf;
  if ((y == 0 && a_ > 1) || (y == 1 && b_ > 1)) return 0.0;
  const double lb = std::lgamma(a_) + std::lgamma(b_) - std::lgamma(a_ + b_);
  const double la = y == 0 ? 0.0 : (a_ - 1.0) * std::log(y);
  const double lr = y == 1 ? 0.0 : (b_ - 1.0) * std::log1p(-y);
  return std::exp(la + lr - lb) / w;
}
double Beta::cdf(double x) const { return beta_inc_both(a_, b_, (x - lo_) / (hi_ - lo_)).lower; }
double Beta::sf(double x) const { return beta_inc_both(a_, b_, (x - lo_) / (hi_ - lo_)).upper; }
double Beta::logcdf(double x) const { return beta_inc_both(a_, b_, (x - lo_) / (hi_ - lo_)).log_lower; }
double Beta::logpdf(double x) const {
  const double w = hi_ - lo_, y = (x - lo_) / w;
  if (y <= 0 || y >= 1) return std::log(pdf(x));
  const double lb = std::lgamma(a_) + std::lgamma(b_) - std::lgamma(a_ + b_);
  return (a_ - 1.0) * std::log(y) + (b_ - 1.0) * std::log1p(-y) - lb - std::log(w);
}
double Beta::mean() const { return lo_ + (hi_ - lo_) * a_ / (a_ + b_); }
double Beta::stddev() const {
  const double s = a_ + b_;
  return (hi_ - lo_) * std::sqrt(a_ * b_ / (s * s * (s + 1.0)));
}
std::vector<std::pair<std::string, double>> Beta::params() const {
  return {{"alpha", a_}, {"beta", b_}, {"lower", lo_}, {"upper", hi_}};
}

}  // namespace smi::stats
