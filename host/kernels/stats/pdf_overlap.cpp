// SPDX-License-Identifier: MIT
#include "kernels/stats/pdf_overlap.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "kernels/stats/kde.hpp"
#include "platform/core/errors.hpp"

namespace smi::stats {
namespace {

constexpr int kQuantileScan = 400;      // scan points per analytic distribution
constexpr double kLogitSpan = 34.5;     // p from 1/(1+e^34.5) ≈ 1e-15 to 1 − 1e-15
constexpr Eigen::Index kMaxKdeScan = 20000;

/// Where to look for crossings: points dense where d has its mass, on every scale of d.
void add_scan_points(const Distribution& d, std::vector<double>& x) {
  if (const auto* k = dynamic_cast<const Kde*>(&d)) {
    const auto& t = k->data();
    const double h = k->bandwidth(), lo = t[0] - 8.0 * h, hi = t[t.size() - 1] + 8.0 * h;
    const Eigen::Index n =
        static_cast<Eigen::Index>(std::clamp(std::ceil((hi - lo) / (0.25 * h)) + 1.0, 2.0, static_cast<double>(kMaxKdeScan)));
    for (Eigen::Index i = 0; i < n; ++i) x.push_back(lo + (hi - lo) * static_cast<double>(i) / static_cast<double>(n - 1));
  } else {
    for (int i = 0; i <= kQuantileScan; ++i) {
      const double t = kLogitSpan * (2.0 * i / kQuantileScan - 1.0);
      // Lower half by quantile, upper half by isf: each tail keeps its precision.
      x.push_back(t <= 0 ? d.quantile(1.0 / (1.0 + std::exp(-t))) : d.isf(1.0 / (1.0 + std::exp(t))));
    }
  }
  const auto [s0, s1] = d.support();
  if (std::isfinite(s0)) x.push_back(s0);
  if (std::isfinite(s1)) x.push_back(s1);
}

/// pdf of d at x, checked: NaN or negative means d cannot be integrated.
double checked_pdf(const Distribution& d, double x, const char* which) {
  const double f = d.pdf(x);
  if (std::isnan(f) || f < 0.0)
    throw InvalidArgument(fmt::format("the pdf of {} ({}) is {} at x = {}: it cannot be integrated; check its parameters",
                                      d.describe(), which, f, x));
  return f;
}

int sign_of(double v) { return v > 0 ? 1 : v < 0 ? -1 : 0; }

}  // namespace

double mass_between(const Distribution& d, double u, double v) {
  if (!(u < v)) return 0.0;
  const double cv = std::isfinite(v) ? d.cdf(v) : 1.0;
  if (cv <= 0.5) return std::max(0.0, cv - (std::isfinite(u) ? d.cdf(u) : 0.0));
  const double su = std::isfinite(u) ? d.sf(u) : 1.0, sv = std::isfinite(v) ? d.sf(v) : 0.0;
  return std::max(0.0, su - sv);
}

PdfOverlap pdf_overlap(const Distribution& a, const Distribution& b, double lo, double hi) {
  if (std::isnan(lo) || std::isnan(hi) || !(lo < hi))
    throw InvalidArgument(fmt::format("overlap window [{}, {}]: lower must be < upper", lo, hi));
  std::vector<double> xs;
  add_scan_points(a, xs);
  add_scan_points(b, xs);
  xs.erase(std::remove_if(xs.begin(), xs.end(), [&](double x) { return !std::isfinite(x) || x <= lo || x >= hi; }), xs.end());
  std::sort(xs.begin(), xs.end());
  xs.erase(std::unique(xs.begin(), xs.end()), xs.end());

  auto diff = [&](double x) { return checked_pdf(a, x, "first") - checked_pdf(b, x, "second"); };
  // Cuts: window ends, support bounds inside it, and every located crossing.
  std::vector<double> cuts = {lo, hi};
  for (const Distribution* d : {&a, &b}) {
    const auto [s0, s1] = d->support();
    if (s0 > lo && s0 < hi) cuts.push_back(s0);
    if (s1 > lo && s1 < hi) cuts.push_back(s1);
  }
  PdfOverlap out;
  double px = 0.0;
  int ps = 0;  // sign at px; 0 = none yet (or unknown: an infinite pdf at a support bound)
  for (const double x : xs) {
    const double dv = diff(x);
    const int s = std::isfinite(dv) ? sign_of(dv) : 0;
    if (std::isfinite(dv) && dv == 0.0) cuts.push_back(x);
    if (s != 0 && ps != 0 && s != ps) {
      // Bisect the sign change to full precision.
      double l = px, r = x;
      for (int it = 0; it < 200 && r - l > 4e-16 * std::max(std::abs(l), std::abs(r)) && r - l > 1e-300; ++it) {
        const double m = 0.5 * (l + r);
        const double dm = diff(m);
        if (!std::isfinite(dm)) break;
        if (sign_of(dm) == ps) l = m; else r = m;
        if (dm == 0.0) { l = r = m; break; }
      }
      cuts.push_back(0.5 * (l + r));
      ++out.crossings;
    }
    if (s != 0) {
      px = x;
      ps = s;
    }
  }
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    const double ma = mass_between(a, cuts[i], cuts[i + 1]), mb = mass_between(b, cuts[i], cuts[i + 1]);
    out.l1 += std::abs(ma - mb);
    out.intersection += std::min(ma, mb);
  }
  if (!std::isfinite(out.l1) || !std::isfinite(out.intersection))
    throw InvalidArgument(fmt::format("the overlap of {} and {} is not finite: check that their cdfs are", a.describe(), b.describe()));
  out.l1 = std::clamp(out.l1, 0.0, 2.0);
  out.intersection = std::clamp(out.intersection, 0.0, 1.0);
  return out;
}

}  // namespace smi::stats
