// SPDX-License-Identifier: MIT
#pragma once
// Defaults shared by several layers, each in one place: the kernels' option structs, the
// bindings (which read their defaults from those structs), the CLI's help and the docs.
#include <Eigen/Core>
#include <cstdint>

namespace smi {

/// The run's seed when --seed is not given (smi.seed); kernels that default to "the run's seed"
/// use it when called outside a run.
inline constexpr std::uint64_t kDefaultSeed = 20200214;

/// Worker threads of a parallel kernel (KDE, Kriging fit and prediction, u-pooling) unless told.
inline constexpr int kDefaultThreads = 2;

/// Nodes of the §0 integration grid (>= 2001 by the spec; 4001 recommended).
inline constexpr Eigen::Index kDefaultGridNodes = 4001;

/// The fewest nodes an integration grid may have: below this a PDF's shape is not resolved (the
/// calibration's PR grids and the bounded KDE's grid check it; the bindings' schemas say it).
inline constexpr Eigen::Index kMinGridNodes = 101;

/// Points of a distribution's plot series (d:curve()) unless told.
inline constexpr int kDefaultCurvePoints = 401;

}  // namespace smi
