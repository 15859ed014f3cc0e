// SPDX-License-Identifier: MIT
#pragma once
// The Lua face shared by every distribution-like object (families, KDEs): one userdata type
// "smi.dist" holding a DistributionPtr, with pdf/cdf/quantile/sample/mean/std methods.
// Other areas (propagation, calibration) read distributions through to_distribution().
#include <lua.hpp>

#include "kernels/stats/distribution.hpp"

namespace smi::bind {

inline constexpr const char* kDistType = "smi.dist";

/// Pushes a new smi.dist userdata owning `d`.
void push_distribution(lua_State* L, smi::stats::DistributionPtr d);
/// The distribution at idx (an smi.dist); raises a Lua error naming `what` otherwise.
smi::stats::DistributionPtr to_distribution(lua_State* L, int idx, const char* what);
/// nullptr when the value at idx is not an smi.dist.
smi::stats::DistributionPtr test_distribution(lua_State* L, int idx);
/// Registers the smi.dist metatable (called once by open_stats). Extra fields of subtypes
/// (a KDE's bandwidth, ...) come from `getter`, which may be nullptr.
void register_distribution_type(lua_State* L);

}  // namespace smi::bind
