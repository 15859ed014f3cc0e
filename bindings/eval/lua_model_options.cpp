// SPDX-License-Identifier: MIT
// The option schema of smi.model.lua (lua_model_options.hpp): inputs, outputs and fn are read by
// lua_model.cpp (the function stays on the stack).
#include "bindings/eval/lua_model_options.hpp"

#include <vector>

namespace smi::bind::eval {

using namespace smi::lua;

const Schema<LuaModelArgs>& lua_model_schema() {
  using S = LuaModelArgs;
  static const Schema<S> s("smi.model.lua", std::vector<Option<S>>{
      string<S>("name", &S::name, {}, "the model's name"),
      by_hand<S>("inputs", "(required)", "input names (columns of X)"),
      by_hand<S>("outputs", "(required)", "output names"),
      by_hand<S>("fn", "(required)", "function(X) returning {output = vec, ...}, one value per row"),
  });
  return s;
}

}  // namespace smi::bind::eval
