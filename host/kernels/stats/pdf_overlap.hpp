// SPDX-License-Identifier: MIT
#pragma once
// ∫|f_a − f_b| (the probability residual) and ∫min(f_a, f_b) (the intersection area) of two
// distributions without a fixed grid. Between consecutive crossings of f_a and f_b (and the
// support bounds) the sign of f_a − f_b is constant, so on each such piece [u, v]
//   ∫|f_a − f_b| = |ΔF_a − ΔF_b|,  ∫min(f_a, f_b) = min(ΔF_a, ΔF_b),
// with ΔF the mass of the piece from the CDF (or the survival function above the median).
// That is exact where a pdf is infinite at a bound (gamma shape < 1, beta α < 1, Weibull k < 1),
// needs no resolution for narrow or skewed pdfs, and sums to values in [0, 2] and [0, 1].
#include <limits>
#include <string>
#include <vector>

#include "kernels/stats/distribution.hpp"

namespace smi::stats {

struct PdfOverlap {
  double l1 = 0.0;            ///< ∫|f_a − f_b| over the window, in [0, 2]
  double intersection = 0.0;  ///< ∫min(f_a, f_b) over the window, in [0, 1]
  int crossings = 0;          ///< crossings of f_a and f_b found inside the window
  std::vector<std::string> warnings;
};

/// The overlap of a and b over [lo, hi] (default: the whole line). Crossings are located by
/// scanning f_a − f_b at both distributions' quantiles (logit-spaced, 1e-15 .. 1 − 1e-15; a KDE
/// at steps of h/4) and bisecting each sign change to full precision. Throws InvalidArgument
/// naming the distribution when its pdf is NaN or negative somewhere (it cannot be integrated).
PdfOverlap pdf_overlap(const Distribution& a, const Distribution& b, double lo = -std::numeric_limits<double>::infinity(),
                       double hi = std::numeric_limits<double>::infinity());

/// The probability mass of d on [u, v] from cdf (or sf where cdf(v) > ½, which keeps the
/// relative precision of upper-tail masses); u, v may be infinite.
double mass_between(const Distribution& d, double u, double v);

}  // namespace smi::stats
