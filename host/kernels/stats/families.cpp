// SPDX-License-Identifier: MIT
// Normal, lognormal, uniform, truncated normal, triangular; shared Parametric code.
#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "kernels/stats/families.hpp"
#include "kernels/stats/special.hpp"
#include "platform/core/errors.hpp"
#include "platform/core/normal.hpp"

namespace smi::stats {
namespace {
constexpr double kSqrt3 = 1.7320508075688772935;
constexpr double kLogSqrt2Pi = 0.91893853320467274178;

void require_positive(double v, const char* name, const char* family) {
  if (!(v > 0.0) || !std::isfinite(v))
    throw InvalidArgument(fmt::format("{}: {} must be a positive finite number, got {}", family, name, v));
}
void require_finite_param(double v, const char* name, const char* family) {
  if (!std::isfinite(v)) throw InvalidArgument(fmt::format("{}: {} must be finite, got {}", family, name, v));
}
void require_order(double lo, double hi, const char* family) {
  if (!(lo < hi))
    throw InvalidArgument(fmt::format("{}: lower ({}) must be < upper ({}); swap them or widen the interval", family, lo, hi));
}
}  // namespace

// ---- Parametric ---------------------------------------------------------------------------

double Parametric::quantile(double p) const {
  const auto [lo, hi] = support();
  if (!(p > 0.0)) return p == 0.0 ? lo : std::numeric_limits<double>::quiet_NaN();
  if (!(p < 1.0)) return p == 1.0 ? hi : std::numeric_limits<double>::quiet_NaN();
  return p > 0.5 ? invert(1.0 - p, true) : invert(p, false);
}

double Parametric::isf(double q) const {
  const auto [lo, hi] = support();
  if (!(q > 0.0)) return q == 0.0 ? hi : std::numeric_limits<double>::quiet_NaN();
  if (!(q < 1.0)) return q == 1.0 ? lo : std::numeric_limits<double>::quiet_NaN();
  return q > 0.5 ? invert(1.0 - q, false) : invert(q, true);
}

double Parametric::invert(double t, bool upper) const {
  // r(x) increases with x and is 0 at the answer; upper-tail targets are matched on sf, whose
  // small values carry full relative precision (1 − cdf would not).
  auto r = [&](double x) { return upper ? t - sf(x) : cdf(x) - t; };
  auto [lo, hi] = support();
  const double m = mean(), s = stddev();
  if (!std::isfinite(lo)) {
    lo = m - s;
    while (r(lo) > 0) lo = m - 2.0 * (m - lo);
  }
  if (!std::isfinite(hi)) {
    hi = m + s;
    while (r(hi) < 0) hi = m + 2.0 * (hi - m);
  }
  double x = 0.5 * (lo + hi);
  for (int it = 0; it < 2000; ++it) {
    const double f = r(x);
    if (f == 0.0) return x;
    if (f > 0) hi = x; else lo = x;
    const double d = pdf(x);
    double xn = d > 0 && std::isfinite(d) ? x - f / d : 0.5 * (lo + hi);
    if (!(xn > lo && xn < hi)) xn = 0.5 * (lo + hi);
    const double tol = 4e-16 * std::max(std::abs(xn), 1e-300);
    if (std::abs(xn - x) <= tol || hi - lo <= tol) return xn;
    x = xn;
  }
  return x;
}

std::string Parametric::describe() const {
  std::string s = family() + "(";
  bool first = true;
  for (const auto& [k, v] : params()) {
    s += fmt::format("{}{}={:.10g}", first ? "" : ", ", k, v);
    first = false;
  }
  return s + ")";
}

std::optional<double> Parametric::field(std::string_view name) const {
  for (const auto& [k, v] : params())
    if (k == name) return v;
  return std::nullopt;
}

// ---- Normal -------------------------------------------------------------------------------

Normal::Normal(double mean, double sd) : m_(mean), s_(sd) {
  require_finite_param(mean, "mean", "normal");
  require_positive(sd, "std", "normal");
}
double Normal::pdf(double x) const { return normal_pdf((x - m_) / s_) / s_; }
double Normal::cdf(double x) const { return normal_cdf((x - m_) / s_); }
double Normal::quantile(double p) const { return m_ + s_ * normal_quantile(p); }
double Normal::logpdf(double x) const {
  const double z = (x - m_) / s_;
  return -0.5 * z * z - kLogSqrt2Pi - std::log(s_);
}
double Normal::logcdf(double x) const { return log_normal_cdf((x - m_) / s_); }
double Normal::sf(double x) const { return normal_cdf((m_ - x) / s_); }
double Normal::isf(double q) const { return m_ - s_ * normal_quantile(q); }
std::pair<double, double> Normal::support() const { return {-kInf, kInf}; }
Eigen::VectorXd Normal::pdf(const Eigen::VectorXd& x) const {
  return ((-0.5 * ((x.array() - m_) / s_).square()).exp() * (kInvSqrt2Pi / s_)).matrix();
}

// ---- LogNormal ----------------------------------------------------------------------------

LogNormal LogNormal::from_moments(double mean, double sd) {
  require_positive(mean, "mean", "lognormal");
  require_positive(sd, "std", "lognormal");
  const double s2 = std::log1p((sd / mean) * (sd / mean));
  return LogNormal(std::log(mean) - 0.5 * s2, std::sqrt(s2));
}
LogNormal LogNormal::from_log_params(double mu_log, double sigma_log) {
  require_finite_param(mu_log, "mu_log", "lognormal");
  require_positive(sigma_log, "sigma_log", "lognormal");
  return LogNormal(mu_log, sigma_log);
}
double LogNormal::pdf(double x) const { return x <= 0 ? 0.0 : normal_pdf((std::log(x) - mu_) / sig_) / (sig_ * x); }
double LogNormal::cdf(double x) const { return x <= 0 ? 0.0 : normal_cdf((std::log(x) - mu_) / sig_); }
double LogNormal::quantile(double p) const { return std::exp(mu_ + sig_ * normal_quantile(p)); }
double LogNormal::logpdf(double x) const {
  if (x <= 0) return -kInf;
  const double z = (std::log(x) - mu_) / sig_;
  return -0.5 * z * z - kLogSqrt2Pi - std::log(sig_ * x);
}
double LogNormal::logcdf(double x) const { return x <= 0 ? -kInf : log_normal_cdf((std::log(x) - mu_) / sig_); }
double LogNormal::sf(double x) const { return x <= 0 ? 1.0 : normal_cdf((mu_ - std::log(x)) / sig_); }
double LogNormal::isf(double q) const { return std::exp(mu_ - sig_ * normal_quantile(q)); }
double LogNormal::mean() const { return std::exp(mu_ + 0.5 * sig_ * sig_); }
double LogNormal::stddev() const { return mean() * std::sqrt(std::expm1(sig_ * sig_)); }
std::pair<double, double> LogNormal::support() const { return {0.0, kInf}; }
std::vector<std::pair<std::string, double>> LogNormal::params() const {
  return {{"mean", mean()}, {"std", stddev()}, {"mu_log", mu_}, {"sigma_log", sig_}};
}

// ---- Uniform ------------------------------------------------------------------------------

Uniform::Uniform(double lower, double upper) : a_(lower), b_(upper) {
  require_finite_param(lower, "lower", "uniform");
  require_finite_param(upper, "upper", "uniform");
  require_order(lower, upper, "uniform");
}
Uniform Uniform::from_moments(double mean, double sd) {
  require_finite_param(mean, "mean", "uniform");
  require_positive(sd, "std", "uniform");
  return Uniform(mean - kSqrt3 * sd, mean + kSqrt3 * sd);
}
double Uniform::pdf(double x) const { return x < a_ || x > b_ ? 0.0 : 1.0 / (b_ - a_); }
double Uniform::cdf(double x) const { return x <= a_ ? 0.0 : x >= b_ ? 1.0 : (x - a_) / (b_ - a_); }
double Uniform::quantile(double p) const { return a_ + p * (b_ - a_); }
double Uniform::logpdf(double x) const { return x < a_ || x > b_ ? -kInf : -std::log(b_ - a_); }
double Uniform::sf(double x) const { return x <= a_ ? 1.0 : x >= b_ ? 0.0 : (b_ - x) / (b_ - a_); }
double Uniform::isf(double q) const { return b_ - q * (b_ - a_); }
double Uniform::stddev() const { return (b_ - a_) / (2.0 * kSqrt3); }

// ---- TruncNormal --------------------------------------------------------------------------

TruncNormal::TruncNormal(double mu, double sigma, double lower, double upper) : mu_(mu), sig_(sigma), a_(lower), b_(upper) {
  require_finite_param(mu, "mean", "truncnormal");
  require_positive(sigma, "std", "truncnormal");
  require_order(lower, upper, "truncnormal");
  al_ = (a_ - mu_) / sig_;
  be_ = (b_ - mu_) / sig_;
  z_ = normal_mass(al_, be_);
  if (!(z_ > 1e-300))
    throw InvalidArgument(fmt::format("truncnormal: [{}, {}] holds no mass of normal({}, {}); move the interval", a_, b_, mu_, sig_));
}
double TruncNormal::pdf(double x) const { return x < a_ || x > b_ ? 0.0 : normal_pdf((x - mu_) / sig_) / (sig_ * z_); }
// Masses as Φ-differences by normal_mass: on [6, ∞) Φ(x) − Φ(6) would cancel to 1e-7 garbage.
// Widths from the bound, (x − a)/σ, keep their precision where (x − μ)/σ − α would not.
double TruncNormal::cdf(double x) const {
  if (x <= a_) return 0.0;
  if (x >= b_) return 1.0;
  return (std::isfinite(a_) ? normal_mass_width(al_, (x - a_) / sig_) : normal_cdf((x - mu_) / sig_)) / z_;
}
double TruncNormal::sf(double x) const {
  if (x <= a_) return 1.0;
  if (x >= b_) return 0.0;
  const double xi = (x - mu_) / sig_;
  return (std::isfinite(b_) ? normal_mass_width(xi, (b_ - x) / sig_) : normal_cdf(-xi)) / z_;
}
// In log space: far below the mean (α, ξ < −5) both Φ's underflow long before their logarithms;
// log(Φ(ξ) − Φ(α)) = logΦ(ξ) + log1p(−exp(logΦ(α) − logΦ(ξ))).
double TruncNormal::logcdf(double x) const {
  if (x <= a_) return -kInf;
  if (x >= b_) return 0.0;
  const double xi = (x - mu_) / sig_;
  const double logz = std::log(z_);
  if (!std::isfinite(a_)) return log_normal_cdf(xi) - logz;
  if (xi < -5.0) {
    const double lx = log_normal_cdf(xi), la = log_normal_cdf(al_);
    return lx + std::log(-std::expm1(la - lx)) - logz;
  }
  const double c = cdf(x);
  if (c > 0.5) return std::log1p(-sf(x));  // the complement keeps what rounding c to 1 loses
  return c > 0.0 ? std::log(c) : std::log(normal_pdf(xi)) + std::log((x - a_) / sig_) - logz;  // a sliver above a
}
double TruncNormal::logpdf(double x) const {
  if (x < a_ || x > b_) return -kInf;
  const double z = (x - mu_) / sig_;
  return -0.5 * z * z - kLogSqrt2Pi - std::log(sig_ * z_);
}
double TruncNormal::mean() const {
  const double al = al_, be = be_;
  return mu_ + sig_ * (normal_pdf(al) - normal_pdf(be)) / z_;
}
double TruncNormal::stddev() const {
  const double al = al_, be = be_;
  const double pa = normal_pdf(al), pb = normal_pdf(be);
  const double ta = std::isfinite(al) ? al * pa : 0.0, tb = std::isfinite(be) ? be * pb : 0.0;
  const double r = (pa - pb) / z_;
  return sig_ * std::sqrt(std::max(0.0, 1.0 + (ta - tb) / z_ - r * r));
}
std::vector<std::pair<std::string, double>> TruncNormal::params() const {
  return {{"mean", mu_}, {"std", sig_}, {"lower", a_}, {"upper", b_}};
}

// ---- Triangular ---------------------------------------------------------------------------

Triangular::Triangular(double lower, double mode, double upper) : a_(lower), c_(mode), b_(upper) {
  require_finite_param(lower, "lower", "triangular");
  require_finite_param(upper, "upper", "triangular");
  require_order(lower, upper, "triangular");
  if (!(mode >= lower && mode <= upper))
    throw InvalidArgument(fmt::format("triangular: mode ({}) must lie in [lower, upper] = [{}, {}]", mode, lower, upper));
}
double Triangular::pdf(double x) const {
  if (x < a_ || x > b_) return 0.0;
  return x < c_ ? 2.0 * (x - a_) / ((b_ - a_) * (c_ - a_)) : x == c_ ? 2.0 / (b_ - a_) : 2.0 * (b_ - x) / ((b_ - a_) * (b_ - c_));
}
// Near a mode at a bound, 1 − (b − x)²/((b − a)(b − c)) and b − √(…) cancel (1e-4 relative lost
// at x − a = 1e-8 (b − a)). Expanding with b − a = (b − x) + (x − a) and b − c = (b − x) + (x − c):
//   (b − a)(b − c) − (b − x)² = (b − x)(x − c) + (x − a)(b − x) + (x − a)(x − c),
// a sum of non-negative terms for c <= x <= b; the mirror image serves sf below the mode, and the
// quantiles use (b − a) − √((1 − p)(b − a)(b − c)) = (b − a)((c − a) + p (b − c)) / ((b − a) + √(…)).
double Triangular::cdf(double x) const {
  if (x <= a_) return 0.0;
  if (x >= b_) return 1.0;
  if (x <= c_) return (x - a_) * (x - a_) / ((b_ - a_) * (c_ - a_));
  return ((b_ - x) * (x - c_) + (x - a_) * (b_ - x) + (x - a_) * (x - c_)) / ((b_ - a_) * (b_ - c_));
}
double Triangular::logcdf(double x) const {
  if (x <= a_) return -kInf;
  if (x >= b_) return 0.0;
  // in log space below the mode: (x − a)² underflows long before its logarithm does
  const double c = cdf(x);
  if (c > 0.5) return std::log1p(-sf(x));  // the complement keeps what rounding c to 1 loses
  if (x <= c_) return 2.0 * std::log(x - a_) - std::log(b_ - a_) - std::log(c_ - a_);
  return std::log(c);
}
// Each point from its nearer bound: b − d is exact near b, a + (b − a)(…)/(…) near a.
double Triangular::quantile(double p) const {
  const double fc = (c_ - a_) / (b_ - a_);
  if (p < fc) return a_ + std::sqrt(p * (b_ - a_) * (c_ - a_));
  const double s = std::sqrt((1.0 - p) * (b_ - a_) * (b_ - c_));
  if (s <= 0.5 * (b_ - a_)) return b_ - s;
  return a_ + (b_ - a_) * ((c_ - a_) + p * (b_ - c_)) / ((b_ - a_) + s);
}
double Triangular::sf(double x) const {
  if (x <= a_) return 1.0;
  if (x >= b_) return 0.0;
  if (x >= c_) return (b_ - x) * (b_ - x) / ((b_ - a_) * (b_ - c_));
  return ((x - a_) * (c_ - x) + (b_ - x) * (x - a_) + (b_ - x) * (c_ - x)) / ((b_ - a_) * (c_ - a_));
}
double Triangular::isf(double q) const {
  const double fc = (b_ - c_) / (b_ - a_);  // sf at the mode
  if (q <= fc) {
    const double s = std::sqrt(q * (b_ - a_) * (b_ - c_));
    if (s <= 0.5 * (b_ - a_)) return b_ - s;
    return a_ + (b_ - a_) * ((c_ - a_) + (1.0 - q) * (b_ - c_)) / ((b_ - a_) + s);
  }
  const double s = std::sqrt((1.0 - q) * (b_ - a_) * (c_ - a_));
  if (s <= 0.5 * (b_ - a_)) return a_ + s;
  return b_ - (b_ - a_) * ((b_ - c_) + q * (c_ - a_)) / ((b_ - a_) + s);
}
double Triangular::logpdf(double x) const { return std::log(pdf(x)); }
double Triangular::stddev() const {
  return std::sqrt((a_ * a_ + b_ * b_ + c_ * c_ - a_ * b_ - a_ * c_ - b_ * c_) / 18.0);
}
std::vector<std::pair<std::string, double>> Triangular::params() const {
  return {{"lower", a_}, {"mode", c_}, {"upper", b_}};
}

}  // namespace smi::stats
