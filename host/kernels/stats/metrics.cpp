#include "stats/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "core/errors.hpp"
#include "stats/ecdf.hpp"
#include "stats/kde.hpp"
#include "stats/quadrature.hpp"

namespace smi {
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
  return d.pdf(g.nodes());
}

double l1_area_on_grid(ConstVec f, ConstVec g, const Grid& grid) {
  check_sizes(f, g, grid);
  return grid.trapezoid((f - g).cwiseAbs());
}

double intersection_area_on_grid(ConstVec f, ConstVec g, const Grid& grid) {
  check_sizes(f, g, grid);
  return grid.trapezoid(f.cwiseMin(g));
}

Grid comparison_grid(const Distribution& a, const Distribution& b, Eigen::Index n) {
  const auto [a0, a1] = bulk(a);
  const auto [b0, b1] = bulk(b);
  Grid g{std::min(a0, b0), std::max(a1, b1), n};
  g.validate();
  return g;
}

double pr(const Distribution& a, const Distribution& b, const Grid& g) {
  return l1_area_on_grid(pdf_grid(a, g), pdf_grid(b, g), g);
}

double pr(const Distribution& a, const Distribution& b) { return pr(a, b, comparison_grid(a, b)); }

double intersection_area(const Distribution& a, const Distribution& b, const Grid& g) {
  return intersection_area_on_grid(pdf_grid(a, g), pdf_grid(b, g), g);
}

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
  double s = 0.0;
  int nf = 0;
  for (Eigen::Index i = 0; i < f.size(); ++i) {
    if (!(f[i] > floor)) {
      ++nf;
      s += std::log(floor);
    } else {
      s += std::log(f[i]);
    }
  }
  if (floored) *floored = nf;
  return s;
}

}  // namespace smi
