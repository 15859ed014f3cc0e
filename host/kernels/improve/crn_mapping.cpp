// SPDX-License-Identifier: MIT
#include "kernels/improve/crn_mapping.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "kernels/stats/families.hpp"
#include "platform/core/errors.hpp"
#include "platform/core/normal.hpp"
#include "platform/core/rng.hpp"

namespace smi::improve {

const char* const kInputFamiliesHelp =
    "the calibrated parameters are mean and std of the variable for \"normal\", \"lognormal\", \"uniform\", \"gumbel\", "
    "\"gamma\" (fixed loc = 0), \"weibull\" (fixed loc = 0), \"beta\" (fixed lower = 0, upper = 1) and \"triangular\" (fixed "
    "mode_at = (mode - lower)/(upper - lower) = 0.5); mean and std of the parent normal for \"truncnormal\" (fixed lower, upper); "
    "value (or mean) for \"constant\"";

namespace {
constexpr std::pair<std::string_view, InputFamily> kFamilies[] = {
    {"normal", InputFamily::normal},   {"lognormal", InputFamily::lognormal},     {"uniform", InputFamily::uniform},
    {"constant", InputFamily::constant}, {"truncnormal", InputFamily::truncnormal}, {"weibull", InputFamily::weibull},
    {"gumbel", InputFamily::gumbel},   {"gamma", InputFamily::gamma},             {"beta", InputFamily::beta},
    {"triangular", InputFamily::triangular}};
constexpr double kEulerGamma = 0.57721566490153286061;

/// Weibull shape k with coefficient of variation cv: cv(k)² = Γ(1+2/k)/Γ(1+1/k)² − 1 falls
/// monotonically in k; bisection on log k over [0.05, 2000] (cv from 1.6e5 down to 6.4e-4).
double weibull_shape_for_cv(double cv, std::string_view what) {
  auto cv_of = [](double k) {
    return std::sqrt(std::max(0.0, std::exp(std::lgamma(1.0 + 2.0 / k) - 2.0 * std::lgamma(1.0 + 1.0 / k)) - 1.0));
  };
  double lo = std::log(0.05), hi = std::log(2000.0);
  if (!(cv < cv_of(0.05) && cv > cv_of(2000.0)))
    throw InvalidArgument(fmt::format("{}: weibull with std/(mean - loc) = {} is outside what a Weibull can have ({:.3g} .. {:.3g})", what, cv,
                                      cv_of(2000.0), cv_of(0.05)));
  for (int it = 0; it < 200 && hi - lo > 1e-15; ++it) {
    const double m = 0.5 * (lo + hi);
    if (cv_of(std::exp(m)) > cv) lo = m; else hi = m;
  }
  return std::exp(0.5 * (lo + hi));
}
}  // namespace

InputFamily parse_family(std::string_view name, std::string_view what) {
  for (const auto& [n, f] : kFamilies)
    if (n == name) return f;
  throw InvalidArgument(fmt::format("{}: unknown distribution \"{}\" (use one of normal, lognormal, uniform, truncnormal, weibull, gumbel, "
                                    "gamma, beta, triangular, constant; {})",
                                    what, name, kInputFamiliesHelp));
}

std::string family_name(InputFamily f) {
  for (const auto& [n, g] : kFamilies)
    if (g == f) return std::string(n);
  return "?";
}

stats::DistributionPtr input_distribution(InputFamily family, double mean, double std, const InputShape& shape, std::string_view what) {
  if (family == InputFamily::constant || !(std > 0.0)) return nullptr;
  try {
    switch (family) {
      case InputFamily::normal: return std::make_shared<stats::Normal>(mean, std);
      case InputFamily::lognormal: return std::make_shared<stats::LogNormal>(stats::LogNormal::from_moments(mean, std));
      case InputFamily::uniform: return std::make_shared<stats::Uniform>(stats::Uniform::from_moments(mean, std));
      case InputFamily::constant: return nullptr;
      case InputFamily::truncnormal: return std::make_shared<stats::TruncNormal>(mean, std, shape.lower, shape.upper);
      case InputFamily::gumbel: {
        const double scale = std * std::sqrt(6.0) / M_PI;
        return std::make_shared<stats::Gumbel>(mean - kEulerGamma * scale, scale);
      }
      case InputFamily::gamma: {
        const double m = mean - shape.loc;
        if (!(m > 0.0)) throw InvalidArgument(fmt::format("gamma needs mean > loc = {}, got mean = {}", shape.loc, mean));
        return std::make_shared<stats::Gamma>(m * m / (std * std), std * std / m, shape.loc);
      }
      case InputFamily::weibull: {
        const double m = mean - shape.loc;
        if (!(m > 0.0)) throw InvalidArgument(fmt::format("weibull needs mean > loc = {}, got mean = {}", shape.loc, mean));
        const double k = weibull_shape_for_cv(std / m, what);
        return std::make_shared<stats::Weibull>(k, m / std::exp(std::lgamma(1.0 + 1.0 / k)), shape.loc);
      }
      case InputFamily::beta: {
        const double lo = std::isfinite(shape.lower) ? shape.lower : 0.0, hi = std::isfinite(shape.upper) ? shape.upper : 1.0;
        const double w = hi - lo, m = (mean - lo) / w, v = (std / w) * (std / w);
        if (!(m > 0.0 && m < 1.0 && v < m * (1.0 - m)))
          throw InvalidArgument(fmt::format("beta on [{}, {}] needs lower < mean < upper and std < sqrt((mean - lower)(upper - mean)) = {:.6g}, "
                                            "got mean = {}, std = {}",
                                            lo, hi, w * std::sqrt(std::max(0.0, m * (1.0 - m))), mean, std));
        const double nu = m * (1.0 - m) / v - 1.0;
        return std::make_shared<stats::Beta>(m * nu, (1.0 - m) * nu, lo, hi);
      }
      case InputFamily::triangular: {
        const double c = shape.mode_at;
        if (!(c >= 0.0 && c <= 1.0)) throw InvalidArgument(fmt::format("triangular mode_at must be in [0, 1], got {}", c));
        const double w = std / std::sqrt((1.0 - c + c * c) / 18.0), lo = mean - w * (1.0 + c) / 3.0;
        return std::make_shared<stats::Triangular>(lo, lo + c * w, lo + w);
      }
    }
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(fmt::format("{}: {}", what, e.what()));
  }
  return nullptr;
}

LognormalParams lognormal_params(double mean, double std) {
  if (!(mean > 0.0) || !std::isfinite(mean))
    throw InvalidArgument(fmt::format("lognormal needs mean > 0, got mean = {} (use \"normal\" or shift the variable)", mean));
  if (!(std >= 0.0) || !std::isfinite(std)) throw InvalidArgument(fmt::format("lognormal needs finite std >= 0, got {}", std));
  const double r = std / mean;
  const double s2 = std::log1p(r * r);
  return {std::log(mean) - 0.5 * s2, std::sqrt(s2)};
}

UniformBounds uniform_bounds(double mean, double std) {
  if (!std::isfinite(mean) || !(std >= 0.0) || !std::isfinite(std))
    throw InvalidArgument(fmt::format("uniform needs finite mean and std >= 0, got mean = {}, std = {}", mean, std));
  const double h = std::sqrt(3.0) * std;
  return {mean - h, mean + h};
}

Eigen::VectorXd map_standard_normal(InputFamily family, double mean, double std, const Eigen::Ref<const Eigen::VectorXd>& z,
                                    std::string_view what, const InputShape& shape) {
  if (!std::isfinite(mean) || !std::isfinite(std) || std < 0.0)
    throw InvalidArgument(fmt::format("{}: need finite mean and std >= 0, got mean = {}, std = {}", what, mean, std));
  switch (family) {
    case InputFamily::normal: return (mean + std * z.array()).matrix();
    case InputFamily::constant: return Eigen::VectorXd::Constant(z.size(), mean);
    case InputFamily::lognormal: {
      if (!(mean > 0.0))
        throw InvalidArgument(fmt::format("{}: lognormal needs mean > 0, got {} (raise the lower bound of the mean above 0)",
                                          what, mean));
      const LognormalParams p = lognormal_params(mean, std);
      return (p.mu_ln + p.sigma_ln * z.array()).exp().matrix();
    }
    case InputFamily::uniform: {
      const UniformBounds b = uniform_bounds(mean, std);
      Eigen::VectorXd x(z.size());
      for (Eigen::Index i = 0; i < z.size(); ++i) x[i] = b.lower + (b.upper - b.lower) * normal_cdf(z[i]);
      return x;
    }
    default: {
      const stats::DistributionPtr d = input_distribution(family, mean, std, shape, what);
      if (!d) return Eigen::VectorXd::Constant(z.size(), mean);  // std = 0: the point mass
      Eigen::VectorXd x(z.size());
      for (Eigen::Index i = 0; i < z.size(); ++i) x[i] = z[i] <= 0 ? d->quantile(normal_cdf(z[i])) : d->isf(normal_cdf(-z[i]));
      return x;
    }
  }
  throw InvalidArgument(fmt::format("{}: unknown family", what));
}

Eigen::MatrixXd crn_matrix(Eigen::Index n, Eigen::Index k, std::uint64_t seed, CrnKind kind) {
  if (n < 1 || k < 0) throw InvalidArgument(fmt::format("CRN matrix needs n >= 1 and k >= 0, got n = {}, k = {}", n, k));
  Rng rng(seed, hash_label("crn"));
  if (kind == CrnKind::random) return rng.normal_matrix(n, k);
  Eigen::VectorXd q(n);
  for (Eigen::Index i = 0; i < n; ++i) q[i] = normal_quantile((static_cast<double>(i) + 0.5) / static_cast<double>(n));
  Eigen::MatrixXd z(n, k);
  std::vector<Eigen::Index> perm(static_cast<std::size_t>(n));
  for (Eigen::Index j = 0; j < k; ++j) {
    std::iota(perm.begin(), perm.end(), Eigen::Index{0});
    // Column 1 stays ordered (the 1-D deterministic variant of spec §7); later columns are
    // Fisher–Yates permutations so that inputs are not perfectly correlated (a midpoint LHS).
    if (j > 0)
      for (Eigen::Index i = n - 1; i > 0; --i) std::swap(perm[static_cast<std::size_t>(i)], perm[static_cast<std::size_t>(rng.integer(0, i))]);
    for (Eigen::Index i = 0; i < n; ++i) z(i, j) = q[perm[static_cast<std::size_t>(i)]];
  }
  return z;
}

}  // namespace smi::improve
