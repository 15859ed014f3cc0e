// SPDX-License-Identifier: MIT
#include "kernels/stats/fit.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "kernels/stats/families.hpp"
#include "kernels/stats/metrics.hpp"
#include "kernels/stats/nelder_mead.hpp"
#include "platform/core/errors.hpp"

namespace smi::stats {
namespace {


/// −log L of the data under the distribution built from parameters p (inf when infeasible).
template <class Make>
double nll(ConstVec x, const Eigen::VectorXd& p, Make&& make) {
  try {
    const auto d = make(p);
    double s = 0.0;
    for (Eigen::Index i = 0; i < x.size(); ++i) {
      const double f = d.pdf(x[i]);
      if (!(f > 0.0) || !std::isfinite(f)) return kInf;
      s -= std::log(f);
    }
    return s;
  } catch (const InvalidArgument&) {
    return kInf;
  }
}

template <class Make>
DistributionPtr fit_nm(ConstVec x, Eigen::VectorXd p0, Eigen::VectorXd step, Make&& make) {
  const auto p = detail::nelder_mead([&](const Eigen::VectorXd& q) { return nll(x, q, make); }, std::move(p0), step);
  return std::make_shared<decltype(make(p))>(make(p));
}

}  // namespace

const std::vector<std::string>& fit_family_names() {
  static const std::vector<std::string> n{"normal", "lognormal", "uniform", "weibull", "gumbel", "gamma", "beta", "triangular", "truncnormal"};
  return n;
}

double ks_statistic(ConstVec data, const Distribution& d) {
  const Eigen::VectorXd s = sorted(data);
  const Eigen::VectorXd F = d.cdf(s);
  const double n = static_cast<double>(s.size());
  double D = 0.0;
  for (Eigen::Index i = 0; i < s.size(); ++i)
    D = std::max({D, static_cast<double>(i + 1) / n - F[i], F[i] - static_cast<double>(i) / n});
  return D;
}

FitResult fit_family(ConstVec x, const std::string& fam) {
  require_size(x, 2, "data");
  require_finite(x, "data");
  const double n = static_cast<double>(x.size());
  const double m = x.mean();
  const double sb = std::sqrt((x.array() - m).square().mean());  // MLE (biased) std
  const double lo = x.minCoeff(), hi = x.maxCoeff(), r = hi - lo;
  if (!(r > 0.0)) throw InvalidArgument(fmt::format("all {} data values are equal ({}): no family can be fitted", x.size(), lo));
  FitResult out;
  out.family = fam;
  if (fam == "normal") {
    out.dist = std::make_shared<Normal>(m, sb);
    out.k = 2;
  } else if (fam == "lognormal") {
    if (!(lo > 0.0)) throw InvalidArgument("lognormal needs positive data (min is " + std::to_string(lo) + ")");
    const Eigen::ArrayXd l = x.array().log();
    const double ml = l.mean();
    out.dist = std::make_shared<LogNormal>(LogNormal::from_log_params(ml, std::sqrt((l - ml).square().mean())));
    out.k = 2;
  } else if (fam == "uniform") {
    out.dist = std::make_shared<Uniform>(lo, hi);
    out.k = 2;
  } else if (fam == "weibull") {
    if (!(lo > 0.0)) throw InvalidArgument("weibull (loc = 0) needs positive data");
    const double k0 = std::max(0.2, 1.2 * m / sb);
    Eigen::Vector2d p0(std::log(k0), std::log(m / std::tgamma(1.0 + 1.0 / k0))), st(0.3, 0.1 * sb / m + 0.01);
    out.dist = fit_nm(x, p0, st, [](const Eigen::VectorXd& p) { return Weibull(std::exp(p[0]), std::exp(p[1])); });
    out.k = 2;
  } else if (fam == "gumbel") {
    const double b0 = sb * std::sqrt(6.0) / M_PI;
    Eigen::Vector2d p0(m - 0.5772156649 * b0, std::log(b0)), st(0.3 * b0, 0.3);
    out.dist = fit_nm(x, p0, st, [](const Eigen::VectorXd& p) { return Gumbel(p[0], std::exp(p[1])); });
    out.k = 2;
  } else if (fam == "gamma") {
    if (!(lo > 0.0)) throw InvalidArgument("gamma (loc = 0) needs positive data");
    const double k0 = m * m / (sb * sb);
    Eigen::Vector2d p0(std::log(k0), std::log(sb * sb / m)), st(0.3, 0.3);
    // Parametrise by (log shape, log mean) to decorrelate the two.
    p0[1] = std::log(m);
    st[1] = 0.1 * sb / m;
    out.dist = fit_nm(x, p0, st, [](const Eigen::VectorXd& p) {
      const double k = std::exp(p[0]);
      return Gamma(k, std::exp(p[1]) / k);
    });
    out.k = 2;
  } else if (fam == "beta" || fam == "triangular" || fam == "truncnormal") {
    const double a = lo - r / n, b = hi + r / n, w = b - a;
    if (fam == "beta") {
      const double mu = (m - a) / w, v = sb * sb / (w * w), c = std::max(0.5, mu * (1 - mu) / v - 1.0);
      Eigen::Vector2d p0(std::log(mu * c), std::log((1 - mu) * c)), st(0.3, 0.3);
      out.dist = fit_nm(x, p0, st, [a, b](const Eigen::VectorXd& p) { return Beta(std::exp(p[0]), std::exp(p[1]), a, b); });
    } else if (fam == "triangular") {
      Eigen::VectorXd p0(1), st(1);
      p0[0] = std::clamp(3.0 * m - a - b, a, b);
      st[0] = 0.1 * w;
      out.dist = fit_nm(x, p0, st, [a, b](const Eigen::VectorXd& p) { return Triangular(a, p[0], b); });
    } else {
      Eigen::Vector2d p0(m, std::log(sb)), st(0.3 * sb, 0.3);
      out.dist = fit_nm(x, p0, st, [a, b](const Eigen::VectorXd& p) { return TruncNormal(p[0], std::exp(p[1]), a, b); });
    }
    out.k = fam == "triangular" ? 1 : 2;
  } else {
    std::string list;
    for (const auto& f : fit_family_names()) list += (list.empty() ? "" : ", ") + f;
    throw InvalidArgument(fmt::format("unknown family '{}'; known: {}", fam, list));
  }
  out.loglik = loglik(x, *out.dist, 1e-300);
  out.aic = 2.0 * out.k - 2.0 * out.loglik;
  out.bic = out.k * std::log(n) - 2.0 * out.loglik;
  out.ks = ks_statistic(x, *out.dist);
  return out;
}

std::vector<FitResult> fit(ConstVec data, const std::vector<std::string>& families) {
  if (families.empty()) throw InvalidArgument("families is empty: name at least one, e.g. {\"normal\", \"weibull\"}");
  std::vector<FitResult> out;
  for (const auto& f : families) out.push_back(fit_family(data, f));
  std::stable_sort(out.begin(), out.end(), [](const FitResult& a, const FitResult& b) {
    return a.aic < b.aic || (a.aic == b.aic && a.bic < b.bic);
  });
  return out;
}

}  // namespace smi::stats
