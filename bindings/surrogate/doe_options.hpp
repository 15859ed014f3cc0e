// SPDX-License-Identifier: MIT
#pragma once
// The option schemas of smi.doe.lhs and smi.doe.sobol (luax/option_schema.hpp); doc.cpp lists
// their options from them.
#include <cstdint>

#include "kernels/surrogate/doe.hpp"
#include "luax/option_schema.hpp"

namespace smi::bind::surrogate {

/// smi.doe.lhs's options: the kernel's, plus the design's seed (the run's unless given).
struct LhsArgs : smi::surrogate::doe::LhsOptions {
  std::uint64_t seed = 0;
};

const lua::Schema<LhsArgs>& lhs_schema();
const lua::Schema<smi::surrogate::doe::SobolOptions>& sobol_schema();

}  // namespace smi::bind::surrogate
