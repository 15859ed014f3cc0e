// SPDX-License-Identifier: MIT
#pragma once
// The option schema of smi.screen (luax/option_schema.hpp): the full screening's options and the
// surrogate method's; model, inputs and order are read by model_arg.cpp. doc.cpp lists them.
#include <optional>
#include <string>

#include "kernels/surrogate/screen.hpp"
#include "kernels/surrogate/screen_surrogate.hpp"
#include "luax/option_schema.hpp"

namespace smi::bind::surrogate {

struct ScreenArgs {
  smi::surrogate::screen::Options full;
  smi::surrogate::screen::SurrogateOptions surrogate;
  std::string method = "full";        ///< "full" (eq. 3 on the model) or "surrogate"
  std::optional<std::string> output;  ///< the one output to rank (none: all)
};

const lua::Schema<ScreenArgs>& screen_schema();

}  // namespace smi::bind::surrogate
