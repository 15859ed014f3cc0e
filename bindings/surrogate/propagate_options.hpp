// SPDX-License-Identifier: MIT
#pragma once
// The option schema of smi.propagate (luax/option_schema.hpp): n and seed; model, inputs and
// order are read by model_arg.cpp. doc.cpp lists them.
#include <Eigen/Core>

#include <cstdint>

#include "kernels/surrogate/propagate.hpp"
#include "luax/option_schema.hpp"

namespace smi::bind::surrogate {

struct PropagateArgs {
  Eigen::Index n = smi::surrogate::propagate::kDefaultSampleSize;  ///< sample size
  std::uint64_t seed = 0;                                          ///< the run's seed unless given
};

const lua::Schema<PropagateArgs>& propagate_schema();

}  // namespace smi::bind::surrogate
