#include "improve/crn_mapping.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "core/errors.hpp"
#include "core/normal.hpp"
#include "core/rng.hpp"

namespace smi::improve {

InputFamily parse_family(std::string_view name, std::string_view what) {
  if (name == "normal") return InputFamily::normal;
  if (name == "lognormal") return InputFamily::lognormal;
  if (name == "uniform") return InputFamily::uniform;
  if (name == "constant") return InputFamily::constant;
  throw InvalidArgument(fmt::format("{}: unknown distribution \"{}\" (use \"normal\", \"lognormal\", \"uniform\" or \"constant\")",
                                    what, name));
}

std::string family_name(InputFamily f) {
  switch (f) {
    case InputFamily::normal: return "normal";
    case InputFamily::lognormal: return "lognormal";
    case InputFamily::uniform: return "uniform";
    case InputFamily::constant: return "constant";
  }
  return "?";
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
                                    std::string_view what) {
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
