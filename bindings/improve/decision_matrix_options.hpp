// SPDX-License-Identifier: MIT
#pragma once
// The option schema of smi.refine.decision_matrix (luax/option_schema.hpp); the candidates and
// criteria lists are read by hand (decision_matrix.cpp).
#include "kernels/improve/decision_matrix.hpp"
#include "luax/option_schema.hpp"

namespace smi::bind::improve {

const lua::Schema<smi::improve::DecisionOptions>& decision_matrix_schema();

}  // namespace smi::bind::improve
