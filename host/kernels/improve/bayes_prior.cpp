// SPDX-License-Identifier: MIT
#include "kernels/improve/bayes_prior.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "kernels/stats/families.hpp"
#include "platform/core/errors.hpp"

namespace smi::improve {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// The mass of `d` within [lo, hi], from the tail where it is small (keeps digits when the
/// range sits in a tail).
double mass_within(const stats::Distribution& d, double lo, double hi) {
  const double median = d.quantile(0.5);
  if (lo >= median) return (std::isfinite(lo) ? d.sf(lo) : 1.0) - (std::isfinite(hi) ? d.sf(hi) : 0.0);
  return (std::isfinite(hi) ? d.cdf(hi) : 1.0) - (std::isfinite(lo) ? d.cdf(lo) : 0.0);
}

}  // namespace

std::string prior_kind_name(PriorKind k) {
  switch (k) {
    case PriorKind::uniform: return "uniform";
    case PriorKind::normal: return "normal";
    case PriorKind::lognormal: return "lognormal";
  }
  return "?";
}

PriorSet::PriorSet(std::vector<Prior> priors) : priors_(std::move(priors)) {
  if (priors_.empty()) throw InvalidArgument("no parameters: give at least one prior");
  for (const Prior& p : priors_) {
    const std::string who = fmt::format("parameter '{}'", p.name);
    if (std::isnan(p.lower) || std::isnan(p.upper) || !(p.lower < p.upper))
      throw InvalidArgument(fmt::format("{}: the range must have lower < upper, got [{}, {}]", who, p.lower, p.upper));
    Part part;
    if (p.kind == PriorKind::uniform) {
      if (!std::isfinite(p.lower) || !std::isfinite(p.upper))
        throw InvalidArgument(fmt::format("{}: a uniform prior needs a finite range, got [{}, {}]; give lower and upper or a normal prior", who,
                                          p.lower, p.upper));
      part.dist = std::make_shared<stats::Uniform>(p.lower, p.upper);
    } else {
      if (!std::isfinite(p.mean) || !(p.std > 0.0) || !std::isfinite(p.std))
        throw InvalidArgument(fmt::format("{}: a {} prior needs a finite mean and a std > 0, got mean {} std {}", who, prior_kind_name(p.kind), p.mean, p.std));
      if (p.kind == PriorKind::normal) {
        part.dist = std::make_shared<stats::Normal>(p.mean, p.std);
      } else {
        if (!(p.mean > 0.0)) throw InvalidArgument(fmt::format("{}: a lognormal prior needs mean > 0, got {}", who, p.mean));
        part.dist = std::make_shared<stats::LogNormal>(stats::LogNormal::from_moments(p.mean, p.std));
      }
      const double mass = mass_within(*part.dist, p.lower, p.upper);
      if (!(mass > 1e-300))
        throw InvalidArgument(fmt::format("{}: the {} prior (mean {}, std {}) has no mass within [{}, {}]; widen the range or move the prior", who,
                                          prior_kind_name(p.kind), p.mean, p.std, p.lower, p.upper));
      part.log_mass = std::log(mass);
    }
    part.cdf_lower = std::isfinite(p.lower) ? part.dist->cdf(p.lower) : 0.0;
    part.cdf_upper = std::isfinite(p.upper) ? part.dist->cdf(p.upper) : 1.0;
    parts_.push_back(part);
  }
}

std::vector<std::string> PriorSet::names() const {
  std::vector<std::string> n;
  for (const Prior& p : priors_) n.push_back(p.name);
  return n;
}

Eigen::VectorXd PriorSet::log_density(const Eigen::MatrixXd& Theta) const {
  if (Theta.cols() != size()) throw DimensionMismatch(fmt::format("prior of {} parameters evaluated at points of {}", size(), Theta.cols()));
  Eigen::VectorXd out = Eigen::VectorXd::Zero(Theta.rows());
  for (Eigen::Index i = 0; i < Theta.rows(); ++i)
    for (Eigen::Index k = 0; k < size(); ++k) {
      const double x = Theta(i, k);
      const Prior& p = priors_[static_cast<std::size_t>(k)];
      if (!(x >= p.lower && x <= p.upper)) {
        out[i] = -kInf;
        break;
      }
      out[i] += parts_[static_cast<std::size_t>(k)].dist->logpdf(x) - parts_[static_cast<std::size_t>(k)].log_mass;
    }
  return out;
}

Eigen::MatrixXd PriorSet::from_uniforms(const Eigen::MatrixXd& U) const {
  Eigen::MatrixXd X(U.rows(), U.cols());
  for (Eigen::Index k = 0; k < size(); ++k) {
    const Part& part = parts_[static_cast<std::size_t>(k)];
    const Prior& p = priors_[static_cast<std::size_t>(k)];
    for (Eigen::Index i = 0; i < U.rows(); ++i) {
      const double q = part.cdf_lower + U(i, k) * (part.cdf_upper - part.cdf_lower);
      X(i, k) = std::clamp(part.dist->quantile(std::clamp(q, 1e-300, 1.0 - 1e-16)), p.lower, p.upper);
    }
  }
  return X;
}

}  // namespace smi::improve
