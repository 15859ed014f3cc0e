// SPDX-License-Identifier: MIT
#pragma once
// Adaptive Gauss–Kronrod (7/15) quadrature on a finite interval: the "adaptive quadrature" of
// the area metric for smooth CDFs, and of exact null moments.
#include <functional>

namespace smi::stats {

/// ∫_a^b f by globally adaptive bisection of the panel with the largest |K15 − G7|, until the
/// summed error estimate is <= max(abs_tol, rel_tol·|I|) or max_panels panels are used.
double integrate(const std::function<double(double)>& f, double a, double b, double abs_tol = 1e-12,
                 double rel_tol = 1e-12, int max_panels = 2000);

}  // namespace smi::stats
