#pragma once
// The Lua type smi.Kriging: a fitted model plus the names of its inputs and output, shared by
// the kriging, propagation and screening bindings.
#include <string>
#include <vector>
#include <lua.hpp>

#include "surrogate/kriging.hpp"

namespace smi::bind::surrogate {

inline constexpr const char* kKrigingType = "smi.Kriging";

struct KrigingBox {
  kriging::Model model;
  std::vector<std::string> inputs;  // may be empty (unnamed)
  std::string output = "y";
};

/// nullptr when the value at idx is not an smi.Kriging (or is closed).
KrigingBox* test_kriging(lua_State* L, int idx);
void open_kriging(lua_State* L);  // smi.kriging.fit / .load and the type

}  // namespace smi::bind::surrogate
