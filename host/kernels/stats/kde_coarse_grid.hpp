// SPDX-License-Identifier: MIT
#pragma once
// A KDE on a uniform grid far finer than its bandwidth. The probability residual's grids are
// sized for the narrowest density of a calibration (the data's KDE), so a prediction's KDE is
// often resolved by hundreds of nodes per bandwidth, and summing every kernel at every node of
// its window costs as much again. Such a KDE is summed on a grid `ratio` times coarser (spacing
// at most h/8) and carried to the fine nodes by 8-point Lagrange interpolation (degree 7), exact
// at every ratio-th node. For one Gaussian kernel the error is below 6.5e-9 of its peak at
// spacing h/8 (2.6e-11 at h/16); a KDE's, averaged over its kernels, is smaller (measured in
// tests/kernels/stats/test_kde.cpp). The interpolation is linear in the coarse values, so the
// result stays a smooth function of the data, and its adjoint gives the exact gradient of what
// was computed.
#include <Eigen/Core>
#include <optional>

#include "kernels/stats/grid.hpp"

namespace smi::stats {

/// The coarsest spacing, in bandwidths, at which a KDE is summed before interpolation.
inline constexpr double kCoarseKdeStep = 1.0 / 8.0;

struct CoarseGrid {
  Grid coarse;             ///< nodes every Δ from 3Δ before fine.lo to 4Δ past the last coarse step
  Eigen::Index ratio = 1;  ///< fine steps per coarse step (Δ = ratio × fine step)
  Eigen::Index fine_n = 0;
};

/// The coarse grid for bandwidth h, or nothing when the fine grid is not at least twice finer
/// than h·kCoarseKdeStep (then summing on it directly costs no more).
std::optional<CoarseGrid> coarse_grid(const Grid& fine, double h);

/// Values at the fine nodes from values at the coarse nodes.
Eigen::VectorXd interpolate_to_fine(const CoarseGrid& c, ConstVec coarse_values);

/// The adjoint of interpolate_to_fine: Σ_j a_j ∂fine_j/∂coarse_c for weights a on the fine nodes.
Eigen::VectorXd interpolate_adjoint(const CoarseGrid& c, ConstVec fine_weights);

/// kde_pdf on the nodes of g, through the coarse grid c when there is one (coarse_grid(g, h)):
/// a caller that also needs the gradient passes the same c to interpolate_adjoint.
Eigen::VectorXd kde_pdf_resolved(ConstVec data, double h, const Grid& g, const std::optional<CoarseGrid>& c, int threads);
/// The same, deciding the coarse grid itself.
Eigen::VectorXd kde_pdf_resolved(ConstVec data, double h, const Grid& g, int threads);

}  // namespace smi::stats
