// SPDX-License-Identifier: MIT
// luaopen_smi: the `smi` module table, assembled from every binding area.
#include "bindings/modules.hpp"

int luaopen_smi(lua_State* L) {
  lua_newtable(L);  // stack: [smi]
  smi::bind::open_vec(L);
  smi::bind::open_mat(L);
  smi::bind::open_rng(L);
  smi::bind::open_csv(L);
  smi::bind::open_json(L);
  smi::bind::open_stats(L);
  smi::bind::open_surrogate(L);
  smi::bind::open_eval(L);
  smi::bind::open_improve(L);
  smi::bind::open_members(L);
  return 1;
}
