// SPDX-License-Identifier: MIT
// Entry point of the improve binding area (see modules.hpp): smi.calibrate, smi.calibrate_bayes and smi.refine.
#include "bindings/improve/calibrate.hpp"
#include "bindings/improve/calibrate_bayes.hpp"
#include "bindings/improve/decision_matrix_binding.hpp"
#include "bindings/modules.hpp"

namespace smi::bind {

void open_improve(lua_State* L) {
  // stack: [smi]
  lua_pushcfunction(L, improve::calibrate);
  lua_setfield(L, -2, "calibrate");
  improve::register_bayes_meta(L);
  lua_pushcfunction(L, improve::calibrate_bayes);
  lua_setfield(L, -2, "calibrate_bayes");
  improve::register_decision_meta(L);
  lua_newtable(L);
  lua_pushcfunction(L, improve::decision_matrix);
  lua_setfield(L, -2, "decision_matrix");
  lua_setfield(L, -2, "refine");
}

}  // namespace smi::bind
