// SPDX-License-Identifier: MIT
#include "kernels/stats/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "kernels/stats/ecdf.hpp"
#include "kernels/stats/kde.hpp"
#include "kernels/stats/quadrature.hpp"
#include "platform/core/errors.hpp"

namespace smi::stats {
namespace {

/// [lo, hi] holding all but ~1e-10 of d's mass (a KDE: data range ± 6h, §0).
std::pair<double, double> bulk(const Distribution& d) {
  if (const auto* k = dynamic_cast<const Kde*>(&d)) {
    const auto& t = k->data();
    return {t[0] - 6.0 * k->bandwidth(), t[t.size() - 1] + 6.0 * k->bandwidth()};
  }
  auto [lo, hi] = d.support();
  if (!std::isfinite(lo)) lo = d.quantile(1e-10);
  if (!std::isfinite(hi)) hi = d.quantile(1.0 - 1e-10);
  return {lo, hi};
}

void check_sizes(ConstVec f, ConstVec g, const Grid& grid) {
  if (f.size() != grid.n || g.size() != grid.n)
    throw DimensionMismatch(fmt::format("values at the grid nodes: grid has {} nodes, got {} and {}", grid.n, f.size(), g.size()));
}

}  // namespace

Eigen::VectorXd pdf_grid(const Distribution& d, const Grid& g) {
  g.validate();
  Eigen::VectorXd f = d.pdf(g.nodes());
  const double h = g.step();
  for (Eigen::Index i = 0; i < f.size(); ++i) {
    if (std::isinf(f[i])) {
      const double x = g.node(i);
      f[i] = mass_between(d, x - 0.5 * h, x + 0.5 * h) / h;
    }
    // (Tiny negative values of a binned KDE are its stated error, not a broken pdf.)
    if (std::isnan(f[i]))
      throw InvalidArgument(fmt::format("the pdf of {} is {} at x = {}: it cannot be integrated; check its parameters", d.describe(),
                                        f[i], g.node(i)));
  }
  return f;
}

double l1_area_on_grid(ConstVec f, ConstVec g, const Grid& grid) {
  check_sizes(f, g, grid);
  const double v = grid.trapezoid((f - g).cwiseAbs());
  if (!std::isfinite(v)) throw InvalidArgument("∫|f − g| on the grid: the pdf values at the nodes hold NaN or inf");
  return v;
}

double intersection_area_on_grid(ConstVec f, ConstVec g, const Grid& grid) {
  check_sizes(f, g, grid);
  const double v = grid.trapezoid(f.cwiseMin(g));
  if (!std::isfinite(v)) throw InvalidArgument("∫min(f, g) on the grid: the pdf values at the nodes hold NaN or inf");
  return v;
}

Grid comparison_grid(const Distribution& a, const Distribution& b, Eigen::Index n) {
  const auto [a0, a1] = bulk(a);
  const auto [b0, b1] = bulk(b);
  Grid g{std::min(a0, b0), std::max(a1, b1), n};
  g.validate();
  return g;
}

GridComparison compare_on_grid(const Distribution& a, const Distribution& b, const Grid& g) {
  g.validate();
  const Eigen::VectorXd x = g.nodes();
  const Eigen::VectorXd fa = a.pdf(x), fb = b.pdf(x);
  GridComparison out;
  // Does the grid resolve each pdf? Its trapezoid mass plus its mass outside the grid is 1.
  for (const auto& [d, f] : {std::pair<const Distribution*, const Eigen::VectorXd*>{&a, &fa}, {&b, &fb}}) {
    if (!f->allFinite()) {
      Eigen::Index i = 0;
      while (std::isfinite((*f)[i])) ++i;
      if (std::isnan((*f)[i]))
        throw InvalidArgument(fmt::format("the pdf of {} is {} at x = {}: it cannot be integrated; check its parameters",
                                          d->describe(), (*f)[i], x[i]));
      out.warnings.push_back(fmt::format("the pdf of {} is infinite at the grid node {}; integrated exactly between the pdf "
                                         "crossings instead of on the grid",
                                         d->describe(), x[i]));
      continue;
    }
    const double m = g.trapezoid(*f) + mass_between(*d, -std::numeric_limits<double>::infinity(), g.lo) +
                     mass_between(*d, g.hi, std::numeric_limits<double>::infinity());
    if (!(std::abs(m - 1.0) <= 1e-3))
      out.warnings.push_back(fmt::format("the pdf of {} integrates to {:.6g} on the grid [{:.6g}, {:.6g}] of {} nodes (step {:.3g}), "
                                         "not 1: the grid does not resolve it; integrated exactly between the pdf crossings instead",
                                         d->describe(), m, g.lo, g.hi, g.n, g.step()));
  }
  if (out.warnings.empty()) {
    out.pr = std::clamp(g.trapezoid((fa - fb).cwiseAbs()), 0.0, 2.0);
    out.intersection = std::clamp(g.trapezoid(fa.cwiseMin(fb)), 0.0, 1.0);
    return out;
  }
  const PdfOverlap o = pdf_overlap(a, b, g.lo, g.hi);
  out.pr = o.l1;
  out.intersection = o.intersection;
  return out;
}

double pr(const Distribution& a, const Distribution& b, const Grid& g) { return compare_on_grid(a, b, g).pr; }

double pr(const Distribution& a, const Distribution& b) { return pdf_overlap(a, b).l1; }

double intersection_area(const Distribution& a, const Distribution& b, const Grid& g) { return compare_on_grid(a, b, g).intersection; }

double intersection_area(const Distribution& a, const Distribution& b) { return pdf_overlap(a, b).intersection; }

double area_metric_samples(ConstVec a, ConstVec b) {
  require_size(a, 1, "sample a");
  require_size(b, 1, "sample b");
  require_finite(a, "sample a");
  require_finite(b, "sample b");
  const Eigen::VectorXd sa = sorted(a), sb = sorted(b);
  const double na = static_cast<double>(sa.size()), nb = static_cast<double>(sb.size());
  // Walk the merged jump points; between consecutive ones both CDFs are constant.
  Eigen::Index i = 0, j = 0;
  double area = 0.0, x = std::min(sa[0], sb[0]);
  while (i < sa.size() || j < sb.size()) {
    const double next = (j >= sb.size() || (i < sa.size() && sa[i] <= sb[j])) ? sa[i] : sb[j];
    area += std::abs(static_cast<double>(i) / na - static_cast<double>(j) / nb) * (next - x);
    x = next;
    while (i < sa.size() && sa[i] == x) ++i;
    while (j < sb.size() && sb[j] == x) ++j;
  }
  return area;
}

double area_metric(ConstVec sample, const Distribution& predicted) {
  require_size(sample, 1, "data");
  require_finite(sample, "data");
  if (const auto* e = dynamic_cast<const Ecdf*>(&predicted)) return area_metric_samples(sample, e->data());
  const Eigen::VectorXd s = sorted(sample);
  const auto n = s.size();
  const auto [lo, hi] = bulk(predicted);
  auto F = [&](double y) { return predicted.cdf(y); };
  // Tails: ∫_{lo}^{s1} F and ∫_{sn}^{hi} (1 − F).
  double area = 0.0;
  if (lo < s[0]) area += integrate(F, lo, s[0], 1e-13, 1e-12);
  if (hi > s[n - 1]) area += integrate([&](double y) { return 1.0 - F(y); }, s[n - 1], hi, 1e-13, 1e-12);
  for (Eigen::Index i = 0; i + 1 < n; ++i) {
    const double a = s[i], b = s[i + 1], c = static_cast<double>(i + 1) / static_cast<double>(n);
    if (b <= a) continue;
    auto g = [&](double y) { return std::abs(F(y) - c); };
    // Split at the crossing F = c (the kink of |F − c|) when it lies inside.
    const double xc = predicted.quantile(c);
    if (xc > a && xc < b)
      area += integrate(g, a, xc, 1e-13, 1e-12) + integrate(g, xc, b, 1e-13, 1e-12);
    else
      area += integrate(g, a, b, 1e-13, 1e-12);
  }
  return area;
}

double area_metric(const Distribution& a, const Distribution& b) {
  const auto* ea = dynamic_cast<const Ecdf*>(&a);
  const auto* eb = dynamic_cast<const Ecdf*>(&b);
  if (ea && eb) return area_metric_samples(ea->data(), eb->data());
  if (ea) return area_metric(ea->data(), b);
  if (eb) return area_metric(eb->data(), a);
  const auto [a0, a1] = bulk(a);
  const auto [b0, b1] = bulk(b);
  const double lo = std::min(a0, b0), hi = std::max(a1, b1);
  return integrate([&](double y) { return std::abs(a.cdf(y) - b.cdf(y)); }, lo, hi, 1e-11, 1e-10, 5000);
}

double loglik(ConstVec y, const Distribution& d, double floor, int* floored) {
  require_size(y, 1, "data");
  require_finite(y, "data");
  const Eigen::VectorXd f = d.pdf(Eigen::VectorXd(y));
  const double log_floor = std::log(floor);
  double s = 0.0;
  int nf = 0;
  for (Eigen::Index i = 0; i < f.size(); ++i) {
    // Densities that are small, underflowed, infinite or NaN go through logpdf (log space).
    const double lf = std::isnan(f[i]) ? f[i] : f[i] > 1e-280 && std::isfinite(f[i]) ? std::log(f[i]) : d.logpdf(y[i]);
    if (std::isnan(lf))
      throw InvalidArgument(fmt::format("loglik: the density of {} is NaN at data[{}] = {}; check its parameters", d.describe(), i + 1, y[i]));
    if (lf == std::numeric_limits<double>::infinity())
      throw InvalidArgument(fmt::format("loglik: the density of {} is infinite at data[{}] = {} (a support bound): the likelihood is "
                                        "unbounded; move the bound (loc, lower) so the data lie inside the support",
                                        d.describe(), i + 1, y[i]));
    if (!(lf > log_floor)) {
      ++nf;
      s += log_floor;
    } else {
      s += lf;
    }
  }
  if (floored) *floored = nf;
  return s;
}

}  // namespace smi::stats
