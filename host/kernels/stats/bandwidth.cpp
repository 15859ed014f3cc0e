// SPDX-License-Identifier: MIT
#include "kernels/stats/bandwidth.hpp"

#include <cmath>
#include <fmt/format.h>

#include "kernels/stats/pair_sums.hpp"
#include "platform/core/errors.hpp"
#include "platform/core/normal.hpp"

namespace smi::stats {
namespace {

double n_pow(ConstVec x, double e) { return std::pow(static_cast<double>(x.size()), e); }

/// sd with the checks every rule shares: >= 2 finite points, not all equal.
double checked_sd(ConstVec x) {
  require_size(x, 2, "data");
  require_finite(x, "data");
  const double sd = stddev(x);
  if (!(sd > 0.0))
    throw InvalidArgument(fmt::format("all {} data values are equal ({}): a bandwidth rule needs spread; "
                                      "pass a bandwidth explicitly, e.g. {{bandwidth = 0.1}}", x.size(), x[0]));
  return sd;
}

}  // namespace

double bandwidth_normal_reference(ConstVec x) {
  const double sd = checked_sd(x);
  return std::pow(4.0 / (3.0 * static_cast<double>(x.size())), 0.2) * sd;
}

double bandwidth_normal_106(ConstVec x) { return 1.06 * checked_sd(x) * n_pow(x, -0.2); }

double bandwidth_scott(ConstVec x) { return checked_sd(x) * n_pow(x, -0.2); }

double bandwidth_robust(ConstVec x) {
  const double sd = checked_sd(x);
  const Eigen::VectorXd s = sorted(x);
  const double iqr = quantile_sorted(s, 0.75) - quantile_sorted(s, 0.25);
  const double scale = iqr > 0.0 ? std::min(sd, iqr / 1.34) : sd;
  return 0.9 * scale * n_pow(x, -0.2);
}

double bandwidth_mad(ConstVec x) {
  checked_sd(x);
  double scale = mad(x) / 0.6745;
  if (!(scale > 0.0)) scale = x.maxCoeff() - x.minCoeff();
  if (!(scale > 0.0)) return 1.0;
  return scale * std::pow(4.0 / (3.0 * static_cast<double>(x.size())), 0.2);
}

double bandwidth_lscv(ConstVec x) {
  const double h0 = bandwidth_normal_reference(x);
  const double n = static_cast<double>(x.size());
  const detail::PairSums pairs(x);
  const double c = 1.0 / (2.0 * std::sqrt(M_PI));
  // LSCV(h) = ∫f² − 2/n Σ f_{−i}(x_i); pair sums over i < j (hence the factors 2).
  auto score = [&](double h) {
    const double s4 = pairs.sum([&](double d) { return std::exp(-d * d / (4.0 * h * h)); });
    const double s2 = pairs.sum([&](double d) { return std::exp(-d * d / (2.0 * h * h)); });
    return c / (n * h) + 2.0 * c * s4 / (n * n * h) - 2.0 * 2.0 * kInvSqrt2Pi * s2 / (n * (n - 1.0) * h);
  };
  // Coarse scan on log h (LSCV has spurious local minima), then golden section around the best.
  const int m = 48;
  const double la = std::log(0.05 * h0), lb = std::log(2.0 * h0), dl = (lb - la) / m;
  int best = 0;
  double fbest = score(std::exp(la));
  for (int i = 1; i <= m; ++i) {
    const double f = score(std::exp(la + i * dl));
    if (f < fbest) fbest = f, best = i;
  }
  double a = la + std::max(0, best - 1) * dl, b = la + std::min(m, best + 1) * dl;
  const double r = 0.5 * (std::sqrt(5.0) - 1.0);
  double c1 = b - r * (b - a), c2 = a + r * (b - a);
  double f1 = score(std::exp(c1)), f2 = score(std::exp(c2));
  for (int it = 0; it < 60 && b - a > 1e-10; ++it) {
    if (f1 < f2) {
      b = c2, c2 = c1, f2 = f1, c1 = b - r * (b - a), f1 = score(std::exp(c1));
    } else {
      a = c1, c1 = c2, f1 = f2, c2 = a + r * (b - a), f2 = score(std::exp(c2));
    }
  }
  return std::exp(0.5 * (a + b));
}

double bandwidth_sheather_jones(ConstVec x) {
  const double sd = checked_sd(x);
  const double n = static_cast<double>(x.size());
  const Eigen::VectorXd s = sorted(x);
  const double iqr = quantile_sorted(s, 0.75) - quantile_sorted(s, 0.25);
  const double scale = iqr > 0.0 ? std::min(sd, iqr / 1.349) : sd;
  const detail::PairSums pairs(x);
  // ψ_r(g) = 1/(n(n−1) g^{r+1}) Σ_{i,j} φ^{(r)}(d_ij/g), diagonal included as in Sheather &
  // Jones' estimator (φ⁗(0) = 3φ(0), φ⁽⁶⁾(0) = −15φ(0)); the i≠j part is twice the i<j sum.
  auto psi4 = [&](double g) {
    const double sum = pairs.sum([&](double d) {
      const double z2 = (d / g) * (d / g);
      return (z2 * z2 - 6.0 * z2 + 3.0) * std::exp(-0.5 * z2);
    });
    return kInvSqrt2Pi * (2.0 * sum + 3.0 * n) / (n * (n - 1.0) * std::pow(g, 5));
  };
  auto psi6 = [&](double g) {
    const double sum = pairs.sum([&](double d) {
      const double z2 = (d / g) * (d / g);
      return (z2 * z2 * z2 - 15.0 * z2 * z2 + 45.0 * z2 - 15.0) * std::exp(-0.5 * z2);
    });
    return kInvSqrt2Pi * (2.0 * sum - 15.0 * n) / (n * (n - 1.0) * std::pow(g, 7));
  };
  // Pilots (Sheather & Jones 1991, in the scale of min(sd, IQR/1.349)), then solve
  // h = [R(K) / (n ψ4(α2(h)))]^{1/5} with α2(h) = 1.357 (S_D(a)/T_D(b))^{1/7} h^{5/7}.
  const double a = 1.24 * scale * std::pow(n, -1.0 / 7.0), b = 1.23 * scale * std::pow(n, -1.0 / 9.0);
  const double sda = psi4(a), tdb = -psi6(b);
  if (!(sda > 0.0) || !(tdb > 0.0)) throw NotConverged("Sheather-Jones: pilot functional estimates are not positive; use another rule");
  const double alpha_c = 1.357 * std::pow(sda / tdb, 1.0 / 7.0);
  const double rk = 1.0 / (2.0 * std::sqrt(M_PI));
  auto eq = [&](double h) {
    const double p = psi4(alpha_c * std::pow(h, 5.0 / 7.0));
    return p > 0.0 ? std::pow(rk / (n * p), 0.2) - h : 1.0;
  };
  double lo = 0.01 * scale * std::pow(n, -0.2), hi = 4.0 * sd;
  double flo = eq(lo), fhi = eq(hi);
  for (int k = 0; k < 40 && flo * fhi > 0.0; ++k) lo *= 0.5, flo = eq(lo);
  if (flo * fhi > 0.0) throw NotConverged("Sheather-Jones: no root of the bandwidth equation; use another rule");
  for (int it = 0; it < 100 && hi - lo > 1e-12 * hi; ++it) {
    const double m = 0.5 * (lo + hi), fm = eq(m);
    if ((fm > 0.0) == (flo > 0.0)) lo = m, flo = fm; else hi = m, fhi = fm;
  }
  return 0.5 * (lo + hi);
}

const std::vector<std::string>& bandwidth_rule_names() {
  static const std::vector<std::string> names{"silverman", "normal_reference", "1.06", "robust", "scott", "mad", "lscv", "sj"};
  return names;
}

double bandwidth_by_name(ConstVec x, std::string_view rule) {
  if (rule == "silverman" || rule == "normal_reference" || rule == "normal") return bandwidth_normal_reference(x);
  if (rule == "1.06") return bandwidth_normal_106(x);
  if (rule == "robust" || rule == "silverman_robust") return bandwidth_robust(x);
  if (rule == "scott") return bandwidth_scott(x);
  if (rule == "mad" || rule == "matlab") return bandwidth_mad(x);
  if (rule == "lscv" || rule == "ucv" || rule == "cv") return bandwidth_lscv(x);
  if (rule == "sj" || rule == "sheather_jones") return bandwidth_sheather_jones(x);
  std::string list;
  for (const auto& n : bandwidth_rule_names()) list += (list.empty() ? "" : ", ") + n;
  throw InvalidArgument(fmt::format("unknown bandwidth rule '{}'; use a number or one of: {}", rule, list));
}

}  // namespace smi::stats
