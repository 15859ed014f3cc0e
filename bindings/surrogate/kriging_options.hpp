// SPDX-License-Identifier: MIT
#pragma once
// The option schemas of smi.kriging.fit and m:predict (luax/option_schema.hpp); doc.cpp lists
// their options from them.
#include <string>
#include <vector>

#include "kernels/surrogate/kriging.hpp"
#include "luax/option_schema.hpp"
#include "platform/core/defaults.hpp"

namespace smi::bind::surrogate {

/// smi.kriging.fit's options: the kernel's, plus the names the model carries.
struct KrigingFitArgs : smi::surrogate::kriging::FitOptions {
  std::vector<std::string> inputs;  ///< input names (none: x1, x2, ...)
  std::string output = "y";         ///< the response's name
};

/// m:predict's options.
struct KrigingPredictArgs {
  bool mse = true;              ///< also return the mean squared error
  int threads = kDefaultThreads;
};

const lua::Schema<KrigingFitArgs>& kriging_fit_schema();
const lua::Schema<KrigingPredictArgs>& kriging_predict_schema();

}  // namespace smi::bind::surrogate
