// SPDX-License-Identifier: MIT
#pragma once
// The option schema of smi.model.lua (luax/option_schema.hpp); doc.cpp lists it.
#include <string>

#include "luax/option_schema.hpp"

namespace smi::bind::eval {

struct LuaModelArgs {
  std::string name = "lua";  ///< the model's name
};

const lua::Schema<LuaModelArgs>& lua_model_schema();

}  // namespace smi::bind::eval
