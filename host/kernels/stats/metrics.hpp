#pragma once
// Distances between 1-D distributions (spec §2, §3, §5): the L1 area between PDFs (probability
// residual PR, screening e_k), the intersection area, the area metric between CDFs and the
// log-likelihood. All PDF integrals use a §0 Grid and the trapezoid rule.
#include <Eigen/Core>
#include <vector>

#include "core/descriptive.hpp"
#include "stats/distribution.hpp"
#include "stats/grid.hpp"

namespace smi {

/// The PDF of d at the nodes of g (one vectorised call).
Eigen::VectorXd pdf_grid(const Distribution& d, const Grid& g);
/// ∫|f − g| dy by the trapezoid rule from values at the nodes of `grid` (f, g of size grid.n).
double l1_area_on_grid(ConstVec f, ConstVec g, const Grid& grid);
/// ∫ min(f, g) dy on the grid (intersection area, §1.2); equals 1 − ½ L1 for unit masses.
double intersection_area_on_grid(ConstVec f, ConstVec g, const Grid& grid);

/// A §0 grid for comparing a and b: covers both supports' bulk. For KDEs: data range ± 6 h_max;
/// for other distributions their 1e-10 and 1-1e-10 quantiles (finite support ends when finite).
Grid comparison_grid(const Distribution& a, const Distribution& b, Eigen::Index n = 4001);

/// Probability residual PR = ∫|f_a − f_b| dy on grid g, in [0, 2] (§2.1).
double pr(const Distribution& a, const Distribution& b, const Grid& g);
/// PR on comparison_grid(a, b).
double pr(const Distribution& a, const Distribution& b);
/// Intersection area ∫ min(f_a, f_b) on g.
double intersection_area(const Distribution& a, const Distribution& b, const Grid& g);

/// Area metric ∫|F(y) − S_n(y)| dy between the ECDF of `sample` and a predicted CDF (§5):
/// adaptive Gauss–Kronrod on each ECDF step interval plus the two tails (tolerance 1e-10 abs).
double area_metric(ConstVec sample, const Distribution& predicted);
/// Area metric between two samples: exact (both CDFs are steps; merge of the sorted samples).
double area_metric_samples(ConstVec a, ConstVec b);
/// Area metric between two distributions: adaptive quadrature of |F_a − F_b| over the union of
/// their 1e-12..1−1e-12 quantile ranges.
double area_metric(const Distribution& a, const Distribution& b);

/// Σ log f(y_i), densities floored at `floor` (§2.2); `floored` (if given) counts the floored.
double loglik(ConstVec y, const Distribution& d, double floor = 1e-300, int* floored = nullptr);

}  // namespace smi
