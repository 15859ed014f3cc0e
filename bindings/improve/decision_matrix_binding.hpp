// SPDX-License-Identifier: MIT
#pragma once
// smi.refine.decision_matrix (bindings/improve/decision_matrix.cpp).
#include <lua.hpp>

namespace smi::bind::improve {

int decision_matrix(lua_State* L);
/// The metatable of decision results (__tostring prints the table). Stack unchanged.
void register_decision_meta(lua_State* L);

}  // namespace smi::bind::improve
