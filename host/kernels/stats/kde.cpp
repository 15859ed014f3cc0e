// SPDX-License-Identifier: MIT
// The Kde distribution object (sums in kde_sums.cpp).
#include "kernels/stats/kde.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "kernels/stats/bandwidth.hpp"
#include "kernels/stats/special.hpp"
#include "platform/core/errors.hpp"
#include "platform/core/normal.hpp"

namespace smi::stats {

Kde::Kde(Eigen::VectorXd data, double h, KdeOptions opt) : t_(std::move(data)), h_(h), opt_(opt) {
  require_size(t_, 1, "data");
  require_finite(t_, "data");
  if (!(h > 0.0) || !std::isfinite(h))
    throw InvalidArgument(fmt::format("bandwidth must be a positive finite number, got {}", h));
  std::sort(t_.data(), t_.data() + t_.size());
  mean_ = t_.mean();
  var_ = (t_.array() - mean_).square().mean();
}

std::string Kde::describe() const {
  return fmt::format("kde(n={}, bandwidth={:.10g}{}{})", t_.size(), h_, label_.empty() ? "" : ", ", label_);
}

double Kde::stddev() const { return std::sqrt(var_ + h_ * h_); }

std::pair<double, double> Kde::support() const {
  return {-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
}

bool kde_uses_binned(Eigen::Index n_data, Eigen::Index n_points, const KdeOptions& opt) {
  switch (opt.method) {
    case KdeMethod::Exact: return false;
    case KdeMethod::Binned: return true;
    case KdeMethod::Auto: break;
  }
  return n_data > 2000 && static_cast<double>(n_data) * static_cast<double>(n_points) > 2e7;
}

double kde_bin_width(double h, const KdeOptions& opt) { return h * std::sqrt(8.0 * opt.binned_tol); }

Eigen::VectorXd kde_pdf_grid(ConstVec data, double h, const Grid& g, const KdeOptions& opt) {
  if (!kde_uses_binned(data.size(), g.n, opt)) return kde_pdf_grid(data, h, g, opt.threads);
  g.validate();
  return kde_pdf_binned(data, h, g.nodes(), kde_bin_width(h, opt), opt.threads);
}

namespace {
bool use_binned(const Kde& k, Eigen::Index m) { return kde_uses_binned(k.data().size(), m, k.options()); }
double bin_width(const Kde& k) { return kde_bin_width(k.bandwidth(), k.options()); }
}  // namespace

Eigen::VectorXd Kde::pdf(const Eigen::VectorXd& x) const {
  if (use_binned(*this, x.size())) return kde_pdf_binned(t_, h_, x, bin_width(*this), opt_.threads);
  return kde_pdf(t_, h_, x, opt_.threads);
}

Eigen::VectorXd Kde::cdf(const Eigen::VectorXd& x) const { return kde_cdf(t_, h_, x, opt_.threads); }

double Kde::pdf(double x) const { return kde_pdf(t_, h_, Eigen::VectorXd::Constant(1, x), 1)[0]; }
double Kde::cdf(double x) const {
  // beyond 8 h below the data the fast kernel cdf rounds to 0; the log-space sum does not
  if (x < t_[0] - 8.0 * h_) return std::exp(logcdf(x));
  return kde_cdf(t_, h_, Eigen::VectorXd::Constant(1, x), 1)[0];
}

namespace {
/// log Σ exp(l_i) without overflow or underflow.
double log_sum_exp(const Eigen::VectorXd& l) {
  const double m = l.maxCoeff();
  if (!std::isfinite(m)) return m;
  return m + std::log((l.array() - m).exp().sum());
}
/// x in [lo, hi] where the increasing (up) or decreasing function g crosses 0, by bisection to
/// the last bit.
template <class G>
double bisect(G&& g, double lo, double hi, bool up) {
  for (int it = 0; it < 400 && hi - lo > 4e-16 * std::max(std::abs(lo), std::abs(hi)); ++it) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    if ((g(mid) > 0.0) == up) hi = mid;
    else lo = mid;
  }
  return 0.5 * (lo + hi);
}
}  // namespace

double Kde::logpdf(double x) const {
  const Eigen::VectorXd t = (x - t_.array()) / h_;
  return log_sum_exp((-0.5 * t.array().square()).matrix()) - std::log(static_cast<double>(t_.size()) * h_ * std::sqrt(2.0 * M_PI));
}

double Kde::logcdf(double x) const {
  const double n = static_cast<double>(t_.size());
  Eigen::VectorXd l(t_.size());
  for (Eigen::Index i = 0; i < l.size(); ++i) l[i] = log_normal_cdf((x - t_[i]) / h_);
  const double lc = log_sum_exp(l) - std::log(n);
  // above the median log1p(−sf) keeps what rounding the cdf to 1 loses
  return lc > -M_LN2 ? std::log1p(-sf(x)) : lc;
}

double Kde::sf(double x) const {
  Eigen::VectorXd l(t_.size());
  for (Eigen::Index i = 0; i < l.size(); ++i) l[i] = log_normal_cdf((t_[i] - x) / h_);
  return std::exp(log_sum_exp(l) - std::log(static_cast<double>(t_.size())));
}

double Kde::isf(double q) const {
  if (q >= 1e-3) return quantile(1.0 - q);
  if (q <= 0.0) return std::numeric_limits<double>::infinity();
  // every kernel's own q-isf brackets the mixture's
  const double zq = -normal_quantile(q);
  const double lq = std::log(q);
  const double lo = t_[0] + h_ * zq, hi = t_[t_.size() - 1] + h_ * zq;
  if (lo == hi) return lo;
  return bisect([&](double x) { return std::log(sf(x)) - lq; }, lo, hi, false);
}

double Kde::quantile(double p) const {
  if (p <= 0.0) return -std::numeric_limits<double>::infinity();
  if (p >= 1.0) return std::numeric_limits<double>::infinity();
  if (p < 1e-3) {
    const double zp = normal_quantile(p), lp = std::log(p);
    const double lo = t_[0] + h_ * zp, hi = t_[t_.size() - 1] + h_ * zp;
    if (lo == hi) return lo;
    return bisect([&](double x) { return logcdf(x) - lp; }, lo, hi, true);
  }
  // Bracket: every kernel's own p-quantile lies in [t_min + h z_p, t_max + h z_p].
  const double zp = normal_quantile(p);
  double lo = t_[0] + h_ * zp, hi = t_[t_.size() - 1] + h_ * zp;
  if (lo == hi) return lo;
  double x = 0.5 * (lo + hi);
  for (int it = 0; it < 200; ++it) {
    const double f = cdf(x) - p;
    if (f > 0) hi = x; else lo = x;
    const double d = pdf(x);
    double xn = d > 0 ? x - f / d : 0.5 * (lo + hi);
    if (!(xn > lo && xn < hi)) xn = 0.5 * (lo + hi);
    if (std::abs(xn - x) <= 1e-14 * std::max(1.0, std::abs(x)) || hi - lo <= 1e-14 * std::max(1.0, std::abs(x)))
      return xn;
    x = xn;
  }
  return x;
}

Eigen::VectorXd Kde::quantile(const Eigen::VectorXd& p) const {
  Eigen::VectorXd q(p.size());
  for (Eigen::Index i = 0; i < p.size(); ++i) q[i] = quantile(p[i]);
  return q;
}

Eigen::VectorXd Kde::sample(Rng& rng, Eigen::Index n) const {
  Eigen::VectorXd y(n);
  const auto last = static_cast<std::int64_t>(t_.size() - 1);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double base = t_[static_cast<Eigen::Index>(rng.integer(0, last))];
    y[i] = base + h_ * rng.normal();
  }
  return y;
}

std::optional<double> Kde::field(std::string_view name) const {
  if (name == "bandwidth" || name == "h") return h_;
  if (name == "n") return static_cast<double>(t_.size());
  if (name == "error_bound")
    return opt_.method == KdeMethod::Exact ? 0.0 : binned_error_bound(h_, bin_width(*this));
  for (const auto& [k, v] : extra_)
    if (k == name) return v;
  return std::nullopt;
}

std::shared_ptr<Kde> make_kde(const Eigen::VectorXd& data, const std::string& rule, KdeOptions opt) {
  require_finite(data, "data");
  auto k = std::make_shared<Kde>(data, bandwidth_by_name(data, rule), opt);
  k->set_label(rule);
  return k;
}

std::shared_ptr<Kde> make_kde(const Eigen::VectorXd& data, double h, KdeOptions opt) {
  return std::make_shared<Kde>(data, h, opt);
}

}  // namespace smi::stats
