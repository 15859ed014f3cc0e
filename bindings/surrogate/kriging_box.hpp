// SPDX-License-Identifier: MIT
#pragma once
// The Lua type smi.kriging: a fitted model plus the names of its inputs and output, shared by
// the kriging, propagation and screening bindings.
#include <cstddef>
#include <string>
#include <vector>
#include <lua.hpp>

#include "kernels/surrogate/kriging.hpp"

namespace smi::bind::surrogate {

inline constexpr const char* kKrigingType = "smi.kriging";

struct KrigingBox {
  smi::surrogate::kriging::Model model;
  std::vector<std::string> inputs;  // may be empty (unnamed)
  std::string output = "y";
};

/// The heap a fitted model holds (its n x n Cholesky factor dominates), counted against
/// --max-memory by lua::push_box (found by argument-dependent lookup).
inline std::size_t heap_bytes(const KrigingBox& k) {
  const auto& m = k.model;
  const auto doubles = m.theta.size() + m.S.size() + m.Y.size() + m.C.size() + m.Ft.size() + m.Q.size() + m.G.size() +
                       m.beta.size() + m.gamma.size() + m.lower.size() + m.upper.size();
  return static_cast<std::size_t>(doubles) * sizeof(double);
}

/// nullptr when the value at idx is not an smi.kriging (or is closed).
KrigingBox* test_kriging(lua_State* L, int idx);
void open_kriging(lua_State* L);  // smi.kriging.fit / .load and the type

}  // namespace smi::bind::surrogate
