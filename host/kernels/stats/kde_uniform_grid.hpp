// SPDX-License-Identifier: MIT
#pragma once
// Nearly exp-free Gaussian KDE sums on uniformly spaced evaluation points (the §0 grids, plot
// curves, linspaces). Along a uniform grid z_j = z_0 + jδ (δ = spacing/h), so
//   φ(z_j) ∝ e^{−z0²/2} · (e^{−z0 δ})^j · e^{−δ² j²/2},
// i.e. two exps per kernel and block of 64 nodes and a few multiplications per node (rounding
// ~1e-14 relative). The CDF uses the chain φ(z_{j+1}) = φ(z_j)·r_j, r_j = exp(−z_j δ − δ²/2),
// r_{j+1} = r_j·exp(−δ²), restarted from exact values every block. The CDF advances from exact
// table values at each block start by the corrected trapezoid rule on the same φ chain (used
// when δ <= 1/256: truncation δ⁵·1.7e-3 per step, < 1e-13 over a block).
// The pdf chain holds for δ up to kUniformPdfMaxStep = 1/4: a kernel reaching a 64-node block has
// z0 in [−(cutoff + 64δ), cutoff], so the chain's largest factor e^{|z0| δ j} stays below e^{400}
// and e^{−z0²/2} above e^{−320}, both far inside a double's range; the products keep full
// relative precision. Coarser grids (δ > 1/4: a kernel spans under 72 nodes) sum exps directly.
#include <Eigen/Core>
#include <optional>

#include "platform/core/descriptive.hpp"

namespace smi::stats::detail {

/// The coarsest node spacing, in bandwidths, that takes the blocked pdf recurrences (see above).
inline constexpr double kUniformPdfMaxStep = 0.25;

/// Spacing of x when x is uniform to rounding (|x_j − (x_0 + jΔ)| <= 8 ulp of max|x|), M >= 128.
std::optional<double> uniform_spacing(ConstVec x);

/// Unnormalised Σ_i φ((x_j − t_i)/h) for sorted t and uniform x with spacing dx <= h·kUniformPdfMaxStep;
/// result identical for any thread count.
void uniform_pdf_sums(ConstVec t, double h, ConstVec x, double dx, Eigen::VectorXd& out, int threads);
/// Unnormalised Σ_i Φ((x_j − t_i)/h) for sorted t and uniform x with spacing dx <= h/256.
void uniform_cdf_sums(ConstVec t, double h, ConstVec x, double dx, Eigen::VectorXd& out, int threads);

}  // namespace smi::stats::detail
