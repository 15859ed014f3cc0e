// SPDX-License-Identifier: MIT
#pragma once
// One solver run as a function: inputs -> results of §10. Shared by the program, the tests and
// the experimental-data generator so they cannot drift apart.
#include "inputs.hpp"
#include "results.hpp"

namespace cfe {

Results run_model(const Inputs& in);

}  // namespace cfe
