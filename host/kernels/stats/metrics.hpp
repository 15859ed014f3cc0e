// SPDX-License-Identifier: MIT
#pragma once
// Distances between 1-D distributions (spec §2, §3, §5): the L1 area between PDFs (probability
// residual PR, screening e_k), the intersection area, the area metric between CDFs and the
// log-likelihood. PDF integrals on a caller's §0 Grid use the trapezoid rule (the calibration
// loop's fast path on KDE values); without a grid, and wherever a grid cannot resolve a pdf,
// they are exact sums of CDF masses between the pdf crossings (stats/pdf_overlap.hpp).
#include <Eigen/Core>
#include <vector>

#include "kernels/stats/distribution.hpp"
#include "kernels/stats/grid.hpp"
#include "kernels/stats/pdf_overlap.hpp"
#include "platform/core/descriptive.hpp"

namespace smi::stats {

/// The PDF of d at the nodes of g (one vectorised call). A node where the pdf is infinite (a
/// support bound of gamma shape < 1, beta α < 1, Weibull k < 1) gets the mean density of its
/// cell, (F(x + step/2) − F(x − step/2)) / step, so that sums over the nodes stay finite and
/// keep the cell's mass.
Eigen::VectorXd pdf_grid(const Distribution& d, const Grid& g);
/// ∫|f − g| dy by the trapezoid rule from values at the nodes of `grid` (f, g of size grid.n).
/// Throws InvalidArgument when the values hold NaN or inf (never returns NaN).
double l1_area_on_grid(ConstVec f, ConstVec g, const Grid& grid);
/// ∫ min(f, g) dy on the grid (intersection area, §1.2); equals 1 − ½ L1 for unit masses.
double intersection_area_on_grid(ConstVec f, ConstVec g, const Grid& grid);

/// A §0 grid for comparing a and b: covers both supports' bulk. For KDEs: data range ± 6 h_max;
/// for other distributions their 1e-10 and 1-1e-10 quantiles (finite support ends when finite).
Grid comparison_grid(const Distribution& a, const Distribution& b, Eigen::Index n = kDefaultGridNodes);

/// PR and intersection area of a and b on grid g, with the reasons it was not the plain
/// trapezoid: when a pdf is infinite at a node, or integrates on the grid (plus its mass
/// outside [g.lo, g.hi]) more than 1e-3 away from 1, the grid does not resolve it; then the
/// values are the exact integrals over [g.lo, g.hi] (pdf_overlap) and `warnings` says which pdf
/// and by how much.
struct GridComparison {
  double pr = 0.0;
  double intersection = 0.0;
  std::vector<std::string> warnings;
};
GridComparison compare_on_grid(const Distribution& a, const Distribution& b, const Grid& g);

/// Probability residual PR = ∫|f_a − f_b| dy on grid g, in [0, 2] (§2.1) (compare_on_grid).
double pr(const Distribution& a, const Distribution& b, const Grid& g);
/// PR over the whole line, exact (pdf_overlap): no grid, no NaN, in [0, 2].
double pr(const Distribution& a, const Distribution& b);
/// Intersection area ∫ min(f_a, f_b) on g (compare_on_grid), in [0, 1].
double intersection_area(const Distribution& a, const Distribution& b, const Grid& g);
/// Intersection area over the whole line, exact (pdf_overlap).
double intersection_area(const Distribution& a, const Distribution& b);

/// Area metric ∫|F(y) − S_n(y)| dy between the ECDF of `sample` and a predicted CDF (§5):
/// adaptive Gauss–Kronrod on each ECDF step interval plus the two tails (tolerance 1e-10 abs).
double area_metric(ConstVec sample, const Distribution& predicted);
/// Area metric between two samples: exact (both CDFs are steps; merge of the sorted samples).
double area_metric_samples(ConstVec a, ConstVec b);
/// Area metric between two distributions: adaptive quadrature of |F_a − F_b| over the union of
/// their 1e-12..1−1e-12 quantile ranges.
double area_metric(const Distribution& a, const Distribution& b);

/// The density floor of loglik unless told (a density below it counts as floored).
inline constexpr double kLoglikFloor = 1e-300;

/// Σ log f(y_i), densities floored at `floor` (§2.2); `floored` (if given) counts the floored.
/// Small densities are taken through d.logpdf (finite where the pdf underflows). Throws
/// InvalidArgument naming d and the data point where the density is NaN, or infinite (an
/// observation on a singular support bound: the likelihood is unbounded).
double loglik(ConstVec y, const Distribution& d, double floor = kLoglikFloor, int* floored = nullptr);

}  // namespace smi::stats
